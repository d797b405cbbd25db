// The turbodyn command line.
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/bearing_command.h"
#include "app/command_line.h"
#include "app/identify_command.h"
#include "app/journal_command.h"
#include "app/modal_command.h"
#include "app/optimize_command.h"
#include "app/response_command.h"
#include "app/run_command.h"
#include "app/stability_command.h"
#include "app/sweep_command.h"
#include "model/io/model_file.h"
#include "model/io/result_header.h"
#include "model/rotor/rotor.h"

namespace {

constexpr int kExitModelError = 2;

int run_check(const std::filesystem::path& file, const std::vector<turbodyn::Override>& overrides) {
  const turbodyn::MachineSpec spec = turbodyn::load_model(file, overrides);
  const turbodyn::Rotor rotor = turbodyn::build_rotor(spec);
  std::cout << file.string() << ": ok\n"
            << "  name            " << spec.name << "\n"
            << "  shaft length    " << spec.shaft_length() * 1e3 << " mm in " << spec.shaft.size() << " sections\n"
            << "  mesh            " << rotor.node_z.size() << " nodes, " << rotor.elements.size() << " elements, "
            << rotor.n_dof << " DOF\n"
            << "  rotor mass      " << rotor.total_mass << " kg\n"
            << "  disks           " << rotor.disks.size() << "\n"
            << "  bearings        " << spec.bearings.size() << "\n";
  for (const turbodyn::RigidDisk& d : rotor.disks)
    std::cout << "    disk " << d.name << " at z = " << rotor.node_z[d.node] * 1e3 << " mm, m = " << d.mass
              << " kg, unbalance " << d.unbalance * 1e6 << " g*mm\n";
  for (const turbodyn::BearingSpec& b : spec.bearings)
    std::cout << "    bearing " << b.name << " (" << to_string(b.type) << ") at z = " << b.z * 1e3 << " mm\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  turbodyn::app::set_command_line(argc, argv);
  CLI::App app{"turbodyn: nonlinear run-up simulation of turbocharger rotors"};
  app.set_version_flag("--version", std::string("turbodyn ") + turbodyn::turbodyn_version());
  app.require_subcommand(1);

  std::vector<std::string> sets;
  auto add_sets = [&](CLI::App* cmd) {
    cmd->add_option("--set", sets,
                    "Override a model-file value: PATH=VALUE, e.g. bearings.compressor.kxx=2e7 (repeatable)");
  };

  std::filesystem::path check_file;
  CLI::App* check = app.add_subcommand("check", "Read a model file, report errors, print a short summary");
  check->add_option("MODEL", check_file, "Model file (TOML)")->required();
  add_sets(check);

  turbodyn::app::ModalCommandOptions modal_options;
  std::string frame = "inertial";
  CLI::App* modal = app.add_subcommand("modal", "Complex modes, Campbell diagram and critical speeds");
  modal->add_option("MODEL", modal_options.model_file, "Model file (TOML)")->required();
  modal->add_option("-o,--output", modal_options.output_dir, "Output directory")->capture_default_str();
  modal->add_option("--speeds", modal_options.speeds,
                    "Speeds: START:END:COUNT or a comma list, units allowed (\"0:150000 rpm:31\"); "
                    "default from [modal] in the model file");
  modal->add_option("--modes", modal_options.n_modes, "Number of modes per speed (default from the model file)")
      ->check(CLI::PositiveNumber);
  modal->add_option("--frame", frame, "inertial (default) or rotating (paper Eq. 9 in the shaft frame)")
      ->check(CLI::IsMember({"inertial", "rotating"}));
  modal->add_flag("!--no-plots", modal_options.plots, "Do not draw PNG pictures");
  modal->add_option("--amplitudes", modal_options.amplitudes,
                    "Also the forward 1x critical speeds at these whirl amplitudes (START:END:COUNT or a comma "
                    "list, \"0.1:500 um:25\"), the ball bearings' quasi-static reaction at each");
  modal->add_option("--amplitude-at", modal_options.amplitude_at,
                    "Where the amplitude is measured: disks.NAME or bearings.NAME (default: for each branch the "
                    "disk that moves most in its mode)");
  add_sets(modal);

  turbodyn::app::BearingCommandOptions bearing_options;
  CLI::App* bearing = app.add_subcommand(
      "bearing", "Quasi-static equilibrium of one ball bearing, or steady operating points of one floating-ring "
                 "bearing, at speeds: loads, ring speed, temperatures, power loss, stiffness, damping");
  bearing->add_option("MODEL", bearing_options.model_file, "Model file (TOML)")->required();
  bearing->add_option("--bearing", bearing_options.bearing, "Name of a ball or floating-ring bearing (default: the model's first)");
  bearing->add_option("--speeds", bearing_options.speeds,
                      "Speeds: START:END:COUNT or a comma list, units allowed (\"0:150000 rpm:16\"); "
                      "default: 11 speeds over [modal]");
  bearing->add_option("--load", bearing_options.load,
                      "Static load on the inner ring or journal \"Fx,Fy[,Fz]\" (N, units allowed); Fz adds to a ball "
                      "bearing's preload")
      ->capture_default_str();
  bearing->add_option("--radial-travel", bearing_options.radial_travel,
                      "Ball bearings: load-deflection curve at each speed, the inner ring moved radially by these "
                      "travels with its tilt held: START:END:COUNT or a comma list of lengths (\"0:60 um:31\")");
  bearing->add_option("-o,--output", bearing_options.output_dir, "Output directory")->capture_default_str();
  bearing->add_flag("!--no-plots", bearing_options.plots, "Do not draw PNG pictures");
  add_sets(bearing);

  turbodyn::app::StabilityCommandOptions stability_options;
  CLI::App* stability = app.add_subcommand(
      "stability", "Eigenvalues of the whole nonlinear model (rotor, balls, cages, friction) linearised about its "
                   "steady turning state at speeds: whirl frequencies, growth rates, damping ratios");
  stability->add_option("MODEL", stability_options.model_file, "Model file (TOML)")->required();
  stability->add_option("--speeds", stability_options.speeds,
                        "Speeds: START:END:COUNT or a comma list, units allowed (\"20000:150000 rpm:14\"); "
                        "default: 11 speeds over [modal]");
  stability->add_option("--min-rotor-share", stability_options.min_rotor_share,
                        "Table and pictures: modes with at least this fraction of their motion in the rotor")
      ->capture_default_str();
  stability->add_option("--continuation-steps", stability_options.continuation_step_factor,
                        "Fraction (0, 1] of the steady state's continuation steps in speed: 0.5 halves them, to check "
                        "that the state found does not depend on them")
      ->capture_default_str();
  stability->add_option("-o,--output", stability_options.output_dir, "Output directory")->capture_default_str();
  stability->add_flag("!--no-plots", stability_options.plots, "Do not draw PNG pictures");
  add_sets(stability);

  turbodyn::app::RunCommandOptions run_options;
  CLI::App* run = app.add_subcommand("run", "Run-up simulation: time series, summary, spectrograms, orbits");
  run->add_option("MODEL", run_options.model_file, "Model file (TOML)")->required();
  run->add_option("-o,--output", run_options.output_dir, "Output directory")->capture_default_str();
  run->add_flag("!--no-plots", run_options.plots, "Do not draw PNG pictures");
  run->add_option("-j,--threads", run_options.threads,
                  "Threads for the bearings of one right-hand side (at most one per bearing; same results)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  add_sets(run);

  turbodyn::app::PlotCommandOptions plot_options;
  CLI::App* plot = app.add_subcommand("plot", "Redraw the pictures of a run from its timeseries.h5 (e.g. other spectrogram settings)");
  plot->add_option("RUN_DIR", plot_options.run_dir, "Output directory of turbodyn run")->required();
  plot->add_option("--campbell", plot_options.campbell_csv,
                   "campbell.csv of turbodyn modal: draw its natural frequencies on the spectrograms");
  plot->add_option("--backbone", plot_options.backbone_json,
                   "modal.json of turbodyn modal --amplitudes: draw its critical speeds at an amplitude on that "
                   "disk's 1x order track (may be given more than once)");
  plot->add_option("--response", plot_options.response_json,
                   "response.json of turbodyn response --nonlinear: draw its steady states on the disks' 1x order "
                   "tracks (may be given more than once)");
  add_sets(plot);

  turbodyn::app::ResponseCommandOptions response_options;
  CLI::App* response =
      app.add_subcommand("response", "Steady-state synchronous unbalance response of the linear rotor");
  response->add_option("MODEL", response_options.model_file, "Model file (TOML)")->required();
  response->add_option("-o,--output", response_options.output_dir, "Output directory")->capture_default_str();
  response->add_option("--speeds", response_options.speeds,
                       "Speeds: START:END:COUNT or a comma list, units allowed; default from [modal]");
  response->add_flag("!--no-plots", response_options.plots, "Do not draw PNG pictures");
  response->add_flag("--nonlinear", response_options.nonlinear,
                     "Also the nonlinear steady state on the ball bearings' quasi-static reaction, traced through "
                     "its folds (jump speeds)");
  add_sets(response);

  // The study commands' common options: the study file, the output directory and the parallel runs.
  auto add_study_options = [](CLI::App* cmd, const std::string& study_kind, std::filesystem::path& study_file,
                              std::filesystem::path& output_dir, const std::string& output_help, int& threads) {
    cmd->add_option("STUDY", study_file, study_kind + " file (TOML)")->required();
    cmd->add_option("-o,--output", output_dir, output_help)->capture_default_str();
    cmd->add_option("-j,--threads", threads, "Parallel runs (default: the study's, else all cores)")
        ->check(CLI::NonNegativeNumber);
  };

  turbodyn::app::SweepCommandOptions sweep_options;
  CLI::App* sweep = app.add_subcommand("sweep", "Parameter study: runs of a design in parallel, table and pictures");
  add_study_options(sweep, "Study", sweep_options.study_file, sweep_options.output_dir,
                    "Output directory (resumes the runs found there)", sweep_options.threads);
  sweep->add_option("--shard", sweep_options.shard, "Run only the slice K/N of the design (runs i with i % N == K)");
  sweep->add_flag("!--no-plots", sweep_options.plots, "Do not draw PNG pictures");

  std::filesystem::path merge_study, merge_output = "out/merged";
  std::vector<std::filesystem::path> merge_dirs;
  bool merge_plots = true;
  CLI::App* merge = app.add_subcommand("merge", "Join the runs of several sweep shards into one results set");
  merge->add_option("STUDY", merge_study, "Study file (TOML)")->required();
  merge->add_option("DIRS", merge_dirs, "Shard output directories")->required();
  merge->add_option("-o,--output", merge_output, "Output directory")->capture_default_str();
  merge->add_flag("!--no-plots", merge_plots, "Do not draw PNG pictures");

  turbodyn::app::JournalCommandOptions jo;
  CLI::App* journal = app.add_subcommand(
      "journal", "One plain journal bearing at a given state: forces, Sommerfeld number, linearised coefficients (JSON)");
  journal->add_option("--diameter", jo.diameter, "Journal diameter")->capture_default_str();
  journal->add_option("--length", jo.length, "Bearing width");
  journal->add_option("--ld", jo.ld, "Width as a ratio L/D (instead of --length)");
  journal->add_option("--clearance", jo.clearance, "Radial clearance")->capture_default_str();
  journal->add_option("--viscosity", jo.viscosity, "Dynamic viscosity (default: SAE 30 Vogel fit at --temperature)");
  journal->add_option("--temperature", jo.temperature, "Oil temperature")->capture_default_str();
  journal->add_option("--speed", jo.speed, "Journal speed")->capture_default_str();
  journal->add_option("--outer-speed", jo.outer_speed, "Bush speed")->capture_default_str();
  journal->add_option("--eccentricity", jo.eccentricity, "Eccentricity ratio e/c")->capture_default_str();
  journal->add_option("--attitude", jo.attitude, "Direction of the eccentricity from +x towards +y")
      ->capture_default_str();
  journal->add_option("--cavitation", jo.cavitation, "gumbel, mass-conserving or none")->capture_default_str();
  journal->add_option("--n-circ", jo.n_circ, "Grid nodes around")->capture_default_str();
  journal->add_option("--n-axial", jo.n_axial, "Grid nodes across")->capture_default_str();
  journal->add_option("--hole-diameter", jo.hole_diameter, "Feed hole at the top, mid-width")->capture_default_str();
  journal->add_option("--groove-width", jo.groove_width,
                      "Full circumferential feed groove at mid-width, instead of the hole")->capture_default_str();
  journal->add_option("--supply-pressure", jo.supply_pressure, "Feed pressure (gauge) at the hole or groove")
      ->capture_default_str();

  turbodyn::app::OptimizeCommandOptions optimize_options;
  CLI::App* optimize = app.add_subcommand("optimize", "Design optimisation (NLopt) of model parameters on run metrics");
  add_study_options(optimize, "Optimisation study", optimize_options.study_file, optimize_options.output_dir,
                    "Output directory (restarts from the evaluations found there)", optimize_options.threads);
  optimize->add_option("--maxeval", optimize_options.maxeval, "Replace the study's maxeval (e.g. a quick trial)")
      ->check(CLI::PositiveNumber);
  optimize->add_flag("!--no-plots", optimize_options.plots, "No pictures (and no final run-ups for the spectrograms)");

  turbodyn::app::IdentifyCommandOptions identify_options;
  CLI::App* identify = app.add_subcommand("identify", "Fit bearing and unbalance parameters to a measured run-up (Ceres)");
  add_study_options(identify, "Identification study", identify_options.study_file, identify_options.output_dir,
                    "Output directory", identify_options.threads);
  identify->add_flag("!--no-plots", identify_options.plots, "Do not draw PNG pictures");

  CLI11_PARSE(app, argc, argv);

  try {
    std::vector<turbodyn::Override> overrides;
    for (const std::string& s : sets) overrides.push_back(turbodyn::parse_override(s));
    if (check->parsed()) return run_check(check_file, overrides);
    if (journal->parsed()) return turbodyn::app::run_journal_command(jo);
    if (bearing->parsed()) {
      bearing_options.overrides = overrides;
      return turbodyn::app::run_bearing_command(bearing_options);
    }
    if (stability->parsed()) {
      stability_options.overrides = overrides;
      return turbodyn::app::run_stability_command(stability_options);
    }
    if (sweep->parsed()) return turbodyn::app::run_sweep_command(sweep_options);
    if (identify->parsed()) return turbodyn::app::run_identify_command(identify_options);
    if (optimize->parsed()) return turbodyn::app::run_optimize_command(optimize_options);
    if (merge->parsed()) return turbodyn::app::run_merge_command(merge_study, merge_dirs, merge_output, merge_plots);
    if (run->parsed()) {
      run_options.overrides = overrides;
      return turbodyn::app::run_run_command(run_options);
    }
    if (plot->parsed()) {
      plot_options.overrides = overrides;
      return turbodyn::app::run_plot_command(plot_options);
    }
    if (response->parsed()) {
      response_options.overrides = overrides;
      return turbodyn::app::run_response_command(response_options);
    }
    if (modal->parsed()) {
      modal_options.overrides = overrides;
      modal_options.frame = frame == "rotating" ? turbodyn::Frame::Rotating : turbodyn::Frame::Inertial;
      return turbodyn::app::run_modal_command(modal_options);
    }
  } catch (const turbodyn::ModelError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitModelError;
  } catch (const std::bad_alloc&) {
    // The limits on model input (docs/model-format.md, "Limits") refuse what is known to be too big; this is the
    // last line for what slips through.
    std::cerr << "error: out of memory: the input asks for more memory than this machine has (see the limits in "
                 "docs/model-format.md)\n";
    return 1;
  } catch (const std::length_error&) {
    std::cerr << "error: out of memory: the input asks for an array larger than the program can allocate (see the "
                 "limits in docs/model-format.md)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

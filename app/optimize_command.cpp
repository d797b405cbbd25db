#include "app/optimize_command.h"
#include "app/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "post/plot.h"
#include "model/engine/integrator.h"
#include "model/io/output_file.h"
#include "model/io/overrides.h"
#include "post/run_pictures.h"
#include "post/report.h"
#include "app/command_line.h"
#include "optim/optimizer.h"
#include "optim/report.h"
#include "studies/sweep.h"

namespace turbodyn::app {
namespace {

constexpr int kExitNoFeasibleDesign = 4;
constexpr plot::Size kPanelSize{800, 560};  // one spectrogram of the side-by-side pair


std::string short_number(double v) {
  std::ostringstream os;
  os << std::setprecision(5) << v;
  return os.str();
}

// The design for people: 6 significant digits (best.toml holds the exact values that were evaluated).
std::string design_text(const optim::OptimizationSpec& spec, const std::vector<double>& design) {
  std::string s;
  for (std::size_t i = 0; i < design.size(); ++i) {
    std::ostringstream v;
    v << std::setprecision(6) << design[i];
    s += (i ? ", " : "") + spec.variables[i].path + " = " + v.str() +
         (spec.variables[i].unit.empty() ? "" : " " + spec.variables[i].unit);
  }
  return s;
}

// The run-up of one design in the first operating case, for the spectrograms.
RunupResult final_run(const optim::OptimizationSpec& spec, const std::vector<double>& design, MachineSpec& machine) {
  machine = studies::load_base_model(spec, optim::run_overrides(spec, design, &spec.cases.front()));
  const auto model = make_runup_model(machine);
  RunupOptions ro = runup_options(machine);
  ro.cancel = InterruptGuard::flag();
  if (spec.final_runs == "window") {
    if (spec.speed_window_min > 0.0) ro.t_start = studies::time_at_speed(machine.speed, spec.speed_window_min);
    if (spec.speed_window_max > 0.0) ro.t_end = studies::time_at_speed(machine.speed, spec.speed_window_max);
  }
  return simulate_runup(*model, ro);
}

// Spectrogram of one channel against rotor speed (as `turbodyn run` draws it), without its colour range; none
// unless it has at least two columns and rows.
std::optional<plot::Heatmap> spectrogram(const MachineSpec& machine, const RunupResult& r, const std::string& probe) {
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    if (r.channels[c].name != probe) continue;
    std::optional<plot::Heatmap> hm = post::run_spectrogram(machine.output, r, c);
    if (hm && (hm->x.size() < 2 || hm->y.size() < 2)) hm.reset();
    return hm;
  }
  return std::nullopt;
}

// Two PNGs side by side in one (gnuplot reads them back as RGB images).
void side_by_side(const std::filesystem::path& left, const std::filesystem::path& right,
                  const std::filesystem::path& out) {
  const std::filesystem::path script = out.string() + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size " << 2 * kPanelSize.width << "," << kPanelSize.height << "\n"
       << "set output '" << out.string() << "'\n"
       << "set multiplot layout 1,2\nunset border\nunset tics\nunset key\nset margins 0,0,0,0\nset autoscale fix\n"
       << "set size ratio -1\n"
       << "plot '" << left.string() << "' binary filetype=png with rgbimage\n"
       << "plot '" << right.string() << "' binary filetype=png with rgbimage\nunset multiplot\n";
  }
  const std::string cmd = "'" + plot::gnuplot_executable().string() + "' '" + script.string() + "' 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  std::filesystem::remove(script);
  if (rc != 0 || !std::filesystem::exists(out)) throw plot::PlotError("gnuplot could not join " + left.string() + " and " + right.string());
}

// Runs the initial and the best design (first case) and draws their spectrograms with one colour scale.
void draw_spectrograms(const optim::OptimizationSpec& spec, const std::vector<double>& initial,
                       const std::vector<double>& best, const std::filesystem::path& dir,
                       std::vector<std::string>& written, std::vector<std::string>& warnings) {
  std::cerr << "running the initial and the best design for the spectrograms ("
            << (spec.final_runs == "full" ? "whole run-up" : "speed window") << ")...\n";
  MachineSpec m0, m1;
  auto f0 = std::async(std::launch::async, [&] { return final_run(spec, initial, m0); });
  auto f1 = std::async(std::launch::async, [&] { return final_run(spec, best, m1); });
  const RunupResult r0 = f0.get(), r1 = f1.get();
  for (const auto* r : {&r0, &r1})
    if (!r->complete) warnings.push_back("final run-up " + std::string(r == &r0 ? "of the initial design" : "of the best design") + " " + r->message);
  for (const std::string& probe : spec.spectrogram_probes) {
    std::optional<plot::Heatmap> a = spectrogram(m0, r0, probe), b = spectrogram(m1, r1, probe);
    if (!a || !b) {
      warnings.push_back("no spectrogram of " + probe + ": the run is shorter than one STFT segment");
      continue;
    }
    double zmax = 0.0;
    for (const plot::Heatmap* h : {&*a, &*b})
      for (double v : h->z)
        if (std::isfinite(v)) zmax = std::max(zmax, v);
    if (!(zmax > 0.0)) continue;
    a->zrange = b->zrange = std::make_pair(zmax * 1e-3, zmax);
    a->title = "Initial design: " + probe;
    b->title = "Optimised design: " + probe;
    const std::string stem = "spectrogram_" + post::file_safe(probe);
    plot::render_png(*a, dir / (stem + "_initial.png"), kPanelSize);
    plot::render_png(*b, dir / (stem + "_best.png"), kPanelSize);
    written.push_back(stem + "_initial.png");
    written.push_back(stem + "_best.png");
    try {
      side_by_side(dir / (stem + "_initial.png"), dir / (stem + "_best.png"), dir / (stem + "_comparison.png"));
      written.push_back(stem + "_comparison.png");
    } catch (const std::exception& e) {
      warnings.push_back(e.what());
    }
  }
}

}  // namespace

int run_optimize_command(const OptimizeCommandOptions& options) {
  optim::OptimizationSpec spec = optim::load_optimization(options.study_file);
  if (options.maxeval > 0) spec.algorithm.maxeval = options.maxeval;
  const std::filesystem::path dir = options.output_dir;
  std::filesystem::create_directories(dir);
  std::cout << spec.name << ": " << spec.variables.size() << " variable" << (spec.variables.size() == 1 ? "" : "s") << ", " << spec.cases.size() << " case"
            << (spec.cases.size() == 1 ? "" : "s") << ", " << spec.constraints.size() << " constraint"
            << (spec.constraints.size() == 1 ? "" : "s") << ", algorithm " << spec.algorithm.name << "\n";
  if (!spec.constraints.empty() && !optim::supports_constraints(spec.algorithm.name))
    std::cout << "note: " << spec.algorithm.name
              << " handles bound constraints only: the constraints are handled by NLopt's augmented Lagrangian "
                 "(AUGLAG) around it\n";

  optim::OptimizerOptions oo;
  oo.log_file = dir / "evaluations.jsonl";
  oo.threads = options.threads;
  oo.cancel = InterruptGuard::flag();
  const bool tty = isatty(STDERR_FILENO);
  oo.progress = [&](const optim::HistoryEntry& h, const optim::OptimizationProgress& p) {
    std::ostringstream os;
    os << "eval " << h.request << (h.gradient_point ? " (gradient point" : " (design") << ", "
       << (h.cached ? "cached" : format_duration(h.evaluation.wall_time)) << "): objective "
       << short_number(h.assessment.objective) << (h.assessment.failed ? " FAILED: " + h.assessment.note
                                                   : h.assessment.feasible ? " feasible" : " infeasible")
       << "; best " << (std::isnan(p.best_objective) ? std::string("-") : short_number(p.best_objective)) << "; "
       << p.new_evaluations << " new, " << p.cached_evaluations << " cached, wall " << format_duration(p.wall_time);
    if (tty) std::cerr << "\r" << os.str() << "\033[K" << std::flush;
    else std::cerr << os.str() << "\n";
  };
  const InterruptGuard guard;  // also over the final run-ups and pictures
  const optim::OptimizationResult r = optim::optimize(spec, optim::model_evaluator(spec), oo);
  if (tty) std::cerr << "\n";

  std::vector<std::string> written{"evaluations.jsonl"}, warnings;
  optim::write_history_csv(spec, r, dir / "history.csv");
  written.push_back("history.csv");
  nlohmann::json result = optim::result_json(spec, r);
  if (r.best) {
    const optim::HistoryEntry& best = r.history[*r.best];
    std::ostringstream header;
    header << "Optimised by `turbodyn optimize " << options.study_file.string() << "` (" << r.algorithm << ", "
           << r.nlopt_result << ")\n"
           << "base model: " << spec.model.string() << "\n"
           << "objective " << short_number(best.assessment.objective)
           << (r.best_feasible ? ", all constraints satisfied" : ", CONSTRAINTS VIOLATED (no feasible design found)") << "\n"
           << "design: " << design_text(spec, best.evaluation.design) << "\n";
    if (!spec.fixed.empty()) header << "with the study's fixed overrides applied\n";
    for (const optim::OperatingCase& c : spec.cases)
      if (!c.overrides.empty()) {
        header << "not applied: the overrides of operating case '" << c.name << "':";
        for (const Override& o : c.overrides) header << " " << o.path << "=" << o.value;
        header << "\n";
      }
    const std::vector<Override> o = optim::run_overrides(spec, best.evaluation.design, nullptr);
    studies::write_patched_base_model(spec, o, header.str(), dir / "best.toml");
    written.push_back("best.toml");
  }
  if (options.plots && !r.history.empty()) {
    try {
      optim::write_convergence_plot(spec, r, dir / "convergence.png");
      written.push_back("convergence.png");
      if (r.best && spec.final_runs != "none" && !r.interrupted)
        draw_spectrograms(spec, optim::start_design(spec), r.history[*r.best].evaluation.design, dir, written, warnings);
    } catch (const std::exception& e) {
      warnings.push_back(std::string("pictures: ") + e.what());
    }
  }
  result["files"] = written;
  result["warnings"] = warnings;
  write_output_file(dir / "result.json", result.dump(1) + "\n");
  {
    auto [pictures, others] = post::split_pictures(written);
    others.insert(others.begin(), "result.json");
    post::write_optimize_report(dir, result, {command_line(), pictures, others, {}});
  }

  std::cout << spec.name << ": " << r.nlopt_result << " (" << r.reason << ") after " << r.history.size()
            << (r.history.size() == 1 ? " evaluation (" : " evaluations (") << r.new_evaluations << " run, "
            << r.cached_evaluations << " from the cache), "
            << format_duration(r.wall_time) << "\n";
  if (!r.note.empty()) std::cout << "note: " << r.note << "\n";
  if (r.best) {
    const optim::HistoryEntry& b = r.history[*r.best];
    std::cout << (r.best_feasible ? "best feasible design" : "no feasible design; least infeasible") << " (evaluation "
              << b.request << "): " << design_text(spec, b.evaluation.design) << "\n  objective "
              << short_number(b.assessment.objective) << " (initial "
              << short_number(r.history.front().assessment.objective) << ")\n";
    for (std::size_t k = 0; k < spec.constraints.size(); ++k)
      for (std::size_t c = 0; c < spec.cases.size(); ++c) {
        const std::size_t i = k * spec.cases.size() + c;
        const optim::Constraint& con = spec.constraints[k];
        std::cout << "  " << con.name << (spec.cases.size() > 1 ? " (" + spec.cases[c].name + ")" : "") << " = "
                  << short_number(b.assessment.constraint_values[i]) << " " << spec.metrics[con.metric].unit
                  << (con.upper ? " <= " : " >= ") << short_number(con.bound) << "\n";
      }
  }
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  std::cout << "Wrote " << (dir / "result.json").string() << " and " << written.size() << " more files\n";
  if (r.interrupted) {
    std::cerr << "interrupted: the finished evaluations are in " << (dir / "evaluations.jsonl").string()
              << "; run the same command again to continue\n";
    return kExitInterrupted;
  }
  if (!r.best) {
    std::cerr << "error: every evaluation failed; see history.csv\n";
    return 1;
  }
  return r.best_feasible ? 0 : kExitNoFeasibleDesign;
}

}  // namespace turbodyn::app

#include "app/stability_command.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/command_line.h"
#include "app/modal_command.h"
#include "model/engine/speed_text.h"
#include "model/engine/stability.h"
#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "model/spec/constants.h"
#include "model/spec/errors.h"
#include "post/plot.h"
#include "post/report.h"

namespace turbodyn::app {
namespace {

// Damping ratios below this are drawn at it on the logarithmic axis of the damping picture.
constexpr double kDampingFloor = 1e-6;

void write_stability_pictures(const std::string& name, const std::vector<StabilityPoint>& points, double min_share,
                              const std::filesystem::path& dir) {
  using plot::Series;
  Series stable{"stable", {}, {}, Series::Style::Points, "#1f77b4", 1.0};
  Series unstable{"growing (unstable)", {}, {}, Series::Style::Crosses, "#d62728", 1.4};
  Series cage{"cage frequency", {}, {}, Series::Style::Dashed, "#7f7f7f", 1.2};
  for (const StabilityPoint& p : points)
    if (p.frame_speed > 0.0) {
      cage.x.push_back(p.speed * kRadPerSToRpm);
      cage.y.push_back(p.frame_speed / (2.0 * kPi));
    }
  Series damp{"damping ratio of a stable mode", {}, {}, Series::Style::Points, "#1f77b4", 1.0};
  Series growth{"growth rate / |lambda| of an unstable mode", {}, {}, Series::Style::Crosses, "#d62728", 1.4};
  for (const StabilityPoint& p : points)
    for (const StabilityMode& m : p.modes) {
      if (m.rotor_share < min_share) continue;
      const double rpm = p.speed * kRadPerSToRpm;
      Series& f = m.grows() ? unstable : stable;
      f.x.push_back(rpm);
      f.y.push_back(m.frequency);
      Series& d = m.grows() ? growth : damp;
      d.x.push_back(rpm);
      d.y.push_back(std::max(std::abs(m.damping_ratio), kDampingFloor));
    }
  plot::LineChart chart;
  chart.title = name + ": whirl frequencies of the linearised run-up model (> 0 forward, < 0 backward)";
  chart.xlabel = "rotor speed [rpm]";
  chart.ylabel = "frequency in the housing frame [Hz]";
  chart.series = {cage, stable, unstable};
  plot::render_png(chart, dir / "stability_frequencies.png");
  plot::LineChart dc;
  dc.title = name + ": damping ratios of the modes in the rotor (|value|; red: growing)";
  dc.xlabel = "rotor speed [rpm]";
  dc.ylabel = "|damping ratio| [-]";
  dc.logy = true;
  dc.series = {damp, growth};
  plot::render_png(dc, dir / "stability_damping.png");
}

}  // namespace

int run_stability_command(const StabilityCommandOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const MachineSpec spec = load_model(options.model_file, options.overrides);
  const std::vector<double> speeds = analysis_speeds(spec, options.speeds, 11);
  if (!(options.min_rotor_share >= 0.0 && options.min_rotor_share <= 1.0))
    throw ModelError("--min-rotor-share must lie in [0, 1]");
  if (!(options.continuation_step_factor > 0.0 && options.continuation_step_factor <= 1.0))
    throw ModelError("--continuation-steps must lie in (0, 1]");
  StabilityOptions analysis;
  analysis.continuation_step_factor = options.continuation_step_factor;
  // A speed without a steady state ends the analysis there: the speeds before it are written, marked incomplete.
  std::vector<StabilityPoint> points;
  std::string stopped;
  for (double s : speeds) {
    try {
      points.push_back(analyse_stability(spec, s, analysis, points.empty() ? nullptr : &points.back()));
    } catch (const std::invalid_argument& e) {
      throw ModelError(spec.source.string() + ": " + e.what());
    } catch (const std::runtime_error& e) {
      stopped = spec.source.string() + " at " + rpm_text(s) + ": " + e.what();
      break;
    }
  }
  // The onset of instability: the first analysed speed at which a mode with at least min_rotor_share of its motion
  // in the rotor grows, the interval from the speed before it halved kStabilityOnsetBisections times.
  nlohmann::json onset = nullptr;
  std::vector<double> halving_restarted;  // rad/s
  {
    const StabilityModeFilter filter{options.min_rotor_share, 0.0};
    std::vector<const StabilityPoint*> analysed;
    for (const StabilityPoint& p : points) analysed.push_back(&p);
    const StabilityOnset o = find_stability_onset(spec, analysed, filter, analysis);
    if (o.at_first_speed) {
      onset = {{"speed_rpm", o.speed * kRadPerSToRpm}, {"at_first_speed", true}};
    } else if (o.found) {
      onset = {{"speed_rpm", o.speed * kRadPerSToRpm},
               {"resolution_rpm", o.resolution * kRadPerSToRpm},
               {"halvings", kStabilityOnsetBisections},
               {"at_first_speed", false}};
      if (!o.error.empty()) onset["halving_stopped"] = o.error;
      halving_restarted = o.restarted;
      if (!o.restarted.empty()) {
        onset["halving_restarted_rpm"] = nlohmann::json::array();
        for (double w : o.restarted) onset["halving_restarted_rpm"].push_back(w * kRadPerSToRpm);
      }
    }
  }

  std::filesystem::create_directories(options.output_dir);
  nlohmann::json j = result_header(spec, options.overrides);
  j["min_rotor_share"] = options.min_rotor_share;
  j["continuation_step_factor"] = options.continuation_step_factor;
  j["complete"] = stopped.empty();
  if (!stopped.empty()) j["stopped"] = stopped;
  j["onset"] = onset;
  j["assumptions"] = {
      "steady state at constant speed without gravity and unbalance, rotor centred: balls and cages orbit as a "
      "rigid pattern at the cage speed (a relative equilibrium), found by Newton's method",
      "linearised by central differences of the run-up model's right-hand side (every contact, friction and "
      "damping law as in a run), shaft in its physical DOFs, written in the frame turning with the cages: constant "
      "coefficients, eigenvalues = Floquet exponents of the steady state",
      "frequency: housing frame, > 0 forward whirl; growth rate > 0: the steady state is unstable",
      "ball_set_share: fraction of the mode (states scaled by their typical sizes) in the balls' orbital angles and "
      "rates; ball_set_lobes: circumferential order of the balls' orbital-angle motion in the bearing where it is "
      "largest (0: the ball set turning as a whole, 1: a one-lobed density wave, the balls closing up on one side; "
      "-1: no ball bearing)"};
  nlohmann::json jp = nlohmann::json::array();
  for (const StabilityPoint& p : points) {
    nlohmann::json modes = nlohmann::json::array();
    for (const StabilityMode& m : p.modes)
      modes.push_back({{"frequency_hz", m.frequency},
                       {"frame_frequency_hz", m.frame_frequency},
                       {"growth_rate_per_s", m.growth_rate},
                       {"damping_ratio", m.damping_ratio},
                       {"forward_share", m.forward_share},
                       {"rotor_share", m.rotor_share},
                       {"element_shares", m.element_shares},
                       {"ball_set_share", m.ball_set_share},
                       {"ball_set_lobes", m.ball_set_lobes},
                       {"grows", m.grows()}});
    jp.push_back({{"speed_rad_s", p.speed},
                  {"speed_rpm", p.speed * kRadPerSToRpm},
                  {"cage_speed_rad_s", p.frame_speed},
                  {"states", p.n_states},
                  {"steady_state_residual", p.residual},
                  {"steady_state_restarted", p.restarted},
                  {"elements", p.elements},
                  {"modes", modes}});
  }
  j["results"] = jp;
  write_output_file(options.output_dir / "stability.json", j.dump(1) + "\n");
  {
    OutputFile file(options.output_dir / "stability.csv");
    std::ostream& csv = file.stream();
    csv << "speed_rpm,cage_speed_rad_s,frequency_hz,frame_frequency_hz,growth_rate_per_s,damping_ratio,"
           "forward_share,rotor_share,ball_set_share,ball_set_lobes";
    if (!points.empty())
      for (const std::string& e : points.front().elements) csv << ",share_" << e;
    csv << '\n' << std::setprecision(10);
    for (const StabilityPoint& p : points)
      for (const StabilityMode& m : p.modes) {
        csv << p.speed * kRadPerSToRpm << ',' << p.frame_speed << ',' << m.frequency << ',' << m.frame_frequency << ','
            << m.growth_rate << ',' << m.damping_ratio << ',' << m.forward_share << ',' << m.rotor_share << ','
            << m.ball_set_share << ',' << m.ball_set_lobes;
        for (double s : m.element_shares) csv << ',' << s;
        csv << '\n';
      }
    file.commit();
  }

  std::cout << spec.name << ": linearised about the steady turning state (no gravity, no unbalance); modes with at "
            << "least " << options.min_rotor_share << " of their motion in the rotor, least damped first\n";
  std::cout << "     speed [rpm]   cage [rad/s]   frequency [Hz]   growth [1/s]   damping ratio   rotor share"
               "   ball set   lobes\n";
  constexpr std::size_t kShown = 4;
  for (const StabilityPoint& p : points) {
    std::size_t shown = 0;
    for (const StabilityMode& m : p.modes) {
      if (m.rotor_share < options.min_rotor_share) continue;
      std::cout << std::fixed << std::setw(16) << std::setprecision(0) << p.speed * kRadPerSToRpm << std::setw(15)
                << std::setprecision(1) << p.frame_speed << std::setw(17) << std::setprecision(1) << m.frequency
                << std::setw(15) << std::setprecision(2) << m.growth_rate << std::scientific << std::setw(16)
                << std::setprecision(3) << m.damping_ratio << std::fixed << std::setw(14) << std::setprecision(3)
                << m.rotor_share << std::setw(11) << m.ball_set_share << std::setw(8);
      if (m.ball_set_lobes >= 0)
        std::cout << m.ball_set_lobes;
      else
        std::cout << "-";
      std::cout << (m.grows() ? "   UNSTABLE" : "") << "\n";
      if (++shown == kShown) break;
    }
  }
  std::cout << std::defaultfloat;
  for (const StabilityPoint& p : points)
    if (p.restarted)
      std::cout << "Note: at " << rpm_text(p.speed)
                << " the steady state's branch from the speed before ended (a fold); the state there was found anew "
                   "from rest, on another branch (docs/ball-bearing.md, \"A sweep over speeds\").\n";
  for (double w : halving_restarted)
    std::cout << "Note: the onset's halving at " << rpm_text(w) << " " << kHalvingRestartedText << "\n";
  if (onset.is_null())
    std::cout << "No mode with at least " << options.min_rotor_share << " of its motion in the rotor grows at the "
              << "speeds analysed.\n";
  else if (onset.at("at_first_speed").get<bool>())
    std::cout << "Onset of instability: at or below the first speed, " << std::fixed << std::setprecision(0)
              << onset.at("speed_rpm").get<double>() << " rpm.\n" << std::defaultfloat;
  else
    std::cout << "Onset of instability: " << std::fixed << std::setprecision(0) << onset.at("speed_rpm").get<double>()
              << " rpm (the speed before it halved " << kStabilityOnsetBisections << " times: within "
              << onset.at("resolution_rpm").get<double>() << " rpm below)"
              << (onset.contains("halving_stopped")
                      ? "; halving stopped: " + onset.at("halving_stopped").get<std::string>()
                      : std::string())
              << ".\n" << std::defaultfloat;
  const bool plots = options.plots && !points.empty();
  if (plots) write_stability_pictures(spec.name, points, options.min_rotor_share, options.output_dir);
  post::write_stability_report(options.output_dir, j,
                               {command_line(),
                                plots ? std::vector<std::string>{"stability_frequencies.png", "stability_damping.png"}
                                      : std::vector<std::string>{},
                                {"stability.json", "stability.csv"}, {}});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "Wrote " << (options.output_dir / "stability.json").string() << ", stability.csv, report.html"
            << (plots ? ", stability_frequencies.png, stability_damping.png" : "") << " ("
            << std::setprecision(3) << wall << " s)\n";
  if (!stopped.empty()) {
    std::cerr << "turbodyn stability: incomplete, the speeds from here on are not analysed: " << stopped << "\n";
    return 3;
  }
  return 0;
}

}  // namespace turbodyn::app

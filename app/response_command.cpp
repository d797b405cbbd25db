#include "app/response_command.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/modal_command.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/engine/unbalance_whirl.h"
#include "model/spec/constants.h"
#include "studies/table.h"
#include "post/plot.h"
#include "post/resonance.h"
#include "post/report.h"
#include "app/command_line.h"
#include "model/rotor/response.h"
#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "model/rotor/rotor.h"

namespace turbodyn::app {

namespace {

// The nonlinear response's curve: one row per point of each piece.
nlohmann::json nonlinear_json(const UnbalanceWhirl& nl) {
  nlohmann::json out;
  out["covers_range"] = nl.covers_range;
  out["assumptions"] = {
      "forward circular whirl at the rotor speed: a static deflection in the frame that turns with the shaft",
      "ball bearings: quasi-static reaction at the ring's displacement and tilt (outer-race control, no race "
      "traction, no contact damping, balls at 2 pi j / Z from the displacement), as turbodyn modal --amplitudes",
      "linear bearings and the rotor's non-rotating damping act on the whirl's velocity; no gravity",
      "folds: where the speed turns back a slow run-up on that branch jumps to another one, where it turns forward "
      "again a slow run-down on that branch does"};
  for (const UnbalanceWhirlPiece& piece : nl.pieces) {
    nlohmann::json p;
    p["direction"] = piece.upward ? "up" : "down";
    p["from_speed_rpm"] = piece.start_speed * kRadPerSToRpm;
    if (piece.joins >= 0) p["joins_piece"] = piece.joins + 1;
    p["complete"] = piece.stopped.empty();
    if (!piece.stopped.empty()) p["stopped"] = piece.stopped;
    p["folds"] = nlohmann::json::array();
    for (const UnbalanceWhirlFold& f : piece.folds)
      p["folds"].push_back({{"speed_rad_s", f.speed},
                            {"speed_hz", f.speed / (2 * M_PI)},
                            {"speed_rpm", f.speed * kRadPerSToRpm},
                            {"largest_radius_m", f.largest_radius},
                            {"kind", f.speed_turns_back ? "turns back" : "turns forward"}});
    nlohmann::json& c = p["columns"];
    c["speed_rad_s"] = nlohmann::json::array();
    c["speed_hz"] = nlohmann::json::array();
    c["stable"] = nlohmann::json::array();
    c["divergence_rate_1_s"] = nlohmann::json::array();
    for (const UnbalanceWhirlPoint& pt : piece.points) {
      c["speed_rad_s"].push_back(pt.speed);
      c["speed_hz"].push_back(pt.speed / (2 * M_PI));
      c["stable"].push_back(pt.stable);
      c["divergence_rate_1_s"].push_back(studies::json_number(pt.divergence_rate));
      for (std::size_t d = 0; d < nl.disks.size(); ++d) {
        c["disk." + nl.disks[d] + ".radius_m"].push_back(pt.disk_radius[d]);
        c["disk." + nl.disks[d] + ".phase_rad"].push_back(pt.disk_phase[d]);
      }
      for (std::size_t b = 0; b < nl.bearings.size(); ++b) {
        c["bearing." + nl.bearings[b] + ".force_n"].push_back(pt.bearing_force[b]);
        c["bearing." + nl.bearings[b] + ".max_contact_load_n"].push_back(pt.max_contact_load[b]);
        c["bearing." + nl.bearings[b] + ".max_contact_pressure_pa"].push_back(pt.max_contact_pressure[b]);
      }
    }
    out["pieces"].push_back(p);
  }
  return out;
}

void write_nonlinear_csv(const UnbalanceWhirl& nl, const std::filesystem::path& path) {
  OutputFile file(path);
  std::ostream& csv = file.stream();
  csv << std::setprecision(12) << "piece,direction,speed_rad_s,speed_hz,stable,divergence_rate_1_s";
  for (const std::string& d : nl.disks) csv << ",disk." << d << ".radius_m,disk." << d << ".phase_rad";
  for (const std::string& b : nl.bearings)
    csv << ",bearing." << b << ".force_n,bearing." << b << ".max_contact_load_n,bearing." << b
        << ".max_contact_pressure_pa";
  csv << "\n";
  for (std::size_t k = 0; k < nl.pieces.size(); ++k)
    for (const UnbalanceWhirlPoint& pt : nl.pieces[k].points) {
      csv << k + 1 << "," << (nl.pieces[k].upward ? "up" : "down") << "," << pt.speed << "," << pt.speed / (2 * M_PI)
          << "," << (pt.stable ? 1 : 0) << "," << pt.divergence_rate;
      for (std::size_t d = 0; d < nl.disks.size(); ++d) csv << "," << pt.disk_radius[d] << "," << pt.disk_phase[d];
      for (std::size_t b = 0; b < nl.bearings.size(); ++b)
        csv << "," << pt.bearing_force[b] << "," << pt.max_contact_load[b] << "," << pt.max_contact_pressure[b];
      csv << "\n";
    }
  file.commit();
}

void print_nonlinear(const UnbalanceWhirl& nl) {
  std::cout << "Nonlinear steady state (ball bearings' quasi-static reaction, undamped contacts):\n";
  for (std::size_t k = 0; k < nl.pieces.size(); ++k) {
    const UnbalanceWhirlPiece& p = nl.pieces[k];
    std::ostringstream status;
    if (p.joins >= 0)
      status << ", joins piece " << p.joins + 1;
    else if (p.stopped.empty())
      status << ", reaches the " << (p.upward ? "highest" : "lowest") << " speed";
    else
      status << ", ends early: " << p.stopped;
    std::cout << "  piece " << k + 1 << " (" << (p.upward ? "up" : "down") << " from " << std::fixed
              << std::setprecision(0) << p.start_speed * kRadPerSToRpm << " rpm" << std::defaultfloat
              << "): " << p.points.size() << " points" << status.str() << "\n";
    for (const UnbalanceWhirlFold& f : p.folds)
      std::cout << "    fold at " << std::fixed << std::setprecision(0) << f.speed * kRadPerSToRpm << " rpm ("
                << std::setprecision(1) << f.speed / (2 * M_PI) << " Hz), largest wheel whirl " << std::setprecision(2)
                << f.largest_radius * 1e6 << " um: the speed turns "
                << (f.speed_turns_back ? "back (a slow run-up on this branch jumps off here)"
                                     : "forward (a slow run-down on this branch jumps off here)")
                << std::defaultfloat << "\n";
  }
}

// The resonances of each disk's orbit (major semi-axis) against speed, each peak and half-power point found on the
// response itself (computed anew at any speed), with API RP 684's amplification factor (post/resonance.h).
nlohmann::json resonances_json(const Rotor& rotor, const std::vector<double>& speeds,
                               const std::vector<std::vector<double>>& cols, std::ostream& listing) {
  nlohmann::json out = nlohmann::json::array();
  bool increasing = speeds.size() >= 3;
  for (std::size_t i = 1; i < speeds.size(); ++i) increasing = increasing && speeds[i] > speeds[i - 1];
  if (!increasing) {
    listing << "Resonances: not sought (they need at least three increasing speeds)\n";
    return out;
  }
  listing << "Resonances (peaks of the orbits' major semi-axes, half-power points at 1/sqrt(2) of the peak, "
             "amplification factor AF = speed / band, API RP 684):\n";
  std::size_t found = 0;
  for (std::size_t d = 0; d < rotor.disks.size(); ++d) {
    const RigidDisk& disk = rotor.disks[d];
    const int ix = rotor.dof(disk.node, kX), iy = rotor.dof(disk.node, kY);
    auto orbit_at = [&](double w) {
      const SteadyResponse r = unbalance_response(rotor, w);
      return major_semi_axis(r.q(ix), r.q(iy));
    };
    const std::string column = "disk." + disk.name + ".major_semi_axis_m";
    for (const post::Resonance& r : post::find_resonances(speeds, cols[2 + 4 * d + 2], orbit_at)) {
      out.push_back({{"column", column},
                     {"speed_rad_s", r.speed},
                     {"speed_hz", r.speed / (2 * M_PI)},
                     {"speed_rpm", r.speed * kRadPerSToRpm},
                     {"peak", r.peak},
                     {"lower_speed_hz", studies::json_number(r.lower / (2 * M_PI))},
                     {"upper_speed_hz", studies::json_number(r.upper / (2 * M_PI))},
                     {"amplification_factor", studies::json_number(r.amplification_factor)}});
      ++found;
      listing << "  disk " << disk.name << ": " << std::fixed << std::setprecision(1) << r.speed / (2 * M_PI)
              << " Hz (" << std::setprecision(0) << r.speed * kRadPerSToRpm << " rpm), " << std::setprecision(2)
              << r.peak * 1e6 << " um, ";
      if (std::isfinite(r.amplification_factor))
        listing << "half-power band " << std::setprecision(1) << r.lower / (2 * M_PI) << "-" << r.upper / (2 * M_PI)
                << " Hz, AF " << std::setprecision(r.amplification_factor < 100 ? 2 : 0) << r.amplification_factor
                << (r.amplification_factor < 2.5 ? " (critically damped by API 617's measure, AF < 2.5)" : "");
      else
        listing << "no AF: the response does not fall to 1/sqrt(2) of the peak "
                << (std::isfinite(r.lower) ? "above" : "below") << " it within the speeds";
      listing << std::defaultfloat << "\n";
    }
  }
  if (found == 0) listing << "  none within the speeds\n";
  return out;
}

}  // namespace

int run_response_command(const ResponseCommandOptions& options) {
  const MachineSpec spec = load_model(options.model_file, options.overrides);
  require_linear_supports(spec, true);
  for (const BearingSpec& b : spec.bearings)
    if (b.type == BearingType::FloatingRing)
      throw ModelError(spec.source.string() + ": bearings." + b.name + ": floating-ring bearings are in the linear "
                       "analyses of `turbodyn modal` only; the unbalance response takes linear and ball bearings");
  Rotor rotor = build_rotor(spec);
  const Rotor bare = rotor;  // the nonlinear response takes the ball bearings themselves
  // Ball bearings: their quasi-static linearisation at every speed, as in `turbodyn modal` (docs/ball-bearing.md).
  add_ball_bearing_linearisations(spec, rotor);
  const std::vector<double> speeds = analysis_speeds(spec, options.speeds, std::max(spec.modal.n_speeds, 201));
  std::filesystem::create_directories(options.output_dir);

  // Columns: speed, then per disk |x|, |y|, major semi-axis, phase of x; per bearing |Fx|, |Fy|.
  std::vector<std::string> names{"speed_rad_s", "speed_hz"};
  for (const RigidDisk& d : rotor.disks)
    for (const char* s : {".x_amplitude_m", ".y_amplitude_m", ".major_semi_axis_m", ".x_phase_rad"})
      names.push_back("disk." + d.name + s);
  for (const LinearBearing& b : rotor.bearings)
    for (const char* s : {".fx_amplitude_n", ".fy_amplitude_n"}) names.push_back("bearing." + b.name + s);
  std::vector<std::vector<double>> cols(names.size());
  for (double w : speeds) {
    SteadyResponse r;
    try {
      r = unbalance_response(rotor, w);
    } catch (const QuasiStaticError& e) {
      throw ModelError(spec.source.string() + ": a ball bearing's linearisation failed: " + e.what());
    }
    std::size_t c = 0;
    cols[c++].push_back(w);
    cols[c++].push_back(w / (2 * M_PI));
    for (const RigidDisk& d : rotor.disks) {
      const std::complex<double> x = r.q(rotor.dof(d.node, kX)), y = r.q(rotor.dof(d.node, kY));
      cols[c++].push_back(std::abs(x));
      cols[c++].push_back(std::abs(y));
      cols[c++].push_back(major_semi_axis(x, y));
      cols[c++].push_back(std::arg(x));
    }
    for (std::size_t b = 0; b < rotor.bearings.size(); ++b) {
      cols[c++].push_back(std::abs(r.bearing_fx[b]));
      cols[c++].push_back(std::abs(r.bearing_fy[b]));
    }
  }
  {
    OutputFile file(options.output_dir / "response.csv");
    std::ostream& csv = file.stream();
    csv << std::setprecision(12);
    for (std::size_t c = 0; c < names.size(); ++c) csv << (c ? "," : "") << names[c];
    csv << "\n";
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      for (std::size_t c = 0; c < names.size(); ++c) csv << (c ? "," : "") << cols[c][i];
      csv << "\n";
    }
    file.commit();
  }
  nlohmann::json j = result_header(spec, options.overrides);
  for (std::size_t c = 0; c < names.size(); ++c) j["columns"][names[c]] = cols[c];
  std::ostringstream resonance_listing;
  try {
    j["resonances"] = resonances_json(rotor, speeds, cols, resonance_listing);
  } catch (const QuasiStaticError& e) {
    throw ModelError(spec.source.string() + ": a ball bearing's linearisation failed: " + e.what());
  }
  UnbalanceWhirl nl;
  std::vector<std::string> warnings;
  if (options.nonlinear) {
    UnbalanceWhirlOptions no;
    no.end_speed = speeds.back();
    no.start_speed = speeds.front() > 0.0 ? speeds.front() : std::max(speeds.size() > 1 ? speeds[1] : 0.0,
                                                                       0.01 * speeds.back());
    if (!(no.end_speed > no.start_speed))
      throw ModelError("--speeds '" + options.speeds + "': --nonlinear needs a range of speeds above zero "
                       "(--speeds START:END:COUNT)");
    try {
      nl = nonlinear_unbalance_response(spec, bare, no);
    } catch (const QuasiStaticError& e) {
      throw ModelError(spec.source.string() + ": --nonlinear: a ball bearing's equilibrium failed: " + e.what());
    } catch (const std::runtime_error& e) {
      throw ModelError(spec.source.string() + ": --nonlinear: " + e.what());
    }
    j["nonlinear"] = nonlinear_json(nl);
    // Where the steady whirl loads a ball contact beyond ISO 76's static limit (a real bearing brinells there): per
    // bearing, the lowest speed of a steady state over it and the largest pressure, over every piece.
    for (std::size_t b = 0; b < nl.bearings.size(); ++b) {
      double lowest = std::numeric_limits<double>::infinity(), top = 0.0, top_speed = 0.0;
      for (const UnbalanceWhirlPiece& piece : nl.pieces)
        for (const UnbalanceWhirlPoint& pt : piece.points) {
          const double p = pt.max_contact_pressure[b];
          if (p > kStaticContactPressureLimit) lowest = std::min(lowest, pt.speed);
          if (p > top) {
            top = p;
            top_speed = pt.speed;
          }
        }
      if (!std::isfinite(lowest)) continue;
      std::ostringstream os;
      os << std::fixed << std::setprecision(0) << "the nonlinear response passes the contact pressure's limit of "
         << kStaticContactPressureLimit * 1e-6 << " MPa in bearings." << nl.bearings[b] << " from "
         << lowest * kRadPerSToRpm << " rpm (the lowest speed of such a steady state), up to " << top * 1e-6
         << " MPa at " << top_speed * kRadPerSToRpm << " rpm, " << MaxContactPressureProbe().limit_note;
      warnings.push_back(os.str());
    }
    j["nonlinear"]["warnings"] = warnings;
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
    write_nonlinear_csv(nl, options.output_dir / "response_nonlinear.csv");
  }
  write_output_file(options.output_dir / "response.json", j.dump(1) + "\n");
  if (options.plots) {
    plot::LineChart chart;
    chart.title = "Steady-state unbalance response: " + spec.name;
    chart.xlabel = "rotor speed f_d [Hz]";
    chart.ylabel = "1x orbit major semi-axis [µm]";
    chart.logy = true;
    static const char* const colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
    std::size_t c = 2;
    for (std::size_t k = 0; k < rotor.disks.size(); ++k) {
      const RigidDisk& d = rotor.disks[k];
      std::vector<double> um = cols[c + 2];
      for (double& v : um) v *= 1e6;
      const std::string colour = colours[k % 4];
      if (!options.nonlinear) {
        chart.series.push_back({"disk " + d.name, cols[1], um, plot::Series::Style::Lines, colour, 1.5});
      } else {
        chart.series.push_back({"disk " + d.name + ", linearised", cols[1], um, plot::Series::Style::Dashed, colour,
                                1.0});
        // Each piece in runs of equal stability: stable steady states bold, unstable ones (between two folds)
        // thin; neighbouring runs share their end point.
        bool labelled[2] = {false, false};
        for (const UnbalanceWhirlPiece& piece : nl.pieces) {
          const std::vector<UnbalanceWhirlPoint>& pts = piece.points;
          for (std::size_t i = 0; i < pts.size();) {
            std::size_t j = i;
            while (j + 1 < pts.size() && pts[j + 1].stable == pts[i].stable) ++j;
            std::vector<double> hz, r;
            for (std::size_t m = i; m <= std::min(j + 1, pts.size() - 1); ++m) {
              hz.push_back(pts[m].speed / (2 * M_PI));
              r.push_back(pts[m].disk_radius[k] * 1e6);
            }
            const int u = pts[i].stable ? 0 : 1;
            chart.series.push_back({labelled[u] ? "" : "disk " + d.name + (u ? ", nonlinear, unstable" : ", nonlinear"),
                                    hz, r, plot::Series::Style::Lines, colour, u ? 0.5 : 1.5});
            labelled[u] = true;
            i = j + 1;
          }
        }
      }
      c += 4;
    }
    if (options.nonlinear) {
      std::vector<double> hz, r;
      for (const UnbalanceWhirlPiece& p : nl.pieces)
        for (const UnbalanceWhirlFold& f : p.folds) {
          hz.push_back(f.speed / (2 * M_PI));
          r.push_back(f.largest_radius * 1e6);
        }
      if (!hz.empty()) chart.series.push_back({"folds (jump speeds)", hz, r, plot::Series::Style::Points, "black", 1.5});
    }
    // The resonances' speeds as markers, on this and on the phase picture.
    for (const nlohmann::json& r : j["resonances"]) chart.vertical_lines.push_back(r["speed_hz"].get<double>());
    plot::render_png(chart, options.output_dir / "response.png");
    // The other half of the Bode plot: each wheel's phase lag of x behind the rotor's angle (x = |x| cos(Omega t +
    // phase), lag = -phase, unwrapped from the lowest speed; none where the wheel does not move, at rest), which turns
    // by about 180 degrees through each lightly damped resonance.
    plot::LineChart phase;
    phase.title = "Steady-state unbalance response, phase: " + spec.name;
    phase.xlabel = "rotor speed f_d [Hz]";
    phase.ylabel = "phase lag of x behind the rotor angle [deg]";
    phase.vertical_lines = chart.vertical_lines;
    for (std::size_t k = 0; k < rotor.disks.size(); ++k) {
      std::vector<double> lag;
      double last = std::nan("");
      for (std::size_t i = 0; i < speeds.size(); ++i) {
        if (!(cols[2 + 4 * k][i] > 0.0)) {  // |x| = 0: no phase
          lag.push_back(std::nan(""));
          continue;
        }
        double v = -cols[2 + 4 * k + 3][i] * 180.0 / M_PI;
        if (std::isfinite(last)) v -= 360.0 * std::round((v - last) / 360.0);
        lag.push_back(last = v);
      }
      phase.series.push_back({"disk " + rotor.disks[k].name, cols[1], lag, plot::Series::Style::Lines,
                              colours[k % 4], 1.5});
    }
    plot::render_png(phase, options.output_dir / "response_phase.png");
  }
  std::vector<std::string> files{"response.json", "response.csv"};
  if (options.nonlinear) files.push_back("response_nonlinear.csv");
  post::write_response_report(options.output_dir, j,
                              {command_line(), options.plots ? std::vector<std::string>{"response.png",
                                                                                        "response_phase.png"}
                                                             : std::vector<std::string>{},
                               files, warnings});
  std::cout << resonance_listing.str();
  if (options.nonlinear) print_nonlinear(nl);
  std::cout << "Wrote " << (options.output_dir / "response.csv").string() << ", response.json, report.html"
            << (options.plots ? ", response.png, response_phase.png" : "")
            << (options.nonlinear ? ", response_nonlinear.csv" : "")
            << " (" << speeds.size() << " speeds)\n";
  // Part of the range without a steady state within the model: written so far, exit code 3.
  if (options.nonlinear && !nl.covers_range) {
    std::cerr << "turbodyn response: the nonlinear response leaves part of the speed range without a steady state "
                 "within the model (see the pieces above); written so far\n";
    return 3;
  }
  return 0;
}

}  // namespace turbodyn::app

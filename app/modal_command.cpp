#include "app/modal_command.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/elements/floating_ring_steady.h"
#include "model/engine/backbone.h"
#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "studies/table.h"
#include "post/plot.h"
#include "post/plot_style.h"
#include "post/report.h"
#include "app/command_line.h"
#include "model/rotor/rotor.h"
#include "model/spec/limits.h"
#include "model/spec/units.h"
#include "model/spec/constants.h"
#include "model/spec/text.h"

namespace turbodyn::app {
namespace {

// Where a run-up at the model's ramp (speed.start to speed.end in speed.duration) peaks at each 1x critical with an
// amplification factor: the mode's passage (ramp_passage) with the detuning swept at (1 - s) times the ramp, so the
// rotor speed at the peak is the critical's times 1 + (W / omega_n - 1) / (1 - s). Nothing for a speed table.
void add_runup_passages(const SpeedProfile& speed, Campbell& campbell) {
  if (speed.kind != SpeedProfile::Kind::Ramp || !(speed.duration > 0.0) || !(speed.end > speed.start)) return;
  const double rate = (speed.end - speed.start) / speed.duration;  // rad/s^2
  for (CriticalSpeed& c : campbell.critical) {
    if (c.order != 1.0 || !std::isfinite(c.amplification_factor) || c.speed < speed.start || c.speed > speed.end)
      continue;
    const double detuning = 1.0 - c.branch_slope, omega = 2.0 * M_PI * c.frequency;
    const double lambda = detuning * rate / (omega * omega);
    // ramp_passage's range: a ramp slow against the mode and a mode damped below half of critical (an AF of 2.5 or
    // more allows more only on a steeply falling branch)
    if (!(detuning > 0.0 && lambda < 0.1 && c.damping_ratio < 0.5)) continue;
    const RampPassage p = ramp_passage(lambda, c.damping_ratio);
    c.runup_peak_speed = c.speed * (1.0 + (p.speed_ratio - 1.0) / detuning);
    c.runup_peak_fraction = p.peak_fraction;
  }
}

// ", AF 278 (s = 0.073)": the amplification factor a steady response to the critical's order would show, from its
// damping ratio and branch slope (CriticalSpeed), or API 617's "critically damped" below 2.5; nothing if unstable.
std::string amplification_note(const CriticalSpeed& c) {
  if (c.critically_damped) return ", critically damped (AF < 2.5 by API 617's measure)";
  if (!std::isfinite(c.amplification_factor)) return "";
  std::ostringstream s;
  s << std::fixed << ", AF " << std::setprecision(c.amplification_factor < 100 ? 1 : 0) << c.amplification_factor
    << " (s = " << std::setprecision(3) << c.branch_slope << ")";
  if (std::isfinite(c.runup_peak_speed))
    s << "; the model's ramp peaks at " << std::setprecision(0) << c.runup_peak_speed * kRadPerSToRpm << " rpm ("
      << std::showpos << std::setprecision(1) << 100.0 * (c.runup_peak_speed / c.speed - 1.0) << std::noshowpos
      << " %) with " << std::setprecision(3) << c.runup_peak_fraction << " of the steady peak";
  return s.str();
}

// One value of a list option (`option` "--speeds" and so on), checked for its dimension and plausible size.
double list_value(const std::string& text, const std::string& option, const std::string& whole, const Dimension& d) {
  double v = 0.0;
  try {
    v = parse_quantity(trim_blanks(text), d);
  } catch (const UnitError& e) {
    throw ModelError(option + " '" + whole + "': " + e.what());
  }
  if (const std::string why = limits::implausible(v, d); !why.empty())
    throw ModelError(option + " '" + whole + "': " + why);
  return v;
}

// A bare number among values of which the last written with a unit has one takes that unit ("20000:150000 rpm:14",
// "30000, 95000 rpm"); without any unit the values are in SI units (rad/s, m).
std::vector<double> list_values(const std::vector<std::string>& items, const std::string& option,
                                const std::string& text, const Dimension& d) {
  std::vector<std::optional<std::string>> units;
  std::string unit;
  for (const std::string& it : items) {
    units.push_back(quantity_unit(it));
    if (units.back() && !units.back()->empty()) unit = *units.back();
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const bool bare = !unit.empty() && units[i] && units[i]->empty();
    out.push_back(list_value(bare ? trim_blanks(items[i]) + " " + unit : items[i], option, text, d));
  }
  return out;
}

nlohmann::json complex_list(const Eigen::VectorXcd& v, const Rotor& rotor, Dof d) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t n = 0; n < rotor.node_z.size(); ++n) {
    const std::complex<double> c = v(rotor.dof(static_cast<int>(n), d));
    out.push_back({c.real(), c.imag()});
  }
  return out;
}

// Signed orbit size along the rotor: the major semi-axis of each node's orbit, negative where the node moves in
// antiphase to the node of largest motion.
std::vector<double> signed_major_axis(const Rotor& rotor, const Eigen::VectorXcd& shape) {
  const int n_nodes = static_cast<int>(rotor.node_z.size());
  int ref = 0;
  double best = -1.0;
  for (int n = 0; n < n_nodes; ++n) {
    const double s = std::norm(shape(rotor.dof(n, kX))) + std::norm(shape(rotor.dof(n, kY)));
    if (s > best) {
      best = s;
      ref = n;
    }
  }
  const std::complex<double> xr = shape(rotor.dof(ref, kX)), yr = shape(rotor.dof(ref, kY));
  std::vector<double> out(n_nodes);
  for (int n = 0; n < n_nodes; ++n) {
    const std::complex<double> a = shape(rotor.dof(n, kX)), b = shape(rotor.dof(n, kY));
    // Major semi-axis of the ellipse Re(a e^{iwt}), Re(b e^{iwt}).
    const double p = std::norm(a) + std::norm(b);
    const double q = std::abs(a * a + b * b);
    const double major = std::sqrt(0.5 * (p + q));
    const double phase = (a * std::conj(xr) + b * std::conj(yr)).real();
    out[n] = phase < 0 ? -major : major;
  }
  const double scale = *std::max_element(out.begin(), out.end(), [](double x, double y) {
    return std::abs(x) < std::abs(y);
  });
  if (scale != 0.0)
    for (double& v : out) v /= std::abs(scale);
  return out;
}

std::string speed_tag(double speed) {
  std::ostringstream os;
  os << std::llround(speed * kRadPerSToRpm) << "rpm";
  return os.str();
}

// Damping ratio of each lateral mode below fmax against speed: the stability of the whirl modes (floating rings:
// negative for the films' whirl).
void write_damping_picture(const MachineSpec& spec, const Campbell& campbell, double fmax,
                           const std::filesystem::path& png) {
  using plot::Series;
  plot::LineChart chart;
  chart.title = "Damping ratios of the modes below " + std::to_string(static_cast<int>(fmax)) + " Hz: " + spec.name;
  chart.xlabel = "rotor speed [rpm]";
  chart.ylabel = "damping ratio zeta [-] (< 0: unstable)";
  Series fw{"forward whirl", {}, {}, Series::Style::Points, "#1f77b4", 1.2};
  Series bw{"backward whirl", {}, {}, Series::Style::Points, "#d62728", 1.2};
  Series other{"mixed / planar", {}, {}, Series::Style::Points, "#7f7f7f", 1.2};
  for (const ModalResult& r : campbell.points)
    for (const Mode& m : r.modes) {
      if (m.frequency > fmax || m.whirl == Whirl::Torsional) continue;
      Series& s = m.whirl == Whirl::Forward ? fw : m.whirl == Whirl::Backward ? bw : other;
      s.x.push_back(r.speed * kRadPerSToRpm);
      s.y.push_back(m.damping_ratio);
    }
  const double smin = campbell.points.front().speed, smax = campbell.points.back().speed;
  chart.series.push_back(Series{"zeta = 0", {smin * kRadPerSToRpm, smax * kRadPerSToRpm}, {0.0, 0.0},
                                Series::Style::Lines, "black", 1.0});
  for (Series* s : {&fw, &bw, &other})
    if (!s->x.empty()) chart.series.push_back(*s);
  chart.xrange = std::make_pair(smin * kRadPerSToRpm, smax * kRadPerSToRpm);
  chart.legend_position = "bottom right";
  plot::render_png(chart, png);
}

void write_campbell_picture(const MachineSpec& spec, const Campbell& campbell, const std::vector<double>& orders,
                            double fmax, const std::filesystem::path& png) {
  using plot::Series;
  plot::LineChart chart;
  chart.title = "Campbell diagram: " + spec.name;
  chart.xlabel = "rotor speed [rpm]";
  chart.ylabel = "damped natural frequency [Hz]";
  Series fw{"forward whirl", {}, {}, Series::Style::Points, plot::style::kForward, 1.2};
  Series bw{"backward whirl", {}, {}, Series::Style::Points, plot::style::kBackward, 1.2};
  Series other{"mixed / planar", {}, {}, Series::Style::Points, plot::style::kMixedWhirl, 1.2};
  Series tor{"torsional", {}, {}, Series::Style::Points, plot::style::kTorsional, 1.2};
  for (const ModalResult& r : campbell.points) {
    for (const Mode& m : r.modes) {
      if (m.frequency > fmax) continue;
      Series& s = m.whirl == Whirl::Forward ? fw : m.whirl == Whirl::Backward ? bw : m.whirl == Whirl::Torsional ? tor : other;
      s.x.push_back(r.speed * kRadPerSToRpm);
      s.y.push_back(m.frequency);
    }
  }
  const double smin = campbell.points.front().speed, smax = campbell.points.back().speed;
  // 1x solid black, 0.5x dashed grey (as on the spectrograms), other orders dashed in colours of their own.
  const char* other_colors[] = {"#2ca02c", "#8c564b", "#e377c2", "#bcbd22"};
  int oi = 0;
  for (double order : orders) {
    std::ostringstream label;
    label << order << "x";
    const bool one = order == 1.0, half = order == 0.5;
    Series line{label.str(), {smin * kRadPerSToRpm, smax * kRadPerSToRpm},
                {order * smin / (2 * M_PI), order * smax / (2 * M_PI)},
                one ? Series::Style::Lines : Series::Style::Dashed,
                one ? plot::style::kOrder1x : half ? plot::style::kOrderHalf : other_colors[oi++ % 4], 1.5};
    chart.series.push_back(line);
  }
  for (Series* s : {&fw, &bw, &other, &tor})
    if (!s->x.empty()) chart.series.push_back(*s);
  Series crit{"critical speeds", {}, {}, Series::Style::Points, plot::style::kCriticalSpeed, 2.5};
  for (const CriticalSpeed& c : campbell.critical) {
    if (c.frequency > fmax) continue;
    crit.x.push_back(c.speed * kRadPerSToRpm);
    crit.y.push_back(c.frequency);
  }
  if (!crit.x.empty()) chart.series.push_back(crit);
  chart.xrange = std::make_pair(smin * kRadPerSToRpm, smax * kRadPerSToRpm);
  chart.legend_position = "outside right top";  // not over the branches at top speed
  chart.yrange = std::make_pair(0.0, fmax);
  plot::render_png(chart, png);
}

void write_mode_shape_picture(const MachineSpec& spec, const Rotor& rotor, const ModalResult& r,
                              const std::filesystem::path& png) {
  using plot::Series;
  plot::LineChart chart;
  std::ostringstream title;
  title << "Mode shapes of " << spec.name << " at " << std::llround(r.speed * kRadPerSToRpm) << " rpm";
  chart.title = title.str();
  chart.xlabel = "axial position z [mm]";
  chart.ylabel = "orbit major semi-axis (signed, normalised) [-]";
  std::vector<double> z_mm;
  for (double z : rotor.node_z) z_mm.push_back(z * 1e3);
  const int shown = std::min<int>(6, static_cast<int>(r.modes.size()));
  for (int i = 0; i < shown; ++i) {
    const Mode& m = r.modes[i];
    std::ostringstream label;
    label << "mode " << i + 1 << ": " << std::fixed << std::setprecision(1) << m.frequency << " Hz, "
          << to_string(m.whirl) << ", zeta " << std::setprecision(3) << m.damping_ratio;
    chart.series.push_back(Series{label.str(), z_mm, signed_major_axis(rotor, m.shape), Series::Style::LinesPoints, "", 1.5});
  }
  for (const RigidDisk& d : rotor.disks) {
    chart.vertical_lines.push_back(rotor.node_z[d.node] * 1e3);
    chart.annotations.push_back({rotor.node_z[d.node] * 1e3, 1.15, "disk " + d.name});
  }
  for (const LinearBearing& b : rotor.bearings) {
    chart.vertical_lines.push_back(rotor.node_z[b.node] * 1e3);
    chart.annotations.push_back({rotor.node_z[b.node] * 1e3, 1.15, "bearing " + b.name});
  }
  chart.yrange = std::make_pair(-1.25, 1.25);
  chart.legend_position = "below";
  plot::render_png(chart, png, plot::Size{1000, 800});
}

// The places whose whirl radius may be the amplitude, node and label: --amplitude-at "disks.NAME" or
// "bearings.NAME", or without it every disk (each branch then takes the one that moves most in its mode).
std::vector<std::pair<int, std::string>> amplitude_references(const MachineSpec& spec, const Rotor& rotor,
                                                              const std::string& at) {
  const double length = spec.shaft_length();
  std::vector<std::pair<int, std::string>> out;
  if (at.empty()) {
    for (const DiskSpec& d : spec.disks)
      out.emplace_back(rotor.node_at(std::clamp(d.z, 0.0, length)), "disks." + d.name);
    if (out.empty())
      throw ModelError(spec.source.string() + ": --amplitudes: the model has no disk; say where the amplitude is "
                       "measured with --amplitude-at bearings.NAME");
    return out;
  }
  for (const DiskSpec& d : spec.disks)
    if (at == "disks." + d.name) return {{rotor.node_at(std::clamp(d.z, 0.0, length)), at}};
  for (const BearingSpec& b : spec.bearings)
    if (at == "bearings." + b.name) return {{rotor.node_at(std::clamp(b.z, 0.0, length)), at}};
  std::string names;
  for (const DiskSpec& d : spec.disks) names += (names.empty() ? "" : ", ") + ("disks." + d.name);
  for (const BearingSpec& b : spec.bearings) names += (names.empty() ? "" : ", ") + ("bearings." + b.name);
  throw ModelError(spec.source.string() + ": --amplitude-at '" + at + "': no such disk or bearing (the model has " +
                   names + ")");
}

// modal.json's "backbones" (docs/output-format.md).
nlohmann::json backbone_json(const std::vector<Backbone>& backbones, const std::map<int, std::string>& place) {
  nlohmann::json bbs = nlohmann::json::array();
  for (const Backbone& b : backbones) {
    nlohmann::json pts = nlohmann::json::array();
    for (const BackbonePoint& p : b.points) {
      nlohmann::json brg = nlohmann::json::array();
      for (const BackboneBearing& x : p.bearings)
        brg.push_back({{"name", x.name},
                       {"displacement_m", x.displacement},
                       {"tilt_rad", x.tilt},
                       {"force_n", x.force},
                       {"moment_nm", x.moment},
                       {"max_contact_load_n", x.max_contact_load},
                       {"max_contact_pressure_pa", x.max_contact_pressure}});
      pts.push_back({{"amplitude_m", p.amplitude},
                     {"speed_rad_s", p.speed},
                     {"speed_rpm", p.speed * kRadPerSToRpm},
                     {"frequency_hz", p.speed / (2 * M_PI)},
                     {"bearings", brg}});
    }
    bbs.push_back({{"branch", b.branch},
                   {"amplitude_at", place.at(b.reference_node)},
                   {"linear_speed_rad_s", b.linear_speed},
                   {"linear_speed_rpm", b.linear_speed * kRadPerSToRpm},
                   {"points", pts},
                   {"complete", b.stopped.empty()},
                   {"stopped", b.stopped}});
  }
  return {{"branches", bbs}};
}

// backbone.csv and the listing of the critical speeds at an amplitude.
void write_backbone_table(const std::vector<Backbone>& backbones, const std::map<int, std::string>& place,
                          const std::filesystem::path& path) {
  OutputFile file(path);
  std::ostream& csv = file.stream();
  csv << "branch,amplitude_at,amplitude_m,speed_rad_s,speed_rpm,frequency_hz,bearing,displacement_m,tilt_rad,"
         "force_n,moment_nm,max_contact_load_n,max_contact_pressure_pa\n"
      << std::setprecision(10);
  for (const Backbone& b : backbones)
    for (const BackbonePoint& p : b.points)
      for (const BackboneBearing& x : p.bearings)
        csv << b.branch + 1 << ',' << place.at(b.reference_node) << ',' << p.amplitude << ',' << p.speed << ','
            << p.speed * kRadPerSToRpm << ',' << p.speed / (2 * M_PI) << ',' << x.name << ',' << x.displacement << ','
            << x.tilt << ',' << x.force << ',' << x.moment << ',' << x.max_contact_load << ','
            << x.max_contact_pressure << '\n';
  file.commit();
  std::cout << "Forward 1x critical speeds at a whirl amplitude:\n";
  for (const Backbone& b : backbones) {
    std::cout << "  branch " << b.branch + 1 << " (linearised: " << std::fixed << std::setprecision(0)
              << b.linear_speed * kRadPerSToRpm << " rpm), amplitude at " << place.at(b.reference_node) << "\n";
    for (const BackbonePoint& p : b.points) {
      std::cout << "    " << std::setprecision(3) << std::setw(10) << p.amplitude * 1e6 << " um: " << std::setw(7)
                << std::setprecision(0) << p.speed * kRadPerSToRpm << " rpm (" << std::setprecision(1)
                << p.speed / (2 * M_PI) << " Hz)";
      for (const BackboneBearing& x : p.bearings)
        std::cout << "  " << x.name << " " << std::setprecision(2) << std::abs(x.displacement) * 1e6 << " um "
                  << std::setprecision(0) << std::abs(x.force) << " N";
      std::cout << "\n";
    }
    if (!b.stopped.empty()) std::cout << "    ends: " << b.stopped << "\n";
  }
  std::cout << std::defaultfloat;
}

// Critical speed against amplitude, one line per branch, its linearised critical speed marked at zero amplitude.
void write_backbone_picture(const MachineSpec& spec, const std::vector<Backbone>& backbones,
                            const std::map<int, std::string>& place, const std::filesystem::path& png) {
  using plot::Series;
  plot::LineChart chart;
  chart.title = "Forward 1x critical speeds at an amplitude: " + spec.name;
  chart.xlabel = "whirl amplitude [um] at each branch's place";
  chart.ylabel = "critical speed [rpm]";
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};
  Series lin{"linearised (modal)", {}, {}, Series::Style::Points, plot::style::kCriticalSpeed, 2.5};
  for (const Backbone& b : backbones) {
    Series s{"branch " + std::to_string(b.branch + 1) + " at " + place.at(b.reference_node), {}, {},
             Series::Style::LinesPoints, colors[b.branch % 6], 1.5};
    for (const BackbonePoint& p : b.points) {
      s.x.push_back(p.amplitude * 1e6);
      s.y.push_back(p.speed * kRadPerSToRpm);
    }
    if (s.x.empty()) continue;
    chart.series.push_back(s);
    lin.x.push_back(0.0);
    lin.y.push_back(b.linear_speed * kRadPerSToRpm);
  }
  if (!lin.x.empty()) chart.series.push_back(lin);
  chart.legend_position = "bottom right";
  plot::render_png(chart, png);
}

}  // namespace

void require_linear_supports(const MachineSpec& spec, bool nonlinear_bearings) {
  for (const BearingSpec& b : spec.bearings)
    if (b.type != BearingType::Linear &&
        !(nonlinear_bearings && (b.type == BearingType::Ball || b.type == BearingType::FloatingRing)))
      throw ModelError(spec.source.string() + ": bearings." + b.name + ": a " + to_string(b.type) +
                       " bearing is nonlinear; the linear analyses (modal, response) need linear bearings "
                       "(linearised coefficients, e.g. from `turbodyn journal`, as type = \"linear\")");
  for (const BearingSpec& b : spec.bearings)
    if (b.damper.enabled)
      throw ModelError(spec.source.string() + ": bearings." + b.name +
                       ".damper: squeeze-film dampers are nonlinear; the linear analyses (modal, response) do not "
                       "include them");
  for (const BearingSpec& b : spec.bearings)
    if (b.pedestal_mass > 0.0)
      throw ModelError(spec.source.string() + ": bearings." + b.name +
                       ".pedestal_mass: pedestal masses are part of the run-up model only; the linear analyses "
                       "(modal, response) do not include them yet, so they would give wrong answers");
}

std::vector<double> parse_quantity_list(const std::string& text, const std::string& option, const Dimension& d,
                                        const std::string& noun, long max_count) {
  const std::string what = option + " '" + text + "': ";
  std::vector<double> out;
  if (text.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::stringstream ss(text);
    for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
    if (parts.size() != 3) throw ModelError(what + "expected START:END:COUNT");
    const std::vector<double> ab = list_values({parts[0], parts[1]}, option, text, d);
    const double a = ab[0], b = ab[1];
    const std::string count = trim_blanks(parts[2]);
    long n = 0;
    const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), n);
    if (count.empty() || ec != std::errc() || end != count.data() + count.size() || n < 2 || n > max_count)
      throw ModelError(what + "COUNT must be a whole number from 2 to " + std::to_string(max_count));
    if (!(b > a)) throw ModelError(what + "END must be larger than START");
    for (long i = 0; i < n; ++i) out.push_back(a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1));
  } else {
    std::vector<std::string> items;
    std::stringstream ss(text);
    for (std::string p; std::getline(ss, p, ',');) items.push_back(p);
    out = list_values(items, option, text, d);
    for (std::size_t i = 1; i < out.size(); ++i)
      if (!(out[i] > out[i - 1])) throw ModelError(what + noun + " must be increasing");
  }
  for (double v : out)
    if (v < 0) throw ModelError(what + noun + " must not be negative");
  if (out.size() > static_cast<std::size_t>(max_count))
    throw ModelError(what + "more than " + std::to_string(max_count) + " " + noun);
  if (out.empty()) throw ModelError(option + " is empty");
  return out;
}

std::vector<double> parse_speed_list(const std::string& text) {
  return parse_quantity_list(text, "--speeds", dim::angular_speed, "speeds", limits::kMaxModalSpeeds);
}

std::vector<double> analysis_speeds(const MachineSpec& spec, const std::string& option, int count) {
  if (!option.empty()) return parse_speed_list(option);
  const double smax = spec.modal.speed_max > 0 ? spec.modal.speed_max : spec.speed.end;
  if (!(smax > spec.modal.speed_min))
    throw ModelError(spec.source.string() +
                     ": no speed range: set modal.speed_max (or speed.end) in the model file, or pass --speeds");
  std::vector<double> speeds;
  for (int i = 0; i < count; ++i) speeds.push_back(spec.modal.speed_min + (smax - spec.modal.speed_min) * i / (count - 1));
  return speeds;
}

int run_modal_command(const ModalCommandOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const MachineSpec spec = load_model(options.model_file, options.overrides);
  require_linear_supports(spec, true);
  Rotor rotor = build_rotor(spec);
  // Ball bearings: their quasi-static linearisation at every speed (docs/ball-bearing.md).
  add_ball_bearing_linearisations(spec, rotor);

  const std::vector<double> speeds = analysis_speeds(spec, options.speeds, spec.modal.n_speeds);
  // Floating rings: their films linearised at steady operating points under the rotor's weight, tabulated over the
  // speed range (kRingTableSpeeds, from a fiftieth of the top speed: films at rest carry nothing) and interpolated
  // (docs/thermal-films.md, "Linear analyses").
  constexpr int kRingTableSpeeds = 25;
  {
    const double top = speeds.back(), low = std::max(speeds.front(), top / 50.0);
    std::vector<double> table;
    for (int i = 0; i < kRingTableSpeeds; ++i) table.push_back(low + (top - low) * i / (kRingTableSpeeds - 1));
    if (top > 0.0) add_floating_ring_linearisations(spec, rotor, table);
  }
  if (options.amplitudes.empty() && !options.amplitude_at.empty())
    throw ModelError("--amplitude-at '" + options.amplitude_at + "': says where the amplitudes of --amplitudes are "
                     "measured; give --amplitudes too");
  if (!options.amplitudes.empty())
    for (const BearingSpec& b : spec.bearings)
      if (b.type != BearingType::Ball && b.type != BearingType::Linear)
        throw ModelError(spec.source.string() + ": --amplitudes: bearings." + b.name + ": the critical speeds at an "
                         "amplitude take ball and linear bearings only, not " + to_string(b.type) + " bearings");
  ModalOptions mo;
  mo.n_modes = options.n_modes > 0 ? options.n_modes : spec.modal.n_modes;
  mo.frame = options.frame;
  mo.torsion = spec.modal.torsion;
  Campbell campbell;
  std::vector<double> shape_speeds = spec.modal.mode_shape_speeds;
  if (shape_speeds.empty()) shape_speeds = {speeds.front(), speeds.back()};
  std::vector<ModalResult> shapes;
  try {
    campbell = campbell_diagram(rotor, speeds, spec.modal.orders, mo);
    for (double s : shape_speeds) shapes.push_back(modal_analysis(rotor, s, mo));
  } catch (const QuasiStaticError& e) {
    throw ModelError(spec.source.string() + ": a ball bearing's linearisation failed: " + e.what());
  }
  add_runup_passages(spec.speed, campbell);

  // Critical speeds at an amplitude: each forward 1x critical of the analysed range continued in amplitude.
  std::vector<Backbone> backbones;
  std::map<int, std::string> amplitude_place;
  if (!options.amplitudes.empty()) {
    constexpr long kMaxAmplitudes = 200;
    BackboneOptions bo;
    bo.amplitudes = parse_quantity_list(options.amplitudes, "--amplitudes", dim::length, "amplitudes", kMaxAmplitudes);
    if (!(bo.amplitudes.front() > 0.0))
      throw ModelError("--amplitudes '" + options.amplitudes + "': amplitudes must be greater than zero");
    for (const auto& [node, label] : amplitude_references(spec, rotor, options.amplitude_at)) {
      bo.reference_nodes.push_back(node);
      amplitude_place[node] = label;
    }
    std::vector<double> starts;
    std::vector<int> branches;
    for (const CriticalSpeed& c : campbell.critical)
      if (c.order == 1.0 && c.whirl == Whirl::Forward) {
        starts.push_back(c.speed);
        branches.push_back(c.branch);
      }
    if (starts.empty())
      throw ModelError(spec.source.string() + ": --amplitudes: no forward 1x critical speed between " +
                       std::to_string(std::llround(speeds.front() * kRadPerSToRpm)) + " and " +
                       std::to_string(std::llround(speeds.back() * kRadPerSToRpm)) + " rpm; widen --speeds");
    try {
      backbones = synchronous_backbones(spec, build_rotor(spec), starts, bo);
      for (std::size_t i = 0; i < backbones.size(); ++i) backbones[i].branch = branches[i];  // the Campbell branch
    } catch (const QuasiStaticError& e) {
      throw ModelError(spec.source.string() + ": --amplitudes: a ball bearing's equilibrium failed: " + e.what());
    } catch (const std::invalid_argument& e) {
      throw ModelError(spec.source.string() + ": --amplitudes: " + e.what());
    } catch (const std::runtime_error& e) {
      throw ModelError(spec.source.string() + ": --amplitudes: " + e.what());
    }
  }

  std::filesystem::create_directories(options.output_dir);
  const std::string frame_name = options.frame == Frame::Rotating ? "rotating" : "inertial";

  // modal.json: every number, documented in docs/output-format.md.
  nlohmann::json j = result_header(spec, options.overrides);
  j["model"].update({{"n_nodes", rotor.node_z.size()},
                     {"n_dof", rotor.n_dof},
                     {"total_mass_kg", rotor.total_mass},
                     {"node_z_m", rotor.node_z}});
  j["frame"] = frame_name;
  j["orders"] = spec.modal.orders;
  nlohmann::json points = nlohmann::json::array();
  for (const ModalResult& r : campbell.points) {
    nlohmann::json modes = nlohmann::json::array();
    for (const Mode& m : r.modes)
      modes.push_back({{"frequency_hz", m.frequency},
                       {"damping_ratio", m.damping_ratio},
                       {"eigenvalue", {m.eigenvalue.real(), m.eigenvalue.imag()}},
                       {"whirl", to_string(m.whirl)}});
    points.push_back({{"speed_rad_s", r.speed}, {"speed_rpm", r.speed * kRadPerSToRpm}, {"modes", modes}});
  }
  j["campbell"] = points;
  nlohmann::json crit = nlohmann::json::array();
  for (const CriticalSpeed& c : campbell.critical)
    crit.push_back({{"order", c.order},
                    {"branch", c.branch},
                    {"whirl", to_string(c.whirl)},
                    {"speed_rad_s", c.speed},
                    {"speed_rpm", c.speed * kRadPerSToRpm},
                    {"frequency_hz", c.frequency},
                    {"damping_ratio", c.damping_ratio},
                    {"branch_slope", studies::json_number(c.branch_slope)},
                    {"amplification_factor", studies::json_number(c.amplification_factor)},
                    {"critically_damped", c.critically_damped},
                    {"runup_peak_speed_rpm", studies::json_number(c.runup_peak_speed * kRadPerSToRpm)},
                    {"runup_peak_fraction", studies::json_number(c.runup_peak_fraction)}});
  j["critical_speeds"] = crit;
  nlohmann::json shape_json = nlohmann::json::array();
  for (const ModalResult& r : shapes) {
    nlohmann::json modes = nlohmann::json::array();
    for (const Mode& m : r.modes)
      modes.push_back({{"frequency_hz", m.frequency},
                       {"damping_ratio", m.damping_ratio},
                       {"whirl", to_string(m.whirl)},
                       {"node_whirl", m.node_whirl},
                       {"twist", std::vector<double>(m.twist.data(), m.twist.data() + m.twist.size())},
                       {"x", complex_list(m.shape, rotor, kX)},
                       {"y", complex_list(m.shape, rotor, kY)},
                       {"theta_x", complex_list(m.shape, rotor, kThetaX)},
                       {"theta_y", complex_list(m.shape, rotor, kThetaY)}});
    shape_json.push_back({{"speed_rad_s", r.speed}, {"speed_rpm", r.speed * kRadPerSToRpm}, {"modes", modes}});
  }
  j["mode_shapes"] = shape_json;
  std::vector<std::string> warnings;
  if (!options.amplitudes.empty()) {
    j["backbones"] = backbone_json(backbones, amplitude_place);
    // Where a backbone's whirl loads a ball contact beyond ISO 76's static limit (a real bearing brinells there).
    for (const Backbone& b : backbones) {
      bool warned = false;
      for (const BackbonePoint& p : b.points) {
        for (const BackboneBearing& x : p.bearings)
          if (x.max_contact_pressure > kStaticContactPressureLimit) {
            std::ostringstream os;
            os << std::fixed << std::setprecision(2) << "the backbone of forward branch " << b.branch + 1
               << " passes the contact pressure's limit of " << std::setprecision(0)
               << kStaticContactPressureLimit * 1e-6 << " MPa in bearings." << x.name << " at a whirl amplitude of "
               << std::setprecision(2) << p.amplitude * 1e6 << " um (" << std::setprecision(0)
               << p.speed * kRadPerSToRpm << " rpm, " << x.max_contact_pressure * 1e-6 << " MPa), "
               << MaxContactPressureProbe().limit_note;
            warnings.push_back(os.str());
            warned = true;
            break;
          }
        if (warned) break;
      }
    }
    j["warnings"] = warnings;
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  }
  write_output_file(options.output_dir / "modal.json", j.dump(1) + "\n");
  {
    OutputFile file(options.output_dir / "campbell.csv");
    std::ostream& csv = file.stream();
    csv << "speed_rad_s,speed_rpm,mode,frequency_hz,damping_ratio,whirl\n" << std::setprecision(10);
    for (const ModalResult& r : campbell.points)
      for (std::size_t i = 0; i < r.modes.size(); ++i)
        csv << r.speed << ',' << r.speed * kRadPerSToRpm << ',' << i + 1 << ',' << r.modes[i].frequency << ','
            << r.modes[i].damping_ratio << ',' << to_string(r.modes[i].whirl) << '\n';
    file.commit();
  }

  std::cout << spec.name << ": " << rotor.node_z.size() << " nodes, " << rotor.n_dof << " DOF, rotor mass "
            << std::setprecision(4) << rotor.total_mass << " kg, " << frame_name << " frame\n";
  std::cout << "Modes at " << std::llround(speeds.front() * kRadPerSToRpm) << " rpm:\n";
  for (std::size_t i = 0; i < campbell.points.front().modes.size(); ++i) {
    const Mode& m = campbell.points.front().modes[i];
    std::cout << "  " << std::setw(2) << i + 1 << "  " << std::fixed << std::setprecision(2) << std::setw(10)
              << m.frequency << " Hz  zeta " << std::setprecision(4) << m.damping_ratio << "  "
              << to_string(m.whirl) << "\n";
  }
  std::cout << "Critical speeds (order-line crossings):\n";
  for (const CriticalSpeed& c : campbell.critical)
    std::cout << "  " << std::defaultfloat << c.order << "x " << std::setw(8) << to_string(c.whirl) << " branch "
              << c.branch + 1 << ": " << std::fixed << std::setprecision(0) << c.speed * kRadPerSToRpm << " rpm ("
              << std::setprecision(1) << c.frequency << " Hz), zeta " << std::setprecision(4) << c.damping_ratio
              << amplification_note(c) << "\n";
  std::cout << std::defaultfloat;
  if (!options.amplitudes.empty()) write_backbone_table(backbones, amplitude_place, options.output_dir / "backbone.csv");

  std::vector<std::string> pictures;
  if (options.plots) {
    double fmax = spec.modal.frequency_max;
    if (fmax <= 0) {
      const double top_order = *std::max_element(spec.modal.orders.begin(), spec.modal.orders.end());
      fmax = 1.1 * std::max(top_order * speeds.back() / (2 * M_PI), 1.0);
    }
    write_campbell_picture(spec, campbell, spec.modal.orders, fmax, options.output_dir / "campbell.png");
    pictures.push_back("campbell.png");
    write_damping_picture(spec, campbell, fmax, options.output_dir / "damping.png");
    pictures.push_back("damping.png");
    for (const ModalResult& r : shapes) {
      pictures.push_back("modes_" + speed_tag(r.speed) + ".png");
      write_mode_shape_picture(spec, rotor, r, options.output_dir / pictures.back());
    }
    const bool any_point = std::any_of(backbones.begin(), backbones.end(),
                                       [](const Backbone& b) { return !b.points.empty(); });
    if (any_point) {
      write_backbone_picture(spec, backbones, amplitude_place, options.output_dir / "backbone.png");
      pictures.push_back("backbone.png");
    }
  }
  std::vector<std::string> files{"modal.json", "campbell.csv"};
  if (!options.amplitudes.empty()) files.push_back("backbone.csv");
  post::write_modal_report(options.output_dir, j, {command_line(), pictures, files, warnings});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "Wrote " << (options.output_dir / "modal.json").string() << ", campbell.csv, report.html"
            << (options.plots ? ", campbell.png, damping.png, modes_*.png" : "") << " (" << std::setprecision(3) << wall
            << " s)\n";
  // A backbone that ended before the last amplitude: written so far and marked (complete: false), exit code 3.
  for (const Backbone& b : backbones)
    if (!b.stopped.empty()) {
      std::cerr << "turbodyn modal: branch " << b.branch + 1 << "'s critical speeds at an amplitude end early: "
                << b.stopped << "\n";
      return 3;
    }
  return 0;
}

}  // namespace turbodyn::app

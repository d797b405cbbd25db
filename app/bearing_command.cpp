#include "app/bearing_command.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/modal_command.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/elements/floating_ring_steady.h"
#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "model/spec/units.h"
#include "model/spec/constants.h"
#include "model/spec/text.h"
#include "post/plot.h"
#include "post/report.h"
#include "app/command_line.h"

namespace turbodyn::app {
namespace {

constexpr double kDeg = 180.0 / M_PI;
constexpr double kPerMetreToPerMicrometre = 1e-6;  // pictures show stiffness in N/µm
const char* const kDofNames[5] = {"x", "y", "z", "theta_x", "theta_y"};

nlohmann::json matrix_json(const Matrix5d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 5; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int j = 0; j < 5; ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

bool analysable(BearingType t) { return t == BearingType::Ball || t == BearingType::FloatingRing; }

const BearingSpec& find_bearing(const MachineSpec& spec, const std::string& name) {
  const std::string file = spec.source.string();
  if (name.empty()) {
    for (const BearingSpec& b : spec.bearings)
      if (analysable(b.type)) return b;
    throw ModelError(file + ": the model has no ball or floating-ring bearing (type = \"ball\" or \"floating-ring\"); "
                     "`turbodyn bearing` analyses those");
  }
  std::string names;
  for (const BearingSpec& b : spec.bearings) {
    if (b.name == name) {
      if (!analysable(b.type))
        throw ModelError(file + ": bearings." + name + " is a " + to_string(b.type) +
                         " bearing; --bearing must name a ball or floating-ring bearing (type = \"ball\" or "
                         "\"floating-ring\")");
      return b;
    }
    names += (names.empty() ? "" : ", ") + b.name;
  }
  throw ModelError(file + ": --bearing '" + name + "': no such bearing in the model (it has: " + names + ")");
}

nlohmann::json matrix2_json(const Eigen::Matrix2d& m) {
  return nlohmann::json::array({{m(0, 0), m(0, 1)}, {m(1, 0), m(1, 1)}});
}

// A quantity of a steady operating point, for the pictures.
using PointValue = double (*)(const FloatingRingOperatingPoint&);

void write_ring_pictures(const std::string& title, const std::vector<FloatingRingOperatingPoint>& pts, bool thermal,
                         const std::filesystem::path& dir) {
  using plot::Series;
  std::vector<double> rpm;
  for (const FloatingRingOperatingPoint& p : pts) rpm.push_back(p.speed * kRadPerSToRpm);
  const std::string which = " of floating-ring bearing " + title + (thermal ? " (thermal films)" : " (isothermal films)");
  // One picture against rotor speed: a curve per (label, value), the inner film red and the outer film blue.
  auto draw = [&](const std::string& what, const std::string& ylabel, const std::string& legend,
                  const std::vector<std::pair<std::string, PointValue>>& curves, const std::string& file) {
    plot::LineChart chart;
    chart.title = what + which;
    chart.xlabel = "rotor speed [rpm]";
    chart.ylabel = ylabel;
    for (const auto& [label, value] : curves) {
      Series s{label, rpm, {}, Series::Style::LinesPoints, label == "inner film" ? "#d62728" : "#1f77b4", 1.8};
      for (const FloatingRingOperatingPoint& p : pts) s.y.push_back(value(p));
      chart.series.push_back(s);
    }
    if (!legend.empty()) chart.legend_position = legend;
    plot::render_png(chart, dir / file);
  };
  draw("Ring speed ratio", "ring speed / rotor speed [-]", "bottom left",
       {{"ring speed ratio", [](const FloatingRingOperatingPoint& p) { return p.ring_speed / p.speed; }}},
       "ring_speed_ratio.png");
  draw("Eccentricity ratios", "e/c [-]", "",
       {{"inner film", [](const FloatingRingOperatingPoint& p) { return p.inner_eccentricity; }},
        {"outer film", [](const FloatingRingOperatingPoint& p) { return p.outer_eccentricity; }}},
       "eccentricity.png");
  draw("Power loss", "power [W]", "top left",
       {{"inner film", [](const FloatingRingOperatingPoint& p) { return p.inner_power; }},
        {"outer film", [](const FloatingRingOperatingPoint& p) { return p.outer_power; }}},
       "power_loss.png");
  draw("Film temperatures", "temperature [degC]", "top left",
       {{"inner film", [](const FloatingRingOperatingPoint& p) { return p.inner_temperature - 273.15; }},
        {"outer film", [](const FloatingRingOperatingPoint& p) { return p.outer_temperature - 273.15; }}},
       "temperatures.png");
}

// `turbodyn bearing` for a floating-ring bearing: steady operating points (model/elements/floating_ring_steady.h).
int run_floating_ring(const BearingCommandOptions& options, const MachineSpec& spec, const BearingSpec& b,
                      const std::vector<double>& speeds, const std::vector<double>& load,
                      std::chrono::steady_clock::time_point t0) {
  const std::string where = spec.source.string() + ": bearings." + b.name;
  if (load[2] != 0.0)
    throw ModelError("--load '" + options.load + "': a floating-ring bearing takes no axial load (give \"Fx,Fy\")");
  std::unique_ptr<FloatingRingElement> element;
  try {
    element = std::make_unique<FloatingRingElement>(b.name, b.ring, spec.oil, 0, spec.gravity);
  } catch (const std::invalid_argument& e) {
    throw ModelError(where + ": impossible geometry or data: " + e.what());
  }
  std::vector<double> positive;
  for (double w : speeds)
    if (w > 0.0) positive.push_back(w);
  if (positive.empty()) throw ModelError("--speeds: a floating-ring bearing needs speeds above 0");
  const FloatingRingSteady steady(*element);
  std::vector<FloatingRingOperatingPoint> pts;
  try {
    pts = steady.sweep(positive, Eigen::Vector2d(load[0], load[1]));
  } catch (const SteadyPointError& e) {
    throw ModelError(where + " with --load '" + options.load + "': " + e.what());
  } catch (const std::runtime_error& e) {
    throw ModelError(where + " with --load '" + options.load + "': " + e.what());
  }
  const bool thermal = element->thermal();
  const FloatingRingSpec& f = b.ring;
  std::filesystem::create_directories(options.output_dir);
  nlohmann::json j = result_header(spec, options.overrides);
  j["bearing"] = {{"name", b.name},
                  {"type", "floating-ring"},
                  {"thermal", to_string(f.thermal.model)},
                  {"inner_diameter_m", f.inner_diameter},
                  {"inner_length_m", f.inner_length},
                  {"inner_clearance_m", f.inner_clearance},
                  {"outer_diameter_m", f.outer_diameter},
                  {"outer_length_m", f.outer_length},
                  {"outer_clearance_m", f.outer_clearance},
                  {"ring_mass_kg", f.ring_mass},
                  {"drill_holes", f.drill_holes},
                  {"supply_pressure_pa", f.supply_pressure},
                  {"feed_hole_diameter_m", f.feed_hole_diameter},
                  {"feed_groove_width_m", f.feed_groove_width},
                  {"supply_temperature_k", spec.oil.temperature}};
  if (thermal)
    j["thermal"] = {{"shaft_temperature_k", f.thermal.shaft_temperature},
                    {"housing_temperature_k", f.thermal.housing_temperature},
                    {"oil_specific_heat_j_per_kg_k", f.thermal.oil_specific_heat},
                    {"inner_shaft_conductance_w_per_k", f.thermal.inner_shaft_conductance},
                    {"ring_conductance_w_per_k", f.thermal.ring_conductance},
                    {"outer_housing_conductance_w_per_k", f.thermal.outer_housing_conductance},
                    {"inner_heat_capacity_j_per_k", f.thermal.inner_heat_capacity},
                    {"outer_heat_capacity_j_per_k", f.thermal.outer_heat_capacity}};
  j["assumptions"] = {
      "steady: ring speed from the torque balance of both films, journal and ring positions from the force balances "
      "(the ring's weight included), film temperatures from their heat balances (thermal films)",
      "the balances are averaged over ring angles across one drill-hole pitch (the holes pass the feed hole)",
      "journal and ring aligned (no tilt); the static load acts on the journal at mid-width",
      "linearised coefficients: each film's force against its own surfaces' relative motion, ring speed and "
      "temperatures held (the pair is two such films in series through the ring's mass)"};
  j["load_n"] = {load[0], load[1]};
  // Each film's thinnest point (journal and ring aligned: c (1 - e/c)), against the permissible minimum the model
  // file may give (film_thickness_limit).
  const auto inner_h = [&](const FloatingRingOperatingPoint& p) {
    return f.inner_clearance * (1 - p.inner_eccentricity);
  };
  const auto outer_h = [&](const FloatingRingOperatingPoint& p) {
    return f.outer_clearance * (1 - p.outer_eccentricity);
  };
  std::vector<std::string> warnings;
  if (f.film_thickness_limit > 0.0) {
    j["bearing"]["film_thickness_limit_m"] = f.film_thickness_limit;
    for (const FloatingRingOperatingPoint& p : pts) {
      const double h = std::min(inner_h(p), outer_h(p));
      if (h >= f.film_thickness_limit) continue;
      std::ostringstream os;
      os << std::fixed << std::setprecision(0) << "at " << p.speed * kRadPerSToRpm << " rpm the "
         << (inner_h(p) <= outer_h(p) ? "inner" : "outer") << " film is " << std::setprecision(2) << h * 1e6
         << " µm thin, below its limit of " << f.film_thickness_limit * 1e6 << " µm, "
         << kFilmThicknessLimitNote;
      warnings.push_back(os.str());
    }
  }
  j["warnings"] = warnings;
  nlohmann::json points = nlohmann::json::array();
  for (const FloatingRingOperatingPoint& p : pts)
    points.push_back({{"speed_rad_s", p.speed},
                      {"speed_rpm", p.speed * kRadPerSToRpm},
                      {"ring_speed_rad_s", p.ring_speed},
                      {"ring_speed_ratio", p.ring_speed / p.speed},
                      {"journal_m", {p.journal[0], p.journal[1]}},
                      {"ring_m", {p.ring[0], p.ring[1]}},
                      {"inner_eccentricity", p.inner_eccentricity},
                      {"outer_eccentricity", p.outer_eccentricity},
                      {"inner_min_film_thickness_m", inner_h(p)},
                      {"outer_min_film_thickness_m", outer_h(p)},
                      {"inner_attitude_deg", p.inner_attitude * kDeg},
                      {"outer_attitude_deg", p.outer_attitude * kDeg},
                      {"inner_temperature_k", p.inner_temperature},
                      {"outer_temperature_k", p.outer_temperature},
                      {"inner_power_w", p.inner_power},
                      {"outer_power_w", p.outer_power},
                      {"inner_side_flow_m3_s", p.inner_flow},
                      {"outer_side_flow_m3_s", p.outer_flow},
                      {"drill_hole_pressure_pa", p.drill_hole_pressure},
                      {"heat_to_oil_w", p.heat_to_oil},
                      {"heat_conducted_w", p.heat_conducted},
                      {"inner_stiffness_n_per_m", matrix2_json(p.k_inner)},
                      {"inner_damping_n_s_per_m", matrix2_json(p.c_inner)},
                      {"outer_stiffness_n_per_m", matrix2_json(p.k_outer)},
                      {"outer_damping_n_s_per_m", matrix2_json(p.c_outer)},
                      {"newton_iterations", p.iterations}});
  j["results"] = points;
  write_output_file(options.output_dir / "bearing.json", j.dump(1) + "\n");
  {
    OutputFile file(options.output_dir / "bearing.csv");
    std::ostream& csv = file.stream();
    csv << "speed_rad_s,speed_rpm,ring_speed_ratio,inner_eccentricity,outer_eccentricity,inner_temperature_k,"
           "outer_temperature_k,inner_power_w,outer_power_w,inner_side_flow_m3_s,outer_side_flow_m3_s,heat_to_oil_w,"
           "heat_conducted_w";
    for (const char* film : {"inner", "outer"})
      for (const char* m : {"k", "c"})
        for (const char* rc : {"xx", "xy", "yx", "yy"}) csv << ',' << m << '_' << film << '_' << rc;
    csv << ",inner_min_film_thickness_m,outer_min_film_thickness_m,drill_hole_pressure_pa\n" << std::setprecision(10);
    for (const FloatingRingOperatingPoint& p : pts) {
      csv << p.speed << ',' << p.speed * kRadPerSToRpm << ',' << p.ring_speed / p.speed << ','
          << p.inner_eccentricity << ',' << p.outer_eccentricity << ',' << p.inner_temperature << ','
          << p.outer_temperature << ',' << p.inner_power << ',' << p.outer_power << ',' << p.inner_flow << ','
          << p.outer_flow << ',' << p.heat_to_oil << ',' << p.heat_conducted;
      for (const Eigen::Matrix2d* m : {&p.k_inner, &p.c_inner, &p.k_outer, &p.c_outer})
        csv << ',' << (*m)(0, 0) << ',' << (*m)(0, 1) << ',' << (*m)(1, 0) << ',' << (*m)(1, 1);
      csv << ',' << inner_h(p) << ',' << outer_h(p) << ',' << p.drill_hole_pressure << '\n';
    }
    file.commit();
  }
  std::cout << spec.name << ": floating-ring bearing " << b.name << " (" << to_string(f.thermal.model)
            << " films), load (" << load[0] << ", " << load[1] << ") N\n";
  std::cout << "     speed [rpm]  ring/shaft   e_i/c_i   e_o/c_o  h_i [µm]  h_o [µm]  T_i [degC]  T_o [degC]  "
               "P_i [W]   P_o [W]  Q_i [ml/min]  Q_o [ml/min]  p_h [bar]\n";
  for (const FloatingRingOperatingPoint& p : pts)
    std::cout << std::fixed << std::setw(16) << std::setprecision(0) << p.speed * kRadPerSToRpm << std::setw(12)
              << std::setprecision(4) << p.ring_speed / p.speed << std::setw(10) << std::setprecision(3)
              << p.inner_eccentricity << std::setw(10) << p.outer_eccentricity << std::setw(10)
              << std::setprecision(2) << inner_h(p) * 1e6 << std::setw(10) << outer_h(p) * 1e6
              << std::setw(12) << std::setprecision(1) << p.inner_temperature - 273.15 << std::setw(12)
              << p.outer_temperature - 273.15 << std::setw(9) << std::setprecision(2) << p.inner_power
              << std::setw(10) << p.outer_power << std::setw(14) << p.inner_flow * 6e7 << std::setw(14)
              << p.outer_flow * 6e7 << std::setw(11) << p.drill_hole_pressure * 1e-5 << "\n";
  std::cout << std::defaultfloat;
  if (options.plots) write_ring_pictures(b.name, pts, thermal, options.output_dir);
  post::write_bearing_report(
      options.output_dir, j,
      {command_line(),
       options.plots ? std::vector<std::string>{"ring_speed_ratio.png", "eccentricity.png", "temperatures.png",
                                                "power_loss.png"}
                     : std::vector<std::string>{},
       {"bearing.json", "bearing.csv"}, warnings});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "Wrote " << (options.output_dir / "bearing.json").string() << ", bearing.csv, report.html"
            << (options.plots ? ", ring_speed_ratio.png, eccentricity.png, power_loss.png, temperatures.png" : "")
            << " (" << std::setprecision(3) << wall << " s)\n";
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  return 0;
}

void write_bearing_pictures(const std::string& title, const std::vector<BallBearingEquilibrium>& results,
                            const std::filesystem::path& dir) {
  using plot::Series;
  std::vector<double> rpm;
  for (const BallBearingEquilibrium& r : results) rpm.push_back(r.speed * kRadPerSToRpm);
  const auto series = [&](const std::string& label, int i, const std::string& color, Series::Style style) {
    Series s{label, rpm, {}, style, color, 1.8};
    for (const BallBearingEquilibrium& r : results)
      s.y.push_back(r.stiffness(i, i) * (i < 3 ? kPerMetreToPerMicrometre : 1.0));
    return s;
  };
  plot::LineChart chart;
  chart.title = "Stiffness of ball bearing " + title + " against speed (quasi-static)";
  chart.xlabel = "rotor speed [rpm]";
  chart.ylabel = "stiffness [N/µm]";
  chart.logy = true;
  chart.series.push_back(series("radial k_xx", 0, "#1f77b4", Series::Style::LinesPoints));
  chart.series.push_back(series("radial k_yy", 1, "#ff7f0e", Series::Style::Dashed));
  chart.series.push_back(series("axial k_zz (outer ring on its preload spring)", 2, "#2ca02c", Series::Style::LinesPoints));
  plot::render_png(chart, dir / "stiffness.png");

  plot::LineChart tilt;
  tilt.title = "Tilt stiffness of ball bearing " + title + " against speed (quasi-static)";
  tilt.xlabel = "rotor speed [rpm]";
  tilt.ylabel = "tilt stiffness [N m/rad]";
  tilt.series.push_back(series("k_theta_x theta_x", 3, "#1f77b4", Series::Style::LinesPoints));
  tilt.series.push_back(series("k_theta_y theta_y", 4, "#ff7f0e", Series::Style::Dashed));
  plot::render_png(tilt, dir / "tilt_stiffness.png");
}

}  // namespace

std::vector<double> parse_load(const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string p; std::getline(ss, p, ',');) {
    try {
      out.push_back(parse_quantity(trim_blanks(p), dim::force));
    } catch (const UnitError& e) {
      throw ModelError("--load '" + text + "': " + e.what() + " (expected \"Fx,Fy\" or \"Fx,Fy,Fz\" in N)");
    }
  }
  if (out.size() < 2 || out.size() > 3 || (!text.empty() && text.back() == ','))
    throw ModelError("--load '" + text + "': expected two or three forces \"Fx,Fy\" or \"Fx,Fy,Fz\" (N)");
  if (out.size() == 2) out.push_back(0.0);
  return out;
}

std::vector<double> parse_travel_list(const std::string& text) {
  constexpr long kMaxTravels = 10000;
  return parse_quantity_list(text, "--radial-travel", dim::length, "travels", kMaxTravels);
}

int run_bearing_command(const BearingCommandOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const MachineSpec spec = load_model(options.model_file, options.overrides);
  const BearingSpec& b = find_bearing(spec, options.bearing);
  const std::string where = spec.source.string() + ": bearings." + b.name;
  const std::vector<double> speeds = analysis_speeds(spec, options.speeds, 11);
  const std::vector<double> load = parse_load(options.load);
  const std::vector<double> travel =
      options.radial_travel.empty() ? std::vector<double>{} : parse_travel_list(options.radial_travel);
  if (b.type == BearingType::FloatingRing) {
    if (!travel.empty()) throw ModelError("--radial-travel: load-deflection curves are for ball bearings");
    return run_floating_ring(options, spec, b, speeds, load, t0);
  }
  if (!travel.empty() && (load[0] != 0.0 || load[1] != 0.0 || load[2] != 0.0))
    throw ModelError("--radial-travel and --load: the load-deflection curve starts from the unloaded, centred "
                     "bearing; give one of them");

  std::unique_ptr<BallBearingElement> element;
  try {
    element = std::make_unique<BallBearingElement>(b.name, b.ball, 0, 0.0);
  } catch (const std::invalid_argument& e) {
    throw ModelError(where + ": impossible geometry or data: " + e.what());
  }
  const BallBearingQuasiStatic qs(*element);
  std::vector<BallBearingEquilibrium> results;
  try {
    results = qs.sweep(speeds, Eigen::Vector3d(load[0], load[1], load[2]));
  } catch (const QuasiStaticError& e) {
    throw ModelError(where + " with --load '" + options.load + "': " + e.what());
  }

  std::vector<std::vector<LoadDeflectionPoint>> curves;
  for (const BallBearingEquilibrium& r : results) {
    if (travel.empty()) break;
    try {
      curves.push_back(qs.load_deflection(r.speed, travel, &r));  // r: the unloaded equilibrium (no --load)
    } catch (const QuasiStaticError& e) {
      throw ModelError(where + " with --radial-travel '" + options.radial_travel + "': " + e.what());
    }
  }

  std::filesystem::create_directories(options.output_dir);
  const BallBearingSpec& s = b.ball;
  nlohmann::json j = result_header(spec, options.overrides);
  j["bearing"] = {{"name", b.name},
                  {"n_balls", s.n_balls},
                  {"ball_diameter_m", s.ball_diameter},
                  {"pitch_diameter_m", s.pitch_diameter},
                  {"free_contact_angle_rad", s.contact_angle},
                  {"side", s.side},
                  {"preload_n", s.preload},
                  {"preload_stiffness_n_per_m", s.preload_stiffness},
                  {"contact_damping_n_s_per_m", s.contact_damping},
                  {"contact_damping_ratio_s", s.contact_damping_ratio},
                  {"hertz_law", s.hertz_coefficient > 0.0 ? "paper" : "ellipse"},
                  {"hertz_coefficient", s.hertz_coefficient},
                  {"inner_hertz_constant_n_per_m1_5", element->inner_contact().stiffness},
                  {"outer_hertz_constant_n_per_m1_5", element->outer_contact().stiffness},
                  {"in_squeeze_film_damper", b.damper.enabled}};
  j["assumptions"] = {
      "quasi-static: balls in force equilibrium in their azimuth planes (Jones 1960; Harris & Kotzalas 2007)",
      "outer-race control: each ball's orbital speed and spin axis from its own contact angles, its gyroscopic "
      "moment carried by traction at the outer contact (no gyroscopic slip)",
      "outer ring held radially at the housing centre (also in a squeeze-film damper), axially on its preload "
      "spring; inner ring axially held",
      "no friction other than the gyroscopic traction, no gravity on the balls, no lubricant film",
      "stiffness: -dF/dq with the balls and the outer ring re-equilibrated; damping: the contact damping d of "
      "paper Eq. 21 along each loaded contact normal, the balls following as in the static condensation"};
  j["load_n"] = load;
  j["dofs"] = {"x", "y", "z", "theta_x", "theta_y"};
  j["static_contact_pressure_limit_pa"] = kStaticContactPressureLimit;
  // Hertz pressures p_0 of each ball's contacts, and each speed's largest (against ISO 76's static limit).
  const auto inner_pressure = [&](const QuasiStaticBall& q) {
    return HertzPeakPressure(element->inner_contact(), q.inner_load);
  };
  const auto outer_pressure = [&](const QuasiStaticBall& q) {
    return HertzPeakPressure(element->outer_contact(), q.outer_load);
  };
  std::vector<double> max_pressure;
  std::vector<std::string> warnings;
  for (const BallBearingEquilibrium& r : results) {
    const double p = r.max_contact_pressure(*element);
    max_pressure.push_back(p);
    if (p > kStaticContactPressureLimit) {
      std::ostringstream os;
      os << std::fixed << std::setprecision(0) << "at " << r.speed * kRadPerSToRpm
         << " rpm the largest contact pressure is " << p * 1e-6 << " MPa, above its limit of "
         << kStaticContactPressureLimit * 1e-6 << " MPa, " << MaxContactPressureProbe().limit_note;
      warnings.push_back(os.str());
    }
  }
  for (std::size_t i = 0; i < curves.size(); ++i)
    for (const LoadDeflectionPoint& p : curves[i])
      if (p.max_contact_pressure > kStaticContactPressureLimit) {
        std::ostringstream os;
        os << std::fixed << std::setprecision(0) << "the load-deflection curve at " << results[i].speed * kRadPerSToRpm
           << " rpm passes the contact pressure's limit of " << kStaticContactPressureLimit * 1e-6 << " MPa at "
           << std::setprecision(2) << p.travel * 1e6 << " um of travel (" << std::setprecision(0) << p.load
           << " N, " << p.max_contact_pressure * 1e-6 << " MPa), " << MaxContactPressureProbe().limit_note;
        warnings.push_back(os.str());
        break;
      }
  j["warnings"] = warnings;
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = 0; i < results.size(); ++i) {
    const BallBearingEquilibrium& r = results[i];
    nlohmann::json balls = nlohmann::json::array();
    for (const QuasiStaticBall& q : r.balls)
      balls.push_back({{"azimuth_deg", q.azimuth * kDeg},
                       {"inner_load_n", q.inner_load},
                       {"outer_load_n", q.outer_load},
                       {"inner_pressure_pa", inner_pressure(q)},
                       {"outer_pressure_pa", outer_pressure(q)},
                       {"inner_contact_angle_deg", q.inner_angle * kDeg},
                       {"outer_contact_angle_deg", q.outer_angle * kDeg},
                       {"inner_deflection_m", q.inner_deflection},
                       {"outer_deflection_m", q.outer_deflection},
                       {"radial_position_m", q.rho},
                       {"axial_position_m", q.zeta},
                       {"orbital_speed_rad_s", q.orbital_speed},
                       {"gyroscopic_moment_n_m", q.gyroscopic_moment}});
    nlohmann::json disp;
    for (int i = 0; i < 5; ++i) disp[kDofNames[i]] = r.displacement[i];
    points.push_back({{"speed_rad_s", r.speed},
                      {"speed_rpm", r.speed * kRadPerSToRpm},
                      {"inner_ring_displacement", disp},
                      {"outer_ring_axial_m", r.outer_ring_axial},
                      {"force_on_inner_ring", std::vector<double>(r.shaft_force.data(), r.shaft_force.data() + 5)},
                      {"cage_speed_rad_s", r.cage_speed},
                      {"cage_speed_ratio", r.speed != 0.0 ? r.cage_speed / r.speed : 0.0},
                      {"max_contact_pressure_pa", max_pressure[i]},
                      {"stiffness", matrix_json(r.stiffness)},
                      {"damping", matrix_json(r.damping)},
                      {"newton_iterations", r.iterations},
                      {"balls", balls}});
  }
  j["results"] = points;
  if (!curves.empty()) {
    nlohmann::json jc = nlohmann::json::array();
    for (std::size_t i = 0; i < curves.size(); ++i) {
      nlohmann::json pts = nlohmann::json::array();
      for (const LoadDeflectionPoint& p : curves[i])
        pts.push_back({{"travel_m", p.travel},
                       {"load_n", p.load},
                       {"cross_load_n", p.cross_load},
                       {"moment_x_n_m", p.moment_x},
                       {"moment_y_n_m", p.moment_y},
                       {"secant_stiffness_n_per_m", p.secant},
                       {"tangent_stiffness_n_per_m", p.tangent},
                       {"max_contact_load_n", p.max_contact_load},
                       {"max_contact_pressure_pa", p.max_contact_pressure}});
      jc.push_back({{"speed_rpm", results[i].speed * kRadPerSToRpm}, {"points", pts}});
    }
    j["load_deflection"] = {
        {"description",
         "inner ring moved radially along x from the centred equilibrium, its tilt held at zero (as a shaft between "
         "two bearings holds it), axial place kept; load = force that holds it there; secant = load / travel, the "
         "stiffness a circular whirl of that radius sees; tangent = d load / d travel"},
        {"curves", jc}};
  }
  write_output_file(options.output_dir / "bearing.json", j.dump(1) + "\n");
  if (!curves.empty()) {
    OutputFile file(options.output_dir / "load_deflection.csv");
    std::ostream& csv = file.stream();
    csv << "speed_rpm,travel_m,load_n,cross_load_n,moment_x_n_m,moment_y_n_m,secant_stiffness_n_per_m,"
           "tangent_stiffness_n_per_m,max_contact_load_n,max_contact_pressure_pa\n"
        << std::setprecision(10);
    for (std::size_t i = 0; i < curves.size(); ++i)
      for (const LoadDeflectionPoint& p : curves[i])
        csv << results[i].speed * kRadPerSToRpm << ',' << p.travel << ',' << p.load << ',' << p.cross_load << ','
            << p.moment_x << ',' << p.moment_y << ',' << p.secant << ',' << p.tangent << ',' << p.max_contact_load
            << ',' << p.max_contact_pressure << '\n';
    file.commit();
  }
  {
    OutputFile file(options.output_dir / "bearing.csv");
    std::ostream& csv = file.stream();
    csv << "speed_rad_s,speed_rpm,x_m,y_m,theta_x_rad,theta_y_rad,outer_ring_axial_m,cage_speed_ratio";
    for (const char* m : {"k", "c"})
      for (int r = 0; r < 5; ++r)
        for (int c = 0; c < 5; ++c) csv << ',' << m << '_' << kDofNames[r] << '_' << kDofNames[c];
    csv << '\n' << std::setprecision(10);
    for (const BallBearingEquilibrium& r : results) {
      csv << r.speed << ',' << r.speed * kRadPerSToRpm << ',' << r.displacement[0] << ',' << r.displacement[1] << ','
          << r.displacement[3] << ',' << r.displacement[4] << ',' << r.outer_ring_axial << ','
          << (r.speed != 0.0 ? r.cage_speed / r.speed : 0.0);
      for (const Matrix5d* m : {&r.stiffness, &r.damping})
        for (int i = 0; i < 5; ++i)
          for (int k = 0; k < 5; ++k) csv << ',' << (*m)(i, k);
      csv << '\n';
    }
    file.commit();
  }
  {
    OutputFile file(options.output_dir / "bearing_balls.csv");
    std::ostream& csv = file.stream();
    csv << "speed_rpm,ball,azimuth_deg,inner_load_n,outer_load_n,inner_contact_angle_deg,outer_contact_angle_deg,"
           "orbital_speed_rad_s,gyroscopic_moment_n_m,inner_pressure_pa,outer_pressure_pa\n"
        << std::setprecision(10);
    for (const BallBearingEquilibrium& r : results)
      for (std::size_t i = 0; i < r.balls.size(); ++i) {
        const QuasiStaticBall& q = r.balls[i];
        csv << r.speed * kRadPerSToRpm << ',' << i << ',' << q.azimuth * kDeg << ',' << q.inner_load << ','
            << q.outer_load << ',' << q.inner_angle * kDeg << ',' << q.outer_angle * kDeg << ',' << q.orbital_speed
            << ',' << q.gyroscopic_moment << ',' << inner_pressure(q) << ',' << outer_pressure(q) << '\n';
      }
    file.commit();
  }

  std::cout << spec.name << ": ball bearing " << b.name << ", load (" << load[0] << ", " << load[1] << ", " << load[2]
            << ") N" << (b.damper.enabled ? ", outer ring held at the damper's centre" : "") << "\n";
  std::cout << "     speed [rpm]  cage/shaft  a_i ball 0  a_o ball 0   Q_max [N]   k_xx [N/m]   k_yy [N/m]  "
               "k_tilt [N m/rad]  p_max [MPa]\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const BallBearingEquilibrium& r = results[i];
    const double qmax = r.max_contact_load();
    std::cout << std::fixed << std::setw(16) << std::setprecision(0) << r.speed * kRadPerSToRpm << std::setw(12)
              << std::setprecision(5) << (r.speed != 0.0 ? r.cage_speed / r.speed : 0.0) << std::setw(12)
              << std::setprecision(2) << r.balls[0].inner_angle * kDeg << std::setw(12) << r.balls[0].outer_angle * kDeg
              << std::setw(12) << qmax << std::scientific << std::setprecision(4) << std::setw(13)
              << r.stiffness(0, 0) << std::setw(13) << r.stiffness(1, 1) << std::setw(13) << r.stiffness(3, 3)
              << std::fixed << std::setprecision(0) << std::setw(13) << max_pressure[i] * 1e-6 << "\n";
  }
  for (std::size_t i = 0; i < curves.size(); ++i) {
    std::cout << "  load-deflection at " << std::fixed << std::setprecision(0) << results[i].speed * kRadPerSToRpm
              << " rpm (tilt held):   travel [um]   load [N]   secant [N/m]   tangent [N/m]   Q_max [N]"
              << "  p0_max [MPa]\n";
    for (const LoadDeflectionPoint& p : curves[i])
      std::cout << std::fixed << std::setw(47) << std::setprecision(2) << p.travel * 1e6 << std::setw(11)
                << (std::abs(p.load) < 5e-3 ? 0.0 : p.load)  // no "-0.00" from round-off at zero travel
                << std::scientific << std::setprecision(4) << std::setw(15) << p.secant << std::setw(16) << p.tangent
                << std::fixed << std::setprecision(1) << std::setw(12) << p.max_contact_load << std::setprecision(0)
                << std::setw(14) << p.max_contact_pressure * 1e-6 << "\n";
  }
  std::cout << std::defaultfloat;
  if (options.plots) write_bearing_pictures(b.name, results, options.output_dir);
  if (options.plots && !curves.empty()) {
    plot::LineChart chart;
    chart.title = "Load-deflection of ball bearing " + b.name + " (inner ring moved radially, tilt held)";
    chart.xlabel = "radial travel of the inner ring [µm]";
    chart.ylabel = "radial load [N]";
    static const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"};
    for (std::size_t i = 0; i < curves.size(); ++i) {
      std::ostringstream label;
      label << std::fixed << std::setprecision(0) << results[i].speed * kRadPerSToRpm << " rpm";
      plot::Series line{label.str(), {}, {}, plot::Series::Style::LinesPoints, kColours[i % 7], 1.6};
      for (const LoadDeflectionPoint& p : curves[i]) {
        line.x.push_back(p.travel * 1e6);
        line.y.push_back(p.load);
      }
      chart.series.push_back(line);
    }
    plot::render_png(chart, options.output_dir / "load_deflection.png");
  }
  post::write_bearing_report(options.output_dir, j,
                             {command_line(),
                              options.plots ? (curves.empty() ? std::vector<std::string>{"stiffness.png",
                                                                                         "tilt_stiffness.png"}
                                                              : std::vector<std::string>{"stiffness.png",
                                                                                         "tilt_stiffness.png",
                                                                                         "load_deflection.png"})
                                            : std::vector<std::string>{},
                              curves.empty() ? std::vector<std::string>{"bearing.json", "bearing.csv",
                                                                        "bearing_balls.csv"}
                                             : std::vector<std::string>{"bearing.json", "bearing.csv",
                                                                        "bearing_balls.csv", "load_deflection.csv"},
                              warnings});
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "Wrote " << (options.output_dir / "bearing.json").string() << ", bearing.csv, bearing_balls.csv"
            << (curves.empty() ? "" : ", load_deflection.csv") << ", report.html"
            << (options.plots ? ", stiffness.png, tilt_stiffness.png" : "")
            << (options.plots && !curves.empty() ? ", load_deflection.png" : "") << " (" << std::setprecision(3)
            << wall << " s)\n";
  return 0;
}

}  // namespace turbodyn::app

#include "app/journal_command.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "model/films/film_linearisation.h"
#include "model/io/model_file.h"
#include "model/spec/model_spec.h"
#include "model/films/reynolds.h"
#include "model/spec/limits.h"
#include "model/spec/units.h"

namespace turbodyn::app {
namespace {

double value(const std::string& option, const std::string& text, const Dimension& d) {
  try {
    return parse_quantity(text, d);
  } catch (const UnitError& e) {
    throw ModelError("--" + option + " '" + text + "': " + e.what());
  }
}

}  // namespace

int run_journal_command(const JournalCommandOptions& o) {
  using namespace reynolds;
  const double D = value("diameter", o.diameter, dim::length);
  const double c = value("clearance", o.clearance, dim::length);
  double L = o.length.empty() ? 0.0 : value("length", o.length, dim::length);
  if (!std::isfinite(o.ld) || o.ld < 0.0 || o.ld > 100.0)
    throw ModelError("--ld " + std::to_string(o.ld) + ": the width ratio L/D must lie in (0, 100]");
  if (o.ld > 0.0) L = o.ld * D;
  for (const auto& [option, v, d] : {std::tuple{"diameter", D, dim::length}, std::tuple{"clearance", c, dim::length},
                                     std::tuple{"length", L, dim::length}})
    if (const std::string why = limits::implausible(v, d); !why.empty())
      throw ModelError(std::string("--") + option + ": " + why);
  if (!(D > 0) || !(c > 0) || !(L > 0))
    throw ModelError("journal: diameter, clearance and length (or --ld) must be positive");
  if (!(o.eccentricity >= 0.0 && o.eccentricity < 1.0))
    throw ModelError("--eccentricity: the ratio e/c must lie in [0, 1)");
  OilSpec oil;
  double eta = o.viscosity.empty() ? oil.viscosity_at(value("temperature", o.temperature, dim::temperature))
                                   : value("viscosity", o.viscosity, dim::viscosity);
  const double w = value("speed", o.speed, dim::angular_speed);
  const double w_out = value("outer-speed", o.outer_speed, dim::angular_speed);
  // The direction of the eccentricity, reduced to (-pi, pi] so that a huge angle costs nothing later.
  const double att = std::remainder(value("attitude", o.attitude, dim::angle), 2 * M_PI);
  if (o.n_circ < 8 || o.n_circ > limits::kMaxFilmCirc || o.n_axial < 4 || o.n_axial > limits::kMaxFilmAxial ||
      static_cast<long>(o.n_circ) * o.n_axial > limits::kMaxFilmNodes)
    throw ModelError("--n-circ " + std::to_string(o.n_circ) + " --n-axial " + std::to_string(o.n_axial) +
                     ": the grid needs 8 to " + std::to_string(limits::kMaxFilmCirc) + " nodes around, 4 to " +
                     std::to_string(limits::kMaxFilmAxial) + " across and at most " +
                     std::to_string(limits::kMaxFilmNodes) + " in all");
  for (const auto& [option, v, d] : {std::tuple{"viscosity", eta, dim::viscosity},
                                     std::tuple{"speed", w, dim::angular_speed},
                                     std::tuple{"outer-speed", w_out, dim::angular_speed}})
    if (const std::string why = limits::implausible(v, d); !why.empty())
      throw ModelError(std::string("--") + option + (option == std::string("viscosity") && o.viscosity.empty()
                                                         ? " (from --temperature " + o.temperature + ")"
                                                         : std::string()) +
                       ": " + why);
  if (!(eta > 0.0)) throw ModelError("--viscosity: must be positive");
  FilmGeometry g;
  g.radius = 0.5 * D;
  g.length = L;
  g.clearance = c;
  g.n_circ = o.n_circ;
  g.n_axial = o.n_axial;
  const double hole = value("hole-diameter", o.hole_diameter, dim::length);
  const double groove = value("groove-width", o.groove_width, dim::length);
  const double supply = value("supply-pressure", o.supply_pressure, dim::pressure);
  if (!(hole >= 0.0 && hole < L)) throw ModelError("--hole-diameter: must lie in [0, the bearing length)");
  if (!(groove >= 0.0 && groove < L)) throw ModelError("--groove-width: must lie in [0, the bearing length)");
  if (hole > 0.0 && groove > 0.0)
    throw ModelError("--hole-diameter and --groove-width: the oil enters through a feed hole or a feed groove, not "
                     "both");
  if (!std::isfinite(supply) || (supply != 0.0 && hole == 0.0 && groove == 0.0))
    throw ModelError("--supply-pressure: needs a feed hole (--hole-diameter) or a feed groove (--groove-width) to "
                     "enter the film");
  if (hole > 0.0) g.holes.push_back({M_PI / 2, 0.0, hole, supply});
  if (groove > 0.0) g.grooves.push_back({0.0, groove, supply});
  SolverOptions so;
  if (!from_string(o.cavitation, so.cavitation))
    throw ModelError("--cavitation '" + o.cavitation + "': expected gumbel, mass-conserving or none");
  // The grid and the feed are checked above but for one thing the solver alone knows: a groove must hold a node.
  auto make_film = [&] {
    try {
      return FilmSolver(g, eta, so);
    } catch (const GrooveGridError& e) {
      throw ModelError("--groove-width " + o.groove_width + " --n-axial " + std::to_string(o.n_axial) + ": " +
                       e.reason());
    }
  };
  FilmSolver film = make_film();

  FilmState s;
  s.ex = o.eccentricity * c * std::cos(att);
  s.ey = o.eccentricity * c * std::sin(att);
  s.omega_inner = w;
  s.omega_outer = w_out;
  const Linearisation lin = linearise(film, s);
  const FilmResult& base = lin.at;
  const double W = std::hypot(base.fx, base.fy);
  const double R = 0.5 * D;
  const Eigen::Matrix2d& K = lin.K;
  const Eigen::Matrix2d& C = lin.C;

  nlohmann::json j;
  j["input"] = {{"diameter_m", D}, {"length_m", L}, {"l_over_d", L / D}, {"clearance_m", c},
                {"viscosity_pa_s", eta}, {"speed_rad_s", w}, {"outer_speed_rad_s", w_out},
                {"eccentricity_ratio", o.eccentricity}, {"attitude_of_eccentricity_rad", att},
                {"cavitation", o.cavitation}, {"n_circ", o.n_circ}, {"n_axial", o.n_axial},
                {"hole_diameter_m", hole}, {"groove_width_m", groove},
                {"supply_pressure_pa", supply}};
  j["force_on_journal_n"] = {base.fx, base.fy};
  j["load_n"] = W;
  if (W > 0.0) {
    // Load carried = -film force; attitude angle between the load line and the eccentricity vector.
    const double load_angle = std::atan2(-base.fy, -base.fx);
    const double phi = std::remainder(att - load_angle, 2 * M_PI);
    // Speed of the equivalent journal in a stationary bush (the pressure depends on the sum of the surface speeds).
    const double N = std::abs(w + w_out) / (2 * M_PI);
    const double P = W / (2 * R * L);
    j["sommerfeld_number"] = (R / c) * (R / c) * eta * N / P;
    j["attitude_angle_deg"] = std::abs(phi) * 180 / M_PI;
    j["friction_variable"] = (R / c) * (std::abs(base.torque_inner) / R) / W;
    j["stiffness_n_per_m"] = {{K(0, 0), K(0, 1)}, {K(1, 0), K(1, 1)}};
    j["damping_n_s_per_m"] = {{C(0, 0), C(0, 1)}, {C(1, 0), C(1, 1)}};
    j["stiffness_dimensionless"] = {{K(0, 0) * c / W, K(0, 1) * c / W}, {K(1, 0) * c / W, K(1, 1) * c / W}};
    const double cw = c * std::max(std::abs(w), 1e-12) / W;
    j["damping_dimensionless"] = {{C(0, 0) * cw, C(0, 1) * cw}, {C(1, 0) * cw, C(1, 1) * cw}};
  }
  j["moment_on_journal_n_m"] = {base.mx, base.my};
  j["torque_on_journal_n_m"] = base.torque_inner;
  j["torque_on_bush_n_m"] = base.torque_outer;
  j["friction_power_w"] = -base.torque_inner * w - base.torque_outer * w_out;
  j["flow_out_of_ends_m3_s"] = base.flow_ends;
  j["flow_into_holes_m3_s"] = base.hole_flows;
  // The thinnest point of the film: h0 = c (1 - e/c) for the journal parallel to the bush (Raimondi & Boyd's
  // minimum film thickness variable h0/c = 1 - e/c).
  j["min_film_thickness_m"] = min_film_thickness(g, s);
  j["max_pressure_pa"] = base.max_pressure;
  j["cavitated_fraction"] = base.cavitated_fraction;
  std::cout << std::setw(2) << j << "\n";
  return 0;
}

}  // namespace turbodyn::app

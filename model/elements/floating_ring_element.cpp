#include "model/elements/floating_ring_element.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace turbodyn {

struct FloatingRingElement::Films {
  reynolds::FilmResult inner, outer;  ///< the inner film's force, moment rotated into the housing frame
  double hole_pressure = 0.0;         ///< Pa gauge, mean over the drill holes' inner mouths
};

namespace {

struct RingWorkspace : ElementWorkspace {
  RingWorkspace(reynolds::FilmSolver i, reynolds::FilmSolver o) : inner(std::move(i)), outer(std::move(o)) {
    films.inner.hole_flows.reserve(8);
    films.outer.hole_flows.reserve(8);
    jac_inner.hole_flows.reserve(8);
    jac_outer.hole_flows.reserve(8);
    probe_outer.hole_flows.reserve(8);
    for (reynolds::FilmResult& r : jac_rate_outer) r.hole_flows.reserve(8);
  }
  reynolds::FilmSolver inner, outer;
  FloatingRingElement::Films films;
  RingWorkspace(reynolds::FilmSolver i, reynolds::FilmSolver o, int states)
      : RingWorkspace(std::move(i), std::move(o)) {
    key = EvaluationKey(4, states);
  }
  EvaluationKey key{4, FloatingRingElement::kStates};  // the state of `films`
  bool solvers_at_key = false;  // the solvers' last solves (factorisations, pressures) are those of `films`
  // Jacobian scratch: perturbed films, and the outer films and drill-hole pressures of the ring's rate columns.
  reynolds::FilmResult jac_inner, jac_outer, jac_rate_outer[5];
  reynolds::FilmResult probe_outer;  // the outer film of the last probe evaluation without the heat balance
  std::array<double, 8> jac_rate_holes[5];
};

// Rotates (x, y) by angle a (c = cos a, s = sin a).
inline void rotate(double c, double s, double& x, double& y) {
  const double xr = c * x - s * y;
  y = s * x + c * y;
  x = xr;
}

// Gauge pressure of a solved film at mid-width, angle theta (film frame), linearly interpolated.
double midwidth_pressure(const reynolds::FilmSolver& solver, double theta) {
  const reynolds::FilmGeometry& g = solver.geometry();
  const int n = g.n_circ, nz = g.n_axial;
  double u = theta / (2.0 * M_PI);
  u = (u - std::floor(u)) * n;
  const int i0 = std::min(static_cast<int>(u), n - 1), i1 = (i0 + 1) % n;
  const double w = u - i0;
  // Nodes at z_j = -L/2 + (j + 1) L / (nz + 1): mid-width is node (nz - 1) / 2 for odd nz, halfway between the
  // two middle nodes for even nz.
  const int ja = (nz - 1) / 2, jb = nz / 2;
  auto at = [&](int i) { return 0.5 * (solver.node_pressure(i, ja) + solver.node_pressure(i, jb)); };
  return (1.0 - w) * at(i0) + w * at(i1);
}

}  // namespace

FloatingRingElement::FloatingRingElement(const std::string& name, const FloatingRingSpec& spec, const OilSpec& oil,
                                         int node_dof, double gravity)
    : ForceElement(name, {node_dof, node_dof + 1, node_dof + 2, node_dof + 3},
                   spec.thermal.model == FilmThermal::Bulk ? kMaxStates : kStates),
      spec_(spec),
      oil_(oil),
      thermal_(spec.thermal.model == FilmThermal::Bulk),
      gravity_(gravity),
      density_(oil.density) {
  inner_.radius = 0.5 * spec.inner_diameter;
  inner_.length = spec.inner_length;
  inner_.clearance = spec.inner_clearance;
  outer_.radius = 0.5 * spec.outer_diameter;
  outer_.length = spec.outer_length;
  outer_.clearance = spec.outer_clearance;
  for (reynolds::FilmGeometry* g : {&inner_, &outer_}) {
    g->n_circ = spec.n_circ;
    g->n_axial = spec.n_axial;
  }
  if (spec.feed_hole_diameter > 0.0)
    outer_.holes.push_back({spec.feed_hole_angle, 0.0, spec.feed_hole_diameter, spec.supply_pressure});
  if (spec.feed_groove_width > 0.0) outer_.grooves.push_back({0.0, spec.feed_groove_width, spec.supply_pressure});
  if (spec.drill_holes > 8) throw std::invalid_argument("floating-ring bearing: at most 8 drill holes");
  for (int k = 0; k < spec.drill_holes; ++k)
    inner_.holes.push_back({spec.drill_hole_angle + 2.0 * M_PI * k / spec.drill_holes, 0.0, spec.drill_hole_diameter,
                            0.0});
  options_.cavitation = spec.cavitation;
  options_.axial_grading = spec.axial_grading;
  eta_inner_ = oil.viscosity_at(oil.temperature_or(spec.inner_oil_temperature));
  eta_outer_ = oil.viscosity_at(oil.temperature_or(spec.outer_oil_temperature));
  if (thermal_) {
    const RingThermalSpec& t = spec.thermal;
    if (oil.viscosity > 0.0)
      throw std::invalid_argument("thermal films need a temperature-dependent viscosity (the [oil] Vogel law), not "
                                  "a fixed [oil] viscosity");
    if (!(t.inner_heat_capacity > 0.0 && t.outer_heat_capacity > 0.0 && t.oil_specific_heat > 0.0))
      throw std::invalid_argument("thermal films need positive heat capacities");
    if (!(t.inner_shaft_conductance >= 0.0 && t.ring_conductance >= 0.0 && t.outer_housing_conductance >= 0.0))
      throw std::invalid_argument("thermal films need non-negative conductances");
    eta_inner_ = eta_outer_ = oil.viscosity_at(t.supply_temperature);
  }
  inertia_diametral_ = spec.ring_diametral_inertia;
  if (inertia_diametral_ <= 0.0) {
    // Thick-walled cylinder: bore D_i + 2 c_i, outside D_o - 2 c_o, width of the outer film.
    const double ri = 0.5 * spec.inner_diameter + spec.inner_clearance;
    const double ro = 0.5 * spec.outer_diameter - spec.outer_clearance;
    const double b = spec.outer_length;
    inertia_diametral_ = spec.ring_mass * (3.0 * (ro * ro + ri * ri) + b * b) / 12.0;
  }
  reynolds::FilmSolver a(inner_, eta_inner_, options_), c(outer_, eta_outer_, options_);  // fail now, not mid-run
}

std::unique_ptr<ElementWorkspace> FloatingRingElement::make_workspace() const {
  return std::make_unique<RingWorkspace>(reynolds::FilmSolver(inner_, eta_inner_, options_),
                                         reynolds::FilmSolver(outer_, eta_outer_, options_), n_states());
}

void FloatingRingElement::initial_states(double* z) const {
  std::fill(z, z + n_states(), 0.0);
  if (thermal_) z[kInnerTemperature] = z[kOuterTemperature] = spec_.thermal.supply_temperature;
}

double FloatingRingElement::state_scale(int i) const {
  // Translations 1 um and 1 mm/s (ForceElement's typical displacement and velocity); tilts and their rates as the
  // rotations that move the ring's wider film's edges by as much (the films see a tilt only through the thickness
  // at z = +-L/2), so every state of the ring is resolved to the same film-thickness error; spin 10 rad/s, angle
  // 1 rad, temperatures 1 K.
  const double half_width = 0.5 * std::max(spec_.inner_length, spec_.outer_length);
  switch (i) {
    case kX: case kY: return kTypicalDisplacement;
    case kVx: case kVy: return kTypicalVelocity;
    case kAx: case kAy: return kTypicalDisplacement / half_width;
    case kWx: case kWy: return kTypicalVelocity / half_width;
    case kSpin: return 10.0;
    default: return 1.0;  // angle (rad), temperatures (K)
  }
}

double FloatingRingElement::film_viscosity(double T, const char* which) const {
  if (!(T <= spec_.thermal.max_temperature) || !(T - 273.15 + oil_.vogel_c > 0.0)) {
    std::ostringstream os;
    os << "floating-ring bearing '" << name() << "': the " << which << " film's temperature " << T - 273.15
       << " degC lies outside the oil's viscosity law (above [oil] max_temperature = "
       << spec_.thermal.max_temperature - 273.15 << " degC, or at its Vogel pole); the film overheats: more oil "
       << "flow or conduction (docs/thermal-films.md)";
    throw std::runtime_error(os.str());
  }
  return oil_.viscosity_at(T);
}

void FloatingRingElement::set_viscosities(reynolds::FilmSolver& inner, reynolds::FilmSolver& outer,
                                          const double* z) const {
  if (!thermal_) return;
  inner.set_viscosity(film_viscosity(z[kInnerTemperature], "inner"));
  outer.set_viscosity(film_viscosity(z[kOuterTemperature], "outer"));
}

double FloatingRingElement::centrifugal_head(double w_r) const {
  if (!spec_.drill_hole_centrifugal) return 0.0;
  const double ro = 0.5 * spec_.outer_diameter, ri = 0.5 * spec_.inner_diameter;
  return 0.5 * density_ * w_r * w_r * (ro * ro - ri * ri);
}

reynolds::FilmState FloatingRingElement::outer_state(const double* z) const {
  // The ring in the housing, housing frame.
  reynolds::FilmState out;
  out.ex = z[kX];
  out.ey = z[kY];
  out.vx = z[kVx];
  out.vy = z[kVy];
  out.sx = z[kAy];  // slopes of the ring axis: dx/dz = ay, dy/dz = -ax
  out.sy = -z[kAx];
  out.dsx = z[kWy];
  out.dsy = -z[kWx];
  out.omega_inner = z[kSpin];
  return out;
}

reynolds::FilmState FloatingRingElement::inner_state(const SpinState& s, const double* q, const double* v,
                                                     const double* z, const double* holes) const {
  // The journal relative to the ring, in the ring frame (rotated by -phi_r). A vector e fixed in the housing frame
  // appears as e' = R(-phi) e, with rate R(-phi) e' - w_r J e' (J the quarter turn).
  const double wr = z[kSpin];
  const double c = std::cos(z[kAngle]), sn = std::sin(z[kAngle]);
  reynolds::FilmState in;
  in.ex = q[0] - z[kX];
  in.ey = q[1] - z[kY];
  in.vx = v[0] - z[kVx];
  in.vy = v[1] - z[kVy];
  in.sx = q[3] - z[kAy];
  in.sy = -q[2] + z[kAx];
  in.dsx = v[3] - z[kWy];
  in.dsy = -v[2] + z[kWx];
  rotate(c, -sn, in.ex, in.ey);
  rotate(c, -sn, in.vx, in.vy);
  rotate(c, -sn, in.sx, in.sy);
  rotate(c, -sn, in.dsx, in.dsy);
  in.vx += wr * in.ey;
  in.vy -= wr * in.ex;
  in.dsx += wr * in.sy;
  in.dsy -= wr * in.sx;
  in.omega_inner = s.speed - wr;
  in.omega_outer = 0.0;
  if (!inner_.holes.empty()) {
    in.use_override = true;
    for (std::size_t k = 0; k < inner_.holes.size(); ++k) in.hole_pressure_override[k] = holes[k];
  }
  return in;
}

void FloatingRingElement::drill_hole_pressures(const reynolds::FilmSolver& outer, const double* z,
                                               double* holes) const {
  const double head = centrifugal_head(z[kSpin]);
  for (std::size_t k = 0; k < inner_.holes.size(); ++k) {
    const double p_outer = midwidth_pressure(outer, z[kAngle] + inner_.holes[k].theta);
    holes[k] = std::max(p_outer - head, inner_.cavitation_pressure);
  }
}

double FloatingRingElement::mean_hole_pressure(const double* holes) const {
  double sum = 0.0;
  for (std::size_t k = 0; k < inner_.holes.size(); ++k) sum += holes[k];
  return inner_.holes.empty() ? 0.0 : sum / inner_.holes.size();
}

const FloatingRingElement::Films& FloatingRingElement::Solve(const SpinState& s, const double* q, const double* v,
                                                             const double* z, ElementWorkspace& ws) const {
  auto& w = static_cast<RingWorkspace&>(ws);
  if (w.key.matches(s.speed, q, v, z)) return w.films;
  w.key.invalidate();
  set_viscosities(w.inner, w.outer, z);
  if (!w.outer.solve(outer_state(z), w.films.outer))
    throw std::runtime_error("floating-ring bearing '" + name() + "', outer film: " + w.outer.last_error());
  double holes[8];
  drill_hole_pressures(w.outer, z, holes);
  if (!w.inner.solve(inner_state(s, q, v, z, holes), w.films.inner))
    throw std::runtime_error("floating-ring bearing '" + name() + "', inner film: " + w.inner.last_error());
  reynolds::FilmResult& i = w.films.inner;
  const double c = std::cos(z[kAngle]), sn = std::sin(z[kAngle]);
  rotate(c, sn, i.fx, i.fy);
  rotate(c, sn, i.mx, i.my);
  w.films.hole_pressure = mean_hole_pressure(holes);
  w.key.set(s.speed, q, v, z);
  w.solvers_at_key = true;
  return w.films;
}

thermal::FilmHeatInputs FloatingRingElement::film_heat(const SpinState& s, const double* v,
                                                      const reynolds::FilmResult& i, const reynolds::FilmResult& o,
                                                      const double* z) const {
  // Each film turns into heat the power of its forces, moments and torques on the bodies it separates, with the
  // sign reversed (the housing is fixed): the split of dissipated_power() by film.
  thermal::FilmHeatInputs h;
  h.inner_power = -(i.fx * v[0] + i.fy * v[1] + i.mx * v[2] + i.my * v[3] + i.torque_inner * s.speed -
                    i.fx * z[kVx] - i.fy * z[kVy] - i.mx * z[kWx] - i.my * z[kWy] + i.torque_outer * z[kSpin]);
  h.outer_power = -(o.fx * z[kVx] + o.fy * z[kVy] + o.mx * z[kWx] + o.my * z[kWy] + o.torque_inner * z[kSpin]);
  h.inner_flow = i.flow_ends;
  h.outer_flow = o.flow_ends;
  if (thermal_) {
    h.inner_temperature = z[kInnerTemperature];
    h.outer_temperature = z[kOuterTemperature];
  } else {
    h.inner_temperature = oil_.temperature_or(spec_.inner_oil_temperature);
    h.outer_temperature = oil_.temperature_or(spec_.outer_oil_temperature);
  }
  return h;
}

void FloatingRingElement::loads(const SpinState& s, const double* v, const reynolds::FilmResult& i,
                                const reynolds::FilmResult& o, const double* z, double* f, double* zdot) const {
  f[0] += i.fx;
  f[1] += i.fy;
  f[2] += i.mx;
  f[3] += i.my;
  const double m = spec_.ring_mass, ip = spec_.ring_polar_inertia, id = inertia_diametral_;
  zdot[kX] = z[kVx];
  zdot[kY] = z[kVy];
  zdot[kVx] = (-i.fx + o.fx) / m;
  zdot[kVy] = (-i.fy + o.fy) / m - gravity_;
  // Torque on the ring: from the inner film on its bore (the film's outer surface) and from the outer film on its
  // outer surface (that film's inner surface).
  const double wr = z[kSpin], dwr = (i.torque_outer + o.torque_inner) / ip;
  zdot[kSpin] = dwr;
  zdot[kAngle] = wr;
  if (spec_.ring_tilt) {
    zdot[kAx] = z[kWx];
    zdot[kAy] = z[kWy];
    zdot[kWx] = (-i.mx + o.mx - ip * (wr * z[kWy] + dwr * z[kAy])) / id;
    zdot[kWy] = (-i.my + o.my + ip * (wr * z[kWx] + dwr * z[kAx])) / id;
  } else {
    zdot[kAx] = zdot[kAy] = zdot[kWx] = zdot[kWy] = 0.0;
  }
  if (thermal_) {
    const thermal::FilmHeatFlows h =
        thermal::film_heat_balance(spec_.thermal, density_, !inner_.holes.empty(), film_heat(s, v, i, o, z));
    zdot[kInnerTemperature] = h.inner_rate;
    zdot[kOuterTemperature] = h.outer_rate;
  }
}

void FloatingRingElement::do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z,
                                             ElementWorkspace& ws, double* f, double* zdot) const {
  const Films& films = Solve(s, q, v, z, ws);
  loads(s, v, films.inner, films.outer, z, f, zdot);
}

void FloatingRingElement::add_jacobian(const SpinState& s, const double* q, const double* v, const double* z,
                                       ElementWorkspace& ws, double* J) const {
  auto& w = static_cast<RingWorkspace&>(ws);
  constexpr int d = 4, kMaxRows = d + kMaxStates, kMaxCols = 2 * d + kMaxStates;
  const int m = n_states(), rows = d + m, cols = 2 * d + m;
  // The films at the state, with the solvers holding their factorisations (a Jacobian at the same state before
  // left them at perturbed states).
  if (!w.solvers_at_key) w.key.invalidate();
  const Films& base = Solve(s, q, v, z, ws);
  double out0[kMaxRows] = {};
  loads(s, v, base.inner, base.outer, z, out0, out0 + d);
  double holes0[8], holes_angle[8];
  drill_hole_pressures(w.outer, z, holes0);
  // Inputs [q; v; z] and their steps.
  double in[kMaxCols], step[kMaxCols];
  for (int k = 0; k < d; ++k) in[k] = q[k], in[d + k] = v[k];
  for (int k = 0; k < m; ++k) in[2 * d + k] = z[k];
  for (int j = 0; j < cols; ++j) step[j] = fd_step(j, d, in[j]);
  const double* qp = in;
  const double* vp = in + d;
  const double* zp = in + 2 * d;
  {
    const double saved = in[2 * d + kAngle];
    in[2 * d + kAngle] = saved + step[2 * d + kAngle];
    drill_hole_pressures(w.outer, zp, holes_angle);  // the base outer film seen from the turned ring
    in[2 * d + kAngle] = saved;
  }
  w.solvers_at_key = false;

  // A film re-solved for a perturbed state with the base factorisation and cavitated set while the solver still
  // holds them: exactly if only velocities, speeds or hole pressures changed (kSameMatrix), by one Newton step
  // from the base pressure if the thickness changed too (kLinearised, first order in the step: the derivative for
  // the base cavitated set, like the other columns). Anew otherwise (the viscosity changed).
  enum Reuse { kSameMatrix, kLinearised, kNone };
  bool inner_base = true, outer_base = true;
  auto film = [&](reynolds::FilmSolver& solver, bool& at_base, const reynolds::FilmState& st, Reuse reuse,
                  reynolds::FilmResult& r, const char* which) {
    if (at_base && reuse == kSameMatrix && solver.solve_same_matrix(st, r)) return;
    if (at_base && reuse == kLinearised && solver.solve_linearised(st, r)) return;
    at_base = false;
    if (!solver.solve(st, r))
      throw std::runtime_error("floating-ring bearing '" + name() + "', " + which + " film: " + solver.last_error());
  };
  auto column = [&](int j, const reynolds::FilmResult& inner, const reynolds::FilmResult& outer) {
    double out[kMaxRows] = {};
    loads(s, vp, inner, outer, zp, out, out + d);
    for (int r = 0; r < rows; ++r) J[j * rows + r] += (out[r] - out0[r]) / step[j];
  };
  // The inner film at the perturbed inputs, rotated into the housing frame, into w.jac_inner.
  auto inner = [&](const double* holes, Reuse reuse) -> const reynolds::FilmResult& {
    film(w.inner, inner_base, inner_state(s, qp, vp, zp, holes), reuse, w.jac_inner, "inner");
    const double c = std::cos(zp[kAngle]), sn = std::sin(zp[kAngle]);
    rotate(c, sn, w.jac_inner.fx, w.jac_inner.fy);
    rotate(c, sn, w.jac_inner.mx, w.jac_inner.my);
    return w.jac_inner;
  };
  const bool tilt = spec_.ring_tilt;
  auto skip = [&](int k) { return !tilt && (k == kAx || k == kAy || k == kWx || k == kWy); };

  // 1. The ring's rates and spin change the outer film's right-hand side only: back-substitutions. Their drill-hole
  //    pressures are read from each outer solution before the next.
  constexpr int kRates[5] = {kVx, kVy, kWx, kWy, kSpin};
  for (int a = 0; a < 5; ++a) {
    const int k = kRates[a], j = 2 * d + k;
    w.jac_rate_holes[a].fill(0.0);
    if (skip(k)) continue;
    const double saved = in[j];
    in[j] = saved + step[j];
    film(w.outer, outer_base, outer_state(zp), kSameMatrix, w.jac_rate_outer[a], "outer");
    drill_hole_pressures(w.outer, zp, w.jac_rate_holes[a].data());
    in[j] = saved;
  }
  // 2. Columns that change the inner film's right-hand side only: the shaft's velocities (outer film unchanged)
  //    and the ring's rates and spin (with their outer films from 1.).
  for (int k = 0; k < d; ++k) {
    const int j = d + k;
    const double saved = in[j];
    in[j] = saved + step[j];
    column(j, inner(holes0, kSameMatrix), base.outer);
    in[j] = saved;
  }
  for (int a = 0; a < 5; ++a) {
    const int k = kRates[a], j = 2 * d + k;
    if (skip(k)) continue;
    const double saved = in[j];
    in[j] = saved + step[j];
    column(j, inner(w.jac_rate_holes[a].data(), kSameMatrix), w.jac_rate_outer[a]);
    in[j] = saved;
  }
  // 3. The shaft's displacements and the ring angle change the inner film's thickness (the outer film does not
  //    depend on them): linearised inner solves.
  for (int k = 0; k < d; ++k) {
    const double saved = in[k];
    in[k] = saved + step[k];
    column(k, inner(holes0, kLinearised), base.outer);
    in[k] = saved;
  }
  {
    const int j = 2 * d + kAngle;
    const double saved = in[j];
    in[j] = saved + step[j];
    column(j, inner(holes_angle, kLinearised), base.outer);
    in[j] = saved;
  }
  // 4. The ring's displacements and tilts change both films' thickness: linearised solves of both.
  constexpr int kPositions[4] = {kX, kY, kAx, kAy};
  for (int k : kPositions) {
    if (skip(k)) continue;
    const int j = 2 * d + k;
    const double saved = in[j];
    in[j] = saved + step[j];
    film(w.outer, outer_base, outer_state(zp), kLinearised, w.jac_outer, "outer");
    double holes[8];
    drill_hole_pressures(w.outer, zp, holes);
    column(j, inner(holes, kLinearised), w.jac_outer);
    in[j] = saved;
  }
  // 5. The film temperatures change one film's viscosity each (and through the drill holes' pressures the outer
  //    one changes the inner film too): new solves, at the perturbed viscosity, then the base viscosity back.
  if (thermal_) {
    for (const int k : {kInnerTemperature, kOuterTemperature}) {
      const int j = 2 * d + k;
      const double saved = in[j];
      in[j] = saved + step[j];
      set_viscosities(w.inner, w.outer, zp);
      const reynolds::FilmResult* outer = &base.outer;
      double holes[8];
      std::copy(holes0, holes0 + inner_.holes.size(), holes);
      if (k == kOuterTemperature) {
        film(w.outer, outer_base, outer_state(zp), kNone, w.jac_outer, "outer");
        drill_hole_pressures(w.outer, zp, holes);
        outer = &w.jac_outer;
      }
      column(j, inner(holes, kNone), *outer);
      in[j] = saved;
    }
    set_viscosities(w.inner, w.outer, z);
  }
}

std::vector<ProbeInfo> FloatingRingElement::probes() const {
  const std::string who = "bearing '" + name() + "': ";
  std::vector<ProbeInfo> p =
      housing_force_probes(who, "", {{"ring_speed_ratio", "1", "ring speed / rotor speed"},
                                     {"inner_eccentricity", "1", "inner-film eccentricity ratio at mid-width"},
                                     {"outer_eccentricity", "1", "outer-film eccentricity ratio at mid-width"},
                                     {"ring_tilt", "rad", "ring tilt against the housing (magnitude)"},
                                     {"drill_hole_pressure", "Pa",
                                      "pressure at the drill holes' inner mouths, mean over the holes"},
                                     min_film_probe("inner_min_film_thickness", "inner", spec_.film_thickness_limit),
                                     min_film_probe("outer_min_film_thickness", "outer", spec_.film_thickness_limit)});
  if (thermal_) {
    const std::vector<ProbeInfo> more = {
        {"inner_temperature", "K", "inner-film temperature"},
        {"outer_temperature", "K", "outer-film temperature"},
        {"inner_power_loss", "W", "power dissipated in the inner film"},
        {"outer_power_loss", "W", "power dissipated in the outer film"},
        {"inner_side_flow", "m^3/s", "oil leaving the inner film at its ends"},
        {"outer_side_flow", "m^3/s", "oil leaving the outer film at its ends"},
        {"heat_to_oil", "W", "heat the oil carries out of the bearing (over the supply temperature)"},
        {"heat_conducted", "W", "heat conducted from the films into shaft and housing"},
        {"stored_heat", "J", "heat stored in the films and the ring above the supply temperature"}};
    append_probes(p, who, more);
  }
  return p;
}

FloatingRingElement::Heat FloatingRingElement::heat(const SpinState& s, const double* q, const double* v,
                                                    const double* z, ElementWorkspace& ws) const {
  const Films& films = Solve(s, q, v, z, ws);
  Heat h;
  h.films = film_heat(s, v, films.inner, films.outer, z);
  if (thermal_) h.flows = thermal::film_heat_balance(spec_.thermal, density_, !inner_.holes.empty(), h.films);
  h.drill_hole_pressure = films.hole_pressure;
  return h;
}

void FloatingRingElement::eval_probes(const SpinState& s, const double* q, const double* v, const double* z,
                                     ElementWorkspace& ws, double* out) const {
  auto& w = static_cast<RingWorkspace&>(ws);
  const reynolds::FilmResult* outer = nullptr;
  double hole_pressure = 0.0;
  const Films* films = nullptr;
  if (thermal_ || w.key.matches(s.speed, q, v, z)) {
    films = &Solve(s, q, v, z, ws);
    outer = &films->outer;
    hole_pressure = films->hole_pressure;
  } else {
    // Without the heat balance every probe comes from the outer film (the housing force, the drill holes'
    // pressure) and the ring's state: the inner film, half the cost of a probe, is not solved. The solvers then no
    // longer hold the films of the key's state.
    w.key.invalidate();
    w.solvers_at_key = false;
    if (!w.outer.solve(outer_state(z), w.probe_outer))
      throw std::runtime_error("floating-ring bearing '" + name() + "', outer film: " + w.outer.last_error());
    double holes[8];
    drill_hole_pressures(w.outer, z, holes);
    outer = &w.probe_outer;
    hole_pressure = mean_hole_pressure(holes);
  }
  out[0] = -outer->fx;
  out[1] = -outer->fy;
  out[2] = s.speed != 0.0 ? z[kSpin] / s.speed : 0.0;
  out[3] = std::hypot(q[0] - z[kX], q[1] - z[kY]) / spec_.inner_clearance;
  out[4] = std::hypot(z[kX], z[kY]) / spec_.outer_clearance;
  out[5] = std::hypot(z[kAx], z[kAy]);
  out[6] = hole_pressure;
  // The inner film's thinnest point needs only the journal's offset and slopes against the ring, the same in the
  // housing frame as in the ring's.
  reynolds::FilmState in;
  in.ex = q[0] - z[kX];
  in.ey = q[1] - z[kY];
  in.sx = q[3] - z[kAy];
  in.sy = -q[2] + z[kAx];
  out[7] = reynolds::min_film_thickness(inner_, in);
  out[8] = reynolds::min_film_thickness(outer_, outer_state(z));
  if (thermal_) {
    const thermal::FilmHeatInputs h = film_heat(s, v, films->inner, films->outer, z);
    const thermal::FilmHeatFlows b = thermal::film_heat_balance(spec_.thermal, density_, !inner_.holes.empty(), h);
    out[9] = h.inner_temperature;
    out[10] = h.outer_temperature;
    out[11] = h.inner_power;
    out[12] = h.outer_power;
    out[13] = h.inner_flow;
    out[14] = h.outer_flow;
    out[15] = b.oil();
    out[16] = b.conducted();
    out[17] = thermal::stored_heat(spec_.thermal, h.inner_temperature, h.outer_temperature);
  }
}

double FloatingRingElement::kinetic_energy(const double* z) const {
  return 0.5 * spec_.ring_mass * (z[kVx] * z[kVx] + z[kVy] * z[kVy]) +
         0.5 * inertia_diametral_ * (z[kWx] * z[kWx] + z[kWy] * z[kWy]) +
         0.5 * spec_.ring_polar_inertia * z[kSpin] * z[kSpin];
}

double FloatingRingElement::potential_energy(const double*, const double* z) const {
  return spec_.ring_mass * gravity_ * z[kY];
}

double FloatingRingElement::dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                                            ElementWorkspace& ws) const {
  // All the films turn into heat: minus the power of their forces, moments and torques on the shaft and the ring
  // (the housing is fixed).
  const Films& films = Solve(s, q, v, z, ws);
  const reynolds::FilmResult& i = films.inner;
  const reynolds::FilmResult& o = films.outer;
  const double shaft = i.fx * v[0] + i.fy * v[1] + i.mx * v[2] + i.my * v[3] + i.torque_inner * s.speed;
  const double ring = (-i.fx + o.fx) * z[kVx] + (-i.fy + o.fy) * z[kVy] + (-i.mx + o.mx) * z[kWx] +
                      (-i.my + o.my) * z[kWy] + (i.torque_outer + o.torque_inner) * z[kSpin];
  return -(shaft + ring);
}

double FloatingRingElement::drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                                       ElementWorkspace& ws) const {
  return -Solve(s, q, v, z, ws).inner.torque_inner * s.speed;
}

}  // namespace turbodyn

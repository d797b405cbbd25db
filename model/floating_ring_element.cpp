#include "model/floating_ring_element.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace turbodyn {

struct FloatingRingElement::Films {
  reynolds::FilmResult inner, outer;
};

namespace {

struct RingWorkspace : ElementWorkspace {
  RingWorkspace(reynolds::FilmSolver i, reynolds::FilmSolver o) : inner(std::move(i)), outer(std::move(o)) {
    films.inner.hole_flows.reserve(8);
    films.outer.hole_flows.reserve(8);
  }
  reynolds::FilmSolver inner, outer;
  FloatingRingElement::Films films;
  double key[14] = {};  // inputs of `films`: speed, q[4], v[4], z[5]
  bool valid = false;
};

}  // namespace

FloatingRingElement::FloatingRingElement(const std::string& name, const FloatingRingSpec& spec, const OilSpec& oil,
                                         int node_dof, double gravity)
    : ForceElement(name, {node_dof, node_dof + 1, node_dof + 2, node_dof + 3}, 5), spec_(spec), gravity_(gravity) {
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
  if (!reynolds::cavitation_from_string(spec.cavitation, options_.cavitation))
    throw std::logic_error("unknown cavitation model '" + spec.cavitation + "'");
  eta_inner_ = oil.viscosity_at(spec.inner_oil_temperature > 0 ? spec.inner_oil_temperature : oil.temperature);
  eta_outer_ = oil.viscosity_at(spec.outer_oil_temperature > 0 ? spec.outer_oil_temperature : oil.temperature);
  reynolds::FilmSolver a(inner_, eta_inner_, options_), b(outer_, eta_outer_, options_);  // fail now, not mid-run
}

std::unique_ptr<ElementWorkspace> FloatingRingElement::make_workspace() const {
  return std::make_unique<RingWorkspace>(reynolds::FilmSolver(inner_, eta_inner_, options_),
                                         reynolds::FilmSolver(outer_, eta_outer_, options_));
}

const FloatingRingElement::Films& FloatingRingElement::Solve(const SpinState& s, const double* q, const double* v,
                                                             const double* z, ElementWorkspace& ws) const {
  auto& w = static_cast<RingWorkspace&>(ws);
  double key[14] = {s.speed};
  std::memcpy(key + 1, q, 4 * sizeof(double));
  std::memcpy(key + 5, v, 4 * sizeof(double));
  std::memcpy(key + 9, z, 5 * sizeof(double));
  static_assert(sizeof(key) == sizeof(w.key));
  if (w.valid && std::memcmp(key, w.key, sizeof key) == 0) return w.films;
  w.valid = false;
  reynolds::FilmState in;  // journal (shaft) relative to the ring; the ring does not tilt in this version
  in.ex = q[0] - z[0];
  in.ey = q[1] - z[1];
  in.vx = v[0] - z[2];
  in.vy = v[1] - z[3];
  in.sx = q[3];
  in.sy = -q[2];
  in.dsx = v[3];
  in.dsy = -v[2];
  in.omega_inner = s.speed;
  in.omega_outer = z[4];
  reynolds::FilmState out;  // ring relative to the housing
  out.ex = z[0];
  out.ey = z[1];
  out.vx = z[2];
  out.vy = z[3];
  out.omega_inner = z[4];
  if (!w.inner.solve(in, w.films.inner))
    throw std::runtime_error("floating-ring bearing '" + name() + "', inner film: " + w.inner.last_error());
  if (!w.outer.solve(out, w.films.outer))
    throw std::runtime_error("floating-ring bearing '" + name() + "', outer film: " + w.outer.last_error());
  std::memcpy(w.key, key, sizeof key);
  w.valid = true;
  return w.films;
}

void FloatingRingElement::DoCalcAndAddForces(const SpinState& s, const double* q, const double* v, const double* z,
                                             ElementWorkspace& ws, double* f, double* zdot) const {
  const Films& films = Solve(s, q, v, z, ws);
  const reynolds::FilmResult& i = films.inner;
  const reynolds::FilmResult& o = films.outer;
  f[0] += i.fx;
  f[1] += i.fy;
  f[2] += i.mx;
  f[3] += i.my;
  const double m = spec_.ring_mass;
  zdot[0] = z[2];
  zdot[1] = z[3];
  zdot[2] = (-i.fx + o.fx) / m;
  zdot[3] = (-i.fy + o.fy) / m - gravity_;
  // Torque on the ring: from the inner film on its bore (the film's outer surface) and from the outer film on its
  // outer surface (that film's inner surface).
  zdot[4] = (i.torque_outer + o.torque_inner) / spec_.ring_polar_inertia;
}

std::vector<ProbeInfo> FloatingRingElement::probes() const {
  const std::string who = "bearing '" + name() + "': ";
  return {{"fx", "N", who + "force transmitted to the housing, horizontal (x)"},
          {"fy", "N", who + "force transmitted to the housing, vertical (y)"},
          {"ring_speed_ratio", "1", who + "ring speed / rotor speed"},
          {"inner_eccentricity", "1", who + "inner-film eccentricity ratio"},
          {"outer_eccentricity", "1", who + "outer-film eccentricity ratio"}};
}

void FloatingRingElement::EvalProbes(const SpinState& s, const double* q, const double* v, const double* z,
                                     ElementWorkspace& ws, double* out) const {
  const Films& films = Solve(s, q, v, z, ws);
  out[0] = -films.outer.fx;
  out[1] = -films.outer.fy;
  out[2] = s.speed != 0.0 ? z[4] / s.speed : 0.0;
  out[3] = std::hypot(q[0] - z[0], q[1] - z[1]) / spec_.inner_clearance;
  out[4] = std::hypot(z[0], z[1]) / spec_.outer_clearance;
}

double FloatingRingElement::KineticEnergy(const double* z) const {
  return 0.5 * spec_.ring_mass * (z[2] * z[2] + z[3] * z[3]) + 0.5 * spec_.ring_polar_inertia * z[4] * z[4];
}

double FloatingRingElement::PotentialEnergy(const double*, const double* z) const {
  return spec_.ring_mass * gravity_ * z[1];
}

double FloatingRingElement::DissipatedPower(const SpinState& s, const double* q, const double* v, const double* z,
                                            ElementWorkspace& ws) const {
  // Power the films take out of the lateral motion and the ring spin (the drive supplies the rotor spin):
  // minus the power of the film forces and torques on the shaft's lateral DOFs and on the ring.
  const Films& films = Solve(s, q, v, z, ws);
  const reynolds::FilmResult& i = films.inner;
  const reynolds::FilmResult& o = films.outer;
  const double shaft = i.fx * v[0] + i.fy * v[1] + i.mx * v[2] + i.my * v[3];
  const double ring = (-i.fx + o.fx) * z[2] + (-i.fy + o.fy) * z[3] + (i.torque_outer + o.torque_inner) * z[4];
  return -(shaft + ring);
}

}  // namespace turbodyn

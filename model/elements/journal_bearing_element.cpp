#include "model/elements/journal_bearing_element.h"

#include <cmath>
#include <stdexcept>

namespace turbodyn {
namespace {

struct JournalWorkspace : ElementWorkspace {
  explicit JournalWorkspace(reynolds::FilmSolver s) : solver(std::move(s)) { result.hole_flows.reserve(8); }
  reynolds::FilmSolver solver;
  reynolds::FilmResult result;
  reynolds::FilmState last;   // state of `result`: probes and dissipation at the same state reuse it
  bool valid = false;
};

bool same(const reynolds::FilmState& a, const reynolds::FilmState& b) {
  return a.ex == b.ex && a.ey == b.ey && a.vx == b.vx && a.vy == b.vy && a.sx == b.sx && a.sy == b.sy &&
         a.dsx == b.dsx && a.dsy == b.dsy && a.omega_inner == b.omega_inner && a.omega_outer == b.omega_outer;
}

}  // namespace

JournalBearingElement::JournalBearingElement(const std::string& name, const JournalBearingSpec& spec,
                                             const OilSpec& oil, int node_dof)
    : ForceElement(name, {node_dof, node_dof + 1, node_dof + 2, node_dof + 3}, 0) {
  geometry_ = film_geometry(spec, options_);
  viscosity_ = oil.viscosity_at(oil.temperature_or(spec.oil_temperature));
  film_limit_ = spec.film_thickness_limit;
  reynolds::FilmSolver check(geometry_, viscosity_, options_);  // throws for inconsistent geometry now, not mid-run
}

std::unique_ptr<ElementWorkspace> JournalBearingElement::make_workspace() const {
  return std::make_unique<JournalWorkspace>(reynolds::FilmSolver(geometry_, viscosity_, options_));
}

reynolds::FilmState JournalBearingElement::film_state(const SpinState& s, const double* q, const double* v) const {
  // Journal axis: dx/dz = theta_y, dy/dz = -theta_x (timoshenko.h); the bush is fixed and centred.
  reynolds::FilmState f;
  f.ex = q[0];
  f.ey = q[1];
  f.vx = v[0];
  f.vy = v[1];
  f.sx = q[3];
  f.sy = -q[2];
  f.dsx = v[3];
  f.dsy = -v[2];
  f.omega_inner = s.speed;
  f.omega_outer = 0.0;
  return f;
}

const reynolds::FilmResult& JournalBearingElement::Solve(const SpinState& s, const double* q, const double* v,
                                                         ElementWorkspace& ws) const {
  auto& w = static_cast<JournalWorkspace&>(ws);
  const reynolds::FilmState state = film_state(s, q, v);
  if (w.valid && same(state, w.last)) return w.result;
  w.valid = false;
  if (!w.solver.solve(state, w.result))
    throw std::runtime_error("bearing '" + name() + "': " + w.solver.last_error());
  w.last = state;
  w.valid = true;
  return w.result;
}

void JournalBearingElement::do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double*,
                                               ElementWorkspace& ws, double* f, double*) const {
  const reynolds::FilmResult& r = Solve(s, q, v, ws);
  f[0] += r.fx;
  f[1] += r.fy;
  f[2] += r.mx;
  f[3] += r.my;
}

std::vector<ProbeInfo> JournalBearingElement::probes() const {
  const std::string who = "bearing '" + name() + "': ";
  return housing_force_probes(who, "", {{"eccentricity", "1", "journal eccentricity ratio e/c at mid-width"},
                                        {"friction_power", "W", "friction power loss in the film"},
                                        {"max_pressure", "Pa", "highest film pressure"},
                                        min_film_probe("min_film_thickness", "", film_limit_)});
}

void JournalBearingElement::eval_probes(const SpinState& s, const double* q, const double* v, const double*,
                                       ElementWorkspace& ws, double* out) const {
  const reynolds::FilmResult& r = Solve(s, q, v, ws);
  out[0] = -r.fx;  // the film pushes the housing opposite to the journal
  out[1] = -r.fy;
  out[2] = std::hypot(q[0], q[1]) / geometry_.clearance;
  out[3] = -r.torque_inner * s.speed;
  out[4] = r.max_pressure;
  out[5] = reynolds::min_film_thickness(geometry_, film_state(s, q, v));
}

double JournalBearingElement::dissipated_power(const SpinState& s, const double* q, const double* v, const double*,
                                              ElementWorkspace& ws) const {
  // All the film turns into heat: minus the power of its forces, moments and torque on the journal (the bush is
  // fixed).
  const reynolds::FilmResult& r = Solve(s, q, v, ws);
  return -(r.fx * v[0] + r.fy * v[1] + r.mx * v[2] + r.my * v[3] + r.torque_inner * s.speed);
}

double JournalBearingElement::drive_power(const SpinState& s, const double* q, const double* v, const double*,
                                         ElementWorkspace& ws) const {
  return -Solve(s, q, v, ws).torque_inner * s.speed;
}

}  // namespace turbodyn

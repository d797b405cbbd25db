#include "model/elements/damper_element.h"

#include "model/films/film_geometry.h"

#include <cmath>
#include <stdexcept>

namespace turbodyn {
namespace {

struct DamperWorkspace : ElementWorkspace {
  explicit DamperWorkspace(reynolds::FilmSolver s) : solver(std::move(s)) { result.hole_flows.reserve(8); }
  reynolds::FilmSolver solver;
  reynolds::FilmResult result;
  double last[4] = {NAN, NAN, NAN, NAN};  // ring state of `result`
};

}  // namespace

DamperElement::DamperElement(const LinearBearing& bearing, int x_dof, const DamperSpec& damper, const OilSpec& oil,
                             double gravity)
    : ForceElement(bearing.name, {x_dof, x_dof + 1}, 4),
      bearing_(bearing),
      damper_(damper),
      gravity_(gravity) {
  geometry_ = film_geometry(damper, options_);
  viscosity_ = oil.viscosity_at(oil.temperature_or(damper.oil_temperature));
  reynolds::FilmSolver check(geometry_, viscosity_, options_);  // inconsistent geometry fails now, not mid-run
}

std::unique_ptr<ElementWorkspace> DamperElement::make_workspace() const {
  auto w = std::make_unique<DamperWorkspace>(reynolds::FilmSolver(geometry_, viscosity_, options_));
  w->solver.set_forces_only(true);  // the ring reads the film's fx, fy alone
  return w;
}

void DamperElement::initial_states(double* z) const {
  for (int i = 0; i < 4; ++i) z[i] = 0.0;  // ring centred at rest
}

const reynolds::FilmResult& DamperElement::Film(const double* z, ElementWorkspace& ws) const {
  auto& w = static_cast<DamperWorkspace&>(ws);
  if (z[0] == w.last[0] && z[1] == w.last[1] && z[2] == w.last[2] && z[3] == w.last[3]) return w.result;
  reynolds::FilmState f;  // the ring is the (non-rotating) journal, the housing the bush
  f.ex = z[0];
  f.ey = z[1];
  f.vx = z[2];
  f.vy = z[3];
  w.last[0] = NAN;
  if (!w.solver.solve(f, w.result))
    throw std::runtime_error("squeeze-film damper of bearing '" + name() + "': " + w.solver.last_error());
  for (int i = 0; i < 4; ++i) w.last[i] = z[i];
  return w.result;
}

void DamperElement::do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z,
                                       ElementWorkspace& ws, double* f, double* zdot) const {
  Eigen::Matrix2d k, c;
  bearing_.coefficients(s.speed, k, c);
  const Eigen::Vector2d du(q[0] - z[0], q[1] - z[1]), dv(v[0] - z[2], v[1] - z[3]);
  const Eigen::Vector2d fb = k * du + c * dv;  // bearing force on the ring (and minus that on the shaft)
  f[0] -= fb(0);
  f[1] -= fb(1);
  const reynolds::FilmResult& film = Film(z, ws);
  const double m = damper_.ring_mass, kc = damper_.centring_stiffness;
  zdot[0] = z[2];
  zdot[1] = z[3];
  zdot[2] = (fb(0) + film.fx - kc * z[0]) / m;
  zdot[3] = (fb(1) + film.fy - kc * z[1]) / m - gravity_;
}

std::vector<ProbeInfo> DamperElement::probes() const {
  const std::string who = "bearing '" + name() + "': ";
  return damper_probes(who, damper_.film_thickness_limit);
}

void DamperElement::eval_probes(const SpinState&, const double*, const double*, const double* z, ElementWorkspace& ws,
                               double* out) const {
  const reynolds::FilmResult& film = Film(z, ws);
  const double kc = damper_.centring_stiffness;
  out[0] = -film.fx + kc * z[0];  // the film and the spring push the housing
  out[1] = -film.fy + kc * z[1];
  out[2] = z[0];
  out[3] = z[1];
  out[4] = std::hypot(z[0], z[1]) / damper_.clearance;
  out[5] = reynolds::min_film_thickness(geometry_, {.ex = z[0], .ey = z[1]});  // the damper film does not tilt
}

double DamperElement::potential_energy(const double* q, const double* z) const {
  Eigen::Matrix2d k, c;
  bearing_.coefficients(0.0, k, c);
  const Eigen::Vector2d du(q[0] - z[0], q[1] - z[1]);
  return 0.5 * du.dot(0.5 * (k + k.transpose()) * du) +
         0.5 * damper_.centring_stiffness * (z[0] * z[0] + z[1] * z[1]) + damper_.ring_mass * gravity_ * z[1];
}

double DamperElement::kinetic_energy(const double* z) const {
  return 0.5 * damper_.ring_mass * (z[2] * z[2] + z[3] * z[3]);
}

double DamperElement::dissipated_power(const SpinState& s, const double*, const double* v, const double* z,
                                      ElementWorkspace& ws) const {
  Eigen::Matrix2d k, c;
  bearing_.coefficients(s.speed, k, c);
  const Eigen::Vector2d dv(v[0] - z[2], v[1] - z[3]);
  const reynolds::FilmResult& film = Film(z, ws);
  return dv.dot(c * dv) - (film.fx * z[2] + film.fy * z[3]);
}

}  // namespace turbodyn

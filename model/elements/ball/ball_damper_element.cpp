#include "model/elements/ball/ball_damper_element.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "model/films/film_geometry.h"

namespace turbodyn {

struct BallDamperElement::Evaluation {
  BallBearingLoads loads;
  reynolds::FilmResult film;
  std::vector<double> zdot;  ///< core-state derivatives (sized once)
};

namespace {

BallBearingSpec external(BallBearingSpec s) {
  s.outer_ring_mode = OuterRingMode::External;
  return s;
}

struct BallDamperWorkspace : ElementWorkspace {
  BallDamperWorkspace(reynolds::FilmSolver s, int n_states, int n_core) : solver(std::move(s)), key(4, n_states) {
    eval.film.hole_flows.reserve(8);
    eval.zdot.resize(n_core);
  }
  reynolds::FilmSolver solver;
  BallDamperElement::Evaluation eval;
  EvaluationKey key;  // the state of `eval`
  // add_jacobian: the bearing's workspace, and the film at the base ring state fd_key (x, y, vx, vy), which most
  // finite-difference evaluations share (only the ring's own columns move the film); fd_column the film of such a
  // column, from the base solve's factorisation while fd_factorised says the solver still holds it.
  std::unique_ptr<ElementWorkspace> bearing;
  reynolds::FilmResult fd_film, fd_column;
  double fd_key[4] = {0, 0, 0, 0};
  bool fd_valid = false, fd_factorised = false;
};

}  // namespace

BallDamperElement::BallDamperElement(const std::string& name, const BallBearingSpec& bearing,
                                     const DamperSpec& damper, const OilSpec& oil, int node_dof, double gravity)
    : ForceElement(name, {node_dof, node_dof + 1, node_dof + 2, node_dof + 3},
                   BallBearingElement(name, external(bearing), node_dof, gravity).n_core_states() + 4),
      bearing_(name, external(bearing), node_dof, gravity),
      damper_(damper),
      gravity_(gravity),
      ring_mass_(bearing.outer_ring_mass),
      n_core_(bearing_.n_core_states()) {
  geometry_ = film_geometry(damper, options_);
  viscosity_ = oil.viscosity_at(oil.temperature_or(damper.oil_temperature));
  reynolds::FilmSolver check(geometry_, viscosity_, options_);  // inconsistent geometry fails now, not mid-run
}

std::unique_ptr<ElementWorkspace> BallDamperElement::make_workspace() const {
  auto w = std::make_unique<BallDamperWorkspace>(reynolds::FilmSolver(geometry_, viscosity_, options_), n_states(),
                                                 n_core_);
  w->solver.set_forces_only(true);  // the ring reads the film's fx, fy alone
  w->bearing = bearing_.make_workspace();
  w->fd_film.hole_flows.reserve(8);
  w->fd_column.hole_flows.reserve(8);
  return w;
}

void BallDamperElement::add_jacobian(const SpinState& s, const double* q, const double* v, const double* z,
                                    ElementWorkspace& ws, double* J) const {
  auto& w = static_cast<BallDamperWorkspace&>(ws);
  w.fd_valid = false;
  struct Wrapped final : BallBearingElement::JacobianEvaluator {
    Wrapped(const BallDamperElement& e, const SpinState& st, BallDamperWorkspace& w) : e(e), st(st), w(w) {}
    void operator()(const double* q, const double* v, const double* z, double* f, double* zdot,
                    BallShare* shares, BallContactCache* cache, unsigned redo) const override {
      const double* ring = z + e.n_core_;
      const OuterRingKinematics outer{ring[0], ring[1], ring[2], ring[3]};
      BallBearingLoads loads;
      e.bearing_.calc_bearing(st, q, v, z, outer, loads, zdot, shares, cache, redo);
      const reynolds::FilmResult* film = &w.fd_film;
      if (!w.fd_valid) {
        // The base state (add_jacobian_of evaluates it first).
        if (!w.solver.solve(e.FilmState(ring), w.fd_film)) fail();
        std::memcpy(w.fd_key, ring, sizeof w.fd_key);
        w.fd_valid = w.fd_factorised = true;
      } else if (std::memcmp(w.fd_key, ring, sizeof w.fd_key) != 0) {
        // A column of the ring's own states. The film's matrix depends on x, y alone: for a velocity column the
        // base factorisation gives the film exactly, for a position column one Newton step from it (first order
        // in the step, the derivative for the base cavitated set; FilmSolver::solve_linearised), as the
        // floating ring's Jacobian does.
        const reynolds::FilmState column = e.FilmState(ring);
        const bool same_thickness = ring[0] == w.fd_key[0] && ring[1] == w.fd_key[1];
        const bool reused = w.fd_factorised && (same_thickness ? w.solver.solve_same_matrix(column, w.fd_column)
                                                               : w.solver.solve_linearised(column, w.fd_column));
        if (!reused) {
          w.fd_factorised = false;
          if (!w.solver.solve(column, w.fd_column)) fail();
        }
        film = &w.fd_column;
      }
      for (int k = 0; k < 4; ++k) f[k] += loads.shaft[k];
      e.ring_derivatives(ring, loads, *film, zdot + e.n_core_);
    }
    [[noreturn]] void fail() const {
      throw std::runtime_error("squeeze-film damper of bearing '" + e.name() + "': " + w.solver.last_error());
    }
    const BallDamperElement& e;
    const SpinState& st;
    BallDamperWorkspace& w;
  };
  bearing_.add_jacobian_of(*this, Wrapped(*this, s, w), n_states(), q, v, z, *w.bearing, J);
}

reynolds::FilmState BallDamperElement::FilmState(const double* ring) const {
  reynolds::FilmState f;  // the outer ring is the (non-rotating) journal, the housing the bush
  f.ex = ring[0];
  f.ey = ring[1];
  f.vx = ring[2];
  f.vy = ring[3];
  return f;
}

void BallDamperElement::ring_derivatives(const double* ring, const BallBearingLoads& loads,
                                        const reynolds::FilmResult& film, double* dring) const {
  const double kc = damper_.centring_stiffness;
  dring[0] = ring[2];
  dring[1] = ring[3];
  dring[2] = (loads.outer_ring[0] + film.fx - kc * ring[0]) / ring_mass_;
  dring[3] = (loads.outer_ring[1] + film.fy - kc * ring[1]) / ring_mass_ - gravity_;
}

void BallDamperElement::initial_states_at_speed(double speed, double* z) const {
  bearing_.initial_states_at_speed(speed, z);
  for (int i = 0; i < 4; ++i) z[n_core_ + i] = 0.0;  // outer ring centred in the damper, at rest
}

void BallDamperElement::initial_states(double* z) const { initial_states_at_speed(0.0, z); }

bool BallDamperElement::steady_rotation_layout(SteadyRotationLayout* layout) const {
  // A feed hole pushes the ring one way: no steady state turns with the cage. A central feed groove's supply
  // pressure is the same all round and pushes it nowhere.
  const bool pushed =
      damper_.feed_hole_diameter > 0.0 || (damper_.supply_pressure != 0.0 && !(damper_.feed_groove_width > 0.0));
  if (gravity_ != 0.0 || pushed) return false;
  bearing_.core_rotation_layout(layout);
  layout->planar_pairs.emplace_back(n_core_, n_core_ + 1);
  layout->planar_pairs.emplace_back(n_core_ + 2, n_core_ + 3);
  return true;
}

double BallDamperElement::state_scale(int i) const {
  if (i < n_core_) return bearing_.state_scale(i);
  return i < n_core_ + 2 ? 1e-6 : 1e-3;
}

double BallDamperElement::tolerance_scale(int i) const {
  return i < n_core_ ? bearing_.tolerance_scale(i) : state_scale(i);
}

double BallDamperElement::ring_velocity_tolerance_factor(double eps) {
  // Radial damping of the short full film, c_rr ~ (1 + 2 e^2) / (1 - e^2)^2.5 (docs/references.md section 3), taken
  // at most at e = 0.98: docs/ball-bearing.md, "In run-ups".
  const auto damping = [](double e) {
    const double q = 1.0 - e * e;
    return (1.0 + 2.0 * e * e) / (q * q * std::sqrt(q));
  };
  return std::min(damping(0.9) / damping(std::min(std::abs(eps), 0.98)), 100.0);
}

void BallDamperElement::absolute_tolerance_factors(const double* z, double* f) const {
  for (int i = 0; i < n_core_ + 2; ++i) f[i] = 1.0;
  const double* ring = z + n_core_;
  f[n_core_ + 2] = f[n_core_ + 3] = ring_velocity_tolerance_factor(std::hypot(ring[0], ring[1]) / damper_.clearance);
}

const BallDamperElement::Evaluation& BallDamperElement::Evaluate(const SpinState& s, const double* q,
                                                                 const double* v, const double* z,
                                                                 ElementWorkspace& ws) const {
  auto& w = static_cast<BallDamperWorkspace&>(ws);
  if (w.key.matches(s.speed, q, v, z)) return w.eval;
  w.key.invalidate();
  const double* ring = z + n_core_;
  const OuterRingKinematics outer{ring[0], ring[1], ring[2], ring[3]};
  bearing_.calc_bearing(s, q, v, z, outer, w.eval.loads, w.eval.zdot.data());
  if (!w.solver.solve(FilmState(ring), w.eval.film))
    throw std::runtime_error("squeeze-film damper of bearing '" + name() + "': " + w.solver.last_error());
  w.key.set(s.speed, q, v, z);
  return w.eval;
}

void BallDamperElement::do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z,
                                           ElementWorkspace& ws, double* f, double* zdot) const {
  const Evaluation& e = Evaluate(s, q, v, z, ws);
  for (int k = 0; k < 4; ++k) f[k] += e.loads.shaft[k];
  std::memcpy(zdot, e.zdot.data(), static_cast<std::size_t>(n_core_) * sizeof(double));
  ring_derivatives(z + n_core_, e.loads, e.film, zdot + n_core_);
}

std::vector<ProbeInfo> BallDamperElement::probes() const {
  const std::string who = "bearing '" + name() + "': ";
  return damper_probes(who, damper_.film_thickness_limit,
                       {{"cage_speed_ratio", "1", "cage speed / rotor speed"},
                        {"max_contact_force", "N", "largest ball-race normal force"},
                        MaxContactPressureProbe()});
}

void BallDamperElement::eval_probes(const SpinState& s, const double* q, const double* v, const double* z,
                                   ElementWorkspace& ws, double* out) const {
  const Evaluation& e = Evaluate(s, q, v, z, ws);
  const double* ring = z + n_core_;
  const double kc = damper_.centring_stiffness;
  out[0] = -e.film.fx + kc * ring[0];  // the film and the spring push the housing
  out[1] = -e.film.fy + kc * ring[1];
  out[2] = ring[0];
  out[3] = ring[1];
  out[4] = std::hypot(ring[0], ring[1]) / damper_.clearance;
  out[5] = reynolds::min_film_thickness(geometry_, {.ex = ring[0], .ey = ring[1]});  // the damper film does not tilt
  const double cage_spin = z[bearing_.cage_offset() + 7];
  out[6] = s.speed != 0.0 ? cage_spin / s.speed : 0.0;
  out[7] = e.loads.max_contact_force();
  out[8] = bearing_.max_contact_pressure(e.loads);
}

double BallDamperElement::potential_energy(const double* q, const double* z) const {
  const double* ring = z + n_core_;
  const OuterRingKinematics outer{ring[0], ring[1], ring[2], ring[3]};
  return bearing_.core_potential_energy(q, z, outer) +
         0.5 * damper_.centring_stiffness * (ring[0] * ring[0] + ring[1] * ring[1]) + ring_mass_ * gravity_ * ring[1];
}

double BallDamperElement::kinetic_energy(const double* z) const {
  const double* ring = z + n_core_;
  return bearing_.core_kinetic_energy(z) + 0.5 * ring_mass_ * (ring[2] * ring[2] + ring[3] * ring[3]);
}

double BallDamperElement::dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                                          ElementWorkspace& ws) const {
  const Evaluation& e = Evaluate(s, q, v, z, ws);
  const double* ring = z + n_core_;
  return e.loads.dissipated_power - (e.film.fx * ring[2] + e.film.fy * ring[3]);
}

double BallDamperElement::drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                                     ElementWorkspace& ws) const {
  return -Evaluate(s, q, v, z, ws).loads.shaft_torque * s.speed;
}

}  // namespace turbodyn

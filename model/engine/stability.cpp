#include "model/engine/stability.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "model/elements/force_element.h"
#include "model/engine/runup.h"
#include "model/engine/runup_workspace.h"
#include "model/engine/speed_text.h"
#include "model/spec/constants.h"

namespace turbodyn {
namespace {

using Layout = ForceElement::SteadyRotationLayout;

std::string number_text(double x) {
  std::ostringstream os;
  os << std::setprecision(3) << x;
  return os.str();
}

// Relative central-difference step of both Jacobians: the functions are smooth at the steady state (closed
// Hertz contacts, friction in its creep range), so a step near eps^(1/3) balances truncation and round-off.
constexpr double kRelativeStep = 1e-6;
// Steady state of an element: converged at this largest scaled rate (state derivative over its typical
// magnitude times the speed); kAccepted is the most that is accepted when the iteration stalls (the kinks of the
// contact laws make the last digits ragged).
constexpr double kConverged = 1e-9, kAccepted = 1e-6;
constexpr int kMaxIterations = 400, kMaxNewton = 60;
// Pseudo-time steps (in units of 1 / speed): the first, and the largest (then the iteration is Newton's method).
constexpr double kFirstPseudoStep = 1.0, kLargestPseudoStep = 1e12;
// Continuation in speed: no step larger than this (rad/s), about 2,400 rpm; a step that fails is halved at most
// this many times. From rest, half of it: the first steps start from the no-slip state, far from the steady state,
// and where the rolling state has two branches (docs/ball-bearing.md, "A sweep over speeds") steps of about 245
// rad/s and more settled on the one a run does not take (at 220 N and 25 deg from 40,000 rpm on), steps of 175 and
// 100 rad/s on the run's.
constexpr double kMaxSpeedStep = 250.0, kMaxSpeedStepFromRest = 0.5 * kMaxSpeedStep;
constexpr int kMaxStepHalvings = 6;
// Damping ratios above -this count as round-off for modes above frequency_max.
constexpr double kHighFrequencyNoise = 1e-3;

// One element's steady turning state at rotor speed `speed` with the rotor held centred: G(u) = 0 for the
// element's own equations written in the frame of its phase angle (the cage),
//   u' = G(u),  u_i = z_i / s_i,  G_i = z_i' / (s_i W0)  (s_i the state's typical magnitude, W0 the speed),
// with a turning angle's rate taken relative to the phase angle's rate, psi_j' = psi_j_rate - W, and the phase
// angle held. Newton's method first (newton()); where it stalls, pseudo-transient continuation (solve(); Kelley &
// Keyes 1998, SIAM J. Numer. Anal. 35(2)): implicit Euler steps whose length grows as the rates fall (switched
// evolution relaxation), a damped time integration that follows the physics through the saturated branches of the
// friction law where Newton's method sees no slope, ending as Newton's method. Each linear solve is least-norm: a
// ball floating inside its pocket clearance has a neutral orbital position.
class ElementSteadyState {
 public:
  ElementSteadyState(const ForceElement& e, const Layout& layout)
      : e_(e), layout_(layout), ws_(e.make_workspace()), d_(static_cast<int>(e.dofs().size())), m_(e.n_states()) {
    angle_of_.assign(static_cast<std::size_t>(m_), -1);
    for (std::size_t j = 0; j < layout_.turning_angles.size(); ++j)
      angle_of_[static_cast<std::size_t>(layout_.turning_angles[j].first)] = static_cast<int>(j);
    q_.assign(static_cast<std::size_t>(d_), 0.0);
    v_.assign(static_cast<std::size_t>(d_), 0.0);
    f_.assign(static_cast<std::size_t>(d_), 0.0);
    zdot_.resize(m_);
    scale_.resize(m_);
    for (int i = 0; i < m_; ++i) scale_(i) = std::max(e.state_scale(i), 1e-300);
  }

  /// Newton's method with least-norm steps and a backtracking line search on G(u) = 0, from z (overwritten);
  /// returns the final largest scaled rate. Fast near the steady state; it sees no slope where friction saturates.
  double newton(double speed, Eigen::VectorXd& z) {
    speed_ = speed;
    rate_scale_ = std::max(std::abs(speed), 100.0);
    Eigen::VectorXd g(m_), g_try(m_);
    rates(z, g);
    double norm = g.lpNorm<Eigen::Infinity>();
    Eigen::MatrixXd J(m_, m_);
    for (int it = 0; it < kMaxNewton && norm > kConverged; ++it) {
      jacobian(z, J);
      const Eigen::VectorXd step = J.completeOrthogonalDecomposition().solve(-g);
      if (!step.allFinite()) break;
      bool reduced = false;
      double lambda = 1.0;
      for (int ls = 0; ls < 12 && !reduced; ++ls, lambda *= 0.5) {
        const Eigen::VectorXd z_try = z + lambda * step.cwiseProduct(scale_);
        rates(z_try, g_try);
        const double n_try = g_try.lpNorm<Eigen::Infinity>();
        if (std::isfinite(n_try) && n_try < norm) {
          z = z_try;
          g = g_try;
          norm = n_try;
          reduced = true;
        }
      }
      if (!reduced) break;
    }
    return norm;
  }

  /// Pseudo-transient continuation from z (overwritten); returns the final largest scaled rate.
  double solve(double speed, Eigen::VectorXd& z) {
    speed_ = speed;
    rate_scale_ = std::max(std::abs(speed), 100.0);
    Eigen::VectorXd g(m_), g_try(m_);
    rates(z, g);
    double norm = g.lpNorm<Eigen::Infinity>(), dt = kFirstPseudoStep;
    Eigen::MatrixXd J(m_, m_), H(m_, m_);
    for (int it = 0; it < kMaxIterations && norm > kConverged; ++it) {
      jacobian(z, J);
      bool advanced = false;
      for (int attempt = 0; attempt < 30 && !advanced; ++attempt) {
        H = -J;
        H.diagonal().array() += 1.0 / dt;
        const Eigen::VectorXd step = H.completeOrthogonalDecomposition().solve(g);
        const Eigen::VectorXd z_try = z + step.cwiseProduct(scale_);
        rates(z_try, g_try);
        const double n_try = g_try.lpNorm<Eigen::Infinity>();
        if (step.allFinite() && std::isfinite(n_try) && n_try < 2.0 * norm) {
          // Switched evolution relaxation: the pseudo-time step grows as the rates fall.
          dt = std::min(kLargestPseudoStep, dt * std::clamp(norm / n_try, 0.5, 10.0));
          z = z_try;
          g = g_try;
          norm = n_try;
          advanced = true;
        } else {
          dt = std::max(kFirstPseudoStep, 0.25 * dt);
        }
      }
      if (!advanced) break;
    }
    return norm;
  }

  /// dz/dspeed along the steady states through z (a steady state at `speed`): the tangent -J^+ dG/dspeed of the
  /// implicit function G(z, speed) = 0, least-norm (a ball's neutral place in its pocket does not move), turning
  /// angles held.
  Eigen::VectorXd tangent(double speed, const Eigen::VectorXd& z) {
    speed_ = speed;
    rate_scale_ = std::max(std::abs(speed), 100.0);  // held while the speed is varied: G's scale is not G
    Eigen::MatrixXd J(m_, m_);
    jacobian(z, J);
    const double h = kRelativeStep * rate_scale_;
    Eigen::VectorXd gp(m_), gm(m_);
    speed_ = speed + h;
    rates(z, gp);
    speed_ = speed - h;
    rates(z, gm);
    speed_ = speed;
    Eigen::VectorXd t = J.completeOrthogonalDecomposition().solve(-(gp - gm) / (2.0 * h));
    t = t.cwiseProduct(scale_);
    for (const auto& a : layout_.turning_angles) t(a.first) = 0.0;
    return t;
  }

  /// The frame's speed W at z: the phase angle's rate, or 0 if the element has no turning angles.
  double frame_speed(const Eigen::VectorXd& z) const {
    if (layout_.turning_angles.empty()) return 0.0;
    return z(layout_.turning_angles[static_cast<std::size_t>(std::max(layout_.phase_angle, 0))].second);
  }

 private:
  void rates(const Eigen::VectorXd& z, Eigen::VectorXd& g) {
    SpinState s;
    s.speed = speed_;
    std::fill(f_.begin(), f_.end(), 0.0);
    e_.calc_and_add_forces(s, q_.data(), v_.data(), z.data(), *ws_, f_.data(), zdot_.data());
    const double W = frame_speed(z);
    for (int i = 0; i < m_; ++i) {
      const int j = angle_of_[static_cast<std::size_t>(i)];
      const double rate = j < 0 ? zdot_(i) : j == std::max(layout_.phase_angle, 0) ? 0.0 : zdot_(i) - W;
      g(i) = rate / (scale_(i) * rate_scale_);
    }
  }

  void jacobian(const Eigen::VectorXd& z, Eigen::MatrixXd& J) {
    Eigen::VectorXd zp = z, gp(m_), gm(m_);
    for (int k = 0; k < m_; ++k) {
      const double h = kRelativeStep * std::max(std::abs(z(k)), scale_(k));
      zp(k) = z(k) + h;
      rates(zp, gp);
      zp(k) = z(k) - h;
      rates(zp, gm);
      zp(k) = z(k);
      J.col(k) = (gp - gm) * (scale_(k) / (2.0 * h));  // per unit of the scaled state
    }
  }

  const ForceElement& e_;
  const Layout& layout_;
  std::unique_ptr<ElementWorkspace> ws_;
  int d_ = 0, m_ = 0;
  std::vector<int> angle_of_;  // per state: the turning angle it is, or -1
  std::vector<double> q_, v_, f_;
  Eigen::VectorXd zdot_, scale_;
  double speed_ = 0.0, rate_scale_ = 1.0;
};

// Continuation of the element's steady state x (at speed `from`) to speed `to`, each step started from the secant
// through the last two solutions (angles excepted). A step that finds no steady state is retried at half the length,
// down to 1/2^kMaxStepHalvings of the regular step (kMaxSpeedStep, from rest kMaxSpeedStepFromRest, times the
// layout's continuation_step_factor), and the step grows back after a success. From rest (from = 0) the first step
// starts from the no-slip state; from a steady state at speed, along the steady states' tangent there. Returns false
// (x at the last speed reached, *failed_at and *norm of the step that failed) if the smallest step fails.
bool continue_steady_state(ElementSteadyState& solver, const ForceElement& e, const Layout& layout, double from,
                           double to, Eigen::VectorXd& x, double* norm, double* failed_at, double* smallest_step) {
  const int m = e.n_states();
  const double max_step = (from == 0.0 ? kMaxSpeedStepFromRest : kMaxSpeedStep) * layout.continuation_step_factor;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(to - from) / max_step)));
  // Positions along the continuation in units of the smallest step: an undisturbed continuation lands on
  // from + (to - from) * k / steps exactly (the power-of-two units cancel), whatever steps were halved elsewhere.
  constexpr long kUnits = 1L << kMaxStepHalvings;
  const long end = static_cast<long>(steps) * kUnits;
  long at = 0, step = kUnits;
  const auto speed_at = [&](long position) {
    return from + (to - from) * static_cast<double>(position) / static_cast<double>(end);
  };
  *smallest_step = std::abs(to - from) / static_cast<double>(end);
  Eigen::VectorXd prev = x, tangent;
  double prev_speed = from, last_speed = from;
  bool first = true;
  while (at < end) {
    const long next = std::min(end, at + step);
    const double s = speed_at(next);
    Eigen::VectorXd guess(m);
    if (first) {
      guess = x;
      if (from == 0.0) {
        e.initial_states_at_speed(s, guess.data());
      } else {
        // Along the tangent of the steady states at `from`: the secant of a continuation that came this way. (A
        // guess with the balls' rates left as they were is a slip beyond the creep range, where friction saturates
        // and Newton's method sees no slope: even steps of 4 rad/s failed. The no-slip change of the rates as the
        // guess worked, with more halvings: 2.9 s for the example's 11 speeds against 1.6 s.)
        if (tangent.size() == 0) tangent = solver.tangent(from, x);
        guess += tangent * (s - from);
      }
    } else {
      guess = x + (x - prev) * ((s - last_speed) / (last_speed - prev_speed));
      // Angles are not extrapolated: a ball's place in its pocket is neutral and may have moved in the last solve.
      for (const auto& a : layout.turning_angles) guess(a.first) = x(a.first);
    }
    const Eigen::VectorXd start = guess;
    *norm = solver.newton(s, guess);
    if (!(*norm <= kAccepted)) {
      guess = start;
      *norm = solver.solve(s, guess);
    }
    if (!(*norm <= kAccepted)) {
      if (step > 1) {
        step /= 2;
        continue;
      }
      *failed_at = s;
      return false;
    }
    prev = x;
    prev_speed = last_speed;
    x = guess;
    last_speed = s;
    at = next;
    step = std::min(kUnits, 2 * step);
    first = false;
  }
  return true;
}

// The element's steady state at `speed`: by continuation from rest (the preload equilibrium). If that fails below
// kMaxSpeedStep (250 rad/s, a speed near rest whatever the continuation's steps: a lubricated (EHL) contact's
// traction is stiffest at the smallest entrainment speeds, where its film is thinnest; with 200 N of preload the
// iteration stops at 31 rpm), the steady state is sought directly from the balls' and cage's no-slip state, as a run
// started mid-ramp starts them: at `speed`, else at 2, 1/2, 4, 1/4 and 8 times it (not below kMaxSpeedStep),
// continued from there to `speed`. A failure farther from rest (a rolling state that folds back) stays a failure.
// Returns the states and the frame speed in *frame.
//
// With `below` (the element's steady state at the lower speed `below_speed`, from an earlier analysis), the state is
// first continued up from there, along the branch it is on, without retracing the speeds below (where the rolling
// state has two branches, e.g. the balls' spin axes near outer- or near inner-race control, a sweep stays on one;
// docs/ball-bearing.md). If that fails, the search starts over from rest.
Eigen::VectorXd element_steady_state(const ForceElement& e, const Layout& layout, double speed, double* frame,
                                     double* residual, const double* below = nullptr, double below_speed = 0.0,
                                     bool* restarted = nullptr) {
  ElementSteadyState solver(e, layout);
  const int m = e.n_states();
  double norm = 0.0, failed_at = 0.0, smallest = 0.0;
  if (restarted) *restarted = false;
  if (below) {
    Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(below, m);
    if (continue_steady_state(solver, e, layout, below_speed, speed, x, &norm, &failed_at, &smallest)) {
      *frame = solver.frame_speed(x);
      *residual = norm;
      return x;
    }
    if (restarted) *restarted = true;
  }
  Eigen::VectorXd rest = Eigen::VectorXd::Zero(m);
  e.initial_states(rest.data());
  Eigen::VectorXd x = rest;
  bool found = continue_steady_state(solver, e, layout, 0.0, speed, x, &norm, &failed_at, &smallest);
  const double first_failure = failed_at, first_norm = norm, first_smallest = smallest;
  std::string direct_note;
  if (!found && failed_at <= kMaxSpeedStep && speed > 0.0) {
    for (const double factor : {1.0, 2.0, 0.5, 4.0, 0.25, 8.0}) {
      const double anchor = speed * factor;
      if (found || (factor < 1.0 && anchor < kMaxSpeedStep)) continue;
      Eigen::VectorXd z = rest;
      e.initial_states_at_speed(anchor, z.data());
      const Eigen::VectorXd no_slip = z;
      double n = solver.newton(anchor, z);
      if (!(n <= kAccepted)) {
        z = no_slip;
        n = solver.solve(anchor, z);
      }
      if (!(n <= kAccepted)) continue;
      norm = n;
      found = anchor == speed || continue_steady_state(solver, e, layout, anchor, speed, z, &norm, &failed_at,
                                                       &smallest);
      if (found) x = z;
    }
    if (!found) direct_note = ", nor from the no-slip state at 1/4 to 8 times the speed";
  }
  if (!found)
    throw std::runtime_error("element '" + e.name() + "': no steady state found at " + rpm_text(first_failure) +
                             " (the iteration stopped at a scaled rate of " + number_text(first_norm) +
                             " with continuation steps of " + number_text(first_smallest * kRadPerSToRpm) +
                             " rpm" + direct_note +
                             "; where friction saturates, e.g. the balls' gyroscopic moment above what the "
                             "traction carries, it finds no slope, and where the rolling state folds back on a "
                             "falling friction law, friction_sliding < friction_static, it ends)");
  *frame = solver.frame_speed(x);
  *residual = norm;
  return x;
}

[[noreturn]] void throw_unsupported(const ForceElement& e) {
  throw std::invalid_argument("bearing '" + e.name() + "': its element has no steady state about a centred "
                              "rotor that the stability analysis knows (it covers ball bearings with a fixed or "
                              "spring-mounted outer ring or in a squeeze-film damper without feed hole and with "
                              "either no supply pressure or a central feed groove, and linear bearings, all acting the "
                              "same in every direction)");
}

}  // namespace

MachineSpec stability_machine(const MachineSpec& spec_in, double speed) {
  if (!std::isfinite(speed) || speed < 0.0) throw std::invalid_argument("the speed must be finite and >= 0");
  MachineSpec spec = spec_in;
  spec.gravity = 0.0;
  for (DiskSpec& d : spec.disks) d.unbalance = 0.0;
  spec.speed = SpeedProfile{};
  spec.speed.kind = SpeedProfile::Kind::Ramp;
  spec.speed.start = spec.speed.end = speed;
  spec.speed.duration = 1.0;
  spec.solver.reduction_cutoff = 0.0;  // physical DOFs: the rotor's (x, y) pairs are explicit
  return spec;
}

void check_stability_supported(const MachineSpec& spec_in) {
  const std::unique_ptr<RunupModel> model = make_runup_model(stability_machine(spec_in, 0.0));
  Layout layout;
  for (const auto& e : model->elements())
    if (!e->steady_rotation_layout(&layout)) throw_unsupported(*e);
}

StabilityPoint analyse_stability(const MachineSpec& spec_in, double speed, const StabilityOptions& options,
                                 const StabilityPoint* below) {
  const MachineSpec spec = stability_machine(spec_in, speed);
  const std::unique_ptr<RunupModel> model = make_runup_model(spec);
  if (below && !(below->speed <= speed && below->steady_state.size() ==
                                              static_cast<std::size_t>(model->n_states())))
    throw std::logic_error("analyse_stability: the analysis to continue from is not one of this machine below " +
                           rpm_text(speed));
  if (!(options.continuation_step_factor > 0.0 && std::isfinite(options.continuation_step_factor)))
    throw std::logic_error("analyse_stability: continuation_step_factor must be positive and finite");
  const Rotor& rotor = model->rotor();
  const int n = model->n_dof(), N = model->n_states() - 2;  // the two energy accounts are left out

  StabilityPoint out;
  out.speed = speed;
  out.n_states = N;
  std::vector<double> y(static_cast<std::size_t>(model->n_states()), 0.0);
  std::vector<Layout> layouts(model->elements().size());
  bool have_frame = false;
  for (std::size_t k = 0; k < model->elements().size(); ++k) {
    const ForceElement& e = *model->elements()[k];
    out.elements.push_back(e.name());
    if (!e.steady_rotation_layout(&layouts[k])) throw_unsupported(e);
    layouts[k].continuation_step_factor *= options.continuation_step_factor;
    if (e.n_states() == 0) continue;
    double frame = 0.0, residual = 0.0;
    bool restarted = false;
    const int offset = model->state_offset(static_cast<int>(k));
    const Eigen::VectorXd z =
        element_steady_state(e, layouts[k], speed, &frame, &residual,
                             below ? below->steady_state.data() + offset : nullptr, below ? below->speed : 0.0,
                             &restarted);
    out.restarted = out.restarted || restarted;
    std::copy(z.data(), z.data() + z.size(), y.begin() + offset);
    out.residual = std::max(out.residual, residual);
    if (layouts[k].turning_angles.empty()) continue;
    if (have_frame && std::abs(frame - out.frame_speed) > 1e-6 * std::max(std::abs(frame), 1.0))
      throw std::invalid_argument("bearing '" + e.name() + "': its cage turns at " + number_text(frame) +
                                  " rad/s, another at " + number_text(out.frame_speed) +
                                  " rad/s; the linearisation needs one turning frame (identical bearings)");
    out.frame_speed = frame;
    have_frame = true;
  }
  const double W = out.frame_speed;
  out.steady_state = y;

  // Typical magnitudes of the states (scaled tolerances at atol = 1 typical displacement).
  const Eigen::VectorXd typical = model->AbsoluteTolerances(ForceElement::kTypicalDisplacement, true).head(N);
  RunupWorkspacePtr ws = model->make_workspace();
  ws->energy = false;
  std::vector<double> ydot(y.size()), yp(y), yd_p(y.size()), yd_m(y.size());
  model->Rhs(0.0, y.data(), ydot.data(), *ws);
  // The rotor must be at rest in the steady state: the elements' forces on the centred shaft cancel.
  for (int i = n; i < 2 * n; ++i)
    out.residual = std::max(out.residual, std::abs(ydot[static_cast<std::size_t>(i)]) /
                                              (typical(i) * std::max(speed, 100.0)));

  // A = dF/dy by central differences, in scaled states: As = D^-1 A D.
  Eigen::MatrixXd A(N, N);
  for (int j = 0; j < N; ++j) {
    const double h = kRelativeStep * std::max(std::abs(y[static_cast<std::size_t>(j)]), typical(j));
    yp[static_cast<std::size_t>(j)] = y[static_cast<std::size_t>(j)] + h;
    model->Rhs(0.0, yp.data(), yd_p.data(), *ws);
    yp[static_cast<std::size_t>(j)] = y[static_cast<std::size_t>(j)] - h;
    model->Rhs(0.0, yp.data(), yd_m.data(), *ws);
    yp[static_cast<std::size_t>(j)] = y[static_cast<std::size_t>(j)];
    for (int i = 0; i < N; ++i)
      A(i, j) = (yd_p[static_cast<std::size_t>(i)] - yd_m[static_cast<std::size_t>(i)]) / (2.0 * h) * typical(j) /
                typical(i);
  }
  // The turning frame: w_a' = x_a' + W x_b, w_b' = x_b' - W x_a for every housing-frame pair (a, b).
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t node = 0; node < rotor.node_z.size(); ++node)
    for (int offset : {0, n}) {
      pairs.emplace_back(offset + rotor.dof(static_cast<int>(node), kX), offset + rotor.dof(static_cast<int>(node), kY));
      pairs.emplace_back(offset + rotor.dof(static_cast<int>(node), kThetaX),
                         offset + rotor.dof(static_cast<int>(node), kThetaY));
    }
  for (std::size_t k = 0; k < layouts.size(); ++k)
    for (const auto& [a, b] : layouts[k].planar_pairs)
      pairs.emplace_back(model->state_offset(static_cast<int>(k)) + a, model->state_offset(static_cast<int>(k)) + b);
  for (const auto& [a, b] : pairs) {
    A(a, b) += W * typical(b) / typical(a);
    A(b, a) -= W * typical(a) / typical(b);
  }

  const Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  if (es.info() != Eigen::Success) throw std::runtime_error("the eigenvalue solver did not converge");
  double f_max = options.frequency_max;
  if (f_max <= 0.0) f_max = std::max(5000.0, 4.0 * speed / (2.0 * kPi));
  const Eigen::VectorXcd& lambda = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  for (int k = 0; k < N; ++k) {
    const std::complex<double> l = lambda(k);
    if (l.imag() < 0.0) continue;  // each conjugate pair once
    const Eigen::VectorXcd v = V.col(k);
    double fwd = 0.0, bwd = 0.0;
    for (std::size_t node = 0; node < rotor.node_z.size(); ++node) {
      const std::complex<double> a = v(rotor.dof(static_cast<int>(node), kX)),
                                 b = v(rotor.dof(static_cast<int>(node), kY));
      const std::complex<double> i(0.0, 1.0);
      fwd += std::norm(a + i * b);
      bwd += std::norm(a - i * b);
    }
    StabilityMode mode;
    mode.frame_frequency = l.imag() / (2.0 * kPi);
    mode.growth_rate = l.real();
    const double w_fwd = l.imag() + W, w_bwd = W - l.imag();  // housing-frame frequencies of the two parts
    const double w = fwd >= bwd ? w_fwd : w_bwd;
    mode.frequency = w / (2.0 * kPi);
    mode.forward_share = fwd + bwd > 0.0 ? (fwd + (w_bwd > 0.0 ? bwd : 0.0)) / (fwd + bwd) : 0.0;
    const double magnitude = std::hypot(l.real(), w);
    mode.damping_ratio = magnitude > 0.0 ? -l.real() / magnitude : 0.0;
    const double total = v.squaredNorm();
    mode.rotor_share = v.head(2 * n).squaredNorm() / total;
    for (std::size_t e = 0; e < model->elements().size(); ++e)
      mode.element_shares.push_back(
          v.segment(model->state_offset(static_cast<int>(e)), model->elements()[e]->n_states()).squaredNorm() / total);
    double largest = 0.0;
    for (std::size_t e = 0; e < layouts.size(); ++e) {
      const int offset = model->state_offset(static_cast<int>(e));
      const std::vector<std::pair<int, int>>& angles = layouts[e].turning_angles;
      std::vector<std::complex<double>> psi;  // the balls' angles in this mode
      std::vector<double> phi;                // their steady places
      double share = 0.0;
      for (std::size_t b = 0; b < angles.size(); ++b) {
        if (static_cast<int>(b) == layouts[e].phase_angle) continue;  // the cage
        const int a = offset + angles[b].first, r = offset + angles[b].second;
        share += std::norm(v(a)) + std::norm(v(r));
        psi.push_back(v(a));
        phi.push_back(y[static_cast<std::size_t>(a)]);
      }
      mode.ball_set_share += share / total;
      if (psi.empty() || share <= largest) continue;
      largest = share;
      const int Z = static_cast<int>(psi.size());
      std::vector<double> power(static_cast<std::size_t>(Z));
      for (int m = 0; m < Z; ++m) {
        std::complex<double> sum = 0.0;
        for (int j = 0; j < Z; ++j)
          sum += psi[static_cast<std::size_t>(j)] * std::polar(1.0, -m * phi[static_cast<std::size_t>(j)]);
        power[static_cast<std::size_t>(m)] = std::norm(sum);
      }
      double best = -1.0;
      for (int m = 0; 2 * m <= Z; ++m) {
        const double p = power[static_cast<std::size_t>(m)] +
                         (m > 0 && 2 * m < Z ? power[static_cast<std::size_t>(Z - m)] : 0.0);
        if (p > best) best = p, mode.ball_set_lobes = m;
      }
    }
    if (mode.ball_set_share < kStabilityBallSetMinShare) mode.ball_set_lobes = -1;
    // Above frequency_max only clearly growing modes are kept: the round-off of the central differences grows
    // with |lambda| (a nearly rigid shaft's bending modes at MHz come out with damping ratios of -1e-5 to -6e-5).
    const bool above = magnitude / (2.0 * kPi) > f_max;
    if (above ? mode.damping_ratio > -kHighFrequencyNoise
              : !mode.grows() && mode.rotor_share < options.min_rotor_share)
      continue;
    out.modes.push_back(std::move(mode));
  }
  std::sort(out.modes.begin(), out.modes.end(),
            [](const StabilityMode& a, const StabilityMode& b) { return a.growth_rate > b.growth_rate; });
  return out;
}

bool grows_counted(const StabilityPoint& p, const StabilityModeFilter& filter) {
  for (const StabilityMode& m : p.modes)
    if (filter.counts(m) && m.grows()) return true;
  return false;
}

double refine_stability_onset(const MachineSpec& spec, const StabilityPoint& stable, double unstable,
                              const StabilityModeFilter& filter, std::string* error,
                              std::vector<double>* restarted, const StabilityOptions& analysis) {
  error->clear();
  StabilityOptions options = analysis;
  options.min_rotor_share = filter.min_rotor_share;
  StabilityPoint lo = stable;  // each halving continues the steady state up from the highest speed found stable
  double hi = unstable;
  for (int i = 0; i < kStabilityOnsetBisections; ++i) {
    const double mid = 0.5 * (lo.speed + hi);
    try {
      StabilityPoint p = analyse_stability(spec, mid, options, &lo);
      if (p.restarted && restarted) restarted->push_back(mid);
      if (grows_counted(p, filter))
        hi = mid;
      else
        lo = std::move(p);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {
      *error = "stability analysis at " + rpm_text(mid) + ": " + e.what();
      break;
    }
  }
  return hi;
}

StabilityOnset find_stability_onset(const MachineSpec& spec, const std::vector<const StabilityPoint*>& points,
                                    const StabilityModeFilter& filter, const StabilityOptions& options) {
  StabilityOnset o;
  const std::size_t k = static_cast<std::size_t>(
      std::find_if(points.begin(), points.end(), [&](const StabilityPoint* p) { return grows_counted(*p, filter); }) -
      points.begin());
  if (k >= points.size()) return o;
  o.found = true;
  o.at_first_speed = k == 0;
  o.speed = points[k]->speed;
  if (o.at_first_speed) return o;
  o.speed = refine_stability_onset(spec, *points[k - 1], points[k]->speed, filter, &o.error, &o.restarted, options);
  o.resolution = stability_onset_resolution(points[k]->speed - points[k - 1]->speed);
  return o;
}

}  // namespace turbodyn

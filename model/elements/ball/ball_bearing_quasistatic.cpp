#include "model/elements/ball/ball_bearing_quasistatic.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include <Eigen/Dense>

#include "model/elements/ball/race_geometry.h"
#include "model/spec/errors.h"
#include "model/spec/constants.h"

namespace turbodyn {

namespace {

using Vec3 = Eigen::Vector3d;
using namespace ball_detail;

// Newton on the balls: converged when the largest force residual is below kForceTolerance times the bearing's
// force scale (preload, load, centrifugal force); a residual of 1e-10 of it leaves the finite-difference
// stiffness (steps of kStep, forces changing by k h ~ 1e-1 N) accurate to about 1e-7.
constexpr double kForceTolerance = 1e-11;
// A Newton that can no longer reduce the residual is accepted below this (times the force scale): 1e-8 of it
// leaves the finite-difference stiffness accurate to about 1e-5.
constexpr double kStallTolerance = 1e-8;
// Central-difference steps: 2 nm and 2 nm / R_p. The contact deflections are micrometres, so the truncation
// error (h / delta)^2 is about 1e-5 and the round-off error (residual / (k h)) below 1e-7.
constexpr double kStep = 2e-9;
// Finite-difference step of the ball unknowns in the Newton Jacobian (m).
constexpr double kBallStep = 1e-11;

std::string describe(double speed, const Vector5d& load) {
  std::ostringstream os;
  os << "at " << std::llround(speed * kRadPerSToRpm) << " rpm under the load (" << load[0] << ", " << load[1] << ", "
     << load[2] << ") N";
  return os.str();
}

}  // namespace

double largest_contact_deflection(const std::vector<QuasiStaticBall>& balls) {
  double deflection = 0.0;
  for (const QuasiStaticBall& b : balls) deflection = std::max({deflection, b.inner_deflection, b.outer_deflection});
  return deflection;
}

BallBearingQuasiStatic::BallBearingQuasiStatic(const BallBearingElement& element, QuasiStaticOptions options)
    : element_(element), options_(std::move(options)), n_balls_(element.spec().n_balls) {
  azimuths_ = options_.azimuths;
  if (azimuths_.empty())
    for (int j = 0; j < n_balls_; ++j) azimuths_.push_back(2.0 * kPi * j / n_balls_);
  if (static_cast<int>(azimuths_.size()) != n_balls_)
    throw std::invalid_argument("BallBearingQuasiStatic: QuasiStaticOptions.azimuths must have n_balls entries");
  if (!(options_.outer_traction_share >= 0.0 && options_.outer_traction_share <= 1.0))
    throw std::invalid_argument("BallBearingQuasiStatic: QuasiStaticOptions.outer_traction_share must be in [0, 1]");
  if (!(options_.max_speed_step > 0.0) || !(options_.max_deflection_ratio > 0.0) || options_.max_iterations < 1)
    throw std::invalid_argument("BallBearingQuasiStatic: QuasiStaticOptions.max_speed_step, max_deflection_ratio and "
                                "max_iterations must be positive");
}

Eigen::VectorXd BallBearingQuasiStatic::unknowns(const BallBearingEquilibrium& s) {
  const int Z = static_cast<int>(s.balls.size());
  Eigen::VectorXd u(2 * Z + 1);
  for (int j = 0; j < Z; ++j) u(2 * j) = s.balls[j].rho, u(2 * j + 1) = s.balls[j].zeta;
  u(2 * Z) = s.outer_ring_axial;
  return u;
}

double BallBearingQuasiStatic::evaluate(double speed, const Vector5d& q, double axial_load, const Eigen::VectorXd& u,
                                        Eigen::VectorXd& r, std::vector<QuasiStaticBall>* balls,
                                        Vector5d* shaft_force) const {
  const BallBearingSpec& sp = element_.spec();
  const int Z = n_balls_;
  const double D = sp.ball_diameter, dm = sp.pitch_diameter, side = sp.side;
  const double Rp = element_.pitch_radius(), m = element_.ball_mass(), I = element_.ball_inertia();
  const double Ki = element_.inner_contact().stiffness, Ko = element_.outer_contact().stiffness;
  const BallBearingElement::GrooveCircle gi = element_.inner_groove(), go = element_.outer_groove();
  const double zo = u(2 * Z);
  Race inner, outer;
  inner.dr = gi.radial, inner.dz = gi.axial, inner.r0 = gi.distance;
  outer.dr = go.radial, outer.dz = go.axial, outer.r0 = go.distance;
  Vec3 F_shaft = Vec3::Zero(), M_shaft = Vec3::Zero();
  double F_outer_z = 0.0, max_deflection = 0.0;
  r.resize(2 * Z + 1);
  for (int j = 0; j < Z; ++j) {
    const double psi = azimuths_[j], c = std::cos(psi), sn = std::sin(psi);
    const double rho = u(2 * j), zeta = u(2 * j + 1), R = Rp + rho;
    inner.centre = to_orbital(q[0], q[1], q[2], c, sn);
    inner.tilt = to_orbital(q[3], q[4], 0.0, c, sn);
    outer.centre = Vec3(0.0, 0.0, zo);
    RaceGeometry g_i, g_o;
    race_geometry(inner, R, rho, zeta, g_i, true);
    race_geometry(outer, R, rho, zeta, g_o, true);
    const double Qi = g_i.delta > 0.0 ? Ki * g_i.delta * std::sqrt(g_i.delta) : 0.0;
    const double Qo = g_o.delta > 0.0 ? Ko * g_o.delta * std::sqrt(g_o.delta) : 0.0;
    max_deflection = std::max({max_deflection, g_i.delta, g_o.delta});
    // Contact angles in the azimuth plane: the inner normal points inwards and towards -side, the outer one
    // outwards and towards +side (docs/ball-bearing.md, "Frames and conventions").
    const double a_i = std::atan2(-side * g_i.u.z(), -g_i.u.x());
    const double a_o = std::atan2(side * g_o.u.z(), g_o.u.x());
    // Outer-race control: no spin against the outer race, the ball's spin axis normal to the outer contact
    // line; rolling without slip at both contacts gives the orbital speed (Jones 1960; Harris & Kotzalas 2007,
    // ball kinematics) and the spin speed w_b = w_m d_m / D.
    const double w_m = speed * (1.0 - D / dm * std::cos(a_i)) / (1.0 + std::cos(a_i - a_o));
    const double w_r = w_m * dm / D * side * std::sin(a_o);  // radial component of the ball's angular velocity
    // Gyroscopic moment about e_psi the contacts must supply (the element's Euler equation I psi' w_r = M_psi
    // in steady rolling), carried by traction at the outer contact: F_t = (2 M_g / D) e_psi x u_o.
    const double Mg = I * w_m * w_r;
    const double lambda_o = 2.0 * options_.outer_traction_share, lambda_i = 2.0 - lambda_o;
    const Vec3 Ft = (lambda_o * Mg / D) * Vec3(g_o.u.z(), 0.0, -g_o.u.x());
    const Vec3 Fti = (lambda_i * Mg / D) * Vec3(g_i.u.z(), 0.0, -g_i.u.x());
    const Vec3 F = -Qi * g_i.u - Qo * g_o.u + Ft + Fti + Vec3(m * R * w_m * w_m, 0.0, 0.0);
    r(2 * j) = F.x();
    r(2 * j + 1) = F.z();  // the tangential part goes to the cage
    F_outer_z += Qo * g_o.u.z() - Ft.z();
    if (shaft_force) {
      const Vec3 Fr = Qi * g_i.u - Fti, Mr = g_i.p.cross(Qi * g_i.u_l - Fti);
      F_shaft += to_housing(Fr, c, sn);
      M_shaft += to_housing(Mr, c, sn);
    }
    if (balls) {
      QuasiStaticBall& b = (*balls)[j];
      b.azimuth = psi;
      b.rho = rho;
      b.zeta = zeta;
      b.inner_load = Qi;
      b.outer_load = Qo;
      b.inner_angle = a_i;
      b.outer_angle = a_o;
      b.inner_deflection = g_i.delta;
      b.outer_deflection = g_o.delta;
      b.orbital_speed = w_m;
      b.gyroscopic_moment = Mg;
    }
  }
  // Outer ring, axial: the balls, the preload spring (as in the element) and the axial load through the bearing.
  r(2 * Z) = F_outer_z - side * sp.preload - sp.preload_stiffness * zo - axial_load;
  if (shaft_force) *shaft_force << F_shaft.x(), F_shaft.y(), F_shaft.z(), M_shaft.x(), M_shaft.y();
  return max_deflection;
}

bool BallBearingQuasiStatic::equilibrate_u(double speed, const Vector5d& q, double axial_load, double load,
                                           Eigen::VectorXd& u) const {
  const BallBearingSpec& sp = element_.spec();
  const int n = 2 * n_balls_ + 1;
  const double w_cage = 0.5 * speed;
  const double scale = std::max({1.0, sp.preload, load,
                                 element_.ball_mass() * element_.pitch_radius() * w_cage * w_cage});
  const double tol = kForceTolerance * scale;
  Eigen::VectorXd r(n), r1(n), r2(n), trial(n);
  Eigen::MatrixXd J(n, n);
  evaluate(speed, q, axial_load, u, r, nullptr, nullptr);
  for (int it = 0; it < options_.max_iterations; ++it) {
    if (!r.allFinite()) return false;
    const double norm = r.cwiseAbs().maxCoeff();
    if (norm <= tol) return true;
    for (int k = 0; k < n; ++k) {
      const double saved = u(k);
      u(k) = saved + kBallStep;
      evaluate(speed, q, axial_load, u, r1, nullptr, nullptr);
      u(k) = saved - kBallStep;
      evaluate(speed, q, axial_load, u, r2, nullptr, nullptr);
      u(k) = saved;
      J.col(k) = (r1 - r2) / (2.0 * kBallStep);
    }
    // Least-norm step: a ball with both contacts open (possible at rest with clearance) is force-free, its rows
    // and columns are zero and it stays where it is.
    const Eigen::VectorXd du = J.completeOrthogonalDecomposition().solve(-r);
    if (!du.allFinite()) return false;
    // Backtracking on the largest residual; Hertz's 3/2 power makes full steps overshoot near first contact.
    double alpha = 1.0, trial_norm = 0.0;
    for (int k = 0; k < 40; ++k, alpha *= 0.5) {
      trial = u + alpha * du;
      evaluate(speed, q, axial_load, trial, r1, nullptr, nullptr);
      trial_norm = r1.allFinite() ? r1.cwiseAbs().maxCoeff() : HUGE_VAL;
      if (trial_norm < (1.0 - 1e-4 * alpha) * norm) break;
    }
    // A ball at the edge of a contact (delta -> 0, a clearance bearing's unloaded side) converges only linearly and
    // stalls where the finite differences straddle the kink of delta^(3/2); its remaining force is negligible.
    if (!(trial_norm < norm)) return norm <= kStallTolerance * scale;
    u = trial;
    r = r1;
  }
  return r.cwiseAbs().maxCoeff() <= kStallTolerance * scale;  // the linear convergence at a contact's edge
}

bool BallBearingQuasiStatic::equilibrate(double speed, const Vector5d& q, BallBearingEquilibrium& s) const {
  Eigen::VectorXd u = unknowns(s), r;
  if (!equilibrate_u(speed, q, s.load[2], s.load.head<3>().norm(), u)) return false;
  s.speed = speed;
  s.displacement = q;
  s.outer_ring_axial = u(2 * n_balls_);
  evaluate(speed, q, s.load[2], u, r, &s.balls, &s.shaft_force);
  double sum = 0.0;
  for (const QuasiStaticBall& b : s.balls) sum += b.orbital_speed;
  s.cage_speed = sum / n_balls_;
  return true;
}

void BallBearingQuasiStatic::solve_at_speed(double speed, BallBearingEquilibrium& s) const {
  // Newton on the inner ring's x, y, theta_x, theta_y (z held): F(q) + load = 0 (forces) and M(q) = 0, with the
  // Jacobian -K from central differences of the condensed equilibrium. Moments and tilts are scaled by R_p so
  // that all four unknowns and residuals have the same size.
  static constexpr int kDof[4] = {0, 1, 3, 4};
  const double Rp = element_.pitch_radius();
  const double scales[4] = {1.0, 1.0, 1.0 / Rp, 1.0 / Rp};
  const BallBearingSpec& sp = element_.spec();
  const double force_scale = std::max({1.0, sp.preload, s.load.head<3>().norm()});
  const double tol = 1e-9 * force_scale;
  const std::string where = describe(speed, s.load);
  if (!equilibrate(speed, s.displacement, s))
    throw QuasiStaticError("no equilibrium of the balls found " + where);
  const auto residual = [&](const BallBearingEquilibrium& e) {
    Eigen::Vector4d g;
    for (int i = 0; i < 4; ++i) g(i) = (e.shaft_force(kDof[i]) + e.load(kDof[i])) * (i < 2 ? 1.0 : 1.0 / Rp);
    return g;
  };
  Eigen::Vector4d g = residual(s);
  s.iterations = 0;
  for (int it = 0;; ++it) {
    const double norm = g.cwiseAbs().maxCoeff();
    if (norm <= tol) break;
    if (it >= options_.max_iterations) {
      std::ostringstream os;
      os << "no equilibrium found " << where << ": Newton stopped after " << it << " iterations with a residual of "
         << norm << " N";
      throw QuasiStaticError(os.str());
    }
    Eigen::Matrix4d J;
    for (int k = 0; k < 4; ++k) {
      const double h = kStep * scales[k];
      BallBearingEquilibrium a = s, b = s;
      Vector5d qa = s.displacement, qb = s.displacement;
      qa(kDof[k]) += h;
      qb(kDof[k]) -= h;
      if (!equilibrate(speed, qa, a) || !equilibrate(speed, qb, b))
        throw QuasiStaticError("no equilibrium of the balls found " + where + " (near the inner ring's position)");
      J.col(k) = (residual(a) - residual(b)) / (2.0 * h) * scales[k];  // per scaled unknown theta R_p
    }
    Eigen::Vector4d dq = J.completeOrthogonalDecomposition().solve(-g);  // scaled
    if (!dq.allFinite() || dq.cwiseAbs().maxCoeff() == 0.0)
      throw QuasiStaticError("no equilibrium found " + where + ": the bearing has no stiffness against this load");
    // Hertz contacts stiffen without bound, so a step may not move a contact by more than the ball's clearance
    // scale; limit it to D / 20 and backtrack on the residual.
    const double limit = 0.05 * sp.ball_diameter;
    if (dq.cwiseAbs().maxCoeff() > limit) dq *= limit / dq.cwiseAbs().maxCoeff();
    double alpha = 1.0;
    bool moved = false;
    for (int k = 0; k < 40; ++k, alpha *= 0.5) {
      BallBearingEquilibrium t = s;
      Vector5d qt = s.displacement;
      for (int i = 0; i < 4; ++i) qt(kDof[i]) += alpha * dq(i) * scales[i];
      if (!equilibrate(speed, qt, t)) continue;
      const Eigen::Vector4d gt = residual(t);
      if (gt.cwiseAbs().maxCoeff() < (1.0 - 1e-4 * alpha) * norm) {
        s = std::move(t);
        g = gt;
        moved = true;
        break;
      }
    }
    // A contact at the edge of closing (a clearance bearing) leaves the finite-difference Jacobian a little off
    // and Newton stalls; a residual of 1e-6 of the force scale moves the ring by about 1e-11 m (k ~ 1e7 N/m).
    if (!moved && norm <= 1e3 * tol) break;
    if (!moved) {
      std::ostringstream os;
      os << "no equilibrium found " << where << ": Newton stalled at a residual of " << norm << " N";
      throw QuasiStaticError(os.str());
    }
    s.iterations = it + 1;
    if (s.displacement.cwiseAbs().maxCoeff() > sp.ball_diameter)
      throw QuasiStaticError("no equilibrium found " + where + ": the inner ring moved by more than a ball diameter");
  }
  const double deflection = largest_contact_deflection(s.balls);
  if (deflection > options_.max_deflection_ratio * sp.ball_diameter) {
    std::ostringstream os;
    os << "the bearing cannot carry the load " << where << ": a contact deflection of " << deflection * 1e6
       << " um exceeds " << options_.max_deflection_ratio * 100 << " % of the ball diameter, beyond Hertz theory";
    throw QuasiStaticError(os.str());
  }
}

void BallBearingQuasiStatic::linearise(BallBearingEquilibrium& s) const {
  // K = -dF/dq and the contact approaches' total derivatives d delta_c / dq by central differences of the
  // condensed equilibrium (balls and z_o re-solved for each perturbed q). Damping: the contact dashpots of
  // paper Eq. 21, d + beta k_c (k_c = 1.5 K delta_c^0.5), along each closed contact's normal, with the balls
  // following the rings as in the static condensation (massless balls): C = sum_c d_c g_c g_c^T, g_c = d delta_c / dq.
  const double Rp = element_.pitch_radius();
  const int Z = n_balls_;
  Eigen::MatrixXd G(2 * Z, 5);
  for (int k = 0; k < 5; ++k) {
    const double h = k < 3 ? kStep : kStep / Rp;
    BallBearingEquilibrium a = s, b = s;
    Vector5d qa = s.displacement, qb = s.displacement;
    qa(k) += h;
    qb(k) -= h;
    if (!equilibrate(s.speed, qa, a) || !equilibrate(s.speed, qb, b))
      throw QuasiStaticError("no equilibrium of the balls found " + describe(s.speed, s.load) +
                             " while differentiating it");
    s.stiffness.col(k) = -(a.shaft_force - b.shaft_force) / (2.0 * h);
    for (int j = 0; j < Z; ++j) {
      G(2 * j, k) = (a.balls[j].inner_deflection - b.balls[j].inner_deflection) / (2.0 * h);
      G(2 * j + 1, k) = (a.balls[j].outer_deflection - b.balls[j].outer_deflection) / (2.0 * h);
    }
  }
  s.damping.setZero();
  for (int j = 0; j < Z; ++j) {
    const double di = s.balls[j].inner_deflection, dout = s.balls[j].outer_deflection;
    if (di > 0.0)
      s.damping += element_.race_contact_damping(element_.inner_contact(), std::sqrt(di)) *
                   G.row(2 * j).transpose() * G.row(2 * j);
    if (dout > 0.0)
      s.damping += element_.race_contact_damping(element_.outer_contact(), std::sqrt(dout)) *
                   G.row(2 * j + 1).transpose() * G.row(2 * j + 1);
  }
}

BallBearingEquilibrium BallBearingQuasiStatic::solve(double speed, const Eigen::Vector3d& load,
                                                     const BallBearingEquilibrium* start) const {
  if (!std::isfinite(speed) || !load.allFinite())
    throw QuasiStaticError("speed and load must be finite");
  BallBearingEquilibrium s;
  Vector5d L = Vector5d::Zero();
  L.head<3>() = load;
  if (start && static_cast<int>(start->balls.size()) == n_balls_ && start->load == L) {
    s = *start;
  } else {
    // From rest: the element's static preload equilibrium, then the load at zero speed. A zero-clearance or
    // clearance bearing has no stiffness at zero load, so Newton starts where the radial load is met along its
    // own direction (bisection on the displacement), which also finds the contacts a clearance has to close.
    std::vector<double> z(element_.n_states());
    element_.initial_states(z.data());
    s.speed = 0.0;
    s.load = L;
    s.displacement.setZero();
    s.balls.resize(n_balls_);
    for (int j = 0; j < n_balls_; ++j) {
      s.balls[j].rho = z[element_.ball_offset(j) + 1];
      s.balls[j].zeta = z[element_.ball_offset(j) + 2];
    }
    s.outer_ring_axial = z[element_.outer_offset()];
    const double radial = load.head<2>().norm();
    if (radial > 0.0) {
      const Eigen::Vector2d e = load.head<2>() / radial;
      const auto along = [&](double a, BallBearingEquilibrium& t) {
        Vector5d q = Vector5d::Zero();
        q.head<2>() = a * e;
        if (!equilibrate(0.0, q, t)) throw QuasiStaticError("no equilibrium of the balls found " + describe(0.0, L));
        return t.shaft_force.head<2>().dot(e) + radial;  // > 0 while the load is not yet carried
      };
      double lo = 0.0, hi = 1e-9;
      BallBearingEquilibrium t = s;
      while (along(hi, t) > 0.0) {
        lo = hi;
        hi *= 2.0;
        if (hi > element_.spec().ball_diameter)
          throw QuasiStaticError("the bearing cannot carry the load " + describe(0.0, L) +
                                 ": no inner-ring displacement up to a ball diameter carries it");
      }
      for (int i = 0; i < 60 && hi - lo > 1e-4 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (along(mid, t) > 0.0 ? lo : hi) = mid;
      }
      along(0.5 * (lo + hi), s);
    }
    solve_at_speed(0.0, s);
  }
  // Continuation in speed, halving the step where Newton fails.
  double step = options_.max_speed_step;
  while (s.speed != speed) {
    const double next = std::abs(speed - s.speed) <= step ? speed : s.speed + std::copysign(step, speed - s.speed);
    BallBearingEquilibrium t = s;
    try {
      solve_at_speed(next, t);
      s = std::move(t);
      step = std::min(2.0 * step, options_.max_speed_step);
    } catch (const QuasiStaticError&) {
      step *= 0.5;
      if (step < 1e-3 * options_.max_speed_step) throw;
    }
  }
  linearise(s);
  return s;
}

std::vector<BallBearingEquilibrium> BallBearingQuasiStatic::sweep(const std::vector<double>& speeds,
                                                                  const Eigen::Vector3d& load) const {
  std::vector<BallBearingEquilibrium> out;
  for (double w : speeds) out.push_back(solve(w, load, out.empty() ? nullptr : &out.back()));
  return out;
}

BearingLinearisation ball_bearing_linearisation(const std::string& name, const BallBearingSpec& spec) {
  struct Model {
    Model(const std::string& name, const BallBearingSpec& spec) : element(name, spec, 0, 0.0), qs(element) {}
    BallBearingElement element;
    BallBearingQuasiStatic qs;
  };
  const auto model = std::make_shared<const Model>(name, spec);
  return [model](double speed, Eigen::Matrix4d& k, Eigen::Matrix4d& c) {
    const BallBearingEquilibrium e = model->qs.solve(speed, Eigen::Vector3d::Zero());
    static constexpr int kNode[4] = {0, 1, 3, 4};  // (x, y, theta_x, theta_y) in (x, y, z, theta_x, theta_y)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        k(i, j) = e.stiffness(kNode[i], kNode[j]);
        c(i, j) = e.damping(kNode[i], kNode[j]);
      }
  };
}

double BallBearingEquilibrium::max_contact_load() const {
  double q = 0.0;
  for (const QuasiStaticBall& ball : balls) q = std::max({q, ball.inner_load, ball.outer_load});
  return q;
}

double BallBearingEquilibrium::max_contact_pressure(const BallBearingElement& element) const {
  double p = 0.0;
  for (const QuasiStaticBall& ball : balls)
    p = std::max({p, HertzPeakPressure(element.inner_contact(), ball.inner_load),
                  HertzPeakPressure(element.outer_contact(), ball.outer_load)});
  return p;
}

std::vector<LoadDeflectionPoint> BallBearingQuasiStatic::load_deflection(double speed,
                                                                        const std::vector<double>& travel,
                                                                        const BallBearingEquilibrium* centred_in) const {
  constexpr double kMaxTravelStep = 1e-6;  // m: continuation steps; Newton from the last point converges
  for (std::size_t i = 0; i < travel.size(); ++i)
    if (!(std::isfinite(travel[i]) && travel[i] >= 0.0 && (i == 0 || travel[i] > travel[i - 1])))
      throw std::invalid_argument("load-deflection travels must be finite, non-negative and increasing");
  const BallBearingSpec& sp = element_.spec();
  if (centred_in && (centred_in->speed != speed || !centred_in->load.isZero()))
    throw std::invalid_argument("load_deflection: the centred equilibrium given is not the unloaded one at this speed");
  BallBearingEquilibrium s = centred_in ? *centred_in : solve(speed, Eigen::Vector3d::Zero());
  const Vector5d centred = s.displacement;
  auto at = [&](double x, BallBearingEquilibrium& state) {
    Vector5d q = centred;
    q(0) = x;
    q(1) = q(3) = q(4) = 0.0;
    if (!equilibrate(speed, q, state)) {
      std::ostringstream os;
      os << "no equilibrium of the balls found at " << std::llround(speed * kRadPerSToRpm)
         << " rpm with the inner ring moved by " << x * 1e6 << " um";
      throw QuasiStaticError(os.str());
    }
    const double deflection = largest_contact_deflection(state.balls);
    if (deflection > options_.max_deflection_ratio * sp.ball_diameter) {
      std::ostringstream os;
      os << "the bearing cannot be moved by " << x * 1e6 << " um at " << std::llround(speed * kRadPerSToRpm)
         << " rpm: a contact deflection of " << deflection * 1e6 << " um exceeds "
         << options_.max_deflection_ratio * 100 << " % of the ball diameter, beyond Hertz theory";
      throw QuasiStaticError(os.str());
    }
  };
  std::vector<LoadDeflectionPoint> out;
  double x = 0.0;
  for (double target : travel) {
    while (x < target) {
      x = std::min(target, x + kMaxTravelStep);
      at(x, s);
    }
    LoadDeflectionPoint p;
    p.travel = target;
    p.load = -s.shaft_force(0);
    p.cross_load = -s.shaft_force(1);
    p.moment_x = -s.shaft_force(3);
    p.moment_y = -s.shaft_force(4);
    p.max_contact_load = s.max_contact_load();
    p.max_contact_pressure = s.max_contact_pressure(element_);
    BallBearingEquilibrium a = s, b = s;
    at(target + kStep, a);
    at(target - kStep, b);  // the ring may move to -x: central differences at every travel, 0 included
    p.tangent = -(a.shaft_force(0) - b.shaft_force(0)) / (2.0 * kStep);
    p.secant = target > 0.0 ? p.load / target : p.tangent;
    out.push_back(p);
  }
  return out;
}

void add_ball_bearing_linearisations(const MachineSpec& machine, Rotor& rotor) {
  const double length = machine.shaft_length();
  for (const BearingSpec& b : machine.bearings) {
    if (b.type != BearingType::Ball) continue;
    const std::string where = machine.source.string() + ": bearings." + b.name;
    if (b.damper.enabled)
      throw ModelError(where + ".damper: squeeze-film dampers are nonlinear; the linear analyses (modal, response) "
                       "do not include them (the ball bearing alone: `turbodyn bearing`)");
    if (b.ball.outer_ring_mode == OuterRingMode::Spring)
      throw ModelError(where + ".outer_ring: an outer ring on a radial spring is not in the linear analyses; use "
                       "outer_ring = \"fixed\"");
    if (b.pedestal_mass > 0.0)
      throw ModelError(where + ".pedestal_mass: pedestal masses are part of the run-up model only; the linear "
                       "analyses (modal, response) do not include them yet");
    LinearBearing lb;
    lb.name = b.name;
    lb.node = rotor.node_at(std::clamp(b.z, 0.0, length));
    try {
      lb.linearisation = ball_bearing_linearisation(b.name, b.ball);
    } catch (const std::invalid_argument& e) {
      throw ModelError(where + ": " + e.what());
    }
    rotor.bearings.push_back(std::move(lb));
  }
}

}  // namespace turbodyn

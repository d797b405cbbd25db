#include "model/engine/unbalance_whirl.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>

#include "model/engine/synchronous_whirl.h"
#include "model/rotor/modal.h"
#include "model/spec/constants.h"

namespace turbodyn {

namespace {

// The continuation works in scaled unknowns: the deflection over its largest translation (a tilt counted as the
// displacement it gives kTiltLength away, about a wheel's overhang) and the speed over itself, both taken at the
// last point of the curve, so that a step of the same size is a like change of the whirl at 10 nm and at 500 um.
constexpr double kTiltLength = 0.01;           // m
constexpr double kSmallestScale = 1e-10;       // m
constexpr double kWhirlMaxSpeedStep = 0.01;    // relative change of the speed per step
constexpr double kMaxDeflectionStep = 0.2;     // relative change of the deflection per step
// Newton's corrections: relative to the deflection and the speed, or an absolute 1e-13 m on the deflection, where
// the balls' equilibria leave their reaction exact to about 1e-9 N (a ball at the edge of a contact: Newton on it
// stalls at 1e-8 of its force scale, docs/ball-bearing.md), i.e. 1e-16 m on bearings of 1e7 N/m.
constexpr double kWhirlNewtonTolerance = 1e-8;
constexpr double kAbsoluteTolerance = 1e-13;  // m
constexpr int kWhirlMaxNewton = 10;
constexpr int kFastNewton = 3;                 // at most this many iterations: the next step grows
constexpr double kStepGrowth = 1.5;
constexpr double kSmallestStep = 1e-7;         // scaled arclength
constexpr int kSeeds = 16;                     // intervals of the seeds' speeds across the range
constexpr std::size_t kDuplicatePoints = 3;
// A real eigenvalue above this fraction of the largest |eigenvalue| (the rotor's stiffest element modes, some 1e7
// 1/s) is a divergence, below it round-off.
constexpr double kDivergenceRoundOff = 1e-9;

std::string radius_text(double m) {
  std::ostringstream os;
  os.precision(3);
  os << m * 1e6 << " um";
  return os.str();
}

class Tracer {
 public:
  Tracer(const MachineSpec& machine, const Rotor& rotor, const WhirlProblem& problem)
      : rotor_(rotor), problem_(problem), weights_(problem.size()), mass_(problem.mass()) {
    for (int i = 0; i < problem.size(); ++i) weights_(i) = problem.is_tilt(i) ? kTiltLength : 1.0;
    for (const BearingSpec& b : machine.bearings) {
      Support s;
      s.name = b.name;
      for (int k = 0; k < problem.n_balls(); ++k)
        if (problem.ball_name(k) == b.name) s.ball = k;
      for (std::size_t k = 0; k < rotor.bearings.size(); ++k)
        if (rotor.bearings[k].name == b.name) s.linear = static_cast<int>(k);
      if (s.ball >= 0 || s.linear >= 0) supports_.push_back(s);
    }
  }

  std::vector<std::string> bearing_names() const {
    std::vector<std::string> out;
    for (const Support& s : supports_) out.push_back(s.name);
    return out;
  }

  // The steady state at `speed` reached from the centred rotor (by raising the unbalance if need be): the branch
  // that grows out of the linear response there. False if none is found.
  bool start_at(double speed, WhirlState& w) const {
    w.speed = speed;
    w.p = Eigen::VectorXd::Zero(problem_.size());
    w.bearings = problem_.centred_bearings(speed);
    return solve_at_speed(w);
  }

  // Continues the curve from the steady state w, upwards to `hi` or downwards to `lo`, until it reaches that end,
  // leaves the range at the other, runs into one of `others` (joins it) or ends.
  UnbalanceWhirlPiece trace(WhirlState w, double lo, double hi, bool upward,
                            const std::vector<UnbalanceWhirlPiece>& others, int max_points) const {
    UnbalanceWhirlPiece piece;
    piece.upward = upward;
    piece.start_speed = w.speed;
    const double dir = upward ? 1.0 : -1.0;
    const double to = upward ? hi : lo;
    if (stop_beyond_hertz(w, piece)) return piece;
    Eigen::VectorXd t;
    Eigen::MatrixXd Jp;
    double scale = scale_of(w.p);
    const bool started = start_tangent(w, scale, dir, t, &Jp);
    piece.points.push_back(started ? point(w, &Jp) : point(w));
    if (!started) {
      piece.stopped = "no steady state found beyond " + rpm_text(w.speed);
      return piece;
    }
    double ds = step_limit(t);
    while (static_cast<int>(piece.points.size()) < max_points) {
      ds = std::min(ds, step_limit(t));
      const double predicted = w.speed * (1.0 + ds * t(problem_.size()));
      if (dir * t(problem_.size()) > 0.0 && dir * (predicted - to) >= 0.0) {
        // The last step lands on the end of the range: the deflection predicted along the tangent, then corrected
        // at that speed (on the same branch: no restart from the centre).
        WhirlState last = w;
        const double fraction = (to - w.speed) / (w.speed * t(problem_.size()));
        last.p = w.p + (fraction * scale) * (t.head(problem_.size()).array() / weights_.array()).matrix();
        last.speed = to;
        if (newton_at_speed(last, 1.0)) {
          if (stop_beyond_hertz(last, piece)) return piece;
          piece.points.push_back(point(last));
          return piece;
        }
        ds *= 0.5;
        if (ds < kSmallestStep) break;
        continue;
      }
      WhirlState next = w;
      int iterations = 0;
      if (!correct(w, scale, t, ds, next, iterations)) {
        ds *= 0.5;
        if (ds < kSmallestStep) break;
        continue;
      }
      if (stop_beyond_hertz(next, piece)) return piece;
      const double next_scale = scale_of(next.p);
      // The previous tangent in the new point's scaling orients the new one.
      Eigen::VectorXd previous = t;
      previous.head(problem_.size()) *= scale / next_scale;
      previous(problem_.size()) *= w.speed / next.speed;
      Eigen::VectorXd t_next;
      if (!tangent(next, next_scale, previous, t_next, &Jp)) {
        ds *= 0.5;
        if (ds < kSmallestStep) break;
        continue;
      }
      if ((t(problem_.size()) > 0.0) != (t_next(problem_.size()) > 0.0))
        piece.folds.push_back(fold(w, next, t(problem_.size()) * w.speed, ds, t(problem_.size()) > 0.0));
      if (next.speed < lo || next.speed > hi) {
        piece.stopped = "the response curve turns back out of the range at " + rpm_text(next.speed);
        return piece;
      }
      w = std::move(next);
      scale = next_scale;
      t = t_next;
      piece.points.push_back(point(w, &Jp));  // the tangent's Jacobian at w
      for (std::size_t k = 0; k < others.size(); ++k)
        if (on_piece(piece.points.back(), others[k])) {
          piece.joins = static_cast<int>(k);
          return piece;
        }
      if (iterations <= kFastNewton) ds *= kStepGrowth;
    }
    std::ostringstream os;
    if (static_cast<int>(piece.points.size()) >= max_points)
      os << "the response curve has more than " << max_points << " points; it ends at " << rpm_text(w.speed);
    else
      os << "no steady state found beyond " << rpm_text(w.speed) << " (largest wheel whirl "
         << radius_text(largest_radius(w.p)) << ")";
    piece.stopped = os.str();
    return piece;
  }

  // Whether the point lies on the piece: between two of its points in speed, with every wheel's whirl radius within
  // kSamePoint of the straight line between them (of the largest radius). The steps are short enough (1 % in speed,
  // 20 % in deflection) for the line to stay that close to the curve away from its folds.
  bool on_piece(const UnbalanceWhirlPoint& p, const UnbalanceWhirlPiece& piece) const {
    constexpr double kSamePoint = 0.05;
    double size = 0.0;
    for (double r : p.disk_radius) size = std::max(size, r);
    const double tolerance = kSamePoint * std::max(size, kSmallestScale);
    for (std::size_t i = 0; i + 1 < piece.points.size(); ++i) {
      const UnbalanceWhirlPoint& a = piece.points[i];
      const UnbalanceWhirlPoint& b = piece.points[i + 1];
      if ((p.speed - a.speed) * (p.speed - b.speed) > 0.0 || a.speed == b.speed) continue;
      const double t = (p.speed - a.speed) / (b.speed - a.speed);
      bool close = true;
      for (std::size_t d = 0; d < p.disk_radius.size() && close; ++d)
        close = std::abs(p.disk_radius[d] - (a.disk_radius[d] + t * (b.disk_radius[d] - a.disk_radius[d]))) <=
                tolerance;
      if (close) return true;
    }
    return false;
  }

 private:
  struct Support {
    std::string name;
    int ball = -1, linear = -1;
  };

  double scale_of(const Eigen::VectorXd& p) const {
    return std::max(kSmallestScale, (p.array() * weights_.array()).abs().maxCoeff());
  }

  double largest_radius(const Eigen::VectorXd& p) const {
    double r = 0.0;
    for (const RigidDisk& d : rotor_.disks)
      r = std::max(r, std::hypot(p(problem_.reduced(d.node, kX)), p(problem_.reduced(d.node, kY))));
    return r;
  }

  double step_limit(const Eigen::VectorXd& t) const {
    const int n = problem_.size();
    return std::min(kWhirlMaxSpeedStep / std::max(std::abs(t(n)), 1e-12),
                    kMaxDeflectionStep / std::max(t.head(n).lpNorm<Eigen::Infinity>(), 1e-12));
  }

  bool stop_beyond_hertz(const WhirlState& w, UnbalanceWhirlPiece& piece) const {
    piece.stopped = problem_.beyond_hertz(w, "at " + rpm_text(w.speed) + " (largest wheel whirl " +
                                                 radius_text(largest_radius(w.p)) + ")");
    if (piece.stopped.empty()) return false;
    piece.stopped += "; the response curve ends before it";
    return true;
  }

  // Newton's method on the deflection at the state's speed, with the unbalance scaled by `load`.
  bool newton_at_speed(WhirlState& w, double load) const {
    Eigen::VectorXd r;
    Eigen::MatrixXd Jp;
    for (int it = 0; it < 2 * kWhirlMaxNewton; ++it) {
      if (!problem_.residual(w.p, w.speed, w.bearings, r, load) || !problem_.jacobian_p(w, Jp)) return false;
      const Eigen::VectorXd d = Jp.partialPivLu().solve(-r);
      if (!d.allFinite()) return false;
      w.p += d;
      if ((d.array() * weights_.array()).abs().maxCoeff() <=
          std::max(kWhirlNewtonTolerance * scale_of(w.p), kAbsoluteTolerance))
        return problem_.residual(w.p, w.speed, w.bearings, r, load);
    }
    return false;
  }

  // The steady state at the state's speed from its deflection; if Newton's method fails from there (a large whirl
  // far from the start), the unbalance is raised from a thousandth of its size in steps, each from the last.
  bool solve_at_speed(WhirlState& w) const {
    const WhirlState start = w;
    if (newton_at_speed(w, 1.0)) return true;
    w = start;
    w.p.setZero();
    double load = 0.0, factor = 4.0;  // at no unbalance the centred rotor is the steady state
    while (load < 1.0) {
      WhirlState trial = w;
      const double next = load == 0.0 ? 1e-3 : std::min(1.0, load * factor);
      if (load > 0.0) trial.p *= next / load;
      if (newton_at_speed(trial, next)) {
        w = std::move(trial);
        load = next;
      } else if (load == 0.0 || (factor = std::sqrt(factor)) < 1.01) {
        return false;
      }
    }
    return true;
  }

  // The scaled Jacobian [dr/dp diag(scale / w), dr/dOmega speed_scale] at a state in equilibrium; dr/dp also in
  // `Jp` if given.
  bool scaled_jacobian(const WhirlState& w, double scale, double speed_scale, Eigen::MatrixXd& J,
                       Eigen::MatrixXd* Jp = nullptr) const {
    const int n = problem_.size();
    Eigen::MatrixXd jp;
    Eigen::VectorXd Js;
    if (!problem_.jacobian_p(w, jp) || !problem_.jacobian_speed(w, Js)) return false;
    J.resize(n, n + 1);
    for (int j = 0; j < n; ++j) J.col(j) = jp.col(j) * (scale / weights_(j));
    J.col(n) = Js * speed_scale;
    if (Jp) *Jp = std::move(jp);
    return true;
  }

  bool start_tangent(const WhirlState& w, double scale, double dir, Eigen::VectorXd& t, Eigen::MatrixXd* Jp) const {
    const int n = problem_.size();
    Eigen::MatrixXd J;
    if (!scaled_jacobian(w, scale, w.speed, J, Jp)) return false;
    t.resize(n + 1);
    t.head(n) = J.leftCols(n).partialPivLu().solve(-J.col(n));
    t(n) = 1.0;
    if (!t.allFinite()) return false;
    t *= dir / t.norm();
    return true;
  }

  // The unit tangent at w (scaled), oriented like `previous`; dr/dp at w in `Jp`.
  bool tangent(const WhirlState& w, double scale, const Eigen::VectorXd& previous, Eigen::VectorXd& t,
               Eigen::MatrixXd* Jp) const {
    const int n = problem_.size();
    Eigen::MatrixXd J;
    if (!scaled_jacobian(w, scale, w.speed, J, Jp)) return false;
    Eigen::MatrixXd A(n + 1, n + 1);
    A.topRows(n) = J;
    A.row(n) = previous.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
    rhs(n) = 1.0;
    t = A.partialPivLu().solve(rhs);
    if (!t.allFinite() || t.norm() == 0.0) return false;
    t /= t.norm();
    if (t.dot(previous) < 0.0) t = -t;
    return true;
  }

  // Keller's pseudo-arclength corrector from w along the unit tangent t by ds (scaled at w's `scale`).
  bool correct(const WhirlState& w, double scale, const Eigen::VectorXd& t, double ds, WhirlState& next,
               int& iterations) const {
    const int n = problem_.size();
    auto to_scaled = [&](const WhirlState& s) {
      Eigen::VectorXd z(n + 1);
      z.head(n) = (s.p.array() * weights_.array()).matrix() / scale;
      z(n) = s.speed / w.speed;
      return z;
    };
    const Eigen::VectorXd z0 = to_scaled(w);
    const Eigen::VectorXd predicted = z0 + ds * t;
    next.p = (predicted.head(n).array() / weights_.array()).matrix() * scale;
    next.speed = predicted(n) * w.speed;
    Eigen::VectorXd r;
    Eigen::MatrixXd J, A(n + 1, n + 1);
    for (iterations = 1; iterations <= kWhirlMaxNewton; ++iterations) {
      if (!(next.speed > 0.0) || !problem_.residual(next.p, next.speed, next.bearings, r)) return false;
      if (!scaled_jacobian(next, scale, w.speed, J)) return false;  // scaled at w, as the unknowns
      A.topRows(n) = J;
      A.row(n) = t.transpose();
      Eigen::VectorXd rhs(n + 1);
      rhs.head(n) = -r;
      rhs(n) = -t.dot(to_scaled(next) - predicted);
      const Eigen::VectorXd d = A.partialPivLu().solve(rhs);
      if (!d.allFinite()) return false;
      next.p += (d.head(n).array() / weights_.array()).matrix() * scale;
      next.speed += d(n) * w.speed;
      if (d.head(n).lpNorm<Eigen::Infinity>() <= std::max(kWhirlNewtonTolerance, kAbsoluteTolerance / scale) &&
          std::abs(d(n)) <= kWhirlNewtonTolerance) {
        // Stay near the prediction: a corrector that wanders off may have jumped to another branch.
        if ((to_scaled(next) - z0).norm() > 2.0 * ds) return false;
        return next.speed > 0.0 && problem_.residual(next.p, next.speed, next.bearings, r);
      }
    }
    return false;
  }

  // The fold between a and b: the speed along the curve as a quadratic in the arclength s with the speed and its
  // slope (dOmega/ds = slope) at a and the speed at b (s = h).
  UnbalanceWhirlFold fold(const WhirlState& a, const WhirlState& b, double slope, double h, bool turns_back) const {
    UnbalanceWhirlFold f;
    f.speed_turns_back = turns_back;
    const double c = (b.speed - a.speed - slope * h) / (h * h);
    double s = c != 0.0 ? -slope / (2.0 * c) : h;
    s = std::clamp(s, 0.0, h);
    f.speed = a.speed + slope * s + c * s * s;
    const double ra = largest_radius(a.p), rb = largest_radius(b.p);
    f.largest_radius = ra + (rb - ra) * (s / h);
    return f;
  }

 public:
  // The point with its stability; `Jp`, dr/dp at w, if the caller has it.
  UnbalanceWhirlPoint point(const WhirlState& w, const Eigen::MatrixXd* Jp = nullptr) const {
    UnbalanceWhirlPoint pt = measure(w);
    classify(w, Jp, pt);
    return pt;
  }

  // The point without its stability: speed, wheels, bearings.
  UnbalanceWhirlPoint measure(const WhirlState& w) const {
    UnbalanceWhirlPoint pt;
    pt.speed = w.speed;
    for (const RigidDisk& d : rotor_.disks) {
      const double x = w.p(problem_.reduced(d.node, kX)), y = w.p(problem_.reduced(d.node, kY));
      pt.disk_radius.push_back(std::hypot(x, y));
      pt.disk_phase.push_back(std::atan2(y, x));
    }
    for (const Support& s : supports_) {
      if (s.ball >= 0) {
        const Vector5d f = problem_.ball_force(w, s.ball);
        pt.bearing_force.push_back(std::hypot(f(0), f(1)));
        pt.max_contact_load.push_back(w.bearings[s.ball].max_contact_load());
        pt.max_contact_pressure.push_back(w.bearings[s.ball].max_contact_pressure(problem_.ball_element(s.ball)));
      } else {
        const LinearBearing& lb = rotor_.bearings[s.linear];
        Eigen::Matrix4d k, c;
        lb.coefficients(w.speed, k, c);
        Eigen::Vector4d u;
        u << w.p(problem_.reduced(lb.node, kX)), w.p(problem_.reduced(lb.node, kY)),
            w.p(problem_.reduced(lb.node, kThetaX)), w.p(problem_.reduced(lb.node, kThetaY));
        const Eigen::Vector4d ju(-u(1), u(0), -u(3), u(2));  // the whirl's velocity over Omega
        const Eigen::Vector4d f = k * u + w.speed * (c * ju);
        pt.bearing_force.push_back(std::hypot(f(0), f(1)));
        pt.max_contact_load.push_back(0.0);
        pt.max_contact_pressure.push_back(0.0);
      }
    }
    return pt;
  }

  // The steady state's stability against a jump: the small motions about it in the turning frame,
  //   M dq'' + (D + C_b + Omega G_r) dq' + J dq = 0,
  // J the residual's tangent (the ball bearings' quasi-static tangent stiffness in it), have a real positive
  // eigenvalue on the branch between two folds (a saddle: the whirl drifts off to another branch). Oscillatory
  // eigenvalues are left out: with the contacts undamped and the quasi-static reaction not quite conservative (the
  // gyroscopic moment carried by the outer contact's traction) their real parts are a few 1/s either way, below what
  // this model can tell.
  void classify(const WhirlState& w, const Eigen::MatrixXd* given, UnbalanceWhirlPoint& pt) const {
    const int n = problem_.size();
    Eigen::MatrixXd computed;
    if (!given && !problem_.jacobian_p(w, computed)) {
      pt.divergence_rate = std::numeric_limits<double>::quiet_NaN();
      pt.stable = false;
      return;
    }
    const Eigen::MatrixXd& Jp = given ? *given : computed;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -mass_.solve(Jp);
    A.bottomRightCorner(n, n) = -mass_.solve(problem_.velocity_part(w.speed));
    balance_for_eigenvalues(A);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
    double rate = 0.0, size = 0.0;
    for (int i = 0; i < 2 * n; ++i) {
      const std::complex<double> l = es.eigenvalues()(i);
      size = std::max(size, std::abs(l));
      if (l.imag() == 0.0) rate = std::max(rate, l.real());
    }
    pt.divergence_rate = rate;
    pt.stable = !(rate > kDivergenceRoundOff * size);
  }

 private:
  const Rotor& rotor_;
  const WhirlProblem& problem_;
  Eigen::VectorXd weights_;
  Eigen::LLT<Eigen::MatrixXd> mass_;
  std::vector<Support> supports_;
};

}  // namespace

UnbalanceWhirl nonlinear_unbalance_response(const MachineSpec& machine, const Rotor& rotor,
                                            const UnbalanceWhirlOptions& options) {
  if (!(std::isfinite(options.start_speed) && std::isfinite(options.end_speed) && options.start_speed > 0.0 &&
        options.end_speed > options.start_speed))
    throw std::invalid_argument("the speed range must be finite and increasing from above zero");
  if (options.max_points < 2) throw std::invalid_argument("max_points must be at least 2");
  const WhirlProblem problem(machine, rotor, WhirlProblem::Planes::Both, "the nonlinear unbalance response");
  const Tracer tracer(machine, rotor, problem);
  UnbalanceWhirl out;
  out.bearings = tracer.bearing_names();
  for (const RigidDisk& d : rotor.disks) out.disks.push_back(d.name);
  const double lo = options.start_speed, hi = options.end_speed;
  auto from_end = [&](double speed, bool upward) {
    WhirlState w;
    if (tracer.start_at(speed, w)) return tracer.trace(w, lo, hi, upward, out.pieces, options.max_points);
    UnbalanceWhirlPiece piece;
    piece.upward = upward;
    piece.start_speed = speed;
    piece.stopped = "no steady state found at " + rpm_text(speed);
    return piece;
  };
  out.pieces.push_back(from_end(lo, true));
  if (!out.pieces[0].stopped.empty()) out.pieces.push_back(from_end(hi, false));
  // Branches that neither end reaches (above a critical whose resonant branch the continuation climbs, say): seeded
  // at speeds across the range from the centred rotor, where the point found lies on no piece yet. A seed's piece
  // that joins another within its first steps is that piece again, and is dropped.
  for (int i = 1; i < kSeeds; ++i) {
    const double speed = lo + (hi - lo) * i / kSeeds;
    WhirlState w;
    if (!tracer.start_at(speed, w)) continue;
    const UnbalanceWhirlPoint seed = tracer.measure(w);
    if (std::any_of(out.pieces.begin(), out.pieces.end(),
                    [&](const UnbalanceWhirlPiece& p) { return tracer.on_piece(seed, p); }))
      continue;
    // Both traced against the pieces before the seed.
    UnbalanceWhirlPiece pair[2] = {tracer.trace(w, lo, hi, true, out.pieces, options.max_points),
                                   tracer.trace(w, lo, hi, false, out.pieces, options.max_points)};
    for (UnbalanceWhirlPiece& piece : pair)
      if (!(piece.joins >= 0 && piece.points.size() <= kDuplicatePoints)) out.pieces.push_back(std::move(piece));
  }
  // Covered: the union of the pieces' speed intervals is the range.
  std::vector<std::pair<double, double>> spans;
  for (const UnbalanceWhirlPiece& p : out.pieces) {
    if (p.points.empty()) continue;
    double a = p.points.front().speed, b = a;
    for (const UnbalanceWhirlPoint& q : p.points) a = std::min(a, q.speed), b = std::max(b, q.speed);
    spans.emplace_back(a, b);
  }
  std::sort(spans.begin(), spans.end());
  double reached = lo;
  for (const auto& [a, b] : spans)
    if (a <= reached * (1.0 + 1e-12)) reached = std::max(reached, b);
  out.covers_range = reached >= hi * (1.0 - 1e-12);
  return out;
}

}  // namespace turbodyn

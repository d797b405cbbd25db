#include "model/engine/backbone.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/SVD>

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/spec/constants.h"

namespace turbodyn {

namespace {

// Steps of the central differences of the balls' reaction: 2 nm and 1e-7 rad (a tilt that moves the ring's
// contacts by a few nm), well inside the Hertz contacts' nonlinearity and far above the equilibria's round-off.
constexpr double kTranslationStep = 2e-9;
constexpr double kTiltStep = 1e-7;
constexpr double kRelativeSpeedStep = 1e-6;
constexpr int kMaxNewton = 25;
// Relative correction of the deflection and of the speed: the balls' equilibria leave their reaction exact to
// about 1e-9 of the whirl's forces at the smallest amplitude (kStartTranslation).
constexpr double kNewtonTolerance = 1e-7;
constexpr int kMaxHalvings = 8;
constexpr double kMaxAmplitudeRatio = 1.5;  // per continuation step
constexpr double kMaxSpeedChange = 0.02;    // relative, per continuation step
constexpr double kStartTranslation = 1e-8;  // m, the largest whirl radius of the first point

struct BallSupport {
  std::string name;
  int node = 0;
  std::unique_ptr<BallBearingElement> element;
  std::unique_ptr<BallBearingQuasiStatic> qs;
};

// One state of the continuation: the reduced deflection (x, theta_y per node), the speed, each ball bearing's
// equilibrium (the balls' places, the starting point of the next equilibrate).
struct WhirlState {
  Eigen::VectorXd p;
  double speed = 0.0;
  std::vector<BallBearingEquilibrium> bearings;
};

std::string rpm(double speed) {
  std::ostringstream os;
  os << std::llround(speed * kRadPerSToRpm) << " rpm";
  return os.str();
}

class WhirlProblem {
 public:
  WhirlProblem(const MachineSpec& machine, const Rotor& rotor) : rotor_(rotor) {
    n_nodes_ = rotor.n_dof / kDofPerNode;
    for (const BearingSpec& b : machine.bearings) {
      if (b.type == BearingType::FloatingRing || b.type == BearingType::Journal || !rotor.rings.empty())
        throw std::runtime_error("bearings." + b.name + ": the critical speeds at an amplitude take ball and linear "
                                 "bearings only, not " + to_string(b.type) + " bearings");
      if (b.type != BearingType::Ball) continue;
      if (b.damper.enabled)
        throw std::runtime_error("bearings." + b.name + ": a ball bearing in a squeeze-film damper is not in the "
                                 "critical speeds at an amplitude (the damper is a film, not a quasi-static force)");
      if (b.ball.outer_ring_mode == OuterRingMode::Spring)
        throw std::runtime_error("bearings." + b.name + ": an outer ring on a radial spring is not in the critical "
                                 "speeds at an amplitude; use outer_ring = \"fixed\"");
      if (b.pedestal_mass > 0.0)
        throw std::runtime_error("bearings." + b.name + ": pedestal masses are not in the critical speeds at an "
                                 "amplitude");
      BallSupport s;
      s.name = b.name;
      s.node = rotor.node_at(std::clamp(b.z, 0.0, machine.shaft_length()));
      s.element = std::make_unique<BallBearingElement>(b.name, b.ball, 0, 0.0);
      s.qs = std::make_unique<BallBearingQuasiStatic>(*s.element);
      balls_.push_back(std::move(s));
    }
    m_omega_ = rotor.spin_softening();
  }

  int size() const { return 2 * n_nodes_; }
  int reduced(int node, Dof d) const { return 2 * node + (d == kX ? 0 : 1); }
  const std::vector<BallSupport>& balls() const { return balls_; }

  // The linear part in the x-z plane at `speed`: P^T (K + K_b + speed^2 M_Omega) P. Throws for linear bearings
  // that couple the plane to the other or differ between the planes.
  Eigen::MatrixXd linear_part(double speed) const {
    check_linear_bearings(speed);
    Eigen::MatrixXd K = rotor_.K, D = rotor_.D;
    rotor_.add_bearings(speed, K, D);
    K += speed * speed * m_omega_;
    Eigen::MatrixXd A(size(), size());
    for (int i = 0; i < n_nodes_; ++i)
      for (int j = 0; j < n_nodes_; ++j)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) {
            const int ri = rotor_.dof(i, a == 0 ? kX : kThetaY), cj = rotor_.dof(j, b == 0 ? kX : kThetaY);
            A(2 * i + a, 2 * j + b) = K(ri, cj);
          }
    return A;
  }

  // Each linear bearing's 4 x 4 block at `speed` must commute with the quarter turn (the same in every direction)
  // and leave the x-z plane (x, theta_y) uncoupled from the y-z plane (y, theta_x).
  void check_linear_bearings(double speed) const {
    constexpr double kSymmetryTolerance = 1e-9;
    Eigen::Matrix4d quarter = Eigen::Matrix4d::Zero();  // Rotor::quarter_turn on one node
    quarter(1, 0) = quarter(3, 2) = 1.0;
    quarter(0, 1) = quarter(2, 3) = -1.0;
    for (const LinearBearing& b : rotor_.bearings) {
      Eigen::Matrix4d k, c;
      b.coefficients(speed, k, c);
      double cross = 0.0;
      for (Dof r : {kX, kThetaY})
        for (Dof q : {kY, kThetaX}) cross = std::max(cross, std::abs(k(r, q)));
      const double tolerance = kSymmetryTolerance * (1.0 + k.norm());
      if ((k * quarter - quarter * k).norm() > tolerance || cross > tolerance)
        throw std::runtime_error("the critical speeds at an amplitude need linear bearings that are the same in "
                                 "every direction and not cross-coupled (kxx = kyy, kxy = kyx = 0) at " + rpm(speed));
    }
  }

  // The ball bearings' equilibria at the deflection p and `speed` (starting from, and overwriting, `states`) and
  // their reaction moved to the left-hand side: r += -f on the (x, theta_y) rows. False if a bearing's balls find
  // no equilibrium.
  bool add_balls(const Eigen::VectorXd& p, double speed, std::vector<BallBearingEquilibrium>& states,
                 Eigen::VectorXd& r) const {
    for (std::size_t b = 0; b < balls_.size(); ++b) {
      const BallSupport& s = balls_[b];
      Vector5d q = Vector5d::Zero();
      q(0) = p(reduced(s.node, kX));
      q(4) = p(reduced(s.node, kThetaY));
      if (!s.qs->equilibrate(speed, q, states[b])) return false;
      r(reduced(s.node, kX)) -= states[b].shaft_force(0);
      r(reduced(s.node, kThetaY)) -= states[b].shaft_force(4);
    }
    return true;
  }

  bool residual(const Eigen::VectorXd& p, double speed, std::vector<BallBearingEquilibrium>& states,
                Eigen::VectorXd& r) const {
    r = linear_part(speed) * p;
    return add_balls(p, speed, states, r);
  }

  // Jacobian of the residual in p (n x n) at a state whose bearings are in equilibrium: the linear part plus each
  // ball bearing's tangent by central differences.
  bool jacobian_p(const WhirlState& w, Eigen::MatrixXd& Jp) const {
    Jp = linear_part(w.speed);
    for (std::size_t b = 0; b < balls_.size(); ++b) {
      const BallSupport& s = balls_[b];
      Vector5d q = Vector5d::Zero();
      q(0) = w.p(reduced(s.node, kX));
      q(4) = w.p(reduced(s.node, kThetaY));
      const int rows[2] = {reduced(s.node, kX), reduced(s.node, kThetaY)};
      const int comp[2] = {0, 4};
      const double step[2] = {kTranslationStep, kTiltStep};
      for (int c = 0; c < 2; ++c) {
        BallBearingEquilibrium plus = w.bearings[b], minus = w.bearings[b];
        Vector5d qp = q, qm = q;
        qp(comp[c]) += step[c];
        qm(comp[c]) -= step[c];
        if (!s.qs->equilibrate(w.speed, qp, plus) || !s.qs->equilibrate(w.speed, qm, minus)) return false;
        for (int r = 0; r < 2; ++r)
          Jp(rows[r], rows[c]) -= (plus.shaft_force(comp[r]) - minus.shaft_force(comp[r])) / (2.0 * step[c]);
      }
    }
    return true;
  }

 private:
  const Rotor& rotor_;
  int n_nodes_ = 0;
  std::vector<BallSupport> balls_;
  Eigen::MatrixXd m_omega_;
};

// Newton's method on (p, speed) with p(ref) = amplitude, from `w` (overwritten by the solution). False if it
// does not converge.
bool solve_whirl(const WhirlProblem& problem, int ref, double amplitude, WhirlState& w) {
  const int n = problem.size();
  Eigen::VectorXd r;
  Eigen::MatrixXd Jp, J(n + 1, n + 1);
  const double start_speed = w.speed;
  for (int it = 0; it < kMaxNewton; ++it) {
    if (!problem.residual(w.p, w.speed, w.bearings, r)) return false;
    if (!problem.jacobian_p(w, Jp)) return false;
    // The speed column by central differences of the whole residual (linear part and balls).
    const double h = kRelativeSpeedStep * w.speed;
    std::vector<BallBearingEquilibrium> sp = w.bearings, sm = w.bearings;
    Eigen::VectorXd rp, rm;
    if (!problem.residual(w.p, w.speed + h, sp, rp) || !problem.residual(w.p, w.speed - h, sm, rm)) return false;
    // Scaled unknowns (the deflection over the amplitude, the speed over itself) so that every column is a force
    // of the whirl's own size: near a critical speed the speed column is the small one that matters.
    J.setZero();
    J.topLeftCorner(n, n) = Jp * amplitude;
    J.topRightCorner(n, 1) = (rp - rm) / (2.0 * h) * w.speed;
    J(n, ref) = 1.0;
    Eigen::VectorXd rhs(n + 1);
    rhs.head(n) = -r;
    rhs(n) = (amplitude - w.p(ref)) / amplitude;
    Eigen::VectorXd d = J.partialPivLu().solve(rhs);
    d.head(n) *= amplitude;
    d(n) *= w.speed;
    if (!d.allFinite()) return false;
    w.p += d.head(n);
    w.speed += d(n);
    if (!(w.speed > 0.2 * start_speed && w.speed < 5.0 * start_speed)) return false;
    if (d.head(n).lpNorm<Eigen::Infinity>() <= kNewtonTolerance * w.p.lpNorm<Eigen::Infinity>() &&
        std::abs(d(n)) <= kNewtonTolerance * w.speed)
      return problem.residual(w.p, w.speed, w.bearings, r);  // the bearings' states at the solution
  }
  return false;
}

BackbonePoint make_point(const WhirlProblem& problem, const WhirlState& w, double amplitude) {
  BackbonePoint pt;
  pt.amplitude = amplitude;
  pt.speed = w.speed;
  for (std::size_t b = 0; b < problem.balls().size(); ++b) {
    const BallSupport& s = problem.balls()[b];
    const BallBearingEquilibrium& e = w.bearings[b];
    BackboneBearing bb;
    bb.name = s.name;
    bb.displacement = w.p(problem.reduced(s.node, kX));
    bb.tilt = w.p(problem.reduced(s.node, kThetaY));
    bb.force = -e.shaft_force(0);
    bb.moment = -e.shaft_force(4);
    for (const QuasiStaticBall& ball : e.balls)
      bb.max_contact_load = std::max({bb.max_contact_load, ball.inner_load, ball.outer_load});
    pt.bearings.push_back(bb);
  }
  return pt;
}

// Empty, or why the whirl at amplitude `a` is beyond the model: a ball contact deflected by more than its quasi-static
// model's max_deflection_ratio of the ball diameter.
std::string beyond_hertz(const WhirlProblem& problem, const WhirlState& w, double a) {
  for (std::size_t b = 0; b < problem.balls().size(); ++b) {
    const double dmax = largest_contact_deflection(w.bearings[b].balls);
    const double ratio = problem.balls()[b].qs->options().max_deflection_ratio;
    const double lim = ratio * problem.balls()[b].element->spec().ball_diameter;
    if (dmax > lim) {
      std::ostringstream os;
      os << "at an amplitude of " << a * 1e6 << " um a ball contact of bearings." << problem.balls()[b].name
         << " deflects by " << dmax * 1e6 << " um, beyond " << ratio * 100
         << " % of the ball diameter (Hertz theory); the backbone ends before it";
      return os.str();
    }
  }
  return {};
}

}  // namespace

std::vector<Backbone> synchronous_backbones(const MachineSpec& machine, const Rotor& rotor,
                                            const std::vector<double>& start_speeds, const BackboneOptions& options) {
  const std::vector<double>& amps = options.amplitudes;
  if (amps.empty()) throw std::invalid_argument("no amplitudes given");
  for (std::size_t i = 0; i < amps.size(); ++i)
    if (!(std::isfinite(amps[i]) && amps[i] > 0.0 && (i == 0 || amps[i] > amps[i - 1])))
      throw std::invalid_argument("amplitudes must be finite, positive and increasing");
  if (options.reference_nodes.empty()) throw std::invalid_argument("no reference node given");
  for (int node : options.reference_nodes)
    if (node < 0 || node >= rotor.n_dof / kDofPerNode) throw std::invalid_argument("reference node out of range");
  const WhirlProblem problem(machine, rotor);

  std::vector<Backbone> out;
  for (std::size_t k = 0; k < start_speeds.size(); ++k) {
    Backbone bb;
    bb.branch = static_cast<int>(k);
    bb.linear_speed = start_speeds[k];
    WhirlState w;
    w.speed = start_speeds[k];
    w.p = Eigen::VectorXd::Zero(problem.size());
    for (const BallSupport& s : problem.balls()) w.bearings.push_back(s.qs->solve(w.speed, Eigen::Vector3d::Zero()));
    // The starting shape: the null vector of the tangent problem at the linear critical speed.
    Eigen::MatrixXd Jp;
    Eigen::VectorXd r0;
    if (!problem.residual(w.p, w.speed, w.bearings, r0) || !problem.jacobian_p(w, Jp))
      throw QuasiStaticError("no equilibrium of the ball bearings at " + rpm(w.speed));
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jp, Eigen::ComputeFullV);
    Eigen::VectorXd shape = svd.matrixV().col(problem.size() - 1);
    bb.reference_node = options.reference_nodes.front();
    for (int node : options.reference_nodes)
      if (std::abs(shape(problem.reduced(node, kX))) > std::abs(shape(problem.reduced(bb.reference_node, kX))))
        bb.reference_node = node;
    const int ref = problem.reduced(bb.reference_node, kX);
    if (std::abs(shape(ref)) < 1e-6 * shape.lpNorm<Eigen::Infinity>())
      throw std::invalid_argument("the reference node hardly moves in the mode at " + rpm(w.speed) +
                                  "; take another reference");
    shape /= shape(ref);
    // The first whirl where the linearisation holds: the largest translation anywhere kStartTranslation (the
    // reference may sit near a node of the mode, where the first amplitude asked for is a large whirl elsewhere).
    double largest = 0.0;
    for (int node = 0; node < rotor.n_dof / kDofPerNode; ++node)
      largest = std::max(largest, std::abs(shape(problem.reduced(node, kX))));
    double reached = std::min(amps.front(), kStartTranslation / largest);
    w.p = shape * reached;
    if (!solve_whirl(problem, ref, reached, w)) {
      bb.stopped = "no synchronous whirl found at the start, " + rpm(w.speed);
      out.push_back(std::move(bb));
      continue;
    }
    for (double target : amps) {
      // Steps of at most kMaxAmplitudeRatio and kMaxSpeedChange keep the continuation on its branch (two forward
      // modes' backbones can come close); a step that fails or leaves is halved.
      double a = std::min(target, kMaxAmplitudeRatio * reached);
      int halvings = 0;
      while (reached < target) {
        WhirlState trial = w;
        trial.p = w.p * (a / reached);
        const bool ok =
            solve_whirl(problem, ref, a, trial) && std::abs(trial.speed - w.speed) <= kMaxSpeedChange * w.speed;
        if (ok) {
          w = std::move(trial);
          reached = a;
          bb.stopped = beyond_hertz(problem, w, a);
          if (!bb.stopped.empty()) break;
          a = std::min(target, kMaxAmplitudeRatio * reached);
          halvings = 0;
        } else if (++halvings > kMaxHalvings) {
          std::ostringstream os;
          os << "no synchronous whirl found beyond an amplitude of " << reached * 1e6 << " um (" << rpm(w.speed)
             << "): the amplitude at the reference stops growing along the branch there, or the branch ends; a "
                "reference that moves more in this mode may go further";
          bb.stopped = os.str();
          break;
        } else {
          a = reached + 0.5 * (a - reached);
        }
      }
      if (!bb.stopped.empty()) break;
      bb.points.push_back(make_point(problem, w, target));
    }
    out.push_back(std::move(bb));
  }
  return out;
}

}  // namespace turbodyn

#include "model/engine/backbone.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/SVD>

#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/engine/synchronous_whirl.h"
#include "model/spec/constants.h"

namespace turbodyn {

namespace {

constexpr int kBackboneMaxNewton = 25;
// Relative correction of the deflection and of the speed: the balls' equilibria leave their reaction exact to
// about 1e-9 of the whirl's forces at the smallest amplitude (kStartTranslation).
constexpr double kBackboneNewtonTolerance = 1e-7;
constexpr int kMaxHalvings = 8;
constexpr double kMaxAmplitudeRatio = 1.5;  // per continuation step
constexpr double kMaxSpeedChange = 0.02;    // relative, per continuation step
constexpr double kStartTranslation = 1e-8;  // m, the largest whirl radius of the first point

// Newton's method on (p, speed) with p(ref) = amplitude, from `w` (overwritten by the solution). False if it
// does not converge.
bool solve_whirl(const WhirlProblem& problem, int ref, double amplitude, WhirlState& w) {
  const int n = problem.size();
  Eigen::VectorXd r;
  Eigen::MatrixXd Jp, J(n + 1, n + 1);
  const double start_speed = w.speed;
  for (int it = 0; it < kBackboneMaxNewton; ++it) {
    if (!problem.residual(w.p, w.speed, w.bearings, r)) return false;
    if (!problem.jacobian_p(w, Jp)) return false;
    // The speed column by central differences of the whole residual (linear part and balls).
    Eigen::VectorXd Js;
    if (!problem.jacobian_speed(w, Js)) return false;
    // Scaled unknowns (the deflection over the amplitude, the speed over itself) so that every column is a force
    // of the whirl's own size: near a critical speed the speed column is the small one that matters.
    J.setZero();
    J.topLeftCorner(n, n) = Jp * amplitude;
    J.topRightCorner(n, 1) = Js * w.speed;
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
    if (d.head(n).lpNorm<Eigen::Infinity>() <= kBackboneNewtonTolerance * w.p.lpNorm<Eigen::Infinity>() &&
        std::abs(d(n)) <= kBackboneNewtonTolerance * w.speed)
      return problem.residual(w.p, w.speed, w.bearings, r);  // the bearings' states at the solution
  }
  return false;
}

BackbonePoint make_point(const WhirlProblem& problem, const WhirlState& w, double amplitude) {
  BackbonePoint pt;
  pt.amplitude = amplitude;
  pt.speed = w.speed;
  for (int b = 0; b < problem.n_balls(); ++b) {
    const BallBearingEquilibrium& e = w.bearings[b];
    BackboneBearing bb;
    bb.name = problem.ball_name(b);
    bb.displacement = w.p(problem.reduced(problem.ball_node(b), kX));
    bb.tilt = w.p(problem.reduced(problem.ball_node(b), kThetaY));
    const Vector5d f = problem.ball_force(w, b);
    bb.force = -f(0);
    bb.moment = -f(4);
    bb.max_contact_load = e.max_contact_load();
    bb.max_contact_pressure = e.max_contact_pressure(problem.ball_element(b));
    pt.bearings.push_back(bb);
  }
  return pt;
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
  const WhirlProblem problem(machine, rotor, WhirlProblem::Planes::One, "the critical speeds at an amplitude");

  std::vector<Backbone> out;
  for (std::size_t k = 0; k < start_speeds.size(); ++k) {
    Backbone bb;
    bb.branch = static_cast<int>(k);
    bb.linear_speed = start_speeds[k];
    WhirlState w;
    w.speed = start_speeds[k];
    w.p = Eigen::VectorXd::Zero(problem.size());
    w.bearings = problem.centred_bearings(w.speed);
    // The starting shape: the null vector of the tangent problem at the linear critical speed.
    Eigen::MatrixXd Jp;
    Eigen::VectorXd r0;
    if (!problem.residual(w.p, w.speed, w.bearings, r0) || !problem.jacobian_p(w, Jp))
      throw QuasiStaticError("no equilibrium of the ball bearings at " + rpm_text(w.speed));
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jp, Eigen::ComputeFullV);
    Eigen::VectorXd shape = svd.matrixV().col(problem.size() - 1);
    bb.reference_node = options.reference_nodes.front();
    for (int node : options.reference_nodes)
      if (std::abs(shape(problem.reduced(node, kX))) > std::abs(shape(problem.reduced(bb.reference_node, kX))))
        bb.reference_node = node;
    const int ref = problem.reduced(bb.reference_node, kX);
    if (std::abs(shape(ref)) < 1e-6 * shape.lpNorm<Eigen::Infinity>())
      throw std::invalid_argument("the reference node hardly moves in the mode at " + rpm_text(w.speed) +
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
      bb.stopped = "no synchronous whirl found at the start, " + rpm_text(w.speed);
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
          std::ostringstream where;
          where << "at an amplitude of " << a * 1e6 << " um";
          bb.stopped = problem.beyond_hertz(w, where.str());
          if (!bb.stopped.empty()) {
            bb.stopped += "; the backbone ends before it";
            break;
          }
          a = std::min(target, kMaxAmplitudeRatio * reached);
          halvings = 0;
        } else if (++halvings > kMaxHalvings) {
          std::ostringstream os;
          os << "no synchronous whirl found beyond an amplitude of " << reached * 1e6 << " um (" << rpm_text(w.speed)
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

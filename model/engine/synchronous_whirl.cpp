#include "model/engine/synchronous_whirl.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/elements/ball/ball_bearing.h"
#include "model/spec/constants.h"

namespace turbodyn {

namespace {

// Steps of the central differences of the balls' reaction: 2 nm and 1e-7 rad (a tilt that moves the ring's
// contacts by a few nm), well inside the Hertz contacts' nonlinearity and far above the equilibria's round-off.
constexpr double kTranslationStep = 2e-9;
constexpr double kTiltStep = 1e-7;
constexpr double kRelativeSpeedStep = 1e-6;

// Index of a rotor DOF in the ball bearing's 5-vector (x, y, z, theta_x, theta_y).
int five(Dof d) { return d == kX ? 0 : d == kY ? 1 : d == kThetaX ? 3 : 4; }

// The direction of the ring's displacement in q (cosine, sine; along x at the centre).
void direction(const Vector5d& q, double& c, double& s) {
  const double r = std::hypot(q(0), q(1));
  c = r > 0.0 ? q(0) / r : 1.0;
  s = r > 0.0 ? q(1) / r : 0.0;
}

// v turned about the bearing axis by the angle of cosine c and sine s: the (x, y) and (theta_x, theta_y) pairs.
Vector5d turned(const Vector5d& v, double c, double s) {
  Vector5d t = v;
  t(0) = c * v(0) - s * v(1);
  t(1) = s * v(0) + c * v(1);
  t(3) = c * v(3) - s * v(4);
  t(4) = s * v(3) + c * v(4);
  return t;
}

}  // namespace

struct WhirlProblem::BallSupport {
  std::string name;
  int node = 0;
  std::unique_ptr<BallBearingElement> element;
  std::unique_ptr<BallBearingQuasiStatic> qs;
};

WhirlProblem::WhirlProblem(const MachineSpec& machine, const Rotor& rotor, Planes planes, std::string analysis)
    : rotor_(rotor), planes_(planes), analysis_(std::move(analysis)) {
  n_nodes_ = rotor.n_dof / kDofPerNode;
  for (const BearingSpec& b : machine.bearings) {
    if (b.type == BearingType::FloatingRing || b.type == BearingType::Journal || !rotor.rings.empty())
      throw std::runtime_error("bearings." + b.name + ": " + analysis_ + " take ball and linear bearings only, not " +
                               to_string(b.type) + " bearings");
    if (b.type != BearingType::Ball) continue;
    if (b.damper.enabled)
      throw std::runtime_error("bearings." + b.name + ": a ball bearing in a squeeze-film damper is not in " +
                               analysis_ + " (the damper is a film, not a quasi-static force)");
    if (b.ball.outer_ring_mode == OuterRingMode::Spring)
      throw std::runtime_error("bearings." + b.name + ": an outer ring on a radial spring is not in " + analysis_ +
                               "; use outer_ring = \"fixed\"");
    if (b.pedestal_mass > 0.0)
      throw std::runtime_error("bearings." + b.name + ": pedestal masses are not in " + analysis_);
    auto s = std::make_unique<BallSupport>();
    s->name = b.name;
    s->node = rotor.node_at(std::clamp(b.z, 0.0, machine.shaft_length()));
    s->element = std::make_unique<BallBearingElement>(b.name, b.ball, 0, 0.0);
    s->qs = std::make_unique<BallBearingQuasiStatic>(*s->element);
    balls_.push_back(std::move(s));
  }
  const std::vector<Dof> per_node = planes == Planes::One ? std::vector<Dof>{kX, kThetaY}
                                                          : std::vector<Dof>{kX, kY, kThetaX, kThetaY};
  index_.assign(rotor.n_dof, -1);
  for (int node = 0; node < n_nodes_; ++node)
    for (Dof d : per_node) {
      index_[rotor.dof(node, d)] = static_cast<int>(dofs_.size());
      dofs_.push_back(rotor.dof(node, d));
      tilt_.push_back(d == kThetaX || d == kThetaY);
    }
  m_omega_ = rotor.spin_softening();
  j_ = rotor.quarter_turn();
  g_r_ = rotor.rotating_frame_gyroscopic();
  unbalance_ = Eigen::VectorXd::Zero(size());
  if (planes == Planes::Both)
    for (const RigidDisk& d : rotor.disks) {
      unbalance_(reduced(d.node, kX)) += d.unbalance * std::cos(d.unbalance_phase);
      unbalance_(reduced(d.node, kY)) += d.unbalance * std::sin(d.unbalance_phase);
    }
}

WhirlProblem::~WhirlProblem() = default;

int WhirlProblem::reduced(int node, Dof d) const { return index_.at(rotor_.dof(node, d)); }
const std::string& WhirlProblem::ball_name(int b) const { return balls_.at(b)->name; }
int WhirlProblem::ball_node(int b) const { return balls_.at(b)->node; }
const BallBearingElement& WhirlProblem::ball_element(int b) const { return *balls_.at(b)->element; }
const BallBearingQuasiStatic& WhirlProblem::ball_model(int b) const { return *balls_.at(b)->qs; }

std::vector<BallBearingEquilibrium> WhirlProblem::centred_bearings(double speed) const {
  std::vector<BallBearingEquilibrium> out;
  for (const auto& s : balls_) out.push_back(s->qs->solve(speed, Eigen::Vector3d::Zero()));
  return out;
}

void WhirlProblem::with_linear_bearings(double speed, Eigen::MatrixXd& K, Eigen::MatrixXd& D) const {
  K = rotor_.K;
  D = rotor_.D;
  rotor_.add_bearings(speed, K, D);
}

Eigen::MatrixXd WhirlProblem::linear_part(double speed) const {
  check_linear_bearings(speed);
  Eigen::MatrixXd K, D;
  with_linear_bearings(speed, K, D);
  K += speed * speed * m_omega_;
  if (planes_ == Planes::Both) K += speed * D * j_;
  return reduce(K);
}

Eigen::MatrixXd WhirlProblem::reduce(const Eigen::MatrixXd& full) const {
  const int n = size();
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = full(dofs_[i], dofs_[j]);
  return A;
}

Eigen::VectorXd WhirlProblem::unbalance(double speed) const { return speed * speed * unbalance_; }

Eigen::MatrixXd WhirlProblem::velocity_part(double speed) const {
  if (planes_ != Planes::Both) throw std::logic_error("the whirl's small motions need both planes");
  Eigen::MatrixXd K, D;
  with_linear_bearings(speed, K, D);
  return reduce(D + speed * g_r_);
}

Eigen::MatrixXd WhirlProblem::mass() const { return reduce(rotor_.M); }

// Each linear bearing's 4 x 4 block at `speed` must commute with the quarter turn (the same in every direction);
// with one plane it must also leave the x-z plane (x, theta_y) uncoupled from the y-z plane (y, theta_x).
void WhirlProblem::check_linear_bearings(double speed) const {
  constexpr double kSymmetryTolerance = 1e-9;
  Eigen::Matrix4d quarter = Eigen::Matrix4d::Zero();  // Rotor::quarter_turn on one node
  quarter(1, 0) = quarter(3, 2) = 1.0;
  quarter(0, 1) = quarter(2, 3) = -1.0;
  for (const LinearBearing& b : rotor_.bearings) {
    Eigen::Matrix4d k, c;
    b.coefficients(speed, k, c);
    double cross = 0.0;
    if (planes_ == Planes::One)
      for (Dof r : {kX, kThetaY})
        for (Dof q : {kY, kThetaX}) cross = std::max(cross, std::abs(k(r, q)));
    const double tk = kSymmetryTolerance * (1.0 + k.norm()), tc = kSymmetryTolerance * (1.0 + c.norm());
    const bool isotropic = (k * quarter - quarter * k).norm() <= tk && (c * quarter - quarter * c).norm() <= tc;
    if (planes_ == Planes::One && (!isotropic || cross > tk))
      throw std::runtime_error(analysis_ + " need linear bearings that are the same in every direction and not "
                               "cross-coupled (kxx = kyy, kxy = kyx = 0) at " + rpm_text(speed));
    if (!isotropic)
      throw std::runtime_error("bearings." + b.name + ": " + analysis_ + " need linear bearings that are the same "
                               "in every direction (kxx = kyy, kxy = -kyx, cxx = cyy, cxy = -cyx) at " +
                               rpm_text(speed));
  }
}

Vector5d WhirlProblem::ring_deflection(const Eigen::VectorXd& p, int b) const {
  Vector5d q = Vector5d::Zero();
  for (Dof d : {kX, kY, kThetaX, kThetaY}) {
    const int i = reduced(balls_[b]->node, d);
    if (i >= 0) q(five(d)) = p(i);
  }
  return q;
}

// The bearing's reaction with its balls placed relative to the ring's displacement: the deflection turned so that
// the displacement lies along x (where ball 0 sits), the reaction turned back. So the reaction does not depend on
// the whirl's direction (no ball-pass variation), as the planar backbone's.
bool WhirlProblem::ball_reaction(int b, double speed, const Vector5d& q, BallBearingEquilibrium& state,
                                 Vector5d& f) const {
  double c, s;
  direction(q, c, s);
  Vector5d t = turned(q, c, -s);
  t(0) = std::hypot(q(0), q(1));  // exactly on x
  t(1) = 0.0;
  if (!balls_[b]->qs->equilibrate(speed, t, state)) return false;
  f = turned(state.shaft_force, c, s);
  return true;
}

Vector5d WhirlProblem::ball_force(const WhirlState& w, int b) const {
  double c, s;
  direction(ring_deflection(w.p, b), c, s);
  return turned(w.bearings[b].shaft_force, c, s);
}

bool WhirlProblem::residual(const Eigen::VectorXd& p, double speed, std::vector<BallBearingEquilibrium>& states,
                            Eigen::VectorXd& r, double unbalance_scale) const {
  r = linear_part(speed) * p - unbalance_scale * unbalance(speed);
  for (int b = 0; b < n_balls(); ++b) {
    Vector5d f;
    if (!ball_reaction(b, speed, ring_deflection(p, b), states[b], f)) return false;
    for (Dof d : {kX, kY, kThetaX, kThetaY}) {
      const int i = reduced(balls_[b]->node, d);
      if (i >= 0) r(i) -= f(five(d));
    }
  }
  return true;
}

bool WhirlProblem::jacobian_p(const WhirlState& w, Eigen::MatrixXd& Jp) const {
  Jp = linear_part(w.speed);
  for (int b = 0; b < n_balls(); ++b) {
    const Vector5d q = ring_deflection(w.p, b);
    std::vector<int> rows;
    std::vector<Dof> comps;
    for (Dof d : {kX, kY, kThetaX, kThetaY})
      if (reduced(balls_[b]->node, d) >= 0) {
        rows.push_back(reduced(balls_[b]->node, d));
        comps.push_back(d);
      }
    for (std::size_t c = 0; c < comps.size(); ++c) {
      const double step = (comps[c] == kX || comps[c] == kY) ? kTranslationStep : kTiltStep;
      BallBearingEquilibrium plus = w.bearings[b], minus = w.bearings[b];
      Vector5d qp = q, qm = q, fp, fm;
      qp(five(comps[c])) += step;
      qm(five(comps[c])) -= step;
      if (!ball_reaction(b, w.speed, qp, plus, fp) || !ball_reaction(b, w.speed, qm, minus, fm)) return false;
      for (std::size_t r = 0; r < comps.size(); ++r)
        Jp(rows[r], rows[c]) -= (fp(five(comps[r])) - fm(five(comps[r]))) / (2.0 * step);
    }
  }
  return true;
}

bool WhirlProblem::jacobian_speed(const WhirlState& w, Eigen::VectorXd& Js) const {
  const double h = kRelativeSpeedStep * w.speed;
  std::vector<BallBearingEquilibrium> sp = w.bearings, sm = w.bearings;
  Eigen::VectorXd rp, rm;
  if (!residual(w.p, w.speed + h, sp, rp) || !residual(w.p, w.speed - h, sm, rm)) return false;
  Js = (rp - rm) / (2.0 * h);
  return true;
}

std::string WhirlProblem::beyond_hertz(const WhirlState& w, const std::string& where) const {
  for (int b = 0; b < n_balls(); ++b) {
    const double dmax = largest_contact_deflection(w.bearings[b].balls);
    const double ratio = balls_[b]->qs->options().max_deflection_ratio;
    const double lim = ratio * balls_[b]->element->spec().ball_diameter;
    if (dmax > lim) {
      std::ostringstream os;
      os << where << " a ball contact of bearings." << balls_[b]->name << " deflects by " << dmax * 1e6
         << " um, beyond " << ratio * 100 << " % of the ball diameter (Hertz theory)";
      return os.str();
    }
  }
  return {};
}

}  // namespace turbodyn

// The rotor's synchronous forward whirl as a static deflection in the frame that turns with the shaft, shared by
// the critical speeds at an amplitude (backbone.h) and the nonlinear unbalance response (unbalance_whirl.h).
//
// A forward circular whirl at the rotor speed Omega is, in the frame that spins with the shaft (paper Eq. 9 in the
// body frame, Rotor::spin_softening), a static deflection q:
//   (K + K_b + Omega^2 M_Omega + Omega (D + C_b) J) q - f(q, Omega) = Omega^2 u,
// K_b, C_b the linear bearings, D the rotor's non-rotating damping (seen from the turning frame it acts on the
// whirl's velocity Omega J q, J the quarter turn of Rotor::quarter_turn), f the ball bearings' forces on the shaft,
// each from its quasi-static equilibrium at the ring's displacement and tilt (BallBearingQuasiStatic::equilibrate),
// and u the wheels' unbalances (U at angle beta: U (cos beta, sin beta) on x, y). This is exact for an
// axisymmetric rotor on supports that are the same in every direction; the balls sit at 2 pi j / Z from the
// ring's displacement (the quasi-static reaction has no ball-pass variation).
//
// With one plane (x, theta_y; the backbones) damping and unbalance are left out: the undamped free whirl. With both
// planes (x, y, theta_x, theta_y) both are in.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/engine/speed_text.h"  // rpm_text, which the whirl analyses' messages use
#include "model/rotor/rotor.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

class BallBearingElement;

/// A state of the whirl: the reduced deflection, the speed, each ball bearing's equilibrium (the balls' places,
/// the starting point of the next equilibrate).
struct WhirlState {
  Eigen::VectorXd p;
  double speed = 0.0;
  std::vector<BallBearingEquilibrium> bearings;
};

class WhirlProblem {
 public:
  enum class Planes { One, Both };
  /// `analysis` names the analysis in the messages ("the critical speeds at an amplitude"). Throws
  /// std::runtime_error for supports it cannot take: floating rings and journal bearings, ball bearings in
  /// squeeze-film dampers, on radial springs or on pedestal masses.
  WhirlProblem(const MachineSpec& machine, const Rotor& rotor, Planes planes, std::string analysis);
  ~WhirlProblem();

  int size() const { return static_cast<int>(dofs_.size()); }
  int n_nodes() const { return n_nodes_; }
  /// Index of the node's DOF in the reduced deflection, -1 if it is not in the problem.
  int reduced(int node, Dof d) const;
  /// The rotor DOF of each reduced one.
  const std::vector<int>& dofs() const { return dofs_; }
  bool is_tilt(int i) const { return tilt_[i]; }
  int n_balls() const { return static_cast<int>(balls_.size()); }
  const std::string& ball_name(int b) const;
  int ball_node(int b) const;
  const BallBearingElement& ball_element(int b) const;
  const BallBearingQuasiStatic& ball_model(int b) const;

  /// Each ball bearing's centred equilibrium at `speed`. Throws QuasiStaticError if there is none.
  std::vector<BallBearingEquilibrium> centred_bearings(double speed) const;

  /// The linear part at `speed` in the reduced DOFs: (K + K_b + speed^2 M_Omega) and, with both planes,
  /// + speed (D + C_b) J. Throws std::runtime_error for linear bearings it cannot take at that speed.
  Eigen::MatrixXd linear_part(double speed) const;
  /// The unbalance force at `speed` in the reduced DOFs (zero with one plane).
  Eigen::VectorXd unbalance(double speed) const;

  /// r = linear_part(speed) p - f(p) - unbalance_scale * unbalance(speed), the bearings' equilibria in `states`
  /// (read as the start, overwritten). False if a ball bearing finds no equilibrium.
  bool residual(const Eigen::VectorXd& p, double speed, std::vector<BallBearingEquilibrium>& states,
                Eigen::VectorXd& r, double unbalance_scale = 1.0) const;
  /// d residual / dp at a state whose bearings are in equilibrium: the linear part plus each ball bearing's tangent
  /// by central differences. False if a ball bearing finds no equilibrium.
  bool jacobian_p(const WhirlState& w, Eigen::MatrixXd& Jp) const;
  /// The velocity matrix of the whirl's small motions in the turning frame at `speed`: D + C_b + speed G_r (the
  /// non-rotating damping and the gyroscopic matrix of paper Eq. 9 in the body frame), in the reduced DOFs; with both
  /// planes only.
  Eigen::MatrixXd velocity_part(double speed) const;
  /// The rotor's mass matrix in the reduced DOFs.
  Eigen::MatrixXd mass() const;
  /// d residual / d speed by central differences of the whole residual.
  bool jacobian_speed(const WhirlState& w, Eigen::VectorXd& Js) const;

  /// The ball bearing's force on the shaft at the state (x, y, z, theta_x, theta_y; N, N m), in the reduced frame.
  Vector5d ball_force(const WhirlState& w, int b) const;
  /// The ring's deflection (x, y, 0, theta_x, theta_y) at the reduced deflection p.
  Vector5d ring_deflection(const Eigen::VectorXd& p, int b) const;
  /// Empty, or why the state is beyond the model: a ball contact deflected by more than its quasi-static model's
  /// max_deflection_ratio of the ball diameter (naming the bearing; `where` says at what).
  std::string beyond_hertz(const WhirlState& w, const std::string& where) const;

 private:
  void check_linear_bearings(double speed) const;
  // The rotor's K and D with the linear bearings' coefficients at `speed` added (full DOFs).
  void with_linear_bearings(double speed, Eigen::MatrixXd& K, Eigen::MatrixXd& D) const;
  Eigen::MatrixXd reduce(const Eigen::MatrixXd& full) const;  // a rotor matrix on the reduced DOFs
  bool ball_reaction(int b, double speed, const Vector5d& q, BallBearingEquilibrium& state, Vector5d& f) const;

  struct BallSupport;
  const Rotor& rotor_;
  Planes planes_;
  std::string analysis_;
  int n_nodes_ = 0;
  std::vector<int> dofs_;
  std::vector<bool> tilt_;
  std::vector<int> index_;  // rotor DOF -> reduced index or -1
  std::vector<std::unique_ptr<BallSupport>> balls_;
  Eigen::MatrixXd m_omega_, j_, g_r_;
  Eigen::VectorXd unbalance_;  // per rad^2/s^2
};

}  // namespace turbodyn

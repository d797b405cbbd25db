// Quasi-static equilibrium of one ball bearing under static loads at a rotor speed, with the balls' centrifugal
// forces and gyroscopic moments (Jones 1960; Harris & Kotzalas 2007, Advanced Concepts, high-speed ball
// bearings), and its linearised stiffness and damping. Same geometry, Hertz constants and preload spring as the
// element (model/elements/ball/ball_bearing.h); docs/ball-bearing.md "Quasi-static equilibrium" gives the
// equations and the assumptions.
//
// Unknowns: the inner ring's x, y, theta_x, theta_y (its axial position z is held, as in the rotor model), the
// outer ring's axial position z_o on the preload spring, and per ball its centre (rho, zeta) in its azimuth plane.
// Kinematics: outer-race control (the ball does not spin against the outer race), which sets each ball's orbital
// speed and spin axis from its own contact angles; its gyroscopic moment is carried by traction at the outer
// contact (no gyroscopic slip).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/elements/ball/ball_bearing.h"
#include "model/rotor/rotor.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

/// No equilibrium found (Newton did not converge) or one outside the model's range (a load the bearing cannot
/// carry). what() says at which speed and load and why.
class QuasiStaticError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One ball at equilibrium.
struct QuasiStaticBall {
  double azimuth = 0.0;            ///< psi (rad), from +x towards +y
  double rho = 0.0, zeta = 0.0;    ///< ball centre: radius - R_p and axial position (m)
  double inner_load = 0.0, outer_load = 0.0;    ///< Q_i, Q_o (N)
  double inner_angle = 0.0, outer_angle = 0.0;  ///< alpha_i, alpha_o (rad; the direction the contact has or
                                                ///< would have if it is open)
  double inner_deflection = 0.0, outer_deflection = 0.0;  ///< delta (m); < 0: open by that gap
  double orbital_speed = 0.0;      ///< omega_m (rad/s), outer-race control
  double gyroscopic_moment = 0.0;  ///< J omega_m omega_r (N m), carried by the outer contact's traction
};

/// The bearing at one speed and load.
struct BallBearingEquilibrium {
  double speed = 0.0;         ///< Omega (rad/s)
  Vector5d load;              ///< external load on the inner ring: Fx, Fy, Fz (N), 0, 0
  /// Inner ring: x, y, z (m; z held at 0), theta_x, theta_y (rad), the rotor's local DOFs (slopes dx/dz = theta_y,
  /// dy/dz = -theta_x).
  Vector5d displacement;
  double outer_ring_axial = 0.0;  ///< z_o (m)
  Vector5d shaft_force;  ///< force and moments of the balls on the inner ring (N, N m) = -load at equilibrium
                         ///< (x, y, moments), the z entry is the axial force the shaft's axial location takes
  std::vector<QuasiStaticBall> balls;
  /// K = -dF/dq and C (N/m, N/rad, N m/m, N m/rad; N s/m ...), rows and columns (x, y, z, theta_x, theta_y),
  /// the balls and the outer ring's z_o condensed (in equilibrium for every q).
  Matrix5d stiffness = Matrix5d::Zero(), damping = Matrix5d::Zero();
  double cage_speed = 0.0;  ///< mean of the balls' orbital speeds (rad/s)
  int iterations = 0;       ///< Newton iterations of the inner-ring equilibrium

  /// The largest ball-race contact load (N), and the largest Hertz pressure p_0 of the contacts (Pa,
  /// HertzPeakPressure with `element`'s inner and outer contact ellipses; against ISO 76's static limit
  /// kStaticContactPressureLimit, as a run's max_contact_pressure probe).
  double max_contact_load() const;
  double max_contact_pressure(const BallBearingElement& element) const;
};

/// One point of a bearing's load-deflection curve (BallBearingQuasiStatic::load_deflection): the inner ring moved
/// radially along x by `travel`, its tilt held at zero and its axial place kept, the balls and the outer ring's
/// axial place in equilibrium.
struct LoadDeflectionPoint {
  double travel = 0.0;                    ///< m
  double load = 0.0;                      ///< radial force that holds the ring there, -F_x of the balls (N)
  double cross_load = 0.0;                ///< -F_y (N); zero for balls spaced evenly about x
  double moment_x = 0.0, moment_y = 0.0;  ///< moments that hold the tilt at zero, -M of the balls (N m)
  /// load / travel (N/m; at zero travel the tangent): for an axisymmetric bearing the force of a ring displaced by
  /// r in any direction is this load along the displacement, so a circular whirl of radius r sees this stiffness.
  double secant = 0.0;
  double tangent = 0.0;            ///< d load / d travel (N/m), central differences
  double max_contact_load = 0.0;   ///< largest Q_i, Q_o (N)
  /// largest Hertz pressure p_0 of the contacts (Pa, HertzPeakPressure; ISO 76's static limit 4,200 MPa)
  double max_contact_pressure = 0.0;
};

struct QuasiStaticOptions {
  /// Ball azimuths psi_j (rad); empty: 2 pi j / Z. The cage holds them (their tangential forces go to the cage).
  std::vector<double> azimuths;
  /// Share of the balls' gyroscopic moment carried by traction at the outer contact, lambda_o / 2 in Harris &
  /// Kotzalas's notation (lambda_i + lambda_o = 2): 1 = outer-race control (the default), 0.5 = shared equally.
  double outer_traction_share = 1.0;
  int max_iterations = 60;              ///< per Newton solve
  double max_speed_step = 2500.0;       ///< rad/s (about 24,000 rpm), continuation step in speed
  /// Largest contact deflection accepted, as a fraction of D: beyond it the load is one the bearing cannot carry
  /// in this model (Hertz theory of small strains; ISO 76's permanent-deformation limit is far below it).
  double max_deflection_ratio = 0.02;
};

/// The quasi-static model of one ball bearing, built on the element's data; immutable and thread-safe after
/// construction; the element must outlive it. The outer ring is held radially at the housing centre (in every
/// outer-ring mode).
class BallBearingQuasiStatic {
 public:
  explicit BallBearingQuasiStatic(const BallBearingElement& element, QuasiStaticOptions options = {});

  /// Equilibrium at rotor speed `speed` (rad/s) under the load (Fx, Fy, Fz) on the inner ring (N), reached by
  /// continuation in speed from `start` (a solution at another speed and the same load) or, without it, from
  /// rest; then stiffness and damping. Fz is an axial force through the bearing in addition to the preload
  /// (docs/ball-bearing.md). Throws QuasiStaticError.
  BallBearingEquilibrium solve(double speed, const Eigen::Vector3d& load,
                               const BallBearingEquilibrium* start = nullptr) const;
  /// solve() at each of `speeds` (rad/s), each continued from the previous one.
  std::vector<BallBearingEquilibrium> sweep(const std::vector<double>& speeds, const Eigen::Vector3d& load) const;

  /// The balls and the outer ring in equilibrium for a given inner-ring displacement q (x, y, z, theta_x, theta_y)
  /// at `speed`, starting from (and overwriting) the ball and outer-ring positions in `state`; fills its
  /// displacement, shaft force and balls. False if Newton did not converge.
  bool equilibrate(double speed, const Vector5d& q, BallBearingEquilibrium& state) const;

  /// The load-deflection curve at `speed` (rad/s) without external load: for each of `travel` (m, >= 0,
  /// increasing) the ring moved along x from the centred equilibrium, reached by continuation in steps of at most
  /// 1 um. The ring's tilt is held, as a shaft between two bearings holds it; with a free tilt a single angular
  /// contact bearing carries little radial load. Throws QuasiStaticError where no equilibrium is found or a contact
  /// deflection exceeds max_deflection_ratio of the ball diameter, std::invalid_argument for a bad travel list.
  /// `centred`: the unloaded equilibrium at `speed` if the caller has it (solve(speed, 0)), else it is solved here.
  std::vector<LoadDeflectionPoint> load_deflection(double speed, const std::vector<double>& travel,
                                                   const BallBearingEquilibrium* centred = nullptr) const;

  const BallBearingElement& element() const { return element_; }
  const QuasiStaticOptions& options() const { return options_; }
  int n_balls() const { return n_balls_; }

 private:
  // Ball and outer-ring residuals (2Z + 1) for unknowns u = (rho_j, zeta_j, z_o), optionally the balls and the
  // shaft force. Returns the largest contact deflection.
  double evaluate(double speed, const Vector5d& q, double axial_load, const Eigen::VectorXd& u, Eigen::VectorXd& r,
                  std::vector<QuasiStaticBall>* balls, Vector5d* shaft_force) const;
  // load: magnitude of the external load (N), for the force scale of the tolerances.
  bool equilibrate_u(double speed, const Vector5d& q, double axial_load, double load, Eigen::VectorXd& u) const;
  void solve_at_speed(double speed, BallBearingEquilibrium& s) const;
  void linearise(BallBearingEquilibrium& s) const;
  static Eigen::VectorXd unknowns(const BallBearingEquilibrium& s);

  const BallBearingElement& element_;
  QuasiStaticOptions options_;
  int n_balls_ = 0;
  std::vector<double> azimuths_;
};

/// The largest contact deflection of the balls (m), to hold against QuasiStaticOptions::max_deflection_ratio of the
/// ball diameter.
double largest_contact_deflection(const std::vector<QuasiStaticBall>& balls);

/// The linearised coefficients of a ball bearing for the rotor's linear analyses (modal): at each speed the
/// quasi-static equilibrium of the centred shaft (preload only, no gravity), reached by continuation from rest,
/// and its stiffness and damping on the node's (x, y, theta_x, theta_y) (the z row and column dropped: the rotor
/// has no axial DOF). Throws std::invalid_argument for a bad spec; the function throws QuasiStaticError.
BearingLinearisation ball_bearing_linearisation(const std::string& name, const BallBearingSpec& spec);

/// Adds to `rotor` (built by build_rotor, which leaves the nonlinear bearings out) the linearisation of each
/// ball bearing of `machine`. Throws ModelError naming the file and the bearing for what the linear model cannot
/// represent: a squeeze-film damper (nonlinear), an outer ring on a spring, a pedestal mass, or a bad spec.
void add_ball_bearing_linearisations(const MachineSpec& machine, Rotor& rotor);

}  // namespace turbodyn

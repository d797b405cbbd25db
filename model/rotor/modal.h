// Linear analyses of the rotor on its linear bearings: complex modes at a speed, Campbell diagram, critical speeds.
//
// The free motion M q'' + (D + D_b + Omega G) q' + (K + K_b) q = 0 is written in first-order form and solved as a
// real non-symmetric eigenproblem; each mode with Im(lambda) > 0 is one damped natural frequency.
#pragma once

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "model/rotor/rotor.h"

namespace turbodyn {

/// Direction of a lateral mode's orbits; Torsional marks a twist mode (no lateral motion).
enum class Whirl { Forward, Backward, Mixed, Planar, Torsional };
std::string to_string(Whirl w);

enum class Frame { Inertial, Rotating };

struct Mode {
  std::complex<double> eigenvalue;  ///< lambda = sigma + i omega_d in 1/s
  double frequency = 0.0;           ///< damped natural frequency omega_d / (2 pi) in Hz
  double damping_ratio = 0.0;       ///< zeta = -sigma / |lambda| [-]
  Whirl whirl = Whirl::Planar;
  Eigen::VectorXcd shape;           ///< n_dof, normalised to a largest translation of 1 (real there)
  /// Per node: +1 forward, -1 backward, 0 planar (orbit nearly a line) or too small to judge.
  std::vector<int> node_whirl;
  Eigen::VectorXd twist;            ///< torsional modes: twist per node, largest 1 (empty for lateral modes)
};

struct ModalResult {
  double speed = 0.0;  ///< rad/s
  std::vector<Mode> modes;  ///< ascending frequency
};

struct ModalOptions {
  int n_modes = 8;
  Frame frame = Frame::Inertial;  ///< Rotating: paper Eq. (9) in the shaft frame (axisymmetric rotors only)
  bool torsion = false;           ///< also list the free-free torsional modes (independent of speed)
};

/// Modes of the rotor at spin speed `speed` (rad/s). At standstill (inertial frame) the modes of a degenerate
/// forward/backward pair are given as their limit at a small speed (shape and whirl; frequency and damping at 0), so
/// each pair has one forward and one backward member. Throws std::runtime_error when the rotor cannot be analysed
/// (e.g. the rotating frame with anisotropic bearings, or matrices that are not finite).
ModalResult modal_analysis(const Rotor& rotor, double speed, const ModalOptions& options = {});

/// Diagonal similarity scaling A <- S^-1 A S with powers of two so that each row and column have similar norms
/// (Parlett & Reinsch 1969, "Balancing a matrix for calculation of eigenvalues and eigenvectors", Numer. Math. 13;
/// the scaling part of LAPACK's xGEBAL); returns the diagonal of S (eigenvectors of the original A are S v). A rotor's
/// first-order matrix mixes rotations, displacements and velocities over many orders of magnitude: without it the
/// low eigenvalues lose all accuracy (errors ~ eps ||A||).
Eigen::VectorXd balance_for_eigenvalues(Eigen::MatrixXd& A);

/// Whirl direction of a mode shape at each node and overall.
Whirl classify_whirl(const Rotor& rotor, const Eigen::VectorXcd& shape, std::vector<int>* node_whirl = nullptr);

/// API 617's bound: a resonance with an amplification factor below it is critically damped (needs no separation
/// margin).
inline constexpr double kCriticallyDampedAmplification = 2.5;

struct CriticalSpeed {
  double order = 1.0;       ///< excitation order (1 = synchronous)
  int branch = 0;           ///< index of the branch among the modes of the same whirl direction, from 0
  Whirl whirl = Whirl::Forward;
  double speed = 0.0;       ///< rad/s
  double frequency = 0.0;   ///< Hz, = order * speed / (2 pi)
  double damping_ratio = 0.0;
  /// s = d f_n / d f_d, the slope of the branch on the Campbell diagram at the crossing (central differences at
  /// +-1e-4 of the speed; NaN where the branch is not found there).
  double branch_slope = std::nan("");
  /// The amplification factor a steady response to this order's excitation would show, to first order in the damping:
  /// |n - s| / (2 n zeta) (the response goes as 1 / (f_n(f_d) - n f_d + i zeta f_n), so its half-power band in rotor
  /// speed is 2 zeta f_c / |n - s|; API RP 684's half-power AF, 1 / (2 zeta) without gyroscopic effects;
  /// docs/references.md §11). NaN for zeta <= 0 (no resonance: the mode is unstable), without the slope, and where
  /// it would be below 2.5: a mode that damped has no half-power band a first-order reading could give (an unbalance
  /// response of one degree of freedom has none at all above zeta of about 0.38), and API 617 calls it critically
  /// damped (critically_damped).
  double amplification_factor = std::nan("");
  bool critically_damped = false;
  /// For the 1x criticals with an amplification factor, when the caller gives a ramp (ramp_passage): the speed (rad/s)
  /// where a run-up at that rate peaks, and the peak's fraction of the steady resonance; NaN otherwise.
  double runup_peak_speed = std::nan("");
  double runup_peak_fraction = std::nan("");
};

/// Where a mode run up through its critical speed at a constant rate peaks: one degree of freedom forced like an
/// unbalance, x'' + 2 zeta x' + x = W^2 cos(phi), phi' = W = lambda t (time in 1 / omega_n, x in the unit unbalance's
/// static deflection), integrated by classical RK4 (400 steps per period) from W = 0.5, started on the steady response
/// there, to the peak of |x|. lambda = (n - s) (d Omega / dt) / omega_c^2 for order n on a branch of slope s (the ramp
/// sweeps the mode's detuning at (n - s) times its rate). A finite ramp makes the peak late and low: the speed ratio
/// grows about as the square root of lambda, and a mode whose steady peak 1 / (2 zeta) would need longer than the
/// passage to ring up reaches a fraction of it (F. M. Lewis, "Vibration during acceleration through a critical speed",
/// Trans. ASME 54 (1932) 253-261, the classical study; docs/validation.md, "The reference rotor on linear bearings").
/// Below lambda = 1e-5 the passage is taken as quasi-steady: the steady peak, at W^2 = 1 / (1 - 2 zeta^2).
struct RampPassage {
  double speed_ratio = 1.0;  ///< W / omega_n at the peak
  double peak = 0.0;         ///< |x| at the peak (the static deflection of the unbalance's force being 1)
  double peak_fraction = 1.0;  ///< peak over the steady resonance's 1 / (2 zeta sqrt(1 - zeta^2)); 0 for zeta = 0
};
/// Throws std::invalid_argument unless 0 < lambda < 0.1 and 0 <= zeta < 0.5.
RampPassage ramp_passage(double lambda, double zeta);

struct Campbell {
  std::vector<ModalResult> points;      ///< one per speed
  std::vector<CriticalSpeed> critical;  ///< ascending speed
};

/// Campbell diagram over `speeds` (rad/s, ascending) with the crossings of the order lines `orders` with the
/// forward and backward branches, refined by bisection to a relative speed tolerance of 1e-6.
Campbell campbell_diagram(const Rotor& rotor, const std::vector<double>& speeds, const std::vector<double>& orders,
                          const ModalOptions& options = {});

}  // namespace turbodyn

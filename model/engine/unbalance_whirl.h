// Nonlinear steady-state unbalance response of a rotor on ball bearings (`turbodyn response --nonlinear`,
// docs/ball-bearing.md "Nonlinear unbalance response").
//
// At a constant speed the wheels' unbalances drive a forward circular whirl at the rotor speed, which in the frame
// that turns with the shaft is a static deflection (synchronous_whirl.h):
//   (K + K_b + Omega^2 M_Omega + Omega (D + C_b) J) q - f(q, Omega) = Omega^2 u,
// f the ball bearings' quasi-static reactions. On linear bearings this is the linear unbalance response
// (response.h) written in the turning frame. On ball bearings the response curve bends with the bearings'
// stiffness: it may fold over, and between two folds three steady states exist at one speed. The curve is traced by
// pseudo-arclength continuation in (q, Omega) (Keller 1977; Seydel, Practical Bifurcation and Stability Analysis,
// Springer 2010, ch. 4), so it follows a fold instead of stopping at it. At a fold where the speed turns back a slow
// run-up leaves the branch it is on and jumps to another one (Nayfeh & Mook 1979, §4.1, the jump phenomenon); at
// one where the speed turns forward again a slow run-down does (each on the branch it arrives on). Branches that
// neither end of the range reaches are found from seeds across the range.
#pragma once

#include <string>
#include <vector>

#include "model/rotor/rotor.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

struct UnbalanceWhirlPoint {
  double speed = 0.0;                 ///< rad/s
  std::vector<double> disk_radius;    ///< per Rotor::disks: radius of the wheel centre's circular whirl (m)
  /// per Rotor::disks: angle of the wheel centre's deflection from the shaft's reference line (rad): x(t) =
  /// radius cos(Omega t + phase), as the linear response's phase of x.
  std::vector<double> disk_phase;
  std::vector<double> bearing_force;     ///< per bearing (model order): amplitude of the force on the housing (N)
  std::vector<double> max_contact_load;  ///< per bearing: a ball bearing's largest contact load (N), 0 if linear
  /// per bearing: a ball bearing's largest Hertz contact pressure (Pa; ISO 76's static limit 4,200 MPa), 0 if linear
  std::vector<double> max_contact_pressure;
  /// The largest real positive eigenvalue of the whirl's small motions about it in the turning frame (1/s; 0 if
  /// none), and whether it is round-off (< 1e-9 of the largest |eigenvalue|): a steady state with one drifts off to
  /// another branch (the middle branch between two folds). Oscillatory growth is not judged (contacts undamped).
  double divergence_rate = 0.0;
  bool stable = true;
};

/// A fold of the response curve: the speed turns back (a run-up on this branch jumps off here) or forward again (a
/// run-down on it does).
struct UnbalanceWhirlFold {
  double speed = 0.0;         ///< rad/s, from a quadratic through the neighbouring points
  double largest_radius = 0.0;  ///< the largest wheel whirl radius there (m)
  bool speed_turns_back = true;  ///< true: the largest speed of a stretch of the curve
};

/// One stretch of the curve, continued in one direction from its first point.
struct UnbalanceWhirlPiece {
  bool upward = true;       ///< continued towards higher speeds
  double start_speed = 0.0;  ///< rad/s, its first point: an end of the range or a seed
  std::vector<UnbalanceWhirlPoint> points;  ///< in the order of the continuation
  std::vector<UnbalanceWhirlFold> folds;
  int joins = -1;  ///< index of an earlier piece it ran into (and ended on), or -1
  /// Empty if it reached the end of the range it went towards or joined another piece; else why it ended (a
  /// contact beyond Hertz theory, no steady state found, out of the range at the other end), naming the speed.
  std::string stopped;
};

struct UnbalanceWhirl {
  std::vector<std::string> bearings;  ///< names, model order (the order of bearing_force)
  std::vector<std::string> disks;     ///< names, Rotor::disks order
  /// The first continued upwards from the lowest speed. If it ends early, a second downwards from the highest, and
  /// then pairs (up, down) from seeds across the range that lie on neither: branches no end reaches.
  std::vector<UnbalanceWhirlPiece> pieces;
  /// True if the pieces together give a steady state at every speed of the range.
  bool covers_range = false;
};

struct UnbalanceWhirlOptions {
  double start_speed = 0.0, end_speed = 0.0;  ///< rad/s, 0 < start < end
  int max_points = 5000;                      ///< per piece
};

/// The steady-state synchronous unbalance response over [start_speed, end_speed]. `machine` gives the ball
/// bearings, `rotor` is built from it by build_rotor (its linear bearings and disks with their unbalances).
/// Throws std::invalid_argument for a bad range, std::runtime_error for supports it cannot take (floating rings,
/// journal bearings, dampers, radial springs, pedestal masses, linear bearings that differ between directions) and
/// QuasiStaticError if a ball bearing has no centred equilibrium.
UnbalanceWhirl nonlinear_unbalance_response(const MachineSpec& machine, const Rotor& rotor,
                                            const UnbalanceWhirlOptions& options);

}  // namespace turbodyn

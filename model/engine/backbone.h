// Amplitude-dependent synchronous critical speeds of a rotor on ball bearings (`turbodyn modal --amplitudes`,
// docs/ball-bearing.md "Critical speeds at an amplitude").
//
// A forward circular whirl at the rotor speed is, in the frame that turns with the shaft, a static deflection
// (Rotor::spin_softening, paper Eq. 9 in the body frame):
//   (K + K_b + Omega^2 M_Omega) q - f(q, Omega) = 0,
// with K_b the linear bearings and f the ball bearings' forces on the shaft at the deflection q, each from its
// quasi-static equilibrium (BallBearingQuasiStatic::equilibrate: balls and the outer ring's axial place in
// equilibrium with their centrifugal forces, the ring displaced and tilted). For small q this is the 1x forward
// critical speed of the linearised rotor (`turbodyn modal`); for a finite q, fixed by the amplitude at one node,
// the speed Omega(A) at which the undamped rotor whirls synchronously with that amplitude: the backbone of the
// nonlinear resonance (Nayfeh & Mook, Nonlinear Oscillations, Wiley 1979, ch. 4: with light damping the peak of a
// forced response lies on it). The deflection stays in one plane through the axis (the x-z plane: x and theta_y),
// which the axisymmetric rotor and bearings allow. Damping is not part of it (an undamped critical).
#pragma once

#include <string>
#include <vector>

#include "model/rotor/rotor.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

/// One ball bearing at a point of a backbone: its inner ring's deflection and the balls' reaction.
struct BackboneBearing {
  std::string name;
  /// Inner ring in the whirl's plane (the reference node's displacement positive): displacement (m; its size is
  /// the radius of the ring's whirl) and tilt (rad, theta_y: the slope dx/dz).
  double displacement = 0.0, tilt = 0.0;
  /// Force and moment (theta_y sense) that hold the ring there against the balls, i.e. the balls' reaction on the
  /// shaft negated (N, N m): the secant stiffness of the whirl is force / displacement.
  double force = 0.0, moment = 0.0;
  double max_contact_load = 0.0;      ///< largest ball contact load (N)
  double max_contact_pressure = 0.0;  ///< largest Hertz pressure of its contacts (Pa; ISO 76's limit 4,200 MPa)
};

struct BackbonePoint {
  double amplitude = 0.0;  ///< whirl radius at the reference node (m)
  double speed = 0.0;      ///< critical speed at that amplitude (rad/s); the whirl frequency is speed / 2 pi
  std::vector<BackboneBearing> bearings;  ///< the ball bearings, in model order
};

struct Backbone {
  int branch = 0;              ///< index of the start speed it continues (ascending), from 0; callers may relabel
  double linear_speed = 0.0;   ///< the linearised rotor's critical speed it starts from (rad/s)
  int reference_node = 0;      ///< the node whose whirl radius is the amplitude (from BackboneOptions)
  std::vector<BackbonePoint> points;  ///< one per amplitude reached, ascending amplitude
  /// Empty if every amplitude was reached; else why the backbone ends before the last (no equilibrium of the
  /// whirl found, a contact beyond Hertz theory), naming the amplitude.
  std::string stopped;
};

struct BackboneOptions {
  /// The nodes whose x may be the amplitude: with one, it is every branch's; with several, each branch takes the
  /// one that moves most in its linearised mode (e.g. the wheels: the one that is not near the mode's node).
  std::vector<int> reference_nodes;
  std::vector<double> amplitudes;   ///< m, > 0, increasing
};

/// The backbone of each of `start_speeds` (rad/s: the linearised rotor's forward 1x critical speeds, e.g. from
/// campbell_diagram) over options.amplitudes. `machine` gives the ball bearings, `rotor` is built from it by
/// build_rotor (linear bearings only; no floating rings). Continuation in amplitude from the first, each step by
/// Newton's method on the deflection and the speed, halved where it fails (at most 8 times). Throws
/// std::invalid_argument for bad amplitudes or a reference node that does not move in a mode, std::runtime_error
/// for supports the analysis cannot take (anisotropic or cross-coupled linear bearings, floating rings, dampers,
/// pedestal masses, an outer ring on a spring) and QuasiStaticError if a ball bearing has no centred equilibrium.
std::vector<Backbone> synchronous_backbones(const MachineSpec& machine, const Rotor& rotor,
                                            const std::vector<double>& start_speeds, const BackboneOptions& options);

}  // namespace turbodyn

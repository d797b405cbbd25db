// Linearised stability of the whole run-up model (rotor and every force element with its internal states) about a
// steady state at constant speed: `turbodyn stability`, docs/ball-bearing.md ("Linearised stability").
//
// A rotor on ball bearings has no equilibrium at speed: its balls and cages orbit. Without gravity and unbalance,
// with the rotor centred, they orbit as a rigid pattern at the cage speed W_c, a relative equilibrium: constant in
// a frame turning at W_c about the rotor axis. The rotor (axisymmetric), its gyroscopic terms at constant speed and
// each element's equations are the same in every direction, so in that frame the linearised equations
//   w' = A~ w,   A~ = A + W_c S
// have constant coefficients: A = dF/dy at the steady state (central differences of the run-up model's
// right-hand side, every friction, damping and contact law included), S adds the frame's turning to each housing-
// frame (x, y) pair (rotor translations and tilts, cage centre): w_x' = x' + W_c y, w_y' = y' - W_c x. Its
// eigenvalues are the Floquet exponents of the orbiting steady state (an exact linearisation, not a frozen-time
// one). A mode lambda~ = s + i w~ with housing-frame motion x + i y made of a forward part at w~ + W_c and a
// backward part at W_c - w~ is reported at the frequency of the larger part (signed: > 0 forward whirl), with its
// growth rate s (> 0: the state is unstable) and damping ratio -s / |lambda| in the housing frame.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "model/spec/model_spec.h"

namespace turbodyn {

struct StabilityOptions {
  /// Modes above this housing-frame frequency are dropped (Hz) unless they clearly grow (damping ratio below
  /// -1e-3); 0 = 4 x the rotor speed frequency, at least 5 kHz.
  double frequency_max = 0.0;
  /// Keep only modes whose rotor share (StabilityMode::rotor_share) is at least this; 0 keeps the balls' own modes.
  double min_rotor_share = 0.0;
  /// Multiplies the steady state's continuation steps in speed (each element's own, which the analysis' regular
  /// steps times ForceElement::SteadyRotationLayout::continuation_step_factor give): below 1 to check that the
  /// state found does not depend on them.
  double continuation_step_factor = 1.0;
};

/// Damping ratios above -this are round-off of the central differences (the undamped shaft's bending modes near
/// 1e6 rad/s come out with |Re| ~ 1e-7 |lambda|; the balls' neutral places in their pockets with |Re| ~ 1e-10).
inline constexpr double kStabilityNoiseDamping = 1e-5;
/// Growth rates below this (1/s) are neutral: an e-folding time of 100 s is nothing in a run-up of seconds, and a
/// neutral mode at 0 Hz in the housing frame (a damper ring's free place) has a damping ratio of -1 from round-off.
inline constexpr double kStabilityNeutralRate = 1e-2;

/// A mode's ball-set order (StabilityMode::ball_set_lobes) is given from this ball-set share on.
inline constexpr double kStabilityBallSetMinShare = 1e-2;

struct StabilityMode {
  double frequency = 0.0;           ///< Hz in the housing frame, > 0 forward whirl, < 0 backward
  double frame_frequency = 0.0;     ///< Hz in the turning frame, Im(lambda~) / 2 pi (>= 0)
  double growth_rate = 0.0;         ///< 1/s, Re(lambda); > 0 grows
  double damping_ratio = 0.0;       ///< -growth_rate / |lambda| in the housing frame
  double forward_share = 0.0;       ///< of the rotor's translational motion, the fraction whirling forward
  /// Fractions of the mode's state vector (each state over its typical magnitude, RunupModel::AbsoluteTolerances)
  /// in the rotor coordinates and in each element's states; they sum to 1.
  double rotor_share = 0.0;
  std::vector<double> element_shares;
  /// Fraction of the mode's state vector (scaled as above) in the balls' orbital angles and orbital rates, all
  /// elements together: how much of the mode is a change of the ball sets' spacing or of their turning as a whole.
  double ball_set_share = 0.0;
  /// Circumferential order n of the balls' orbital-angle motion in the element where that motion is largest: the
  /// largest |sum_j psi_j exp(-i m phi_j)|^2 + (its m -> Z - m alias) over m = 0 .. Z/2, psi_j the mode's angle of
  /// ball j and phi_j its steady place. 0: the ball set turning as a whole (against the races); 1: a one-lobed
  /// density wave (the balls closing up on one side, the set's mass centre off the axis); -1: no ball-set states,
  /// or ball_set_share below kStabilityBallSetMinShare (the order of round-off is no order).
  int ball_set_lobes = -1;
  /// The mode grows beyond round-off: the steady state is unstable.
  bool grows() const { return damping_ratio < -kStabilityNoiseDamping && growth_rate > kStabilityNeutralRate; }
};

struct StabilityPoint {
  double speed = 0.0;        ///< rotor speed (rad/s)
  double frame_speed = 0.0;  ///< W_c (rad/s): the cages' speed, 0 if no element turns
  int n_states = 0;          ///< size of the linearised system
  /// Largest relative residual of the steady state (each state derivative over its typical magnitude times the
  /// speed), after Newton's method.
  double residual = 0.0;
  /// Given an analysis at a lower speed (analyse_stability's `below`), the continuation from its steady state failed
  /// for some element and that element's state was found anew from rest: the branch through the lower speed ends
  /// between the two (a fold), and this state lies on another branch.
  bool restarted = false;
  std::vector<std::string> elements;  ///< element names, the order of StabilityMode::element_shares
  /// The steady state at t = 0 (RunupModel::n_states() values, energy accounts 0) of the model that
  /// stability_machine(spec, speed) describes: a run started from it (RunupOptions::initial_state) stays there
  /// unless a mode grows.
  std::vector<double> steady_state;
  std::vector<StabilityMode> modes;   ///< largest growth rate first
};

/// The machine the analysis linearises: `spec` at the constant speed `speed` (rad/s), without gravity and
/// unbalance, the shaft in its physical DOFs (no reduction).
MachineSpec stability_machine(const MachineSpec& spec, double speed);

/// Throws std::invalid_argument, naming the bearing, if an element of `spec` has no steady rotating state that the
/// analysis knows (the same check analyse_stability makes first): what a study checks before its runs.
void check_stability_supported(const MachineSpec& spec);

/// Halvings of the interval between a speed without a growing mode and one with: the onset of instability to 1/64
/// of the interval (refine_stability_onset).
inline constexpr int kStabilityOnsetBisections = 6;

/// How closely the halvings place an onset inside a grid interval of `step` (any unit): step / 2^6.
inline constexpr double stability_onset_resolution(double step) {
  return step / static_cast<double>(1 << kStabilityOnsetBisections);
}

/// Which modes an onset or a study's stability metric counts: at least `min_rotor_share` of their motion in the
/// rotor, and a housing-frame frequency |f| of at most `frequency_max` (Hz; 0 = any), e.g. to leave out a rotor's
/// bending modes at kHz that a stiff traction's creep destabilises from the whirl of the ball set.
struct StabilityModeFilter {
  double min_rotor_share = 0.0;
  double frequency_max = 0.0;
  bool counts(const StabilityMode& m) const {
    return m.rotor_share >= min_rotor_share && (frequency_max <= 0.0 || std::abs(m.frequency) <= frequency_max);
  }
};

/// True if a mode of `p` that `filter` counts grows (StabilityMode::grows).
bool grows_counted(const StabilityPoint& p, const StabilityModeFilter& filter);

/// The onset of instability between the analysis `stable` (no counted mode grows at its speed) and the speed
/// `unstable` (rad/s: one does): the interval halved kStabilityOnsetBisections times by analyses at its middle, each
/// continuing the steady state up from the highest speed found stable; returns the lowest speed found growing, so
/// the onset lies within [returned - interval/64, returned]. An analysis that fails (no steady state) ends the
/// halving: *error says at which speed and why ("" if none did), and the lowest speed found growing so far is
/// returned. The speeds (rad/s) of halvings whose steady state was found anew from rest (StabilityPoint::restarted:
/// the branch from the stable speed folds before them) are appended to *restarted if given. The halvings are
/// analysed with `options` (those of the analyses being refined), their rotor share the filter's.
double refine_stability_onset(const MachineSpec& spec, const StabilityPoint& stable, double unstable,
                              const StabilityModeFilter& filter, std::string* error,
                              std::vector<double>* restarted = nullptr, const StabilityOptions& options = {});

/// What the command's output and the report say after "the halving at N rpm" of each of StabilityOnset::restarted.
inline constexpr const char* kHalvingRestartedText =
    "found its steady state anew from rest: the branch from the stable speed below ended before it.";

/// Where a counted mode first grows over speeds analysed in ascending order.
struct StabilityOnset {
  bool found = false;           ///< some counted mode grows at one of the speeds
  double speed = 0.0;           ///< rad/s: the lowest speed found growing
  bool at_first_speed = false;  ///< it grows at the first speed already (no interval below to halve)
  double resolution = 0.0;      ///< rad/s: the onset lies within [speed - resolution, speed]
  std::string error;            ///< an analysis inside the halved interval failed ("" if none)
  std::vector<double> restarted;  ///< rad/s: halvings whose steady state was found anew from rest (a fold below)
};

/// The onset over the analyses `points` of `spec` (ascending speeds): the first whose counted modes grow
/// (grows_counted), the interval from the speed before it halved by refine_stability_onset with `options`.
StabilityOnset find_stability_onset(const MachineSpec& spec, const std::vector<const StabilityPoint*>& points,
                                    const StabilityModeFilter& filter, const StabilityOptions& options = {});

/// The analysis at rotor speed `speed` (rad/s) of the machine `spec` with gravity and unbalance removed and the
/// shaft in its physical DOFs. Throws std::invalid_argument if an element has no steady rotating state
/// (ForceElement::steady_rotation_layout: floating rings, journal bearings, anisotropic linear bearings, linear
/// bearings in dampers and dampers with a feed hole or supply pressure are not covered), or if the
/// elements' frames turn at different speeds; std::runtime_error if Newton's method does not find the steady state.
///
/// `below`, if given, is an analysis of the same `spec` at a speed at most `speed`: the steady state is continued up
/// from its steady state, along its branch and without retracing the speeds below (a sweep over ascending speeds
/// passes each analysis to the next), and from rest if that fails. Without it, each speed is continued from rest.
StabilityPoint analyse_stability(const MachineSpec& spec, double speed, const StabilityOptions& options = {},
                                 const StabilityPoint* below = nullptr);

}  // namespace turbodyn

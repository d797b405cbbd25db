// Force elements: everything that acts on the rotor besides its own linear beam and disk terms (bearings first).
//
// Modelled on Drake's ForceElement (a public non-virtual entry, the one place for checks common to all elements,
// forwarding to a protected virtual that adds into preallocated arrays; it checks nothing yet, as the engine is
// the only caller) and Chrono's elements with internal states: an element reads the rotor displacements and
// velocities at the DOFs it is attached to, plus its own states (ring or ball positions and velocities, a pedestal
// mass...), adds forces on those rotor DOFs and writes the time derivatives of its own states.
//
// An element is immutable after construction and shared by all threads; everything it needs to scribble on
// lives in its ElementWorkspace, created once per simulation. Evaluations allocate nothing.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace turbodyn {

/// Rotor spin at the time of the call.
struct SpinState {
  double time = 0.0;          ///< s
  double speed = 0.0;         ///< Omega in rad/s
  double acceleration = 0.0;  ///< dOmega/dt in rad/s^2
  double angle = 0.0;         ///< phi in rad
};

/// Scratch space of one element for one simulation (derive from it for element-specific buffers).
struct ElementWorkspace {
  virtual ~ElementWorkspace() = default;
};

/// The inputs (rotor speed, q, v, z) of an element's last evaluation, kept in its workspace with what that
/// evaluation computed, so that another call at the same state (the powers and probes after the forces) reuses
/// it. Inputs are compared bit for bit; sized once, allocation-free afterwards.
class EvaluationKey {
 public:
  EvaluationKey() = default;
  /// d rotor DOFs, m internal states.
  EvaluationKey(int d, int m) : d_(d), m_(m), key_(static_cast<std::size_t>(1 + 2 * d + m), 0.0) {}
  bool matches(double speed, const double* q, const double* v, const double* z) const {
    return valid_ && std::memcmp(key_.data(), &speed, sizeof speed) == 0 &&
           std::memcmp(key_.data() + 1, q, bytes(d_)) == 0 && std::memcmp(key_.data() + 1 + d_, v, bytes(d_)) == 0 &&
           std::memcmp(key_.data() + 1 + 2 * d_, z, bytes(m_)) == 0;
  }
  /// Marks (speed, q, v, z) as the state of what the workspace holds.
  void set(double speed, const double* q, const double* v, const double* z) {
    key_[0] = speed;
    std::memcpy(key_.data() + 1, q, bytes(d_));
    std::memcpy(key_.data() + 1 + d_, v, bytes(d_));
    std::memcpy(key_.data() + 1 + 2 * d_, z, bytes(m_));
    valid_ = true;
  }
  /// Call before recomputing, so that a throw leaves nothing stale marked valid.
  void invalidate() { valid_ = false; }

 private:
  static std::size_t bytes(int n) { return static_cast<std::size_t>(n) * sizeof(double); }
  int d_ = 0, m_ = 0;
  std::vector<double> key_;
  bool valid_ = false;
};

/// A named scalar output of an element (e.g. the force it transmits to the housing).
struct ProbeInfo {
  ProbeInfo(std::string name_, std::string unit_, std::string description_,
            double limit_ = std::numeric_limits<double>::infinity(), std::string limit_note_ = {},
            bool limit_below_ = false)
      : name(std::move(name_)), unit(std::move(unit_)), description(std::move(description_)), limit(limit_),
        limit_note(std::move(limit_note_)), limit_below(limit_below_) {}

  std::string name;         ///< unique within the element, e.g. "force_x"
  std::string unit;         ///< e.g. "N"
  std::string description;  ///< e.g. "force on the housing, horizontal"
  /// The largest |value| the element's model describes a sound machine at (same unit; infinite: none), and what
  /// passing it means; a run reports where it is passed (summary.json, a warning). With `limit_below` the limit is
  /// the smallest value instead (a film thickness), passed when the value falls below it.
  double limit = std::numeric_limits<double>::infinity();
  std::string limit_note;
  bool limit_below = false;
};

/// `more` (ProbeInfos), each description opened by `who` ("bearing 'NAME': "), appended to p.
template <class Probes>
void append_probes(std::vector<ProbeInfo>& p, const std::string& who, const Probes& more) {
  for (ProbeInfo m : more) {
    m.description = who + m.description;
    p.push_back(std::move(m));
  }
}

/// How every thinnest-film probe's name ends (min_film_probe): the pictures and the report find them by it.
inline constexpr std::string_view kMinFilmProbeSuffix = "min_film_thickness";

/// What passing a film's permissible minimum thickness means (min_film_probe's limit note).
inline constexpr const char* kFilmThicknessLimitNote =
    "the permissible minimum film thickness of the model file (film_thickness_limit): in a thinner film the "
    "surfaces' roughness touches through the oil (mixed lubrication, wear), which the Reynolds film model does not "
    "describe";

/// The thinnest film of a fluid-film bearing (m; reynolds::min_film_thickness), `what` saying which film; `name`
/// ends in kMinFilmProbeSuffix. A permissible minimum film thickness `limit` > 0 (the model file's
/// film_thickness_limit) is its lower limit.
inline ProbeInfo min_film_probe(std::string name, const std::string& what, double limit) {
  std::string description = "thinnest " + (what.empty() ? "" : what + " ") + "film (tilt included)";
  if (!(limit > 0.0)) return {std::move(name), "m", std::move(description)};
  return {std::move(name), "m", std::move(description), limit, kFilmThicknessLimitNote, true};
}

/// The probes every bearing reports first, fx and fy (N): the force it transmits to the housing, `via` naming the
/// path (e.g. " through the damper"). `who` opens each description ("bearing 'NAME': "); `more` follow.
inline std::vector<ProbeInfo> housing_force_probes(const std::string& who, const std::string& via,
                                                   std::initializer_list<ProbeInfo> more = {}) {
  std::vector<ProbeInfo> p = {{"fx", "N", who + "force transmitted to the housing" + via + ", horizontal (x)"},
                              {"fy", "N", who + "force transmitted to the housing" + via + ", vertical (y)"}};
  append_probes(p, who, more);
  return p;
}

/// housing_force_probes through a squeeze-film damper, then the damper ring's displacement (m), eccentricity ratio
/// and thinnest film (m; `film_limit` > 0 its permissible minimum, min_film_probe), then `more`.
inline std::vector<ProbeInfo> damper_probes(const std::string& who, double film_limit,
                                            std::initializer_list<ProbeInfo> more = {}) {
  std::vector<ProbeInfo> p = housing_force_probes(who, " through the damper",
                                                  {{"damper_x", "m", "outer ring displacement in the damper, horizontal"},
                                                   {"damper_y", "m", "outer ring displacement in the damper, vertical"},
                                                   {"damper_eccentricity", "1", "damper eccentricity ratio e/c"},
                                                   min_film_probe("damper_min_film_thickness", "damper", film_limit)});
  append_probes(p, who, more);
  return p;
}

class ForceElement {
 public:
  virtual ~ForceElement() = default;

  const std::string& name() const { return name_; }
  /// Global rotor DOF indices (into q) the element is attached to, in the element's local order.
  const std::vector<int>& dofs() const { return dofs_; }
  /// Number of internal first-order states (e.g. 4 for a pedestal mass: x, y, vx, vy).
  int n_states() const { return n_states_; }

  virtual std::unique_ptr<ElementWorkspace> make_workspace() const { return std::make_unique<ElementWorkspace>(); }
  /// Initial internal states (n_states values).
  virtual void initial_states(double* z) const { (void)z; }
  /// Initial internal states for a run that starts with the rotor spinning at `speed` (rad/s), e.g. a study's
  /// speed window in the middle of the ramp: by default initial_states(); elements with bodies that spin with
  /// the rotor (balls, cage) start at their steady speeds instead of at rest on a spinning shaft.
  virtual void initial_states_at_speed(double speed, double* z) const {
    (void)speed;
    initial_states(z);
  }

  /// Adds the element's generalised forces on its rotor DOFs into f (local order, dofs().size() values) and writes
  /// the derivatives of its internal states into zdot. q and v are the rotor displacements and velocities at
  /// dofs(); z the internal states.
  void calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                        double* f, double* zdot) const {
    do_calc_and_add_forces(s, q, v, z, ws, f, zdot);
  }

  /// Typical magnitudes of the rotor displacements (m) and velocities (m/s): the smallest step scales of
  /// finite-difference Jacobians (the engine's and an element's own) and the units of scaled tolerances.
  static constexpr double kTypicalDisplacement = 1e-6, kTypicalVelocity = 1e-3;

  /// Typical magnitude of internal state i (SI), used as the smallest step scale when the engine differentiates
  /// the element numerically.
  virtual double state_scale(int i) const {
    (void)i;
    return 1e-6;
  }

  /// The magnitude of internal state i that a scaled absolute tolerance (solver.atol_scaling = "typical") resolves
  /// to the same fraction as 1 um of rotor displacement. By default state_scale(i). An element overrides it for
  /// velocities of parts that vibrate far faster than the rotor: a displacement tolerance of atol at frequency w
  /// corresponds to a velocity tolerance of w atol, and resolving the velocity more finely than that only
  /// resolves the part's own vibration, which its displacement tolerance already bounds.
  virtual double tolerance_scale(int i) const { return state_scale(i); }

  /// Whether the absolute tolerances of the element's states depend on the state (absolute_tolerance_factors()).
  /// Taken with scaled tolerances (solver.atol_scaling = "typical") only.
  virtual bool has_state_dependent_tolerances() const { return false; }
  /// Factors f[i] on the scaled absolute tolerances of the element's states at the state z: the integrator's error
  /// weight of state i is then 1 / (rtol |z_i| + f_i atol_i). Evaluated once per step; allocates nothing.
  virtual void absolute_tolerance_factors(const double* z, double* f) const {
    (void)z;
    for (int i = 0; i < n_states(); ++i) f[i] = 1.0;
  }

  /// Relative step of the engine's forward differences; elements computed by iterative solvers need more than
  /// sqrt(eps) to stay above their solver tolerance.
  virtual double fd_relative_step() const { return 1.4901161193847656e-08; }

  /// Forward-difference step of input j of [q (d); v (d); z] (local numbering) at its value: fd_relative_step()
  /// times the larger of |value| and the input's typical magnitude (kTypicalDisplacement, kTypicalVelocity,
  /// state_scale()). The engine's numerical Jacobian and elements' own use it.
  double fd_step(int j, int d, double value) const {
    const double typical = j < d ? kTypicalDisplacement : j < 2 * d ? kTypicalVelocity : state_scale(j - 2 * d);
    return fd_relative_step() * std::max(std::abs(value), typical);
  }

  /// Sizes of leading blocks of the internal states that do not depend on one another: the derivatives of the
  /// states of one block depend on that block, the states after all blocks (the border) and the rotor only. The
  /// engine then factors the element's Newton block by block (BlockArrowLU). Empty: one dense block.
  virtual std::vector<int> independent_state_blocks() const { return {}; }
  /// Positions at the start of every independent state block whose rates are the block's next states, exactly and
  /// whatever the other states (a ball's orbital angle, radial and axial position and their velocities): the
  /// engine then factors each block's Newton matrix through its velocity rows alone (BlockArrowLU, "kinematic
  /// blocks"). 0: none.
  virtual int kinematic_states_per_block() const { return 0; }

  /// True if add_jacobian() is implemented; otherwise the engine differentiates numerically.
  virtual bool has_jacobian() const { return false; }
  /// Jacobian of [f; zdot] with respect to [q; v; z] (local numbering), column-major, of size
  /// (d + m) x (2d + m) with d = dofs().size(), m = n_states(); added into J.
  virtual void add_jacobian(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                           double* J) const {
    (void)s, (void)q, (void)v, (void)z, (void)ws, (void)J;
  }
  /// Force evaluations one add_jacobian() call makes (0 for an analytic Jacobian), for the engine's count of
  /// force-element calls.
  virtual int jacobian_evaluations() const { return 0; }

  /// How the element's states sit in a steady state at constant speed that turns with a frame about the rotor
  /// axis (a relative equilibrium: balls and cage orbiting at the cage speed), for the linearised stability
  /// analysis (model/engine/stability.h). Indices are the element's own (0 .. n_states() - 1).
  struct SteadyRotationLayout {
    /// Cartesian (x, y) pairs written in the housing frame (a cage's centre and velocity, a ring's radial
    /// position): in the turning frame they are rotated.
    std::vector<std::pair<int, int>> planar_pairs;
    /// (angle, rate) pairs that advance at the frame's speed in the steady state (a ball's orbital angle, the
    /// cage angle); every other state is constant there.
    std::vector<std::pair<int, int>> turning_angles;
    /// Index into turning_angles of the angle that fixes the frame's phase (the cage's), or -1 if there are none.
    int phase_angle = -1;
    /// The fraction of the analysis' regular steps in speed that the continuation of this steady state takes (1:
    /// the regular steps): less where the state changes so quickly with speed that the regular steps land on
    /// another of several nearby steady states.
    double continuation_step_factor = 1.0;
  };
  /// False (the default) if the element has no such steady state about a centred rotor, or the analysis does not
  /// know it; elements without states that act the same in every direction may return true with an empty layout.
  virtual bool steady_rotation_layout(SteadyRotationLayout* layout) const {
    (void)layout;
    return false;
  }

  /// Outputs of the element.
  virtual std::vector<ProbeInfo> probes() const { return {}; }
  virtual void eval_probes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* out) const {
    (void)s, (void)q, (void)v, (void)z, (void)ws, (void)out;
  }

  /// Energy bookkeeping of the run (RunupResult: E(t) - E(t0) = work in - dissipated). The rotor's spin is
  /// prescribed, so the drive supplies whatever torque an element puts on the shaft about the spin axis: that
  /// power is work in (drive_power); what the element turns into heat is dissipated_power.
  /// Potential energy stored in the element (J).
  virtual double potential_energy(const double* q, const double* z) const {
    (void)q, (void)z;
    return 0.0;
  }
  /// Kinetic energy of the element's own bodies (J).
  virtual double kinetic_energy(const double* z) const {
    (void)z;
    return 0.0;
  }
  /// Power dissipated in the element (W, >= 0).
  virtual double dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                                 ElementWorkspace& ws) const {
    (void)s, (void)q, (void)v, (void)z, (void)ws;
    return 0.0;
  }
  /// Power the drive puts into the element through the prescribed spin: -T Omega for a moment T of the element
  /// on the shaft about the spin axis (W; > 0 for a drag).
  virtual double drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                            ElementWorkspace& ws) const {
    (void)s, (void)q, (void)v, (void)z, (void)ws;
    return 0.0;
  }

 protected:
  ForceElement(std::string name, std::vector<int> dofs, int n_states)
      : name_(std::move(name)), dofs_(std::move(dofs)), n_states_(n_states) {}

  virtual void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z,
                                  ElementWorkspace& ws, double* f, double* zdot) const = 0;

 private:
  std::string name_;
  std::vector<int> dofs_;
  int n_states_ = 0;
};

}  // namespace turbodyn

// Angular-contact ball bearing as a multibody force element (paper §2.1.2 and §2.2): inner ring (the shaft),
// Z balls, a ball-guided cage and an outer ring, 11 bodies for Z = 8. Every ball is a rigid sphere in contact
// with both grooves (Hertz, Eq. 20 in the exact-ellipse form, plus linear damping, Eq. 21) and with its cage
// pocket; tangential forces follow the regularised Coulomb law of Eqs. 22-23 at the slip velocity of each contact.
//
// Ball j, in cylindrical coordinates about the bearing axis (psi orbital angle, r = R_p + rho, axial zeta) and
// with its angular velocity w written in the ball's orbital frame (e_r, e_psi, e_z), which turns at psi':
//   m (rho'' - r psi'^2) = F_r,   m (r psi'' + 2 rho' psi') = F_psi,   m zeta'' = F_z,
//   I (w' + psi' e_z x w) = M            (sphere: I = m D^2 / 10, no gyroscopic term of its own)
// Cage: translations x, y, z and spin about z; tilt neglected. Outer ring: axial DOF on the preload spring,
// radial x, y fixed, on a spring-damper, or given by a wrapping element (see calc_bearing). No ring tilt.
// docs/ball-bearing.md gives the equations, the sign conventions and the assumptions.
#pragma once

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "model/elements/force_element.h"
#include "model/spec/ball_bearing_spec.h"

namespace turbodyn {

/// Hertz point contact of two elastic bodies (Johnson 1985, §4.2; Hamrock & Dowson 1981, ch. 3), with the exact
/// ellipse: the ellipticity k = a/b solves k^2 E(e) = (1 + R_y/R_x) K(e) - (R_y/R_x) E(e), e^2 = 1 - 1/k^2
/// (complete elliptic integrals K, E), and then F = K_c delta^(3/2) with K_c = pi k E' sqrt(2 E R / 9) / K^(3/2).
struct HertzPointContact {
  double curvature_sum = 0.0;  ///< 1/R = 1/R_x + 1/R_y in 1/m
  double ellipticity = 1.0;    ///< k = a / b (>= 1)
  double integral_k = 0.0;     ///< K(e), complete elliptic integral of the first kind
  double integral_e = 0.0;     ///< E(e), second kind
  double stiffness = 0.0;      ///< K_c in N/m^1.5: F = K_c delta^1.5
  double cbrt_stiffness = 0.0; ///< K_c^(1/3): F^(1/3) = K_c^(1/3) delta^(1/2)
  /// sqrt(a b) = radius_factor * F^(1/3) (m / N^(1/3)), mean radius of the contact ellipse.
  double radius_factor = 0.0;
  double curvature_x = 0.0;    ///< 1/R_x, curvature sum in the rolling direction (1/m), as given
  double modulus = 0.0;        ///< E' in Pa, as given
};

/// The lubricant of the lubricated traction law (TractionLaw::Eyring).
struct EyringLubricant {
  double viscosity = 0.0;           ///< eta_0 in Pa s at the inlet
  double pressure_viscosity = 0.0;  ///< alpha in 1/Pa (> 0)
  double eyring_stress = 0.0;       ///< tau_0 in Pa
  double limiting_shear = 0.0;      ///< gamma: limiting shear stress / pressure
  /// G in Pa: elastic shear modulus of the film (Maxwell element of the Johnson & Tevaarwerk model); infinite =
  /// a purely viscous (Eyring) film.
  double shear_modulus = std::numeric_limits<double>::infinity();
};

/// Entrainment speeds below this (m/s) are taken as this in the film thickness: a contact at rest keeps a film of
/// molecular size instead of none, so that the traction stays finite and smooth through zero slip.
inline constexpr double kMinEntrainmentSpeed = 0.01;

/// Lubricated traction of a Hertz contact carrying Q (N) at entrainment speed u and slip speed v (m/s), as the
/// force per unit slip F/v in N s/m (finite at v = 0): mean Hertz pressure p = Q / (pi a b); central film
/// thickness h = R_x H_c with H_c = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)), U = eta_0 u / (E' R_x),
/// G = alpha E', W = Q / (E' R_x^2) (Hamrock & Dowson 1977, ASME J. Lubr. Technol. 99); viscosity at p by Barus,
/// eta = eta_0 exp(alpha p); Eyring shear stress tau_E = tau_0 asinh(eta v / (tau_0 h)) (Johnson & Tevaarwerk
/// 1977, Proc. R. Soc. A 356), smoothly capped at the limiting shear stress gamma p (Bair & Winer 1979, ASME
/// J. Lubr. Technol. 101), tau = gamma p tanh(tau_E / (gamma p)); F = tau pi a b. Isothermal. The film's shear
/// elasticity (the Maxwell term tau'/G of Johnson & Tevaarwerk's law) in its small-strain form: a film sheared at
/// a constant rate from the contact inlet carries the mean stress eta_eff v / h over the transit time
/// t = 2 b / u (b the semi-axis along the rolling direction), eta_eff = eta (1 - (1 - exp(-r)) / r), r = t G / eta,
/// which is eta for a fluid that relaxes within the transit and G t / 2 for one that does not; eta_eff takes the
/// place of eta in the Eyring stress. It bounds the law's slope at zero slip, which Barus' eta alone would make as
/// steep as exp(alpha p) (a nearly discontinuous traction at high pressure).
double eyring_traction_per_slip(const EyringLubricant& lub, const HertzPointContact& hz, double Q, double u, double v);

/// curvature_x, curvature_y: principal curvature sums of the two bodies in the two principal planes (1/m, concave
/// negative), both > 0; modulus: E' = 2 / ((1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2) in Pa (Hamrock's E').
HertzPointContact SolveHertzPointContact(double curvature_x, double curvature_y, double modulus);

/// The largest pressure of the contact under the normal load Q (N): p_0 = 3 Q / (2 pi a b) in Pa, a b =
/// (radius_factor Q^(1/3))^2 (Johnson 1985, §4.2); 0 for Q <= 0.
double HertzPeakPressure(const HertzPointContact& hz, double Q);

/// ISO 76:2006's basis of the static load rating of ball bearings (all but self-aligning ones): the Hertz pressure
/// at the most heavily loaded ball-race contact at which the balls and races of bearing steel take a permanent
/// deformation of about 1/10,000 of the ball diameter (Pa). The bearing probes' limit of `max_contact_pressure`.
inline constexpr double kStaticContactPressureLimit = 4.2e9;

/// The probe of BallBearingLoads::max_contact_pressure, with its limit kStaticContactPressureLimit (a ball bearing
/// alone and in a damper).
ProbeInfo MaxContactPressureProbe();

/// The Hertz constant of paper Eq. 20, F = E' sqrt(3 / rho') (2 delta / (3 mu*))^1.5, in N/m^1.5: rho' the sum of
/// the principal curvatures of both bodies (1/m), E' the modulus as HertzPointContact's, mu* the paper's coefficient
/// (Harris & Kotzalas' dimensionless approach delta*: 1 for a sphere on a flat).
double PaperHertzConstant(double curvature_sum, double modulus, double mu_star);

/// Curvature sums (1/m) of a ball of diameter D in a race groove of ratio f at contact angle alpha, pitch
/// diameter d_m, rolling direction x and transverse direction y (Harris & Kotzalas 2007, ch. 2).
void RaceCurvatures(double D, double d_m, double f, double alpha, bool inner, double* curvature_x,
                    double* curvature_y);

/// Radial kinematics of the outer ring in the housing frame: position (m) and velocity (m/s).
struct OuterRingKinematics {
  double x = 0.0, y = 0.0, vx = 0.0, vy = 0.0;
};

/// One ball's share of the sums calc_bearing() forms over the balls (housing frame): forces and moments on the
/// shaft, on the outer ring and on the cage.
struct BallShare {
  double shaft[5] = {0, 0, 0, 0, 0};   ///< x, y (N), about x, y, z (N m)
  double outer[3] = {0, 0, 0};         ///< x, y, z (N)
  double cage[4] = {0, 0, 0, 0};       ///< x, y, z (N), torque about the axis (N m)
};

/// One contact's contribution to a ball's equations and to the sums over the balls (calc_bearing()).
struct BallContactPart {
  double ball[6] = {0, 0, 0, 0, 0, 0};  ///< force (N) and moment (N m) on the ball, orbital basis
  /// On the other body, housing frame: inner race force x, y, z and moment x, y, z; outer race force x, y, z;
  /// pocket force x, y, z on the cage and its torque about the axis.
  double body[6] = {0, 0, 0, 0, 0, 0};
};

/// Which contacts calc_bearing() evaluates anew (a bit mask; the others come from a BallContactCache).
enum BallContacts : unsigned { kInnerContacts = 1u, kOuterContacts = 2u, kPocketContacts = 4u, kAllContacts = 7u };

/// The contacts of one full evaluation, 3 per ball (inner race, outer race, pocket). A finite-difference column
/// that moves only the shaft, only the outer ring or only the cage changes only the inner-race, outer-race or
/// pocket contacts; the others are those of the base state (BallBearingElement::add_jacobian_of).
struct BallContactCache {
  std::vector<BallContactPart> parts;
};

/// What one bearing evaluation gives besides the state derivatives.
struct BallBearingLoads {
  double shaft[4] = {0, 0, 0, 0};       ///< generalised forces on the shaft: x, y (N), about x, y (N m)
  double shaft_torque = 0.0;            ///< moment on the shaft about the spin axis (N m; a drag is < 0)
  double outer_ring[3] = {0, 0, 0};     ///< force of the balls on the outer ring, x, y, z (N)
  /// Largest normal force of the inner-race and of the outer-race contacts (N); their Hertz pressures:
  /// BallBearingElement::max_contact_pressure.
  double max_race_contact_force[2] = {0.0, 0.0};
  /// Largest ball-race normal force (N).
  double max_contact_force() const { return std::max(max_race_contact_force[0], max_race_contact_force[1]); }
  double dissipated_power = 0.0;        ///< contact damping and friction (W, >= 0)
  /// Power of the inner-race contact forces on the shaft's lateral motion (x, y and tilt rates; the spin about
  /// the axis is the drive's): normal (Hertz + damping) and tangential (friction) parts (W). Their mean over a
  /// vibration cycle is the energy the bearing feeds into (> 0) or takes out of (< 0) the rotor's vibration.
  double shaft_power_normal = 0.0;
  double shaft_power_friction = 0.0;
  /// Friction losses (slip and spin) at the inner-race, outer-race and pocket contacts (W, >= 0).
  double friction_loss_inner = 0.0, friction_loss_outer = 0.0, friction_loss_pocket = 0.0;
  double inner_contact_angle = 0.0;     ///< mean direction of the loaded inner contacts (rad), 0 if none
  double outer_contact_angle = 0.0;     ///< same, outer contacts
};

class BallBearingElement final : public ForceElement {
 public:
  /// Attached to the 4 rotor DOFs (x, y, theta_x, theta_y) starting at node_dof. gravity: m/s^2 along -y.
  /// Throws std::invalid_argument naming the bad field if !spec.IsValid().
  ///
  /// States (n_states()), blocks in this order:
  ///   ball j = 0..Z-1, 9 each: psi (rad), rho (m, r - R_p), zeta (m), psi' (rad/s), rho' (m/s), zeta' (m/s),
  ///                            w_r, w_psi, w_z (rad/s, absolute angular velocity in the ball's orbital frame)
  ///   cage, 8:                 x, y, z (m), angle (rad), vx, vy, vz (m/s), spin (rad/s)
  ///   outer ring axial, 2:     z_o (m), v_zo (m/s)
  ///   Spring only, 4:         x_o, y_o (m), vx_o, vy_o (m/s)
  /// The first n_core_states() (all but the last block) are the states calc_bearing() works on.
  BallBearingElement(const std::string& name, const BallBearingSpec& spec, int node_dof, double gravity);

  const BallBearingSpec& spec() const { return spec_; }
  int n_core_states() const { return n_core_; }
  static constexpr int kBallStates = 9, kCageStates = 8;
  int ball_offset(int j) const { return kBallStates * j; }
  int cage_offset() const { return kBallStates * spec_.n_balls; }
  int outer_offset() const { return cage_offset() + kCageStates; }

  /// Static preload equilibrium (no gravity, no speed), balls equally spaced, everything at rest.
  void initial_states(double* z) const override;
  /// initial_states(), then (speed != 0) the no-slip ball and cage speeds of steady_states().
  void initial_states_at_speed(double speed, double* z) const override;
  /// Sets the ball orbital and spin speeds and the cage speed to their no-slip values at rotor speed `speed`
  /// (rad/s): outer-race control, spin axis normal to the outer contact line (Jones 1960; Harris & Kotzalas 2007,
  /// ball kinematics), contact angle from the ball positions in z; positions are left as they are.
  void steady_states(double speed, double* z) const;

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  double state_scale(int i) const override;
  /// state_scale(), except for the balls' radial and axial velocities and spin rates (as surface speeds) and the
  /// cage's translational velocities: a ball rings on its two Hertz contacts at about 61 kHz (reference bearing at
  /// rest), the cage on a pocket at about 8.6 kHz, so 1 um of their displacement corresponds to 0.38 and 0.054 m/s
  /// of velocity. kBallVelocityTolerance and kCageVelocityTolerance (3.8x and 1.1x tighter than that) instead of
  /// 1 mm/s (docs/ball-bearing.md, "In run-ups").
  double tolerance_scale(int i) const override;
  static constexpr double kBallVelocityTolerance = 0.1, kCageVelocityTolerance = 0.05;  // m/s
  /// Balls and cage orbit at the cage speed about a centred shaft: the ball and cage angles turn, the cage's
  /// centre and velocity (and a spring-mounted outer ring's) are housing-frame pairs. False with outer ring
  /// External (the wrapping element answers) and with gravity (nothing is steady in a turning frame then).
  bool steady_rotation_layout(SteadyRotationLayout* layout) const override;
  /// The turning angles and housing-frame pairs of the core states (balls, cage) alone, for a wrapping element.
  void core_rotation_layout(SteadyRotationLayout* layout) const;
  /// The balls: each ball's equations involve only itself, the cage, the outer ring and the shaft.
  std::vector<int> independent_state_blocks() const override {
    return std::vector<int>(static_cast<std::size_t>(spec_.n_balls), kBallStates);
  }
  /// A ball's orbital angle, radial and axial position have its orbital, radial and axial velocity as rates.
  int kinematic_states_per_block() const override { return 3; }
  /// Finite differences that use the balls' independence: the shaft, cage and outer-ring inputs one at a time,
  /// the balls' states one index at a time for all balls at once, each ball's rows and its share of the sums
  /// (BallShare) telling the balls apart: 2d + 19 (+4 with a spring-mounted outer ring) evaluations instead of
  /// 2d + 9 Z + 10. The shaft's, the cage's and the outer ring's columns evaluate only the contacts they move
  /// (inner races, pockets, outer races; BallContactCache). Steps as the engine's (fd_relative_step(), state_scale()).
  bool has_jacobian() const override { return true; }
  int jacobian_evaluations() const override { return 1 + 8 + (n_states() - kBallStates * spec_.n_balls) + kBallStates; }
  void add_jacobian(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                   double* J) const override;
  /// What add_jacobian_of differentiates: an element's outputs [f (4); zdot] at inputs (q, v, z), added to f and
  /// written to zdot, with each ball's share of the sums.
  /// cache and redo are passed on to calc_bearing(): the base state fills the cache, the shaft's, cage's and outer
  /// ring's columns redo only the contacts they move.
  struct JacobianEvaluator {
    virtual ~JacobianEvaluator() = default;
    virtual void operator()(const double* q, const double* v, const double* z, double* f, double* zdot,
                            BallShare* shares, BallContactCache* cache, unsigned redo) const = 0;
  };
  /// add_jacobian for an element `owner` that is this bearing or wraps it (a squeeze-film damper): m states, the
  /// core states first, then (m > n_core_states()) the outer ring's x, y, vx, vy, whose accelerations contain the
  /// balls' force on the ring divided by the outer-ring mass, plus terms that depend on those 4 states only. Steps
  /// are owner.fd_step(); ws is a workspace of this bearing.
  void add_jacobian_of(const ForceElement& owner, const JacobianEvaluator& eval, int m, const double* q,
                     const double* v, const double* z, ElementWorkspace& ws, double* J) const;
  std::vector<ProbeInfo> probes() const override;
  void eval_probes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double kinetic_energy(const double* z) const override;
  double potential_energy(const double* q, const double* z) const override;
  double dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;
  /// Drive power through the drag torque on the shaft, -T Omega (the rotor spin is prescribed).
  double drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                    ElementWorkspace& ws) const override;

  /// The bearing without its outer-ring radial dynamics, for this element and for an element that wraps it
  /// (a squeeze-film damper owning the outer ring's radial states): given the shaft (q, v at the 4 DOFs), the
  /// core states z (n_core_states() values) and the outer ring's radial kinematics, writes the derivatives of
  /// the core states into zdot and the forces into loads (which it overwrites). Allocates nothing.
  /// shares: if not null, n_balls entries that receive each ball's share of the sums.
  /// cache (3 n_balls parts) and redo: with redo = kAllContacts every contact is evaluated and stored in the
  /// cache; otherwise only the contacts in redo are evaluated and the others taken from the cache, which must hold
  /// a full evaluation at the same ball states (and the same shaft, outer ring or cage where those contacts are
  /// taken). Such a partial evaluation gives zdot, shares and the loads' shaft, shaft_torque and outer_ring; the
  /// other loads (powers, losses, angles) cover only the contacts it evaluated. Without a cache: all of them.
  void calc_bearing(const SpinState& s, const double* q, const double* v, const double* z,
                   const OuterRingKinematics& outer, BallBearingLoads& loads, double* zdot,
                   BallShare* shares = nullptr, BallContactCache* cache = nullptr,
                   unsigned redo = kAllContacts) const;
  /// Hertz (races and pockets), preload-spring and gravity energy of the core bodies (J); the radial spring of
  /// Spring and the outer ring's radial gravity are not included.
  double core_potential_energy(const double* q, const double* z, const OuterRingKinematics& outer) const;
  /// Kinetic energy of balls, cage and the outer ring's axial motion (J).
  double core_kinetic_energy(const double* z) const;

  /// The dashpot of a ball-race contact `hz` at the approach delta = root_delta^2 (N s/m): paper Eq. 21's d plus the
  /// lubricant's beta k_c, k_c = 1.5 K delta^0.5 the contact's tangent Hertz stiffness (contact_damping_ratio).
  double race_contact_damping(const HertzPointContact& hz, double root_delta) const {
    return spec_.contact_damping + spec_.contact_damping_ratio * 1.5 * hz.stiffness * root_delta;
  }

  /// Derived constants (for tests and documentation).
  const HertzPointContact& inner_contact() const { return hertz_inner_; }
  /// The largest Hertz pressure of the ball-race contacts of an evaluation (Pa, HertzPeakPressure; computed here
  /// rather than in every evaluation, which only keeps the races' largest forces).
  double max_contact_pressure(const BallBearingLoads& loads) const;
  const HertzPointContact& outer_contact() const { return hertz_outer_; }
  double pocket_stiffness() const { return k_pocket_; }  ///< N/m^1.5
  double ball_mass() const { return m_ball_; }           ///< kg
  double preload_displacement() const { return zo_eq_; } ///< z_o at the static preload equilibrium (m)
  double ball_inertia() const { return i_ball_; }        ///< kg m^2, I = m D^2 / 10
  double pitch_radius() const { return pitch_radius_; }  ///< R_p = d_m / 2 in m
  /// One groove-curvature-centre circle in its ring's frame (docs/ball-bearing.md, "Unloaded geometry").
  struct GrooveCircle {
    double radial = 0.0;    ///< radius of the circle minus R_p (m)
    double axial = 0.0;     ///< axial position (m); the outer ring's circle moves with z_o
    double distance = 0.0;  ///< (f - 1/2) D, groove centre to ball centre when just touching (m)
  };
  GrooveCircle inner_groove() const { return {inner_dr_, inner_z_, inner_r_}; }
  GrooveCircle outer_groove() const { return {outer_dr_, outer_z_, outer_r_}; }

 protected:
  void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 private:
  OuterRingKinematics outer_from_states(const double* z) const;
  /// do_calc_and_add_forces with the balls' shares of the sums (shares: n_balls entries, or null) and the loads
  /// (loads_out, or null).
  void Evaluate(const SpinState& s, const double* q, const double* v, const double* z, double* f, double* zdot,
                BallShare* shares, BallBearingLoads* loads_out = nullptr, BallContactCache* cache = nullptr,
                unsigned redo = kAllContacts) const;
  /// The loads at this state: those of the last engine evaluation if its inputs were the same, else evaluated.
  const BallBearingLoads& loads_at(const SpinState& s, const double* q, const double* v, const double* z,
                                  ElementWorkspace& ws) const;
  BallBearingSpec spec_;
  double gravity_ = 0.0;
  int n_core_ = 0;
  HertzPointContact hertz_inner_, hertz_outer_;
  EyringLubricant lubricant_;
  double k_pocket_ = 0.0;
  double m_ball_ = 0.0, i_ball_ = 0.0, i_cage_ = 0.0;
  double pitch_radius_ = 0.0;
  std::vector<double> pocket_cos_, pocket_sin_;  // cos, sin of 2 pi j / Z: the pockets' angles in the cage
  // cos and sin of pocket j's angle, cage angle + 2 pi j / Z, from those of the cage angle (cage_c, cage_s).
  double pocket_cos(int j, double cage_c, double cage_s) const {
    return cage_c * pocket_cos_[j] - cage_s * pocket_sin_[j];
  }
  double pocket_sin(int j, double cage_c, double cage_s) const {
    return cage_s * pocket_cos_[j] + cage_c * pocket_sin_[j];
  }
  // Groove-centre circles: radius offset from the pitch radius and axial position (ring frames), and the
  // unloaded distance (f - 1/2) D from the groove centre to the ball centre.
  double inner_dr_ = 0.0, inner_z_ = 0.0, inner_r_ = 0.0;
  double outer_dr_ = 0.0, outer_z_ = 0.0, outer_r_ = 0.0;
  // Static preload equilibrium: outer ring z, ball rho and zeta.
  double zo_eq_ = 0.0, rho_eq_ = 0.0, zeta_eq_ = 0.0;
};

}  // namespace turbodyn

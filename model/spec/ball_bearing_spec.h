// Data of an angular-contact ball bearing as the model file gives it (plain data, SI units); the force element that
// uses it is model/elements/ball/ball_bearing.h, the equations are in docs/ball-bearing.md.
#pragma once

#include <string>

namespace turbodyn {

/// How the outer ring moves radially.
enum class OuterRingMode {
  Fixed,     ///< radially held in the housing (rigid); axial DOF on the preload spring only
  Spring,    ///< radial x, y on an isotropic spring-damper to the housing (4 extra states at the end)
  External,  ///< radial x, y given by a wrapping element (squeeze-film damper) through calc_bearing()
};

/// Which slip the race friction of paper Eq. 23 acts on.
enum class RaceTraction {
  /// The whole tangential slip at the contact centre (rolling, cross-rolling and the tangential effect of spin).
  Spatial,
  /// The paper's planar contact (§2.2, Eqs. 17-19: circles in the plane of rolling): friction along the rolling
  /// direction only, i.e. the slip component along e_psi projected into the contact's tangent plane.
  Planar,
};

/// Which law gives the size of the race traction (its direction is the slip's, as race_traction says).
enum class TractionLaw {
  /// Paper Eq. 23: mu(|v|) Q with the regularised Coulomb coefficient of friction_static, friction_sliding,
  /// friction_v1, friction_v2.
  Coulomb,
  /// A lubricated (elastohydrodynamic) contact: the mean shear stress of an Eyring fluid across the central film,
  /// tau = tau_0 asinh(eta(p) |v| / (tau_0 h)), capped at the limiting shear stress gamma p, times the Hertz
  /// contact area (Johnson & Tevaarwerk 1977; Bair & Winer 1979), with eta(p) = eta_0 exp(alpha p) at the mean
  /// Hertz pressure p (Barus) and h the central film thickness of Hamrock & Dowson (1977) at the contact's
  /// entrainment speed. docs/ball-bearing.md, "Lubricated traction".
  Eyring,
};

/// The contact damping ratio beta of a model file that names none [s]: the lower end of Kraemer's range for lubricated
/// rolling bearings, damping = (0.25 ... 2.5)e-5 s x stiffness (Kraemer, Dynamics of Rotors and Foundations, 1993).
inline constexpr double kDefaultContactDampingRatio = 0.25e-5;
/// The largest contact damping ratio a spec accepts [s], 40x the top of Kraemer's range: beyond it a unit is wrong.
inline constexpr double kMaxContactDampingRatio = 1e-3;

/// Data of one ball bearing, SI units. Defaults: docs/reference-machine.md, variant II.
struct BallBearingSpec {
  // Geometry.
  int n_balls = 8;                  ///< Z, number of balls (>= 3)
  double ball_diameter = 4.5e-3;    ///< D in m
  double pitch_diameter = 17.5e-3;  ///< d_m in m
  double inner_groove_ratio = 0.52; ///< f_i = inner groove radius / D (> 0.5)
  double outer_groove_ratio = 0.53; ///< f_o = outer groove radius / D (> 0.5)
  /// Free (unloaded) contact angle alpha_0 in rad, [0, pi/2). It fixes the unloaded geometry: the groove centres
  /// are A = (f_i + f_o - 1) D apart along the line at alpha_0, i.e. the radial (diametral/2) clearance is
  /// P_d / 2 = A (1 - cos alpha_0) (Harris & Kotzalas 2007, ch. 2).
  double contact_angle = 15.0 * 3.14159265358979323846 / 180.0;
  /// +1: the outer contact lies on the +z side of the ball (the outer ring is pushed towards -z by the preload),
  /// -1: the mirror image. A back-to-back pair has opposite sides.
  int side = +1;

  // Materials.
  double ball_youngs_modulus = 208e9;  ///< Pa
  double ball_poisson_ratio = 0.3;     ///< -
  double ball_density = 7800.0;        ///< kg/m^3
  double ring_youngs_modulus = 208e9;  ///< Pa (both rings)
  double ring_poisson_ratio = 0.3;     ///< -

  // Cage (ball-guided: located by the balls in its pockets; ring guidance is not modelled).
  double cage_mass = 1.0e-3;              ///< kg
  double cage_polar_inertia = 0.0;        ///< kg m^2; 0 = thin ring at the pitch radius, m R_p^2
  double cage_diametral_inertia = 0.0;    ///< kg m^2; 0 = m R_p^2 / 2 (unused: cage tilt is not modelled)
  double pocket_clearance = 0.10e-3;      ///< m, clearance between ball and pocket (spherical pocket)
  double cage_youngs_modulus = 8.0e9;     ///< Pa (glass-fibre polyamide; brass: 100e9)
  double cage_poisson_ratio = 0.35;       ///< -
  double pocket_damping = 5.0;            ///< N s/m, linear damping of a pocket contact

  // Contact laws (paper Eqs. 20, 21, 23).
  /// mu* of paper Eq. 20 for both race contacts, F = E' sqrt(3 / rho') (2 delta / (3 mu*))^1.5 with rho' the sum of
  /// the four principal curvatures (the paper's 0.171, "for cylinder against sphere"; for a sphere on a flat it is 1,
  /// and a conforming groove has less, e.g. 0.59 and 0.72 for the reference bearing's inner and outer contacts);
  /// 0 = the exact Hertz ellipse of the contact's curvatures (the default). In (0, 1].
  double hertz_coefficient = 0.0;
  double contact_damping = 15.0;   ///< d in N s/m, ball-race contacts
  /// beta in s: each ball-race contact's damping is d + beta k_c, k_c = dQ/d delta = 1.5 K delta^0.5 its tangent Hertz
  /// stiffness, so that a bearing whose contacts all have it has the damping beta K of its stiffness K (Kraemer's
  /// rule for lubricated rolling bearings, beta = 0.25e-5 to 2.5e-5 s). A spec built in code has none; a model
  /// file's default is the rule's lower end (model/io/model_file.cpp, docs/ball-bearing.md).
  double contact_damping_ratio = 0.0;
  double friction_static = 0.10;   ///< mu_0
  double friction_sliding = 0.05;  ///< mu_r
  double friction_v1 = 0.05;       ///< v_1 in m/s (decay of mu_0 towards mu_r)
  double friction_v2 = 0.005;      ///< v_2 in m/s (tanh regularisation of sgn)
  bool spin_friction = true;       ///< add the spin moment of each race contact (3 pi / 16) mu Q a
  RaceTraction race_traction = RaceTraction::Spatial;  ///< which slip the race friction acts on
  /// Which law sizes the race traction. A model file's default is Eyring, with the [oil]'s viscosity
  /// (model/io/model_file.cpp); a spec built in code names its law, Eq. 23 unless it says otherwise.
  TractionLaw traction_law = TractionLaw::Coulomb;
  // Lubricated traction (TractionLaw::Eyring); defaults typical of a mineral engine oil (docs/ball-bearing.md).
  double lubricant_viscosity = 0.0;          ///< eta_0 in Pa s at the contact inlet; 0 = the model's [oil]
  double pressure_viscosity = 2.0e-8;        ///< alpha in 1/Pa, Barus pressure-viscosity coefficient
  double eyring_stress = 5.0e6;              ///< tau_0 in Pa
  double limiting_shear_coefficient = 0.08;  ///< gamma: limiting shear stress / pressure
  double lubricant_shear_modulus = 1.0e9;    ///< G in Pa, the film's elastic shear modulus (Johnson & Roberts 1974)

  // Axial preload (spring-preloaded outer ring).
  double preload = 40.0;               ///< F_p in N (>= 0), spring force at the unloaded geometry
  double preload_stiffness = 1.0e4;    ///< k_p in N/m (>= 0), stiffness of the preload spring

  // Outer ring.
  OuterRingMode outer_ring_mode = OuterRingMode::Fixed;
  double outer_ring_mass = 8.0e-3;        ///< kg (axial motion; radial motion in Spring)
  double outer_ring_stiffness = 1.0e9;    ///< N/m, radial, Spring only
  double outer_ring_damping = 200.0;      ///< N s/m, radial, Spring only

  /// True if every field is acceptable; otherwise *error names the first bad field and why.
  bool IsValid(std::string* error) const;
};

}  // namespace turbodyn

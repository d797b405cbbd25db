// Timoshenko beam finite element of a spinning shaft.
//
// Degrees of freedom per node, inertial frame, shaft axis z:  q = [x, y, theta_x, theta_y]
//   x, y        lateral displacements of the shaft centre line in m,
//   theta_x/y   rotations of the cross-section about the x and y axes in rad.
// In the Euler-Bernoulli limit theta_y = dx/dz and theta_x = -dy/dz (right-handed rotations).
//
// Interpolation: the "interdependent interpolation element" of Friedman & Kosmatka (1993, Comput. Struct. 47(3)),
// cubic displacements and quadratic rotations that solve the static Timoshenko equations exactly, so the stiffness
// is exact for any shear parameter Phi = 12 E I / (kappa G A L^2); Phi = 0 gives the Hermite (Euler-Bernoulli)
// element. The matrices are integrated by Gauss quadrature of the shape functions (exact for these polynomials),
// which keeps one source of truth for M, G, K and the rotating-frame terms of paper Eq. (9):
//
//   M q'' + (D + Omega G) q' + (K + Omega^2 M_Omega) q = f           (paper Eq. 9)
//
// In the inertial frame used for the run-up and the Campbell diagram M_Omega of an axisymmetric shaft vanishes;
// written in the frame that spins with the shaft (the paper's body frame K), the spin-softening matrix is
// M_Omega = -M_trans + (rho*Ip - rho*Id)-rotary term and the gyroscopic matrix gains the Coriolis terms.
// Both forms are assembled (see RotatingFrameMatrices) so that the rotating-frame equations of the paper can be
// analysed and checked against the inertial ones.
#pragma once

#include <Eigen/Dense>

namespace turbodyn {

/// Cross-section and material data of one beam element.
struct BeamProperties {
  double length = 0.0;          ///< L in m
  double outer_diameter = 0.0;  ///< m
  double inner_diameter = 0.0;  ///< m
  double youngs_modulus = 0.0;  ///< E in Pa
  double shear_modulus = 0.0;   ///< G in Pa
  double density = 0.0;         ///< rho in kg/m^3
  double shear_factor = 1.0;    ///< kappa [-]
  bool shear_deformation = true;
  bool rotary_inertia = true;

  double area() const;              ///< m^2
  double second_moment() const;     ///< I = pi (do^4 - di^4) / 64 in m^4 (diametral)
  double shear_parameter() const;   ///< Phi = 12 E I / (kappa G A L^2) [-], 0 without shear deformation
};

/// Shear factor of a circular tube (solid when inner/outer = 0).
/// Cowper (1966), J. Appl. Mech. 33: kappa = 6(1+nu)(1+m^2)^2 / ((7+6nu)(1+m^2)^2 + (20+12nu) m^2), m = di/do;
/// solid: 6(1+nu)/(7+6nu).
double cowper_shear_factor(double poisson_ratio, double inner_over_outer);
/// Hutchinson (2001), J. Appl. Mech. 68, solid circle: kappa = 6(1+nu)^2 / (7 + 12 nu + 4 nu^2).
/// For hollow sections the thin-walled-tube limit is not covered by this closed form; callers use Cowper there.
double hutchinson_shear_factor_solid(double poisson_ratio);

using Matrix8 = Eigen::Matrix<double, 8, 8>;

/// Element matrices in the inertial frame (8 x 8, node 1 then node 2, each [x, y, theta_x, theta_y]).
struct BeamElementMatrices {
  Matrix8 mass;            ///< M = M_trans + M_rot in kg, kg m, kg m^2
  Matrix8 mass_translational;  ///< rho A part of M
  Matrix8 mass_rotary;     ///< rho I part of M (zero without rotary inertia)
  Matrix8 gyroscopic;      ///< G (multiplies Omega q'), skew-symmetric, from the polar rotary inertia 2 rho I
  Matrix8 stiffness;       ///< K in N/m, N, N m
};

BeamElementMatrices beam_element(const BeamProperties& p);

}  // namespace turbodyn

#include "model/rotor/timoshenko.h"

#include <array>
#include <cmath>

namespace turbodyn {

double BeamProperties::area() const {
  return M_PI * (outer_diameter * outer_diameter - inner_diameter * inner_diameter) / 4.0;
}

double BeamProperties::second_moment() const {
  return M_PI * (std::pow(outer_diameter, 4) - std::pow(inner_diameter, 4)) / 64.0;
}

double BeamProperties::shear_parameter() const {
  if (!shear_deformation) return 0.0;
  return 12.0 * youngs_modulus * second_moment() / (shear_factor * shear_modulus * area() * length * length);
}

double cowper_shear_factor(double nu, double m) {
  const double m2 = m * m;
  const double a = (1.0 + m2) * (1.0 + m2);
  return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m2);
}

double hutchinson_shear_factor_solid(double nu) {
  return 6.0 * (1.0 + nu) * (1.0 + nu) / (7.0 + 12.0 * nu + 4.0 * nu * nu);
}

namespace {

using Row8 = Eigen::Matrix<double, 1, 8>;

// Values at xi of the planar shape functions (w, phi) and their xi-derivatives; see the header for the source.
struct Planar {
  std::array<double, 4> w, dw, phi, dphi;
};

Planar planar_shapes(double xi, double L, double Phi) {
  const double s = 1.0 / (1.0 + Phi);
  const double x2 = xi * xi, x3 = x2 * xi;
  Planar p;
  p.w = {s * (2 * x3 - 3 * x2 - Phi * xi + 1 + Phi), s * L * (x3 - (2 + Phi / 2) * x2 + (1 + Phi / 2) * xi),
         s * (-2 * x3 + 3 * x2 + Phi * xi), s * L * (x3 - (1 - Phi / 2) * x2 - (Phi / 2) * xi)};
  p.dw = {s * (6 * x2 - 6 * xi - Phi), s * L * (3 * x2 - (4 + Phi) * xi + 1 + Phi / 2), s * (-6 * x2 + 6 * xi + Phi),
          s * L * (3 * x2 - (2 - Phi) * xi - Phi / 2)};
  p.phi = {s * 6 * (x2 - xi) / L, s * (3 * x2 - (4 + Phi) * xi + 1 + Phi), -s * 6 * (x2 - xi) / L,
           s * (3 * x2 - (2 - Phi) * xi)};
  p.dphi = {s * (12 * xi - 6) / L, s * (6 * xi - (4 + Phi)), -s * (12 * xi - 6) / L, s * (6 * xi - (2 - Phi))};
  return p;
}

// Planar DOF i of the x-z plane is element DOF kXZ[i] (w = x, phi = theta_y); of the y-z plane kYZ[i] with sign
// kYZsign[i] (w = y, phi = -theta_x).
constexpr std::array<int, 4> kXZ{0, 3, 4, 7};
constexpr std::array<int, 4> kYZ{1, 2, 5, 6};
constexpr std::array<double, 4> kYZsign{1.0, -1.0, 1.0, -1.0};

}  // namespace

BeamElementMatrices beam_element(const BeamProperties& p) {
  const double L = p.length, A = p.area(), I = p.second_moment();
  const double Phi = p.shear_parameter();
  const double rhoA = p.density * A;
  const double rhoI = p.rotary_inertia ? p.density * I : 0.0;
  const double EI = p.youngs_modulus * I;
  const double kGA = p.shear_factor * p.shear_modulus * A;

  // 4-point Gauss-Legendre on [0, 1]: exact for the degree-6 products of cubic shape functions.
  constexpr std::array<double, 4> kNodes{0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                                         0.9305681557970263};
  constexpr std::array<double, 4> kWeights{0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                                           0.1739274225687269};

  BeamElementMatrices m;
  m.mass_translational.setZero();
  m.mass_rotary.setZero();
  m.gyroscopic.setZero();
  m.stiffness.setZero();
  for (std::size_t g = 0; g < kNodes.size(); ++g) {
    const Planar s = planar_shapes(kNodes[g], L, Phi);
    Row8 ux = Row8::Zero(), uy = Row8::Zero(), tx = Row8::Zero(), ty = Row8::Zero();
    Row8 dtx = Row8::Zero(), dty = Row8::Zero(), gx = Row8::Zero(), gy = Row8::Zero();
    for (int i = 0; i < 4; ++i) {
      ux(kXZ[i]) += s.w[i];
      ty(kXZ[i]) += s.phi[i];
      dty(kXZ[i]) += s.dphi[i] / L;
      gx(kXZ[i]) += s.dw[i] / L - s.phi[i];  // shear strain gamma_xz = dx/dz - theta_y
      uy(kYZ[i]) += kYZsign[i] * s.w[i];
      tx(kYZ[i]) -= kYZsign[i] * s.phi[i];
      dtx(kYZ[i]) -= kYZsign[i] * s.dphi[i] / L;
      gy(kYZ[i]) += kYZsign[i] * (s.dw[i] / L - s.phi[i]);  // gamma_yz = dy/dz + theta_x
    }
    const double wL = kWeights[g] * L;
    m.mass_translational += wL * rhoA * (ux.transpose() * ux + uy.transpose() * uy);
    m.mass_rotary += wL * rhoI * (tx.transpose() * tx + ty.transpose() * ty);
    // Polar rotary inertia per length rho * 2I; the x-moment equation carries +Ip Omega dtheta_y/dt.
    m.gyroscopic += wL * 2.0 * rhoI * (tx.transpose() * ty - ty.transpose() * tx);
    m.stiffness += wL * EI * (dtx.transpose() * dtx + dty.transpose() * dty);
    if (p.shear_deformation) m.stiffness += wL * kGA * (gx.transpose() * gx + gy.transpose() * gy);
  }
  m.mass = m.mass_translational + m.mass_rotary;
  return m;
}

}  // namespace turbodyn

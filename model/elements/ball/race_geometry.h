// Ball-race contact geometry shared by the ball-bearing element (ball_bearing.cpp) and its quasi-static
// equilibrium (ball_bearing_quasistatic.cpp): one implementation, so that both see the same contacts.
// docs/ball-bearing.md "Contacts" gives the construction. Internal to model/elements/ball/.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace turbodyn::ball_detail {

/// One race as a ball sees it, all vectors in the orbital basis (e_r, e_psi, e_z) of that ball.
struct Race {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();  ///< ring centre (m, m/s)
  Eigen::Vector3d tilt = Eigen::Vector3d::Zero(), tilt_rate = Eigen::Vector3d::Zero();  ///< rotation (rad), rate
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();  ///< angular velocity of the ring (rad/s)
  double dr = 0.0, dz = 0.0, r0 = 0.0;  ///< groove-centre circle (radius - R_p, axial), unloaded distance (m)
};

struct RaceGeometry {
  double delta = 0.0;   ///< normal approach (m), > 0 in contact
  Eigen::Vector3d p;    ///< ball centre relative to the ring centre, housing orientation
  Eigen::Vector3d u_l;  ///< unit vector groove centre -> ball centre in the ring's (tilted) frame
  Eigen::Vector3d u;    ///< the same in the housing frame: u = (I - [theta x])^T u_l = u_l + theta x u_l
};

/// Ball centre at (R, 0, zeta) in the orbital basis, R = R_p + rho. The ring frame is reached with the
/// small rotation p_l = p - theta x p; the closest groove centre lies in the ring-frame plane through the axis and
/// the ball. Radial differences are formed from small quantities only (no R_p - R_p cancellation).
/// Returns delta > 0; without contact u_l and u are only set if `always_normal` (the direction the contact would
/// have), so that the element's hot path skips them.
inline bool race_geometry(const Race& race, double R, double rho, double zeta, RaceGeometry& g,
                          bool always_normal = false) {
  using Vec3 = Eigen::Vector3d;
  g.p = Vec3(R - race.centre.x(), -race.centre.y(), zeta - race.centre.z());
  const Vec3 tp = race.tilt.cross(g.p);
  const double a = -race.centre.x() - tp.x();  // radial offset of the ball in the ring frame, minus R
  const double b = -race.centre.y() - tp.y();  // tangential offset
  const double zl = g.p.z() - tp.z();
  const double rl = std::sqrt((R + a) * (R + a) + b * b);
  const double rl_minus_R = ((2.0 * R + a) * a + b * b) / (rl + R);
  const double dr = rho - race.dr + rl_minus_R;  // r_l - R_g
  const double dz = zl - race.dz;
  const double dist = std::sqrt(dr * dr + dz * dz);
  g.delta = dist - race.r0;
  if (g.delta <= 0.0 && !always_normal) return false;
  const double s = dr / (dist * rl);
  g.u_l = Vec3(s * (R + a), s * b, dz / dist);
  g.u = g.u_l + race.tilt.cross(g.u_l);
  return g.delta > 0.0;
}

/// Housing-frame components (x, y, z) in the orbital basis of a ball at angle psi (c = cos psi, s = sin psi).
inline Eigen::Vector3d to_orbital(double x, double y, double z, double c, double s) {
  return Eigen::Vector3d(x * c + y * s, -x * s + y * c, z);
}

}  // namespace turbodyn::ball_detail

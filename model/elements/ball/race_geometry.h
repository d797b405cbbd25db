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

/// The inverse of to_orbital: housing-frame components of a vector given in the orbital basis of that ball.
inline Eigen::Vector3d to_housing(const Eigen::Vector3d& a, double c, double s) {
  return Eigen::Vector3d(a.x() * c - a.y() * s, a.x() * s + a.y() * c, a.z());
}

/// Q^(1/3) of a contact load Q = Q_H + (damping) from Q_H^(1/3) = K^(1/3) delta^(1/2), which the Hertz law gives
/// without a cube root: three Halley steps on y^3 = Q (relative error below 5e-16 for |Q/Q_H - 1| <= 0.1, checked
/// against std::cbrt by `BallBearing.LoadCubeRootFromTheHertzApproachIsStdCbrt`), std::cbrt otherwise.
inline double load_cbrt(double Q, double QH, double cbrt_QH) {
  if (Q == QH) return cbrt_QH;
  if (!(std::abs(Q - QH) <= 0.1 * QH)) return std::cbrt(Q);
  double y = cbrt_QH;
  for (int i = 0; i < 3; ++i) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * Q) / (2.0 * y3 + Q);
  }
  return y;
}

/// mu(v) / v of the paper's Eq. 23, mu(v) = (mu_r + (mu_0 - mu_r) exp(-v / v_1)) tanh(v / v_2), for a slip speed
/// v >= 0; finite at v = 0 (mu_0 / v_2). Between v / v_2 = 0.5 and 20 tanh comes from one exp (cheaper than libm's
/// tanh, which goes through expm1; no cancellation there), above 20 it is 1 to double precision.
/// `BallBearing.Eq23FrictionLawIsTheClosedForm` checks it against std::tanh.
inline double eq23_mu_over_slip(double v, double mu0, double mur, double v1, double v2) {
  const double x = v / v2;
  double t;
  if (x < 1e-4) {
    t = (1.0 - x * x / 3.0) / v2;
  } else if (x < 0.5) {
    t = std::tanh(x) / v;
  } else if (x < 20.0) {
    const double e = std::exp(-2.0 * x);  // <= 1/e
    t = (1.0 - e) / ((1.0 + e) * v);
  } else {
    t = 1.0 / v;  // exp(-40) = 4e-18
  }
  return (mur + (mu0 - mur) * std::exp(-v / v1)) * t;
}

/// Pocket of a ball: ball centre relative to the pocket centre (orbital basis) and the pocket centre relative to the
/// cage centre, from the sine and cosine (sd, cd) of dpsi = psi - (cage angle + 2 pi j / Z)
/// (`BallBearing.PocketGeometryIsTheCartesianOne`).
struct PocketGeometry {
  Eigen::Vector3d delta_vec, pocket;
  double dist = 0.0;
};

inline void pocket_geometry(double rho, double zeta, double sd, double cd, double Rp,
                            const Eigen::Vector3d& cage_centre, PocketGeometry& g) {
  // 1 - cos dpsi without cancellation where the ball is near its pocket (cos dpsi > 0): sin^2 / (1 + cos).
  const double one_minus_cos = cd > 0.0 ? sd * sd / (1.0 + cd) : 1.0 - cd;
  g.pocket = Eigen::Vector3d(Rp * (1.0 - one_minus_cos), -Rp * sd, 0.0);
  g.delta_vec = Eigen::Vector3d(rho + Rp * one_minus_cos - cage_centre.x(), Rp * sd - cage_centre.y(),
                                zeta - cage_centre.z());
  g.dist = g.delta_vec.norm();
}

/// Sine and cosine of dpsi = psi - phi from those of the ball's angle psi (c, sn) and of its pocket's angle phi
/// (cp, sp): no second sincos and no reduction of the difference of two large angles.
inline void pocket_offset(double c, double sn, double cp, double sp, double& sd, double& cd) {
  sd = sn * cp - c * sp;
  cd = c * cp + sn * sp;
}

}  // namespace turbodyn::ball_detail

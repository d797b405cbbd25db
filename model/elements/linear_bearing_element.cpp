#include "model/elements/linear_bearing_element.h"

#include <algorithm>
#include <array>

namespace turbodyn {

LinearBearingElement::LinearBearingElement(const LinearBearing& bearing, int x_dof, Pedestal pedestal, double gravity)
    : ForceElement(bearing.name, {x_dof, x_dof + 1}, pedestal.mass > 0.0 ? 4 : 0),
      bearing_(bearing),
      pedestal_(pedestal),
      gravity_(gravity) {}

bool LinearBearingElement::steady_rotation_layout(SteadyRotationLayout* layout) const {
  if (gravity_ != 0.0 || bearing_.linearisation) return false;
  // Table entries k[0..3] = xx, xy, yx, yy; a single value stands for every speed.
  const auto isotropic = [](const std::array<std::vector<double>, 4>& m) {
    const std::size_t n = std::max({m[0].size(), m[1].size(), m[2].size(), m[3].size()});
    const auto at = [](const std::vector<double>& v, std::size_t i) {
      return v.empty() ? 0.0 : v[std::min(i, v.size() - 1)];
    };
    for (std::size_t i = 0; i < n; ++i)
      if (at(m[0], i) != at(m[3], i) || at(m[1], i) != -at(m[2], i)) return false;
    return true;
  };
  if (!isotropic(bearing_.table.k) || !isotropic(bearing_.table.c)) return false;
  layout->planar_pairs.clear();
  layout->turning_angles.clear();
  layout->phase_angle = -1;
  if (n_states() > 0) {
    layout->planar_pairs.emplace_back(0, 1);
    layout->planar_pairs.emplace_back(2, 3);
  }
  return true;
}

void LinearBearingElement::relative(const double* q, const double* v, const double* z, Eigen::Vector2d& du,
                                    Eigen::Vector2d& dv) const {
  du << q[0], q[1];
  dv << v[0], v[1];
  if (n_states() > 0) {
    du -= Eigen::Vector2d(z[0], z[1]);
    dv -= Eigen::Vector2d(z[2], z[3]);
  }
}

void LinearBearingElement::do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z,
                                              ElementWorkspace&, double* f, double* zdot) const {
  Eigen::Matrix2d k, c;
  bearing_.coefficients(s.speed, k, c);
  Eigen::Vector2d du, dv;
  relative(q, v, z, du, dv);
  const Eigen::Vector2d film = k * du + c * dv;  // force from journal onto the housing side
  f[0] -= film(0);
  f[1] -= film(1);
  if (n_states() > 0) {
    zdot[0] = z[2];
    zdot[1] = z[3];
    zdot[2] = (film(0) - pedestal_.stiffness * z[0] - pedestal_.damping * z[2]) / pedestal_.mass;
    zdot[3] = (film(1) - pedestal_.stiffness * z[1] - pedestal_.damping * z[3]) / pedestal_.mass - gravity_;
  }
}

void LinearBearingElement::add_jacobian(const SpinState& s, const double*, const double*, const double*,
                                       ElementWorkspace&, double* J) const {
  // Rows [f_x, f_y, zdot...], columns [q_x, q_y, v_x, v_y, z...], column-major with leading dimension 2 + m.
  Eigen::Matrix2d k, c;
  bearing_.coefficients(s.speed, k, c);
  const int m = n_states(), rows = 2 + m;
  Eigen::Map<Eigen::MatrixXd> Jm(J, rows, 4 + m);
  Jm.block<2, 2>(0, 0) -= k;
  Jm.block<2, 2>(0, 2) -= c;
  if (m > 0) {
    const double mp = pedestal_.mass;
    Jm.block<2, 2>(0, 4) += k;  // d f / d p
    Jm.block<2, 2>(0, 6) += c;  // d f / d p'
    Jm(2, 6) += 1.0;
    Jm(3, 7) += 1.0;
    Jm.block<2, 2>(4, 0) += k / mp;
    Jm.block<2, 2>(4, 2) += c / mp;
    Jm.block<2, 2>(4, 4) -= (k + pedestal_.stiffness * Eigen::Matrix2d::Identity()) / mp;
    Jm.block<2, 2>(4, 6) -= (c + pedestal_.damping * Eigen::Matrix2d::Identity()) / mp;
  }
}

std::vector<ProbeInfo> LinearBearingElement::probes() const {
  const std::string who = "bearing '" + name() + "': ";
  std::vector<ProbeInfo> p = housing_force_probes(who, "");
  if (n_states() > 0) {
    p.push_back({"pedestal_x", "m", who + "pedestal displacement, horizontal"});
    p.push_back({"pedestal_y", "m", who + "pedestal displacement, vertical"});
  }
  return p;
}

void LinearBearingElement::eval_probes(const SpinState& s, const double* q, const double* v, const double* z,
                                      ElementWorkspace&, double* out) const {
  Eigen::Matrix2d k, c;
  bearing_.coefficients(s.speed, k, c);
  Eigen::Vector2d du, dv;
  relative(q, v, z, du, dv);
  if (n_states() > 0) {
    // Force into the ground through the pedestal support.
    out[0] = pedestal_.stiffness * z[0] + pedestal_.damping * z[2];
    out[1] = pedestal_.stiffness * z[1] + pedestal_.damping * z[3];
    out[2] = z[0];
    out[3] = z[1];
  } else {
    const Eigen::Vector2d film = k * du + c * dv;
    out[0] = film(0);
    out[1] = film(1);
  }
}

double LinearBearingElement::potential_energy(const double* q, const double* z) const {
  // Only meaningful for symmetric stiffness; cross-coupled (circulatory) terms store no energy.
  Eigen::Matrix2d k, c;
  bearing_.coefficients(0.0, k, c);
  const double zero[4] = {0, 0, 0, 0};
  Eigen::Vector2d du, dv;
  relative(q, zero, z, du, dv);
  double e = 0.5 * du.dot(0.5 * (k + k.transpose()) * du);
  if (n_states() > 0) e += 0.5 * pedestal_.stiffness * (z[0] * z[0] + z[1] * z[1]) + pedestal_.mass * gravity_ * z[1];
  return e;
}

double LinearBearingElement::kinetic_energy(const double* z) const {
  if (n_states() == 0) return 0.0;
  return 0.5 * pedestal_.mass * (z[2] * z[2] + z[3] * z[3]);
}

double LinearBearingElement::dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                                             ElementWorkspace&) const {
  Eigen::Matrix2d k, c;
  bearing_.coefficients(s.speed, k, c);
  Eigen::Vector2d du, dv;
  relative(q, v, z, du, dv);
  double p = dv.dot(c * dv);
  if (n_states() > 0) p += pedestal_.damping * (z[2] * z[2] + z[3] * z[3]);
  return p;
}

}  // namespace turbodyn

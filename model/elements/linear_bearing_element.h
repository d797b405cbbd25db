// Linear bearing as a force element of the run-up: F on the shaft = -K (u - p) - C (u' - p'), where p is the
// housing point: fixed (p = 0), or a pedestal mass on a spring-damper to ground (internal states p, p').
//
// Pedestal equations (mass m_p, support K_p, C_p):  m_p p'' = K (u - p) + C (u' - p') - K_p p - C_p p'.
#pragma once

#include <Eigen/Dense>

#include "model/elements/force_element.h"
#include "model/rotor/rotor.h"

namespace turbodyn {

/// Housing point of a bearing: a pedestal mass on an isotropic spring-damper to ground.
struct Pedestal {
  double mass = 0.0;        ///< kg (0 = rigid housing, no states)
  double stiffness = 0.0;   ///< N/m
  double damping = 0.0;     ///< N s/m
};

class LinearBearingElement final : public ForceElement {
 public:
  /// `bearing` gives node and coefficient table; `x_dof` is the global index of the node's x DOF (y follows);
  /// `gravity` (m/s^2, acting in -y) loads the pedestal mass.
  LinearBearingElement(const LinearBearing& bearing, int x_dof, Pedestal pedestal = {}, double gravity = 0.0);

  bool has_jacobian() const override { return true; }
  double state_scale(int i) const override { return i < 2 ? 1e-6 : 1e-3; }  // pedestal position, velocity
  /// True if the coefficients act the same in every direction (k_xx = k_yy, k_xy = -k_yx, the same for c, at every
  /// speed of the table) and there is no gravity; a pedestal's position and velocity are housing-frame pairs.
  bool steady_rotation_layout(SteadyRotationLayout* layout) const override;
  void add_jacobian(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                   double* J) const override;
  std::vector<ProbeInfo> probes() const override;
  void eval_probes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double potential_energy(const double* q, const double* z) const override;
  double kinetic_energy(const double* z) const override;
  double dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;

 protected:
  void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 private:
  // Relative displacement and velocity of journal to housing.
  void relative(const double* q, const double* v, const double* z, Eigen::Vector2d& du, Eigen::Vector2d& dv) const;
  LinearBearing bearing_;
  Pedestal pedestal_;
  double gravity_ = 0.0;
};

}  // namespace turbodyn

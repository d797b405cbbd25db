// A linear bearing in a squeeze-film damper: the bearing (stiffness K, damping C, from the shaft to its outer
// ring) and the outer ring, a mass m_r moving in a non-rotating oil film towards the housing, held against
// rotation, optionally centred by a spring k_c. The film force comes from Reynolds' equation at every call.
//   m_r p'' = K (u - p) + C (u' - p') + F_film(p, p') - k_c p - m_r g e_y
#pragma once

#include "model/elements/force_element.h"
#include "model/spec/model_spec.h"
#include "model/films/reynolds.h"
#include "model/rotor/rotor.h"

namespace turbodyn {

class DamperElement final : public ForceElement {
 public:
  DamperElement(const LinearBearing& bearing, int x_dof, const DamperSpec& damper, const OilSpec& oil,
                double gravity);

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  double state_scale(int i) const override { return i < 2 ? 1e-6 : 1e-3; }
  double fd_relative_step() const override { return 1e-6; }
  void initial_states(double* z) const override;
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
  const reynolds::FilmResult& Film(const double* z, ElementWorkspace& ws) const;
  LinearBearing bearing_;
  DamperSpec damper_;
  reynolds::FilmGeometry geometry_;
  reynolds::SolverOptions options_;
  double viscosity_ = 0.0;
  double gravity_ = 0.0;
};

}  // namespace turbodyn

// Full-floating-ring bearing, first version: the ring translates and spins freely between two hydrodynamic
// films (paper §2.3): the inner film between journal and ring bore, the outer film between ring and housing, fed
// through a hole in the housing. Both films are solved with Reynolds' equation at every call.
//   m_r p'' = -F_inner + F_outer - m_r g e_y,   Ip_r w_r' = T_ring(inner film) + T_ring(outer film)
// Not yet modelled: ring tilt (the inner film sees the journal's tilt against an untilted ring) and the drill holes
// coupling the films (issue 4).
#pragma once

#include "model/force_element.h"
#include "model/model_spec.h"
#include "model/reynolds.h"

namespace turbodyn {

class FloatingRingElement final : public ForceElement {
 public:
  /// States: ring x, y (m), ring vx, vy (m/s), ring spin w_r (rad/s).
  FloatingRingElement(const std::string& name, const FloatingRingSpec& spec, const OilSpec& oil, int node_dof,
                      double gravity);

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  double state_scale(int i) const override { return i < 2 ? 1e-6 : i < 4 ? 1e-3 : 10.0; }
  double fd_relative_step() const override { return 1e-6; }
  std::vector<ProbeInfo> probes() const override;
  void EvalProbes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double KineticEnergy(const double* z) const override;
  double PotentialEnergy(const double* q, const double* z) const override;
  double DissipatedPower(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;

 protected:
  void DoCalcAndAddForces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 public:
  struct Films;  ///< both films' results at one state (defined in the .cpp)

 private:
  const Films& Solve(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws) const;
  FloatingRingSpec spec_;
  reynolds::FilmGeometry inner_, outer_;
  reynolds::SolverOptions options_;
  double eta_inner_ = 0.0, eta_outer_ = 0.0, gravity_ = 0.0;
};

}  // namespace turbodyn

// Plain hydrodynamic journal bearing as a force element: the journal is the shaft at the bearing node, the bush
// is fixed; the film force and moment come from a numerical solution of Reynolds' equation at every call
// (model/films/reynolds.h), with the journal's translation, tilt and their rates and the rotor speed.
#pragma once

#include "model/elements/force_element.h"
#include "model/spec/model_spec.h"
#include "model/films/film_geometry.h"

namespace turbodyn {

class JournalBearingElement final : public ForceElement {
 public:
  /// `node_dof` is the global index of the node's x DOF; x, y, theta_x, theta_y follow.
  JournalBearingElement(const std::string& name, const JournalBearingSpec& spec, const OilSpec& oil, int node_dof);

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  /// The film solver converges its active set / film fraction to a relative 1e-8 at best: difference above that.
  double fd_relative_step() const override { return 1e-6; }
  std::vector<ProbeInfo> probes() const override;
  void eval_probes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;
  double drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                    ElementWorkspace& ws) const override;

  const reynolds::FilmGeometry& geometry() const { return geometry_; }
  double viscosity() const { return viscosity_; }
  /// Film state seen by the solver for journal displacement q and velocity v (local order x, y, theta_x, theta_y).
  reynolds::FilmState film_state(const SpinState& s, const double* q, const double* v) const;

 protected:
  void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 private:
  const reynolds::FilmResult& Solve(const SpinState& s, const double* q, const double* v, ElementWorkspace& ws) const;
  reynolds::FilmGeometry geometry_;
  reynolds::SolverOptions options_;
  double viscosity_ = 0.0;
  double film_limit_ = 0.0;  // m, permissible minimum film thickness (0: none)
};

}  // namespace turbodyn

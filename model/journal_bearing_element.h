// Plain hydrodynamic journal bearing as a force element: the journal is the shaft at the bearing node, the bush
// is fixed; the film force and moment come from a numerical solution of Reynolds' equation at every call
// (model/reynolds.h), with the journal's translation, tilt and their rates and the rotor speed.
#pragma once

#include <stdexcept>

#include "model/force_element.h"
#include "model/model_spec.h"
#include "model/reynolds.h"

namespace turbodyn {

/// Film geometry and solver options of a plain film spec (JournalBearingSpec, DamperSpec: diameter, length,
/// clearance, grid, feed hole, cavitation; end seals for dampers). Throws std::logic_error for a cavitation name
/// the loader would refuse.
template <class Film>
reynolds::FilmGeometry film_geometry(const Film& f, reynolds::SolverOptions& options) {
  reynolds::FilmGeometry g;
  g.radius = 0.5 * f.diameter;
  g.length = f.length;
  g.clearance = f.clearance;
  g.n_circ = f.n_circ;
  g.n_axial = f.n_axial;
  if (f.feed_hole_diameter > 0.0) g.holes.push_back({f.feed_hole_angle, 0.0, f.feed_hole_diameter, f.supply_pressure});
  if constexpr (requires { f.end_seal_gap; }) {  // dampers
    g.end_seal_gap = f.end_seal_gap;
    g.end_seal_length = f.end_seal_length;
  }
  if (!reynolds::cavitation_from_string(f.cavitation, options.cavitation))
    throw std::logic_error("unknown cavitation model '" + f.cavitation + "'");
  return g;
}

class JournalBearingElement final : public ForceElement {
 public:
  /// `node_dof` is the global index of the node's x DOF; x, y, theta_x, theta_y follow.
  JournalBearingElement(const std::string& name, const JournalBearingSpec& spec, const OilSpec& oil, int node_dof);

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  /// The film solver converges its active set / film fraction to a relative 1e-8 at best: difference above that.
  double fd_relative_step() const override { return 1e-6; }
  std::vector<ProbeInfo> probes() const override;
  void EvalProbes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double DissipatedPower(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;
  double DrivePower(const SpinState& s, const double* q, const double* v, const double* z,
                    ElementWorkspace& ws) const override;

  const reynolds::FilmGeometry& geometry() const { return geometry_; }
  double viscosity() const { return viscosity_; }
  /// Film state seen by the solver for journal displacement q and velocity v (local order x, y, theta_x, theta_y).
  reynolds::FilmState film_state(const SpinState& s, const double* q, const double* v) const;

 protected:
  void DoCalcAndAddForces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 private:
  const reynolds::FilmResult& Solve(const SpinState& s, const double* q, const double* v, ElementWorkspace& ws) const;
  reynolds::FilmGeometry geometry_;
  reynolds::SolverOptions options_;
  double viscosity_ = 0.0;
};

}  // namespace turbodyn

// Full-floating-ring bearing (paper §2.3): a ring that translates, tilts and spins freely between two hydrodynamic
// films, both solved with Reynolds' equation at every call.
//
//   inner film: journal (shaft) in the ring bore, described in the ring frame (the ring's drill holes are fixed
//               there, as in the paper and its refs. [5-7]); journal speed relative to the ring W - w_r;
//   outer film: ring in the housing, described in the housing frame (the feed hole is fixed there); ring speed w_r.
//
// Equations of the ring (mass m, polar and diametral inertia Ip, Id; translations x, y; small rotations ax, ay
// about x and y; spin w_r; F, M the film forces and moments on the ring):
//   m x'' = F_x,   m y'' = F_y - m g,
//   Id ax'' + Ip (w_r ay' + w_r' ay) = M_x,   Id ay'' - Ip (w_r ax' + w_r' ax) = M_y,
//   Ip w_r' = T(inner film on the bore) + T(outer film on the outer surface),
// the gyroscopic terms as for the rotor's disks (angular momentum Ip w_r (ay, -ax, 1)).
//
// Oil reaches the inner film through radial drill holes in the ring. Each hole's mouth in the inner film is held at
// the pressure the outer film has at the hole's outer mouth, lowered by the centrifugal head of the oil column
// spinning with the ring, rho w_r^2 (R_o^2 - R_i^2) / 2, and not below the cavitation pressure (a starved hole).
// The hole's flow resistance is neglected and the outer film is solved as if its drill-hole mouths were closed
// (the holes draw oil from it without changing its pressure): docs/model-format.md and docs/validation.md.
//
// Thermal films (spec.thermal.model = Bulk, docs/thermal-films.md): two more states, the effective temperatures T_i,
// T_o of the inner and outer film, which set each film's viscosity through the [oil] viscosity law and follow the
// lumped energy balances of model/films/ring_heat_balance.h (heated by the power each film dissipates, cooled by
// its side leakage, the oil the drill holes carry and conduction to shaft, ring and housing). Isothermal films
// (the default) keep 10 states and the fixed temperatures of the spec: the same numbers as before thermal films.
#pragma once

#include "model/elements/force_element.h"
#include "model/spec/model_spec.h"
#include "model/films/reynolds.h"
#include "model/films/ring_heat_balance.h"

namespace turbodyn {

class FloatingRingElement final : public ForceElement {
 public:
  /// States (10): ring x, y (m), vx, vy (m/s), tilts ax, ay (rad), their rates (rad/s), spin w_r (rad/s) and spin
  /// angle phi_r (rad, the ring frame's orientation; the drill holes sit at phi_r + drill_hole_angle + k 2pi/n).
  /// With thermal films (spec.thermal.model = Bulk) two more: the inner and outer film temperatures (K).
  static constexpr int kStates = 10, kMaxStates = 12;
  enum State { kX, kY, kVx, kVy, kAx, kAy, kWx, kWy, kSpin, kAngle, kInnerTemperature, kOuterTemperature };

  FloatingRingElement(const std::string& name, const FloatingRingSpec& spec, const OilSpec& oil, int node_dof,
                      double gravity);

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  /// At rest and centred; thermal films at the supply temperature.
  void initial_states(double* z) const override;
  double state_scale(int i) const override;
  double fd_relative_step() const override { return 1e-6; }
  /// Own Jacobian (forward differences, fd_step()), built on two facts about the films: the outer film does not
  /// depend on the shaft's inputs or the ring angle, and a film's matrix depends on its thickness alone, so the
  /// columns that change only velocities, speeds or the drill holes' pressures (the shaft's velocities, the ring's
  /// translational and tilt rates and its spin) reuse the film's factorisation and cavitated set
  /// (reynolds::FilmSolver::solve_same_matrix): for a fixed cavitated set the pressure is affine in them, so these
  /// columns are exact derivatives. Only the displacement columns (shaft q, ring x, y, tilts, angle) solve films anew:
  /// the inner film 9 times, the outer 4, against 18 solves of each film through the engine's differences. Tilt
  /// columns are skipped when the ring does not tilt (their states never move).
  bool has_jacobian() const override { return true; }
  void add_jacobian(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                    double* J) const override;
  /// Film solves that factorise anew per call: the base solve (when the solvers were left elsewhere) and, with
  /// thermal films, the two columns of the film temperatures, which change a viscosity; every other column is a
  /// back-substitution with the base factorisations (add_jacobian).
  int jacobian_evaluations() const override { return thermal_ ? 3 : 1; }
  std::vector<ProbeInfo> probes() const override;
  void eval_probes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double kinetic_energy(const double* z) const override;
  double potential_energy(const double* q, const double* z) const override;
  double dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;
  double drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                    ElementWorkspace& ws) const override;

  /// Centrifugal pressure drop across a drill hole at ring speed w_r (Pa).
  double centrifugal_head(double w_r) const;
  /// True with thermal films (12 states), false for isothermal ones (10).
  bool thermal() const { return thermal_; }
  const FloatingRingSpec& spec() const { return spec_; }
  /// What the films dissipate, carry off and conduct at a state (W; flows m^3/s), with both temperatures' rates
  /// (zero for isothermal films, whose temperatures are the spec's): the powers are those of dissipated_power()
  /// split by film.
  struct Heat {
    thermal::FilmHeatInputs films;  ///< powers, side leakages and temperatures of both films
    thermal::FilmHeatFlows flows;   ///< the energy balance (zero for isothermal films)
    double drill_hole_pressure = 0.0;  ///< Pa gauge, the drill_hole_pressure probe: the inner film's feed
  };
  Heat heat(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws) const;
  /// Diametral inertia of the ring used (the spec's, or the thick-walled cylinder's if the spec gives none).
  double diametral_inertia() const { return inertia_diametral_; }

 protected:
  void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 public:
  struct Films;  ///< both films' results at one state, in the housing frame (defined in the .cpp)

 private:
  const Films& Solve(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws) const;
  reynolds::FilmState outer_state(const double* z) const;
  /// The inner film's state in the ring frame; `holes`: the drill holes' pressures (inner_.holes.size() values).
  reynolds::FilmState inner_state(const SpinState& s, const double* q, const double* v, const double* z,
                                  const double* holes) const;
  /// Pressures at the drill holes' inner mouths from the solved outer film at ring angle z[kAngle] and spin z[kSpin].
  void drill_hole_pressures(const reynolds::FilmSolver& outer, const double* z, double* holes) const;
  double mean_hole_pressure(const double* holes) const;  // of the inner film's drill holes
  /// [f; zdot] from the two films' results (the inner film's force and moment already in the housing frame).
  void loads(const SpinState& s, const double* v, const reynolds::FilmResult& inner,
             const reynolds::FilmResult& outer, const double* z, double* f, double* zdot) const;
  /// Powers, flows and temperatures of both films from their results (the inner one in the housing frame).
  thermal::FilmHeatInputs film_heat(const SpinState& s, const double* v,
                                    const reynolds::FilmResult& inner, const reynolds::FilmResult& outer,
                                    const double* z) const;
  /// Sets both solvers' viscosities to those at the film temperatures of z (thermal films only); throws naming
  /// [oil] max_temperature when a film is hotter than the viscosity law is used for.
  void set_viscosities(reynolds::FilmSolver& inner, reynolds::FilmSolver& outer, const double* z) const;
  double film_viscosity(double T, const char* which) const;
  FloatingRingSpec spec_;
  OilSpec oil_;
  bool thermal_ = false;
  reynolds::FilmGeometry inner_, outer_;
  reynolds::SolverOptions options_;
  double eta_inner_ = 0.0, eta_outer_ = 0.0, gravity_ = 0.0, density_ = 0.0, inertia_diametral_ = 0.0;
};

}  // namespace turbodyn

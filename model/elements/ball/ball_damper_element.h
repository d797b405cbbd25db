// A ball bearing in a squeeze-film damper (paper §3.3, variant III): the multibody ball bearing of
// model/elements/ball/ball_bearing.h whose outer ring, instead of being held by the housing, moves radially in a non-rotating
// oil film (Reynolds' equation at every call), kept from spinning by an anti-rotation pin and optionally centred by
// a spring k_c:
//   m_o p'' = F_balls(p, p', ...) + F_film(p, p') - k_c p - m_o g e_y,
// p = (x_o, y_o) the outer ring's centre, m_o the outer ring's mass. The balls, the cage and the outer ring's axial
// preload motion are the ball bearing's own states (BallBearingElement::calc_bearing).
#pragma once

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/force_element.h"
#include "model/spec/model_spec.h"
#include "model/films/reynolds.h"

namespace turbodyn {

class BallDamperElement final : public ForceElement {
 public:
  /// `bearing` must have outer_ring_mode = External. States: the ball bearing's core states, then the outer
  /// ring's x_o, y_o (m), vx_o, vy_o (m/s).
  BallDamperElement(const std::string& name, const BallBearingSpec& bearing, const DamperSpec& damper,
                    const OilSpec& oil, int node_dof, double gravity);

  std::unique_ptr<ElementWorkspace> make_workspace() const override;
  void initial_states(double* z) const override;
  void initial_states_at_speed(double speed, double* z) const override;
  double state_scale(int i) const override;
  double tolerance_scale(int i) const override;  // the bearing's for its states, the ring's typical magnitudes
  /// The ring's velocity tolerances follow the film's damping (ring_velocity_tolerance_factor).
  bool has_state_dependent_tolerances() const override { return true; }
  void absolute_tolerance_factors(const double* z, double* f) const override;
  /// Factor on the ring's velocity tolerance scale (1 mm/s) at eccentricity ratio eps: the radial damping of a
  /// short 2-pi squeeze film, proportional to (1 + 2 eps^2) / (1 - eps^2)^2.5, at eps = 0.9 over its value at eps
  /// (eps taken at most 0.98), at most 100. So a velocity error makes about the same film-force error at every
  /// eccentricity: 1 mm/s at eps = 0.9, 18 um/s at 0.98 and above, 42 mm/s at 0.55, 100 mm/s below about 0.33.
  /// Above 0.98 it tightens no further: a ring that bottoms out on a soft centring spring (e/c 0.997) stopped the
  /// integrator (error test failing at steps of 5e-10 s) with the limit at 0.99.
  static double ring_velocity_tolerance_factor(double eps);
  /// The bearing's balls and cage, and the damper ring's centre and velocity as housing-frame pairs. Only for a
  /// film that is the same in every direction (no feed hole, no supply pressure) and without gravity: then the
  /// ring's steady place is the centre; otherwise false.
  bool steady_rotation_layout(SteadyRotationLayout* layout) const override;
  /// The bearing's balls (the damper ring's states join the border).
  std::vector<int> independent_state_blocks() const override { return bearing_.independent_state_blocks(); }
  int kinematic_states_per_block() const override { return bearing_.kinematic_states_per_block(); }
  double fd_relative_step() const override { return 1e-6; }
  /// The bearing's finite differences (BallBearingElement::add_jacobian_of: the balls' states one index at a time
  /// for all balls at once), with the damper film solved again only for the ring's own 4 columns.
  bool has_jacobian() const override { return true; }
  int jacobian_evaluations() const override { return bearing_.jacobian_evaluations() + 4; }
  void add_jacobian(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                   double* J) const override;
  std::vector<ProbeInfo> probes() const override;
  void eval_probes(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                  double* out) const override;
  double potential_energy(const double* q, const double* z) const override;
  double kinetic_energy(const double* z) const override;
  double dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                         ElementWorkspace& ws) const override;
  double drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                    ElementWorkspace& ws) const override;

  const BallBearingElement& bearing() const { return bearing_; }

 protected:
  void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override;

 public:
  struct Evaluation;  ///< one evaluation of bearing and film (defined in the .cpp)

 private:
  const Evaluation& Evaluate(const SpinState& s, const double* q, const double* v, const double* z,
                             ElementWorkspace& ws) const;
  /// The film's input at the ring states (x, y, vx, vy).
  reynolds::FilmState FilmState(const double* ring) const;
  /// Derivatives of the ring's 4 states from the balls' and the film's forces on it and the centring spring.
  void ring_derivatives(const double* ring, const BallBearingLoads& loads, const reynolds::FilmResult& film,
                       double* dring) const;
  BallBearingElement bearing_;
  DamperSpec damper_;
  reynolds::FilmGeometry geometry_;
  reynolds::SolverOptions options_;
  double viscosity_ = 0.0, gravity_ = 0.0, ring_mass_ = 0.0;
  int n_core_ = 0;
};

}  // namespace turbodyn

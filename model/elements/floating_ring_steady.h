// Steady operating point of one floating-ring bearing under a static load on the journal at a constant rotor
// speed (docs/thermal-films.md, "Steady operating points"): the ring speed from the torque balance of its two films,
// the journal's and the ring's positions from the force balances (the ring's weight included), and with thermal
// films both film temperatures from their heat balances, solved together by Newton's method on the element's own
// right-hand side with all rates set to zero. The ring turns, so the drill holes pass the feed hole: the balances
// are averaged over ring angles spread across one hole pitch. With the point come the linearised coefficients of
// each film (stiffness and damping of the inner film between journal and ring, of the outer film between ring and
// housing).
#pragma once

#include <memory>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "model/elements/floating_ring_element.h"
#include "model/rotor/rotor.h"

namespace turbodyn {

/// No operating point found (Newton did not converge, or a film closed).
class SteadyPointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FloatingRingOperatingPoint {
  double speed = 0.0;                 ///< rotor speed W (rad/s)
  Eigen::Vector2d load = Eigen::Vector2d::Zero();  ///< static load on the journal, x and y (N)
  double ring_speed = 0.0;            ///< w_r (rad/s)
  Eigen::Vector2d journal = Eigen::Vector2d::Zero();  ///< journal centre in the housing (m)
  Eigen::Vector2d ring = Eigen::Vector2d::Zero();     ///< ring centre in the housing (m)
  double inner_eccentricity = 0.0, outer_eccentricity = 0.0;  ///< e/c of each film
  double inner_attitude = 0.0, outer_attitude = 0.0;  ///< angle of each film's eccentricity from the load (rad)
  double inner_temperature = 0.0, outer_temperature = 0.0;  ///< K
  double inner_power = 0.0, outer_power = 0.0;        ///< W dissipated in each film
  double inner_flow = 0.0, outer_flow = 0.0;          ///< m^3/s side leakage of each film
  double heat_to_oil = 0.0, heat_conducted = 0.0;     ///< W (thermal films; 0 for isothermal)
  /// Pa gauge at the drill holes' inner mouths, the inner film's feed (the element's drill_hole_pressure probe: the
  /// outer film's pressure at the outer mouths less the oil column's centrifugal head, not below cavitation; mean
  /// over the holes and the ring angles; 0 without drill holes)
  double drill_hole_pressure = 0.0;
  /// Linearised film forces: K = -dF/de, C = -dF/de' (N/m, N s/m), rows and columns x, y, the inner film's
  /// force on the journal against the journal's motion relative to the ring, the outer film's force on the ring
  /// against the ring's motion in the housing (ring speed and temperatures held).
  Eigen::Matrix2d k_inner = Eigen::Matrix2d::Zero(), c_inner = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d k_outer = Eigen::Matrix2d::Zero(), c_outer = Eigen::Matrix2d::Zero();
  int iterations = 0;
};

struct SteadyPointOptions {
  int angles = 4;            ///< ring angles averaged over one drill-hole pitch (1 without drill holes)
  int max_iterations = 80;   ///< Newton iterations per point
  /// On the scaled residual (forces over the load scale, torque over the films' drag, heat over its power). A
  /// Newton iteration that can no longer lower the residual stops there, accepted below stall_tolerance (the film
  /// solver's own tolerance, 1e-8 relative, sets that floor).
  double tolerance = 1e-9, stall_tolerance = 1e-6;
};

/// Operating points of one element (its spec, oil and gravity); the element must outlive it. Not thread-safe
/// (one workspace).
class FloatingRingSteady {
 public:
  explicit FloatingRingSteady(const FloatingRingElement& element, SteadyPointOptions options = {});
  /// The point at `speed` (rad/s, > 0) under `load` (N on the journal), Newton from `start` (a previous point,
  /// scaled to the speed) or from a guess. Throws SteadyPointError.
  FloatingRingOperatingPoint solve(double speed, const Eigen::Vector2d& load,
                                   const FloatingRingOperatingPoint* start = nullptr) const;
  /// Points at increasing speeds, each started from the last.
  std::vector<FloatingRingOperatingPoint> sweep(const std::vector<double>& speeds, const Eigen::Vector2d& load) const;

 private:
  /// Residual (7 or 5 unknowns: journal x, y, ring x, y in clearances; ring speed / W; temperatures in K).
  void residual(double speed, const Eigen::Vector2d& load, const Eigen::VectorXd& u, Eigen::VectorXd& r) const;
  void state(double speed, const Eigen::VectorXd& u, double angle, double* q, double* z) const;
  void finish(FloatingRingOperatingPoint& p, const Eigen::VectorXd& u) const;

  const FloatingRingElement& e_;
  SteadyPointOptions options_;
  std::unique_ptr<ElementWorkspace> ws_;
  int n_ = 5;
  double pitch_ = 0.0;
};

/// The floating-ring bearings of a machine for the modal analysis (Rotor::rings): each bearing's steady operating
/// points under its share of the rotor's weight (two bearings, both floating rings: the reactions of a rigid beam on
/// two supports) at `table_speeds` (rad/s, ascending, > 0), and their films' coefficients interpolated linearly in
/// speed between them (held constant outside). Throws ModelError for other bearing layouts or failed points.
void add_floating_ring_linearisations(const MachineSpec& machine, Rotor& rotor, const std::vector<double>& table_speeds);

}  // namespace turbodyn

// Hydrodynamic film between an inner cylinder (journal) and an outer cylinder (bush or floating ring): the transient,
// isoviscous, incompressible Reynolds equation (the paper's Eq. 24, divided by 12):
//
//   d/dx (h^3/(12 eta) dp/dx) + d/dz (h^3/(12 eta) dp/dz) = (U1 + U2)/2 dh/dx + dh/dt,
//
// x = R theta along the circumference, z axial in [-L/2, L/2], U1 = R omega_inner, U2 = R omega_outer, and the film
// thickness h(theta, z) = c - (ex + z sx) cos(theta) - (ey + z sy) sin(theta) (journal centre relative to bush
// centre at axial position z; sx, sy the relative slopes of the journal axis). Periodic in theta; Dirichlet at
// both ends (ambient pressure, behind an end-seal slot if there is one) and at the nodes inside supply/coupling holes
// and grooves.
//
// Discretisation: second-order finite volumes on a node-centred grid (n_circ nodes in theta, n_axial interior nodes
// in z, the ends one axial step beyond the first and last node), h evaluated exactly at nodes and faces.
// Cavitation: none (full Sommerfeld), the Swift-Stieber/Reynolds condition as a linear complementarity problem
// (p >= p_cav) solved by a primal-dual active-set method, or the mass-conserving JFO model (Elrod-Adams switch
// function, film fraction theta in the cavitated zone, quasi-static in theta, needs an oil supply) solved by an
// active-set (semismooth Newton) iteration.
// Every linear solve is a direct band LDL^T with unknowns ordered axial-fastest (half-bandwidth n_axial, or
// n_axial/2 by mid-width symmetry when the film is symmetric), with a dense border block only when no grid
// column is entirely cavitated. See docs/reynolds.md for the equations, the references and the measured costs.
//
// Units: SI throughout; pressures are gauge pressures in Pa.
#pragma once

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "model/spec/cavitation.h"

namespace turbodyn::reynolds {

using turbodyn::Cavitation;

/// Radial hole in the outer surface. Grid nodes inside its circle (on the unrolled surface) get p = pressure, and
/// the faces from them to free nodes are fitted to the circle (SolverOptions::fitted_holes); a hole smaller than
/// the grid spacing fixes its nearest node.
struct Hole {
  double theta = 0;     ///< rad, position of the centre in the film frame
  double z = 0;         ///< m, from mid-width
  double diameter = 0;  ///< m
  double pressure = 0;  ///< Pa gauge (can be overridden per call, FilmState::hole_pressure_override)
};

/// Full circumferential groove: nodes with |z - groove.z| <= width/2 get p = pressure (at least one row must lie
/// inside: FilmSolver refuses a groove between two rows); the faces from them to free nodes are fitted to its edges
/// (SolverOptions::fitted_holes), so the lands keep their width on any grid. Deep: no shear across its width.
struct Groove {
  double z = 0;         ///< m, from mid-width
  double width = 0;     ///< m
  double pressure = 0;  ///< Pa gauge
};

struct FilmGeometry {
  double radius = 0;     ///< R, m (journal radius; used for both surfaces, thin-film approximation)
  double length = 0;     ///< L, m (axial width)
  double clearance = 0;  ///< c, m (radial)
  int n_circ = 60;       ///< grid nodes around the circumference (>= 8)
  int n_axial = 12;      ///< interior grid nodes along the axis (>= 4); the ends are one step beyond
  double ambient_pressure = 0;     ///< Pa gauge, both ends
  /// End seals (e.g. piston rings) at both ends: the oil leaves each end through a slot of this radial gap and
  /// axial length, q' = gap^3 / (12 eta length) (p_end - p_ambient) per unit circumference, in series with the
  /// land. gap = 0: open ends (p = p_ambient at the ends).
  double end_seal_gap = 0, end_seal_length = 0;
  double cavitation_pressure = 0;  ///< Pa gauge, p_cav of the Gumbel and mass-conserving models
  std::vector<Hole> holes;         ///< at most 8 (FilmState::hole_pressure_override)
  std::vector<Groove> grooves;
};

/// Kinematics of the journal relative to the bush, written in the film frame (x, y perpendicular to the axis,
/// theta measured from +x towards +y).
struct FilmState {
  double ex = 0, ey = 0;    ///< m, journal centre relative to bush centre at mid-width
  double vx = 0, vy = 0;    ///< m/s, its rate
  double sx = 0, sy = 0;    ///< relative slopes dx/dz, dy/dz of the journal axis (tilt) [-]
  double dsx = 0, dsy = 0;  ///< their rates, 1/s
  double omega_inner = 0;   ///< rad/s, journal spin about the axis
  double omega_outer = 0;   ///< rad/s, bush spin about the axis
  std::array<double, 8> hole_pressure_override{};  ///< Pa gauge, per hole in geometry order (coupling)
  bool use_override = false;
};

struct FilmResult {
  double fx = 0, fy = 0;        ///< N, force of the film on the journal
  double mx = 0, my = 0;        ///< N m, moment of the film on the journal about the film centre (axes x, y)
  double torque_inner = 0;      ///< N m about +z, friction torque on the journal
  double torque_outer = 0;      ///< N m about +z, friction torque on the bush
  double flow_ends = 0;         ///< m^3/s leaving through both ends
  std::vector<double> hole_flows;  ///< m^3/s into the film through each hole (size = holes)
  double max_pressure = 0;      ///< Pa gauge
  double cavitated_fraction = 0;  ///< share of the grid nodes in the cavitated zone (Gumbel, MassConserving)
  /// MassConserving: nodes where no steady film fraction exists (a cavitated gap closing faster than the Couette
  /// flow empties it) and the Swift-Stieber condition is used instead (p = p_cav, full film, mass not balanced
  /// there). Zero in steady operation. See docs/reynolds.md.
  int fallback_nodes = 0;
  int iterations = 0;           ///< active-set sweeps (= factorisations)
  int linear_solves = 0;        ///< back-substitutions (mass-conserving: inner fixed-point sweeps)
  bool symmetric = false;       ///< the solve used mid-width symmetry (half the axial unknowns)
};

struct SolverOptions {
  Cavitation cavitation = Cavitation::Gumbel;
  double tolerance = 1e-8;  ///< relative: active-set sign tests and the mass-conserving inner iteration
  int max_iterations = 200;  ///< active-set sweeps (and inner sweeps per active set)
  bool use_symmetry = true;  ///< solve half the film when tilt, holes and grooves are symmetric about mid-width
  /// Holes' edges where they cross the grid lines: a face between a free node and a hole node conducts over the
  /// free node's distance to the hole's circle instead of the grid step (Shortley & Weller 1938), so the hole's
  /// size does not jump with the grid. Likewise a groove's edges along the axis. False: the hole (groove) is the
  /// grid nodes inside its circle (rows inside its width).
  bool fitted_holes = true;
  /// Axial nodes drawn towards both ends, where the pressure profile is steepest: z = (L/2) G(xi) on uniform xi,
  /// G = (1 - b) xi + b sin(pi xi / 2), b in [0, 1); 0 is the uniform grid (docs/reynolds.md §2).
  double axial_grading = 0.0;
};

/// Short-bearing (Ocvirk) and long-bearing (Sommerfeld) closed forms, half-Sommerfeld (Gumbel) cavitation, steady,
/// journal speed omega, stationary bush: magnitudes of the force components of the film on the journal,
/// F = -radial e_r + tangential e_t with e_r along the eccentricity and e_t = e_z x e_r (radial >= 0; tangential has
/// the sign of omega). docs/references.md §2.
struct Closed {
  double radial, tangential;  ///< N
};
Closed short_bearing(double eta, double omega, double R, double L, double c, double eps);
Closed long_bearing(double eta, double omega, double R, double L, double c, double eps);

/// The thinnest film (m) of the journal in the state s: the clearance less the journal axis's largest distance from
/// the bush axis over the film's width, which lies at one of its ends when the journal tilts (|e(z)| is convex in
/// z). Zero or negative: the film closes.
double min_film_thickness(const FilmGeometry& g, const FilmState& s);

/// A groove that the film's axial grid cannot represent: it holds no grid row, or a land beside it (to the film's
/// end or to the next groove) holds none.
/// reason() words it for a user of one central groove ("the groove (2 mm wide at z = 0 mm) holds no node ..."), so
/// that the model file and the command line can name their own key or option beside it.
class GrooveGridError : public std::invalid_argument {
 public:
  explicit GrooveGridError(const std::string& reason)
      : std::invalid_argument("reynolds::FilmSolver: " + reason), reason_(reason) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

/// One solver per film per simulation: holds the grid, the factorisation storage and the warm-start state (last
/// cavitation zone and film fraction). Not thread-safe; copy it to give each thread its own.
class FilmSolver {
 public:
  /// Throws std::invalid_argument for bad input (non-positive radius, length, clearance or viscosity, grid smaller
  /// than 8 x 4, more than 8 holes, a hole or groove not inside the film, overlapping holes, bad options);
  /// GrooveGridError, one of them, for a groove the grid cannot hold.
  FilmSolver(const FilmGeometry& g, double viscosity, const SolverOptions& o = {});
  ~FilmSolver();
  FilmSolver(const FilmSolver&);
  FilmSolver& operator=(const FilmSolver&);
  FilmSolver(FilmSolver&&) noexcept;
  FilmSolver& operator=(FilmSolver&&) noexcept;

  /// Solves the film for the state, warm-started from the previous call; allocation-free (after `r.hole_flows`
  /// has its size). Returns false, leaves `r` unchanged and sets last_error() when the film closes (h <= 0
  /// somewhere in the film), the input is not finite, or the solver fails. Never throws.
  bool solve(const FilmState& s, FilmResult& r);
  const std::string& last_error() const;

  /// Solves the film for a state that differs from that of the last successful solve() only in the velocities
  /// (vx, vy, dsx, dsy), the surface speeds and the hole pressures, keeping that solve's cavitated set and
  /// factorisation: one back-substitution instead of new factorisations. The film matrix depends on the film
  /// thickness alone, and for a fixed cavitated set the pressure is affine in these inputs, so differences of such
  /// solves are exact derivatives of the film wherever its cavitated set does not change (the complementarity
  /// solution is locally affine there). For Jacobians (FloatingRingElement::add_jacobian). None and Gumbel models
  /// only. Returns false, leaves `r` unchanged and sets last_error() if there is no such solve, the thickness
  /// (ex, ey, sx, sy) is not bit-for-bit that solve's, the state changes whether mid-width symmetry applies, or the
  /// model is mass-conserving. Keeps the cavitated set the next solve() starts from. Allocation-free.
  bool solve_same_matrix(const FilmState& s, FilmResult& r);

  /// Solves the film for a state whose film thickness (ex, ey, sx, sy) may also differ from that of the last
  /// successful solve(), by one Newton step from that solve's pressure with its factorisation and cavitated set:
  /// p = p0 + A0^-1 (b - A p0) on its free nodes (A, b: the new state's system). Exact where solve_same_matrix()
  /// is (thickness unchanged) and first order in the thickness change otherwise, so finite differences of such
  /// solves over small steps are the film's derivatives for a fixed cavitated set (one back-substitution per
  /// column instead of new factorisations; FloatingRingElement::add_jacobian). Same conditions and failures as
  /// solve_same_matrix() except the thickness test; fails also if the film closes. Allocation-free.
  bool solve_linearised(const FilmState& s, FilmResult& r);

  /// Pressure of the last successful solve, Pa gauge, n_circ x n_axial, theta-major: p[i * n_axial + j] at
  /// theta_nodes()[i], z_nodes()[j] (the ends, at z = -+L/2, are at ambient pressure). The solves keep their
  /// solution on the grid they solve (half of it with mid-width symmetry); this and film_fraction() expand it to
  /// the full grid on the first call after a solve (no allocation). After a failed solve: unspecified.
  const std::vector<double>& pressure() const;
  /// One node of pressure() (i < n_circ, j < n_axial), without expanding the field.
  double node_pressure(int i, int j) const;
  /// Film fraction of the last solve, same layout: the JFO theta for MassConserving; for the other models 1 in
  /// the full film and 0 where the Swift-Stieber constraint is active.
  const std::vector<double>& film_fraction() const;
  std::vector<double> theta_nodes() const;  ///< rad, i * 2 pi / n_circ
  std::vector<double> z_nodes() const;      ///< m, -L/2 + (j + 1) L / (n_axial + 1) on the uniform grid
  std::vector<double> z_widths() const;     ///< m, axial width of each node's control volume

  /// Forget the warm-start state (the next solve starts cold).
  void reset_warm_start();

  /// For a caller that reads only the loads (a squeeze-film damper): true makes every solve fill fx, fy, mx, my,
  /// max_pressure, cavitated_fraction and the counters as before, bit for bit, and skip the torques, flows and hole
  /// flows, which it sets to NaN. The warm start, pressure() and film_fraction() are those of a full solve.
  void set_forces_only(bool forces_only);

  /// Sets the film's viscosity (Pa s, > 0 and finite; false and nothing changed otherwise) for the following
  /// solves: a film whose temperature is a state of the run (FloatingRingElement's thermal films). A new value
  /// drops the factorisation solve_same_matrix() reuses; the same value changes nothing. Allocation-free.
  bool set_viscosity(double viscosity);

  const FilmGeometry& geometry() const;
  double viscosity() const;
  const SolverOptions& options() const;

  /// The full-film linear system A p = b over all n_circ x n_axial nodes (theta-major order as pressure()),
  /// Dirichlet nodes as identity rows: the system the None model solves, for tests and the SparseLU baseline.
  /// Assumes an open film (check with solve first).
  void assemble_full_film_system(const FilmState& s, Eigen::SparseMatrix<double>& A, Eigen::VectorXd& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace turbodyn::reynolds

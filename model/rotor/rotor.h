// The finite-element rotor: shaft elements, rigid disks and linear bearings assembled into global matrices.
//
// A Rotor is the immutable "model" half of the model/workspace split (hot calls take the read-only model and a
// workspace with the scratch memory of one analysis): built once from a MachineSpec, then shared read-only by every
// analysis and every thread, each thread with its own workspace.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "model/spec/model_spec.h"
#include "model/rotor/timoshenko.h"

namespace turbodyn {

/// Local degree of freedom at a node (see timoshenko.h for the sign conventions).
enum Dof : int { kX = 0, kY = 1, kThetaX = 2, kThetaY = 3 };
inline constexpr int kDofPerNode = 4;

struct RigidDisk {
  std::string name;
  int node = 0;
  double mass = 0.0;              ///< kg
  double polar_inertia = 0.0;     ///< kg m^2
  double diametral_inertia = 0.0; ///< kg m^2
  double unbalance = 0.0;         ///< kg m
  double unbalance_phase = 0.0;   ///< rad
};

/// Stiffness and damping of a bearing at a rotor speed (rad/s) on the 4 DOFs of its node (x, y, theta_x, theta_y):
/// k in N/m, N/rad, N m/m, N m/rad; c likewise per velocity. Called from several threads at once.
using BearingLinearisation = std::function<void(double speed, Eigen::Matrix4d& k, Eigen::Matrix4d& c)>;

struct LinearBearing {
  std::string name;
  int node = 0;
  LinearBearingSpec table;
  /// If set, the bearing's coefficients come from a model of the bearing (a ball bearing's quasi-static
  /// linearisation) on all 4 DOFs of the node instead of the table.
  BearingLinearisation linearisation;
  /// The x, y block at rotor speed `speed` (rad/s): the table linearly interpolated (constant outside it), or the
  /// linearisation's top-left block.
  void coefficients(double speed, Eigen::Matrix2d& k, Eigen::Matrix2d& c) const;
  /// All 4 DOFs: the table in the x, y block and zeros elsewhere, or the linearisation.
  void coefficients(double speed, Eigen::Matrix4d& k, Eigen::Matrix4d& c) const;
};

/// A floating-ring bearing in the linear analyses: its ring a point mass (x, y; no tilt) between the inner film
/// (journal at `node` to ring) and the outer film (ring to housing), each film linearised at the bearing's steady
/// operating point at the rotor speed (FloatingRingSteady). The ring adds two coordinates to the modal problem.
using FilmPairLinearisation = std::function<void(double speed, Eigen::Matrix2d& k_inner, Eigen::Matrix2d& c_inner,
                                                 Eigen::Matrix2d& k_outer, Eigen::Matrix2d& c_outer)>;
struct FloatingRingLinearisation {
  std::string name;
  int node = 0;
  double ring_mass = 0.0;  ///< kg
  FilmPairLinearisation films;  ///< called from several threads at once
};

struct BeamElement {
  int node1 = 0;           ///< first node; the second is node1 + 1
  int section = 0;         ///< index into MachineSpec::shaft
  BeamProperties properties;
};

struct Rotor {
  std::vector<double> node_z;      ///< m, increasing
  std::vector<BeamElement> elements;
  std::vector<RigidDisk> disks;
  std::vector<LinearBearing> bearings;
  /// Floating-ring bearings of the linear analyses (modal only): two ring coordinates each after the n_dof of the
  /// nodes.
  std::vector<FloatingRingLinearisation> rings;
  int n_dof = 0;                   ///< 4 per node

  // Inertial-frame matrices of shaft + disks (n_dof x n_dof); bearings are added per speed (add_bearings).
  Eigen::MatrixXd M;   ///< mass
  Eigen::MatrixXd G;   ///< gyroscopic, multiplies Omega q'
  Eigen::MatrixXd K;   ///< stiffness
  Eigen::MatrixXd D;   ///< structural (Rayleigh) damping, non-rotating
  Eigen::VectorXd gravity_force;  ///< N, consistent nodal load of gravity in -y
  /// Torsion (one twist angle per node, uncoupled from bending in this linear model): shaft elements with linear
  /// interpolation and consistent mass, plus the disks' polar inertias. Free-free (no drive stiffness).
  Eigen::MatrixXd M_torsion;  ///< kg m^2
  Eigen::MatrixXd K_torsion;  ///< N m / rad
  double total_mass = 0.0;        ///< kg

  int dof(int node, Dof d) const { return kDofPerNode * node + d; }
  /// Index of the node at axial position z (m); throws std::out_of_range if there is none within 1 nm.
  int node_at(double z) const;

  /// Adds the bearing stiffness and damping at rotor speed `speed` (rad/s) into K and D: a table's x, y block, a
  /// linearisation's 4 x 4 block.
  void add_bearings(double speed, Eigen::MatrixXd& K_total, Eigen::MatrixXd& D_total) const;

  /// Matrices of paper Eq. (9) in the frame that spins with the shaft (the paper's body frame K):
  ///   M q_r'' + (D + Omega G_r) q_r' + (K + Omega^2 M_Omega) q_r = f_r.
  /// For an axisymmetric rotor, q = R(Omega t) q_r gives G_r = G + 2 M J and M_Omega = -M + G J, where J
  /// rotates each (x, y) and (theta_x, theta_y) pair by +90 degrees.
  Eigen::MatrixXd rotating_frame_gyroscopic() const;
  Eigen::MatrixXd spin_softening() const;
  /// J above (n_dof x n_dof).
  Eigen::MatrixXd quarter_turn() const;
};

/// Builds the finite-element rotor: nodes at section ends, disks and bearings, elements no longer than
/// spec.mesh.max_element_length. Throws ModelError for inconsistent input (e.g. the Hutchinson shear factor on a
/// hollow section).
Rotor build_rotor(const MachineSpec& spec);

}  // namespace turbodyn

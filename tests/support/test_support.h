// Helpers shared by the model tests: small machines and bearings built in code, and reductions of the FE matrices.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "model/io/model_file.h"
#include "model/spec/model_spec.h"
#include "model/rotor/rotor.h"
#include "model/engine/runup.h"
#include "model/rotor/timoshenko.h"

namespace turbodyn::testing {

inline std::string source_dir() { return TURBODYN_SOURCE_DIR; }

/// The path of examples/NAME.
inline std::string example(const std::string& name) { return source_dir() + "/examples/" + name; }

/// The rotor of examples/EXAMPLE with the overrides applied.
inline Rotor load_rotor(const std::string& example, const std::vector<Override>& overrides = {}) {
  return build_rotor(load_model(source_dir() + "/examples/" + example, overrides));
}

/// The floating-ring bearing of docs/reference-machine.md, variant I.
inline FloatingRingSpec reference_ring() {
  FloatingRingSpec f;
  f.inner_diameter = 0.010;
  f.inner_length = 0.007;
  f.inner_clearance = 15e-6;
  f.outer_diameter = 0.016;
  f.outer_length = 0.010;
  f.outer_clearance = 40e-6;
  f.ring_mass = 0.0102;
  f.ring_polar_inertia = 4.5e-7;
  f.supply_pressure = 4.5e5;
  f.feed_hole_diameter = 0.003;
  f.n_circ = 60;
  f.n_axial = 12;
  return f;
}

/// Isoviscous oil of `viscosity` (Pa s).
inline OilSpec oil_of_viscosity(double viscosity) {
  OilSpec oil;
  oil.viscosity = viscosity;
  return oil;
}

/// A plain journal bearing of L/D = 1/4, close to the short-bearing limit.
inline JournalBearingSpec short_bearing_spec() {
  JournalBearingSpec j;
  j.diameter = 0.010;
  j.length = 0.0025;  // L/D = 1/4: close to the short-bearing limit
  j.clearance = 15e-6;
  j.n_circ = 90;
  j.n_axial = 16;
  return j;
}

/// Steel of the beam tests: E in Pa, nu, G = E / (2 (1 + nu)) in Pa, rho in kg/m^3.
inline constexpr double kE = 210e9, kNu = 0.3, kG = kE / (2 * (1 + kNu)), kRho = 7850.0;

/// A solid steel beam element of length L and diameter d (m) with shear factor kappa.
inline BeamProperties solid(double L, double d, double kappa, bool shear = true) {
  BeamProperties p;
  p.length = L;
  p.outer_diameter = d;
  p.youngs_modulus = kE;
  p.shear_modulus = kG;
  p.density = kRho;
  p.shear_factor = kappa;
  p.shear_deformation = shear;
  return p;
}

/// A uniform solid steel-like beam of length L and diameter d, no disks or bearings.
inline MachineSpec uniform_beam(double L, double d, int elements, bool shear, bool rotary) {
  MachineSpec s;
  s.source = "uniform_beam";
  s.materials["steel"] = Material{"steel", 210e9, 210e9 / 2.6, 0.3, 7850.0};
  s.shaft.push_back(ShaftSection{L, d, 0.0, "steel", 0.0});
  s.mesh.max_element_length = L / elements;
  s.mesh.shear_deformation = shear;
  s.mesh.rotary_inertia = rotary;
  s.mesh.gyroscopic = false;
  return s;
}

/// Natural frequencies (rad/s, ascending, > omega_min) of the x-z plane (x, theta_y) with the listed node
/// displacements x fixed to zero.
inline std::vector<double> planar_frequencies(const Rotor& r, const std::vector<int>& pinned_nodes,
                                              double omega_min = 1e-3) {
  std::vector<int> keep;
  for (int n = 0; n < static_cast<int>(r.node_z.size()); ++n) {
    if (std::find(pinned_nodes.begin(), pinned_nodes.end(), n) == pinned_nodes.end()) keep.push_back(r.dof(n, kX));
    keep.push_back(r.dof(n, kThetaY));
  }
  const int m = static_cast<int>(keep.size());
  Eigen::MatrixXd M(m, m), K(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      M(i, j) = r.M(keep[i], keep[j]);
      K(i, j) = r.K(keep[i], keep[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  std::vector<double> w;
  for (int i = 0; i < m; ++i)
    if (es.eigenvalues()(i) > omega_min * omega_min) w.push_back(std::sqrt(es.eigenvalues()(i)));
  return w;
}

/// Largest residual of the block-eliminated Newton solve, |(I - gamma J) x - b|, relative to the size of the terms
/// of (I - gamma J) x, for a random b (J: the model's JacobianMatrix at the last Jacobian(); the two
/// energy-accounting states are passed through and must come back unchanged).
inline double newton_solve_residual(const RunupModel& model, RunupWorkspace& ws, const Eigen::MatrixXd& J,
                                    double gamma) {
  const int ny = model.n_states(), nn = ny - 2;
  if (!model.FactorNewton(gamma, ws)) return INFINITY;
  const Eigen::VectorXd b = Eigen::VectorXd::Random(ny);
  Eigen::VectorXd x(ny);
  model.SolveNewton(gamma, b.data(), x.data(), ws);
  if (x(ny - 2) != b(ny - 2) || x(ny - 1) != b(ny - 1)) return INFINITY;
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(nn, nn) - gamma * J.topLeftCorner(nn, nn);
  const Eigen::VectorXd r = A * x.head(nn) - b.head(nn);
  return r.cwiseAbs().maxCoeff() / (A.cwiseAbs() * x.head(nn).cwiseAbs()).maxCoeff();
}

}  // namespace turbodyn::testing

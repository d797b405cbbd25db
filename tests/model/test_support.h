// Helpers shared by the model tests: small machines built in code, and reductions of the FE matrices.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "model/model_spec.h"
#include "model/rotor.h"

namespace turbodyn::testing {

inline std::string source_dir() { return TURBODYN_SOURCE_DIR; }

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

}  // namespace turbodyn::testing

// Linearised stiffness and damping coefficients of one hydrodynamic film about a state, by central differences
// of the film forces: K_ij = -dF_i/dx_j, C_ij = -dF_i/dv_j (rows and columns x, y of the film frame).
#pragma once

#include <Eigen/Dense>

#include "model/films/reynolds.h"

namespace turbodyn::reynolds {

struct Linearisation {
  FilmResult at;        ///< the film at the state itself
  Eigen::Matrix2d K;    ///< N/m
  Eigen::Matrix2d C;    ///< N s/m
};

/// Steps: 1e-4 c in position, 1e-4 c max(|omega_inner + omega_outer|, 1 rad/s) in velocity. Throws
/// std::runtime_error with the solver's message if the film cannot be solved at a perturbed state.
Linearisation linearise(FilmSolver& film, const FilmState& s);

}  // namespace turbodyn::reynolds

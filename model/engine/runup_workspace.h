// The per-simulation scratch space of a RunupModel (runup.h), private to the engine: the model and the integrator
// glue (integrator.cpp) read it; everyone else holds it through RunupWorkspacePtr.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "model/elements/force_element.h"
#include "model/engine/block_arrow_lu.h"
#include "model/engine/element_team.h"

namespace turbodyn {

// Sized once, reused by every right-hand-side and Jacobian call.
struct RunupWorkspace {
  // Everything one element needs, kept together so that an element's pieces cannot drift apart; d = its rotor
  // DOFs, m = its internal states.
  struct Element {
    Element(const ForceElement& e, int n);
    std::unique_ptr<ElementWorkspace> workspace;
    Eigen::VectorXd q, v, f;         // gathered displacements and velocities, local force (d)
    Eigen::MatrixXd jacobian;        // d[f; zdot] / d[q; v; z], (d + m) x (2d + m)
    Eigen::VectorXd fd_in;           // perturbed inputs [q; v; z] of the forward differences
    Eigen::VectorXd fd_out0, fd_out1;  // outputs [f; zdot] of the forward differences
    // Newton matrix: the factors of the block I - g G_zz, Y = (I - g G_zz)^-1 (-g (G_zv + g G_zq)) (m x d), the
    // right-hand side of Y (m x d), F_z Y (d x d), R' F_z Y (n x d); w, w0 (m) and u (d) are solve scratch.
    BlockArrowLU lu;
    Eigen::MatrixXd Y, T, JY, RJY;
    Eigen::VectorXd w, w0, u;
    double dissipation = 0.0, drive = 0.0;  // powers of the last right-hand side (W)
    long calls = 0;                         // element evaluations of the last Jacobian
  };

  Eigen::VectorXd f;    // generalised force (n)
  Eigen::VectorXd tmp;  // scratch (n)
  std::vector<Element> elements;
  // Jacobian blocks of M v' = f(q, v, z), z' = g(q, v, z).
  Eigen::MatrixXd Fq, Fv, Fz, Gq, Gv, Gz;
  // Newton matrix: the n x n Schur complement on the rotor coordinates and its factorisation.
  Eigen::MatrixXd A;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::VectorXd rhs, sol;
  double jac_t = 0.0;
  SpinState jac_spin;
  long rhs_calls = 0, element_calls = 0, jacobian_evaluations = 0, factorisations = 0;
  bool energy = true;  // accumulate the energy-balance states
  std::unique_ptr<ElementTeam> team;  // null: the elements one after the other

  /// fn(context, k) for the n elements: side by side on the team, else one after the other.
  void for_each_element(int n, void (*fn)(void*, int), void* context) {
    if (team) {
      team->run(n, fn, context);
    } else {
      for (int k = 0; k < n; ++k) fn(context, k);
    }
  }
};

}  // namespace turbodyn

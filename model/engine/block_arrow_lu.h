#pragma once
// Factorisation of a square matrix with block-arrow structure,
//
//       [ D_1            B_1 ]
//   A = [      ...       ... ]      D_i dense square (s_i x s_i), independent of one another;
//       [           D_p  B_p ]      B, C, E dense; b = border size.
//       [ C_1  ...  C_p  E   ]
//
// by eliminating each diagonal block on its own and inverting the Schur complement S = E - sum_i C_i D_i^-1 B_i
// (Golub & Van Loan, Matrix Computations, 4th ed., Sec. 4.5.4 on block elimination); the blocks and S are
// inverted by Gauss-Jordan elimination with partial pivoting. The entries of A outside the blocks, the border rows
// and the border columns are not read: the caller vouches that they are zero. With no blocks A itself is inverted.
// A ball bearing's Newton block (8 balls of 9 states bordered by cage and outer ring) factors in a few percent of
// the dense cost. Allocates only in the constructor.
//
// Kinematic blocks. A Newton block A = shift I + scale G (shift != 0) whose diagonal blocks each start with k
// positions whose rates are the block's next k states (a ball's orbital angle, radial and axial position and their
// velocities: rows [0 I 0] of G, zero in the border columns) is factored through the velocity rows alone. With
// a = scale / shift and the block split into positions q (k) and the rest v (s - k),
//   x_q = (r_q - scale x_v[0..k)) / shift,   (shift I + scale G_vv - scale a [G_vq 0]) x_v = r_v - a G_vq r_q,
// an (s - k) matrix to invert instead of s (for a ball 6 instead of 9: a third of the work). G's kinematic rows are
// then not read: the caller vouches for them.
#include <vector>
#include <Eigen/Dense>

namespace turbodyn {

/// True if the factorisation has no zero or non-finite pivot, i.e. its solves are defined. (Eigen's rcond()
/// answers the same question for a singular matrix but estimates the inverse's norm with several extra solves,
/// which costs as much as the factorisation of a small block.)
inline bool HasRegularPivots(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu) {
  const auto d = lu.matrixLU().diagonal().array();
  return d.allFinite() && (d != 0.0).all();
}

class BlockArrowLU {
 public:
  BlockArrowLU() = default;
  /// n: size of A; blocks: sizes of the leading diagonal blocks (sum <= n; the rest is the border);
  /// max_rhs: the most right-hand-side columns solve() will be given; kinematic: the positions at the start of
  /// every block whose rates are the next states (see above; 0: none), used by compute(G, scale, shift) with
  /// shift != 0.
  BlockArrowLU(int n, const std::vector<int>& blocks, int max_rhs, int kinematic = 0);

  /// Factors A (n x n); false if a pivot block or the Schur complement is singular.
  bool compute(const Eigen::MatrixXd& A);
  /// Factors A = shift I + scale G without forming it (a Newton block I - gamma J from J itself).
  bool compute(const Eigen::Ref<const Eigen::MatrixXd>& G, double scale, double shift);
  /// Overwrites x (n x k, k <= max_rhs) with A^-1 x.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> x);

 private:
  // The work of diagonal block i, with its size S and the border B fixed at compile time (a ball's 9 states, the
  // ball bearing's border) or 0: known at run time.
  template <int S, int B>
  bool factor_block(const double* G, int ld, double scale, double shift, std::size_t i);
  template <int S, int B>
  void forward_block(Eigen::Ref<Eigen::MatrixXd> x, std::size_t i);
  template <int S, int B>
  void back_block(Eigen::Ref<Eigen::MatrixXd> x, std::size_t i);
  // C_i from G and S -= C_i X_i, once X_i is known (both factorisations).
  template <int S, int B>
  void eliminate_onto_border(const double* G, int ld, double scale, std::size_t i);
  // The same for a kinematic block with K positions (0: known at run time).
  template <int S, int B, int K>
  bool factor_kinematic_block(const double* G, int ld, double scale, double shift, std::size_t i);
  template <int S, int B, int K>
  void forward_kinematic_block(Eigen::Ref<Eigen::MatrixXd> x, std::size_t i);

  int n_ = 0, border_ = 0, kinematic_ = 0;
  bool kinematic_factors_ = false;  // the last compute() took the kinematic path
  double scale_ = 1.0, shift_ = 0.0;  // of the last compute()
  std::vector<int> offset_, size_;
  // Per block D_i^-1 (Gauss-Jordan), D_i^-1 B_i (s_i x b) and C_i (b x s_i); the Schur complement and its inverse.
  // The blocks are small (a ball's 9 states), where products with the inverses in loops of a size known at compile
  // time cost a fraction of Eigen's blocked LU, triangular solves and products (bench/README.md).
  // A kinematic block keeps in inverse_ the inverse of its velocity rows' matrix ((s - k) x (s - k)) and in P_ the
  // coupling a G_vq ((s - k) x k).
  std::vector<Eigen::MatrixXd> inverse_, X_, C_, P_;
  Eigen::MatrixXd S_, S_inverse_;
  Eigen::MatrixXd work_, border_work_;  // solve scratch (largest block or border x max_rhs)
  Eigen::VectorXd scratch_;             // of the inversions
};

}  // namespace turbodyn

#pragma once
// LU factorisation of a square matrix with block-arrow structure,
//
//       [ D_1            B_1 ]
//   A = [      ...       ... ]      D_i dense square (s_i x s_i), independent of one another;
//       [           D_p  B_p ]      B, C, E dense; b = border size.
//       [ C_1  ...  C_p  E   ]
//
// by eliminating each diagonal block on its own and factoring the Schur complement S = E - sum_i C_i D_i^-1 B_i
// (Golub & Van Loan, Matrix Computations, 4th ed., Sec. 4.5.4 on block elimination). The entries of A outside
// the blocks, the border rows and the border columns are not read: the caller vouches that they are zero. With no
// blocks it is a plain partial-pivoting LU of A. A ball bearing's Newton block (8 balls of 9 states bordered by
// cage and outer ring) factors in a few percent of the dense cost. Allocates only in the constructor.
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
  /// max_rhs: the most right-hand-side columns solve() will be given.
  BlockArrowLU(int n, const std::vector<int>& blocks, int max_rhs);

  /// Factors A (n x n); false if a pivot block or the Schur complement is singular.
  bool compute(const Eigen::MatrixXd& A);
  /// Overwrites x (n x k, k <= max_rhs) with A^-1 x.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> x);

 private:
  int n_ = 0, border_ = 0;
  std::vector<int> offset_, size_;
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> lu_;  // per block
  // Per block, D_i^-1 from its LU: the blocks are small (a ball's 9 states), where a coefficient-wise product
  // with the inverse costs a fraction of Eigen's blocked triangular solves and matrix products.
  std::vector<Eigen::MatrixXd> inverse_;
  std::vector<Eigen::MatrixXd> X_, C_;                   // per block: D_i^-1 B_i (s_i x b), C_i (b x s_i)
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_s_;            // Schur complement (b x b)
  Eigen::MatrixXd S_, work_, border_work_;
};

}  // namespace turbodyn

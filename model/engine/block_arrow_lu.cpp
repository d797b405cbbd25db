#include "model/engine/block_arrow_lu.h"

#include <algorithm>
#include <stdexcept>

namespace turbodyn {

BlockArrowLU::BlockArrowLU(int n, const std::vector<int>& blocks, int max_rhs) : n_(n) {
  int off = 0, largest = 0;
  for (int s : blocks) {
    if (s <= 0) throw std::invalid_argument("BlockArrowLU: block sizes must be positive");
    offset_.push_back(off);
    size_.push_back(s);
    off += s;
    largest = std::max(largest, s);
  }
  if (off > n) throw std::invalid_argument("BlockArrowLU: blocks larger than the matrix");
  border_ = n - off;
  for (int s : size_) {
    lu_.emplace_back(s);
    inverse_.emplace_back(Eigen::MatrixXd::Zero(s, s));
    X_.emplace_back(Eigen::MatrixXd::Zero(s, border_));
    C_.emplace_back(Eigen::MatrixXd::Zero(border_, s));
  }
  lu_s_ = Eigen::PartialPivLU<Eigen::MatrixXd>(border_);
  S_.setZero(border_, border_);
  work_.setZero(largest, std::max({max_rhs, border_, 1}));
  border_work_.setZero(border_, std::max(max_rhs, 1));
}

bool BlockArrowLU::compute(const Eigen::MatrixXd& A) {
  const int b = border_, nb = n_ - b;
  bool regular = true;
  if (b > 0) S_ = A.bottomRightCorner(b, b);
  for (std::size_t i = 0; i < lu_.size(); ++i) {
    const int o = offset_[i], s = size_[i];
    lu_[i].compute(A.block(o, o, s, s));
    regular = regular && HasRegularPivots(lu_[i]);
    inverse_[i] = lu_[i].inverse();
    if (b == 0) continue;
    X_[i].noalias() = inverse_[i].lazyProduct(A.block(o, nb, s, b));
    C_[i] = A.block(nb, o, b, s);
    S_.noalias() -= C_[i].lazyProduct(X_[i]);
  }
  if (b > 0) {
    lu_s_.compute(S_);
    regular = regular && HasRegularPivots(lu_s_);
  }
  return regular;
}

void BlockArrowLU::solve_in_place(Eigen::Ref<Eigen::MatrixXd> x) {
  const int b = border_, k = static_cast<int>(x.cols());
  // Forward: y_i = D_i^-1 r_i, r_b - sum_i C_i y_i; the border solve; back: x_i = y_i - X_i x_b.
  for (std::size_t i = 0; i < lu_.size(); ++i) {
    const int o = offset_[i], s = size_[i];
    work_.topLeftCorner(s, k).noalias() = inverse_[i].lazyProduct(x.middleRows(o, s));
    x.middleRows(o, s) = work_.topLeftCorner(s, k);
    if (b > 0) x.bottomRows(b).noalias() -= C_[i].lazyProduct(x.middleRows(o, s));
  }
  if (b == 0) return;
  border_work_.leftCols(k).noalias() = lu_s_.solve(x.bottomRows(b));
  x.bottomRows(b) = border_work_.leftCols(k);
  for (std::size_t i = 0; i < lu_.size(); ++i)
    x.middleRows(offset_[i], size_[i]).noalias() -= X_[i].lazyProduct(x.bottomRows(b));
}

}  // namespace turbodyn

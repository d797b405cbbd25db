#include "model/engine/block_arrow_lu.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace turbodyn {

namespace {

// A ball's states (BallBearingElement::independent_state_blocks()): the block size whose kernels are compiled with
// it fixed, so that their loops unroll. Other sizes run the same loops with the size known at run time.
constexpr int kFixedBlock = 9;

// inv = (shift I + scale D)^-1 for the s x s block D (column-major, leading dimension ld) by Gauss-Jordan
// elimination with partial pivoting (Golub & Van Loan, Matrix Computations, 4th ed., Sec. 3.4; the pivots are those
// of the partial-pivoting LU). a (s * s) and l (s) are scratch, apart from D and inv. False if a pivot is zero or not
// finite.
template <int S>
bool invert(const double* __restrict D, int ld, int s_run, double scale, double shift, double* __restrict a,
            double* __restrict l, double* __restrict inv) {
  const int s = S > 0 ? S : s_run;
  for (int c = 0; c < s; ++c)
    for (int r = 0; r < s; ++r) {
      a[c * s + r] = scale * D[c * ld + r] + (r == c ? shift : 0.0);
      inv[c * s + r] = r == c ? 1.0 : 0.0;
    }
  bool regular = true;
  for (int k = 0; k < s; ++k) {
    int p = k;
    for (int r = k + 1; r < s; ++r)
      if (std::abs(a[k * s + r]) > std::abs(a[k * s + p])) p = r;
    const double pivot = a[k * s + p];
    if (!(std::isfinite(pivot) && pivot != 0.0)) {
      regular = false;
      continue;
    }
    if (p != k)
      for (int c = 0; c < s; ++c) {
        std::swap(a[c * s + k], a[c * s + p]);
        std::swap(inv[c * s + k], inv[c * s + p]);
      }
    const double rp = 1.0 / pivot;
    for (int c = k; c < s; ++c) a[c * s + k] *= rp;
    for (int c = 0; c < s; ++c) inv[c * s + k] *= rp;
    // Column k out of every other row: the multipliers l (column k, zero in row k) times row k's entries. Columns
    // left of k are not read again.
    for (int r = 0; r < s; ++r) l[r] = r == k ? 0.0 : a[k * s + r];
    for (int c = k + 1; c < s; ++c) {
      const double f = a[c * s + k];
      for (int r = 0; r < s; ++r) a[c * s + r] -= f * l[r];
    }
    for (int c = 0; c < s; ++c) {
      const double f = inv[c * s + k];
      for (int r = 0; r < s; ++r) inv[c * s + r] -= f * l[r];
    }
  }
  return regular;
}

// Y (rows x k, leading dimension ldy) = alpha M X, or += with Accumulate, for M (rows x s, column-major) and X
// (s x k, leading dimension ldx), a column at a time. R and S fix rows and s at compile time (0: known at run
// time); with R fixed the column of Y is summed in registers. M, X and Y do not overlap.
template <int R, int S, bool Accumulate>
void multiply(double alpha, const double* __restrict M, int rows_run, int s_run, const double* __restrict X, int ldx,
              int k, double* __restrict Y, int ldy) {
  const int rows = R > 0 ? R : rows_run, s = S > 0 ? S : s_run;
  for (int c = 0; c < k; ++c) {
    double* y = Y + c * ldy;
    const double* x = X + c * ldx;
    if constexpr (R > 0) {
      double acc[R];
      for (int r = 0; r < R; ++r) acc[r] = Accumulate ? y[r] : 0.0;
      for (int j = 0; j < s; ++j) {
        const double f = alpha * x[j];
        const double* m = M + j * R;
        for (int r = 0; r < R; ++r) acc[r] += f * m[r];
      }
      for (int r = 0; r < R; ++r) y[r] = acc[r];
    } else {
      if (!Accumulate)
        for (int r = 0; r < rows; ++r) y[r] = 0.0;
      for (int j = 0; j < s; ++j) {
        const double f = alpha * x[j];
        const double* m = M + j * rows;
        for (int r = 0; r < rows; ++r) y[r] += f * m[r];
      }
    }
  }
}

// f.template operator()<S, B>() with the block size S and the border B fixed at compile time for a ball (9 states)
// in a ball bearing (border 10: cage and outer ring) or in a squeeze-film damper (14: the outer ring's 4 more), else
// with both 0 (run time).
template <class F>
decltype(auto) with_sizes(int s, int b, F&& f) {
  if (s == kFixedBlock && b == 10) return f.template operator()<kFixedBlock, 10>();
  if (s == kFixedBlock && b == 14) return f.template operator()<kFixedBlock, 14>();
  return f.template operator()<0, 0>();
}

// The same for a kinematic block: a ball's 9 states with its 3 positions, else everything at run time.
constexpr int kFixedKinematic = 3;
template <class F>
decltype(auto) with_kinematic_sizes(int s, int b, int k, F&& f) {
  if (s == kFixedBlock && k == kFixedKinematic) {
    if (b == 10) return f.template operator()<kFixedBlock, 10, kFixedKinematic>();
    if (b == 14) return f.template operator()<kFixedBlock, 14, kFixedKinematic>();
  }
  return f.template operator()<0, 0, 0>();
}

}  // namespace

BlockArrowLU::BlockArrowLU(int n, const std::vector<int>& blocks, int max_rhs, int kinematic)
    : n_(n), kinematic_(kinematic) {
  int off = 0, largest = 0;
  if (kinematic < 0) throw std::invalid_argument("BlockArrowLU: the kinematic positions must be >= 0");
  for (int s : blocks) {
    if (s <= 0) throw std::invalid_argument("BlockArrowLU: block sizes must be positive");
    if (s < 2 * kinematic)
      throw std::invalid_argument("BlockArrowLU: a block holds fewer states than its positions and their rates");
    offset_.push_back(off);
    size_.push_back(s);
    off += s;
    largest = std::max(largest, s);
  }
  if (off > n) throw std::invalid_argument("BlockArrowLU: blocks larger than the matrix");
  border_ = n - off;
  for (int s : size_) {
    inverse_.emplace_back(Eigen::MatrixXd::Zero(s, s));
    X_.emplace_back(Eigen::MatrixXd::Zero(s, border_));
    C_.emplace_back(Eigen::MatrixXd::Zero(border_, s));
    P_.emplace_back(Eigen::MatrixXd::Zero(s - kinematic, kinematic));
  }
  S_.setZero(border_, border_);
  S_inverse_.setZero(border_, border_);
  const int widest = std::max(largest, border_);
  scratch_.setZero(widest * (widest + 1) + largest * largest);  // a kinematic block's matrix and its inversion
  work_.setZero(largest, std::max(max_rhs, 1));
  border_work_.setZero(border_, std::max(max_rhs, 1));
}

template <int S, int B>
bool BlockArrowLU::factor_block(const double* G, int ld, double scale, double shift, std::size_t i) {
  const int b = border_, nb = n_ - b, o = offset_[i], s = size_[i];
  double* a = scratch_.data();
  const bool regular = invert<S>(G + o * ld + o, ld, s, scale, shift, a, a + s * s, inverse_[i].data());
  if (b == 0) return regular;
  // X_i = D_i^-1 B_i, C_i, S -= C_i X_i (B_i, C_i and S: the scaled entries of G, no shift off the diagonal).
  multiply<S, S, false>(scale, inverse_[i].data(), s, s, G + nb * ld + o, ld, b, X_[i].data(), s);
  eliminate_onto_border<S, B>(G, ld, scale, i);
  return regular;
}

template <int S, int B>
void BlockArrowLU::eliminate_onto_border(const double* G, int ld, double scale, std::size_t i) {
  const int b = border_, nb = n_ - b, o = offset_[i], s = size_[i];
  double* C = C_[i].data();
  for (int c = 0; c < s; ++c)
    for (int r = 0; r < b; ++r) C[c * b + r] = scale * G[(o + c) * ld + nb + r];
  multiply<B, S, true>(-1.0, C, b, s, X_[i].data(), s, b, S_.data(), b);
}

template <int S, int B, int K>
bool BlockArrowLU::factor_kinematic_block(const double* G, int ld, double scale, double shift, std::size_t i) {
  constexpr int V = S > 0 ? S - K : 0;
  const int b = border_, nb = n_ - b, o = offset_[i], s = size_[i], k = K > 0 ? K : kinematic_, v = s - k;
  const double a = scale / shift, scale_a = scale * a;
  const double* Gvq = G + o * ld + o + k;  // G_vq (v x k) and G_vv (v x v), leading dimension ld
  const double* Gvv = G + (o + k) * ld + o + k;
  double* R = scratch_.data();  // the velocity rows' matrix, then the inversion's scratch (v * v + v)
  for (int c = 0; c < v; ++c)
    for (int r = 0; r < v; ++r) R[c * v + r] = scale * Gvv[c * ld + r] + (r == c ? shift : 0.0);
  double* P = P_[i].data();
  for (int c = 0; c < k; ++c)
    for (int r = 0; r < v; ++r) {
      R[c * v + r] -= scale_a * Gvq[c * ld + r];
      P[c * v + r] = a * Gvq[c * ld + r];
    }
  const bool regular = invert<V>(R, v, v, 1.0, 0.0, R + v * v, R + 2 * v * v, inverse_[i].data());
  if (b == 0) return regular;
  // X_i = D_i^-1 B_i: the border columns' kinematic rows are zero, so X_v = R^-1 B_v and X_q = -a X_v[0..k).
  double* X = X_[i].data();
  multiply<V, V, false>(scale, inverse_[i].data(), v, v, G + nb * ld + o + k, ld, b, X + k, s);
  for (int c = 0; c < b; ++c)
    for (int r = 0; r < k; ++r) X[c * s + r] = -a * X[c * s + k + r];
  eliminate_onto_border<S, B>(G, ld, scale, i);
  return regular;
}

// y_v = R^-1 (r_v - P r_q), y_q = (r_q - scale y_v[0..k)) / shift; r_b -= C_i y_i. With the sizes fixed the
// column's values stay in registers.
template <int S, int B, int K>
void BlockArrowLU::forward_kinematic_block(Eigen::Ref<Eigen::MatrixXd> x, std::size_t i) {
  const int b = border_, nb = n_ - b, cols = static_cast<int>(x.cols()), o = offset_[i], s = size_[i];
  const int ld = static_cast<int>(x.outerStride());
  const double* __restrict P = P_[i].data();
  const double* __restrict inv = inverse_[i].data();
  const double inv_shift = 1.0 / shift_, scale = scale_;
  double* xd = x.data();
  if constexpr (S > 0) {
    constexpr int V = S - K;
    for (int c = 0; c < cols; ++c) {
      double* __restrict r = xd + c * ld + o;
      double t[V], y[V];
      for (int j = 0; j < V; ++j) t[j] = r[K + j], y[j] = 0.0;
      for (int q = 0; q < K; ++q) {
        const double f = r[q];
        for (int j = 0; j < V; ++j) t[j] -= f * P[q * V + j];
      }
      for (int j = 0; j < V; ++j) {
        const double f = t[j];
        for (int row = 0; row < V; ++row) y[row] += f * inv[j * V + row];
      }
      for (int q = 0; q < K; ++q) r[q] = (r[q] - scale * y[q]) * inv_shift;
      for (int j = 0; j < V; ++j) r[K + j] = y[j];
    }
  } else {
    const int k = kinematic_, v = s - k;
    double* __restrict t = work_.data();
    for (int c = 0; c < cols; ++c) {
      double* __restrict r = xd + c * ld + o;
      for (int j = 0; j < v; ++j) t[j] = r[k + j];
      for (int q = 0; q < k; ++q) {
        const double f = r[q];
        for (int j = 0; j < v; ++j) t[j] -= f * P[q * v + j];
      }
      multiply<0, 0, false>(1.0, inv, v, v, t, v, 1, r + k, v);
      for (int q = 0; q < k; ++q) r[q] = (r[q] - scale * r[k + q]) * inv_shift;
    }
  }
  if (b > 0) multiply<B, S, true>(-1.0, C_[i].data(), b, s, xd + o, ld, cols, xd + nb, ld);
}

bool BlockArrowLU::compute(const Eigen::MatrixXd& A) { return compute(A, 1.0, 0.0); }

bool BlockArrowLU::compute(const Eigen::Ref<const Eigen::MatrixXd>& G, double scale, double shift) {
  const int b = border_, ld = static_cast<int>(G.outerStride());
  bool regular = true;
  if (b > 0) {
    S_ = scale * G.bottomRightCorner(b, b);
    S_.diagonal().array() += shift;
  }
  kinematic_factors_ = kinematic_ > 0 && shift != 0.0;
  scale_ = scale;
  shift_ = shift;
  for (std::size_t i = 0; i < size_.size(); ++i)
    regular = (kinematic_factors_
                   ? with_kinematic_sizes(size_[i], b, kinematic_,
                                          [&]<int S, int B, int K>() {
                                            return factor_kinematic_block<S, B, K>(G.data(), ld, scale, shift, i);
                                          })
                   : with_sizes(size_[i], b,
                                [&]<int S, int B>() { return factor_block<S, B>(G.data(), ld, scale, shift, i); })) &&
              regular;
  if (b > 0) {
    double* a = scratch_.data();
    regular = invert<0>(S_.data(), b, b, 1.0, 0.0, a, a + b * b, S_inverse_.data()) && regular;
  }
  return regular;
}

// y_i = D_i^-1 r_i, r_b -= C_i y_i.
template <int S, int B>
void BlockArrowLU::forward_block(Eigen::Ref<Eigen::MatrixXd> x, std::size_t i) {
  const int b = border_, nb = n_ - b, k = static_cast<int>(x.cols()), o = offset_[i], s = size_[i];
  const int ld = static_cast<int>(x.outerStride()), lw = static_cast<int>(work_.outerStride());
  double* xd = x.data();
  multiply<S, S, false>(1.0, inverse_[i].data(), s, s, xd + o, ld, k, work_.data(), lw);
  x.middleRows(o, s) = work_.topLeftCorner(s, k);
  if (b > 0) multiply<B, S, true>(-1.0, C_[i].data(), b, s, xd + o, ld, k, xd + nb, ld);
}

// x_i = y_i - X_i x_b.
template <int S, int B>
void BlockArrowLU::back_block(Eigen::Ref<Eigen::MatrixXd> x, std::size_t i) {
  const int b = border_, nb = n_ - b, k = static_cast<int>(x.cols()), o = offset_[i], s = size_[i];
  const int ld = static_cast<int>(x.outerStride());
  multiply<S, B, true>(-1.0, X_[i].data(), s, b, x.data() + nb, ld, k, x.data() + o, ld);
}

void BlockArrowLU::solve_in_place(Eigen::Ref<Eigen::MatrixXd> x) {
  const int b = border_, nb = n_ - b, k = static_cast<int>(x.cols());
  for (std::size_t i = 0; i < size_.size(); ++i)
    if (kinematic_factors_)
      with_kinematic_sizes(size_[i], b, kinematic_,
                           [&]<int S, int B, int K>() { forward_kinematic_block<S, B, K>(x, i); });
    else
      with_sizes(size_[i], b, [&]<int S, int B>() { forward_block<S, B>(x, i); });
  if (b == 0) return;
  const int ld = static_cast<int>(x.outerStride()), lw = static_cast<int>(border_work_.outerStride());
  double* xd = x.data();
  multiply<0, 0, false>(1.0, S_inverse_.data(), b, b, xd + nb, ld, k, border_work_.data(), lw);
  x.bottomRows(b) = border_work_.leftCols(k);
  for (std::size_t i = 0; i < size_.size(); ++i)
    with_sizes(size_[i], b, [&]<int S, int B>() { back_block<S, B>(x, i); });
}

}  // namespace turbodyn

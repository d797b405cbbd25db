// Bordered band L D L^T factorisation of the symmetric positive definite systems of the film discretisation
// (model/films/reynolds.cpp): the periodic grid's band plus the wrap-around border. Kept apart from the film so that
// the film code reads as physics and the solver can be tested and reused on its own.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "model/films/byte_flag.h"

namespace turbodyn::reynolds {

// Symmetric positive definite system whose unknowns split into a band part (n unknowns, half-bandwidth m) and a
// border of na unknowns coupled to any of them (the wrap-around column of a periodic grid):
//   [ A_band  A_b^T ]
//   [ A_b     A_c   ],
// factorised as L D L^T without pivoting. Storage is sized once (reserve); reset() starts a new matrix. Band
// columns flagged as fixed are identity rows and are skipped (Dirichlet and cavitated nodes).
class BorderedBandLdlt {
 public:
  void reserve(int n_max, int m_max) {
    band_.assign(static_cast<std::size_t>(n_max + 1) * (m_max + 1), 0.0);
    border_.assign(static_cast<std::size_t>(n_max) * m_max, 0.0);
    corner_.assign(static_cast<std::size_t>(m_max) * m_max, 0.0);
    corner_d_.assign(m_max, 0.0);
    inv_d_.assign(n_max, 0.0);
    fixed_.assign(n_max, 1);
    y_.assign(n_max + m_max + 1, 0.0);
    ya_.assign(m_max, 0.0);
  }
  void reset(int n, int m, int na) {
    n_ = n;
    m_ = m;
    na_ = na;
    std::fill(band_.begin(), band_.begin() + static_cast<std::ptrdiff_t>(n) * (m + 1), 0.0);
    std::fill(border_.begin(), border_.begin() + static_cast<std::ptrdiff_t>(n) * na, 0.0);
    std::fill(corner_.begin(), corner_.begin() + na * na, 0.0);
  }
  /// Column r of the band: [0] the diagonal, [t] = A(r + t, r), t = 1..m.
  double* column(int r) { return band_.data() + static_cast<std::ptrdiff_t>(r) * (m_ + 1); }
  /// A(n + a, r).
  double& border(int r, int a) { return border_[static_cast<std::size_t>(r) * na_ + a]; }
  /// A(n + a, n + b), a >= b.
  double& corner(int a, int b) { return corner_[a * na_ + b]; }
  void set_fixed(int r, bool f) { fixed_[r] = f ? 1 : 0; }
  ByteFlag* fixed_flags() { return fixed_.data(); }  // set_fixed for a loop: the flags of the n band columns
  double* rhs() { return y_.data(); }          // n values, then m zeros of padding
  double* rhs_border() { return ya_.data(); }  // na values

  bool factor() {
    // Without a border the pair step needs none of the border's code (a separate instance keeps its registers).
    if (na_ == 0)
      return with_sizes([this]<int M, int>() {
        if constexpr (kTwisted<M>) {
          if (two_ended<M>()) return factor_twisted<M>();
        }
        return factor_band<M, 0, false>();
      });
    return with_sizes([this]<int M, int NA>() { return factor_band<M, NA, true>(); }) && factor_corner();
  }
  void solve() {
    with_sizes([this]<int M, int NA>() {
      if constexpr (kTwisted<M>) {
        if (two_ended<M>()) {
          solve_twisted<M>();
          return true;
        }
      }
      if constexpr (M > 0) {
        if (na_ > 0)
          solve_band_windowed<M, true, NA>();
        else
          solve_band_windowed<M, false, 0>();
      } else
        solve_band();
      return true;
    });
  }

 private:
  // Calls f.operator()<M, NA>() with the half-bandwidth as a compile-time constant for the common sizes (M = 0:
  // run-time size) and the border's size NA as one where it is M or, for the examples' half-bandwidths, any size
  // (NA = 0: run-time size). A border loop of compile-time length keeps its values in registers: the bordered
  // factorisation of a 48 x 10 film with 1-3 border nodes is 1.5x faster for it (bench/README.md).
  template <class F>
  bool with_sizes(F&& f) const {
    auto pick = [&]<int M>() {
      if (na_ == M) return f.template operator()<M, M>();
      if constexpr (M == 2 || M == 3 || M == 4 || M == 5 || M == 8 || M == 10) {
        // The examples' half-bandwidths (damper films of 4-8 axial nodes, floating-ring films of 10, half of them
        // by symmetry): each border size 1 .. M - 1 at compile time too.
        bool result = false;
        const bool hit = [&]<int... K>(std::integer_sequence<int, K...>) {
          return ((na_ == K + 1 && (result = f.template operator()<M, K + 1>(), true)) || ...);
        }(std::make_integer_sequence<int, M - 1>{});
        if (hit) return result;
      }
      return f.template operator()<M, 0>();
    };
    switch (m_) {
      case 2: return pick.template operator()<2>();
      case 3: return pick.template operator()<3>();
      case 4: return pick.template operator()<4>();
      case 5: return pick.template operator()<5>();
      case 6: return pick.template operator()<6>();
      case 7: return pick.template operator()<7>();
      case 8: return pick.template operator()<8>();
      case 10: return pick.template operator()<10>();
      case 12: return pick.template operator()<12>();
      case 14: return pick.template operator()<14>();
      case 16: return pick.template operator()<16>();
      case 20: return pick.template operator()<20>();
      case 24: return pick.template operator()<24>();
      default: return f.template operator()<0, 0>();
    }
  }

  // Right-looking band L D L^T; M > 0 fixes the half-bandwidth at compile time (loops unroll and vectorise).
  template <int M, int NA, bool Bordered>
  bool factor_band() {
    const int m = M > 0 ? M : m_, na = !Bordered ? 0 : NA > 0 ? NA : na_, n = n_;
    for (int r = 0; r < n; ++r) {
      if (fixed_[r]) {
        inv_d_[r] = 1.0;
        continue;
      }
      double* col = column(r);
      const double d = col[0];
      if (!(d > 0.0)) return false;
      const double inv = 1.0 / d;
      inv_d_[r] = inv;
      double* w = na > 0 ? border_.data() + static_cast<std::ptrdiff_t>(r) * na : nullptr;
      if (M > 0 && r + m + 1 < n && !fixed_[r + 1]) {
        // Two columns at once (rank-2 update of the trailing triangle: half the loads and stores), with the
        // border rows and the corner updated the same way.
        double* cs = col + (m + 1);  // column s = r + 1
        double lr[M + 1], ls[M + 1];
#pragma GCC unroll 16
        for (int j = 1; j <= m; ++j) lr[j] = col[j] * inv;
        for (int q = 0; q < m; ++q) cs[q] -= col[1 + q] * lr[1];
        const double ds = cs[0];
        if (!(ds > 0.0)) return false;
        const double invs = 1.0 / ds;
        inv_d_[r + 1] = invs;
#pragma GCC unroll 16
        for (int j = 1; j <= m; ++j) ls[j] = cs[j] * invs;
#pragma GCC unroll 16
        for (int j = 2; j <= m; ++j) {
          double* t = col + j * (m + 1);  // column r + j
          const double a = lr[j], b = ls[j - 1];
          for (int q = 0; q <= m - j; ++q) t[q] -= col[j + q] * a + cs[j - 1 + q] * b;
          t[m - j + 1] -= cs[m] * b;
        }
        col[(m + 1) * (m + 1)] -= cs[m] * ls[m];  // diagonal of column r + m + 1
        if (Bordered) pair_border<M, NA>(w, inv, invs, lr, ls);
        for (int j = 1; j <= m; ++j) {
          col[j] = lr[j];
          cs[j] = ls[j];
        }
        ++r;
        continue;
      }
      if (r + m < n) {
#pragma GCC unroll 16
        for (int j = 1; j <= m; ++j) {
          const double l = col[j] * inv;
          double* t = col + j * (m + 1);  // column r + j
          for (int q = 0; q <= m - j; ++q) t[q] -= col[j + q] * l;
        }
      } else {
        for (int j = 1; j <= n - 1 - r; ++j) {
          const double l = col[j] * inv;
          double* t = col + j * (m + 1);
          for (int q = 0; q <= m - j; ++q) t[q] -= col[j + q] * l;
        }
      }
      if (na > 0) {
        const int jmax = std::min(m, n - 1 - r);
        for (int j = 1; j <= jmax; ++j) {
          const double l = col[j] * inv;
          if (l == 0.0) continue;
          double* wt = w + j * na;
          for (int a = 0; a < na; ++a) wt[a] -= w[a] * l;
        }
        for (int a = 0; a < na; ++a) {
          const double wa = w[a] * inv;
          double* fr = corner_.data() + a * na;
          for (int b = 0; b <= a; ++b) fr[b] -= wa * w[b];
        }
        for (int a = 0; a < na; ++a) w[a] *= inv;
      }
      for (int j = 1; j <= m; ++j) col[j] *= inv;
    }
    return true;
  }

  // Two-ended ("twisted") elimination of a band without border, for the small half-bandwidths where one row's
  // elimination is a short chain of dependent operations (a division, then a few multiply-adds feeding the next
  // row's pivot): its time is the chain's latency, not its arithmetic. The rows split into a top part 0 .. k - 1,
  // eliminated downwards as in factor_band, a bottom part n - 1 .. k + M eliminated upwards (U D U^T of that part),
  // and the M separator rows k .. k + M - 1 between them, eliminated last. The top and bottom chains do not depend
  // on each other (they share only their updates of the separator block, subtractions in a fixed order) and run
  // interleaved in one loop, so the processor overlaps their latencies. This is the factorisation of the matrix
  // with its rows ordered top, bottom reversed, separator (a one-level nested dissection; the band analogue of the
  // twisted factorisations of tridiagonal matrices, e.g. Parlett, B. N., Dhillon, I. S.: Fernando's solution to
  // Wilkinson's problem: an application of double factorization, Linear Algebra Appl. 267 (1997) 247-279). Storage: the
  // top's and the separator's L as in factor_band (column r holds L(r + t, r)), the bottom's U in the same slots
  // (column r - t, entry t holds U(r - t, r) for bottom row r), so A's band storage is overwritten in place.
  // Fixed rows keep their identity rows and zero columns; in the substitutions they need no test of their own.
  template <int M>
  bool factor_twisted() {
    constexpr int S = M + 1;  // column stride
    const int n = n_, k = separator_row<M>(), nbot = n - k - M;
    const ByteFlag* fixed = fixed_.data();
    double* inv_d = inv_d_.data();
    double* base = band_.data();
    const int steps = std::max(k, nbot);
    for (int i = 0; i < steps; ++i) {
      if (i < k) {
        const int r = i;
        if (fixed[r]) {
          inv_d[r] = 1.0;
        } else {
          double* col = base + static_cast<std::ptrdiff_t>(r) * S;
          const double d = col[0];
          if (!(d > 0.0)) return false;
          const double inv = 1.0 / d;
          inv_d[r] = inv;
          double l[M + 1];
#pragma GCC unroll 16
          for (int j = 1; j <= M; ++j) l[j] = col[j] * inv;
#pragma GCC unroll 16
          for (int j = 1; j <= M; ++j) {
            double* t = col + j * S;  // column r + j
#pragma GCC unroll 16
            for (int q = 0; q <= M - j; ++q) t[q] -= col[j + q] * l[j];
          }
#pragma GCC unroll 16
          for (int j = 1; j <= M; ++j) col[j] = l[j];
        }
      }
      if (i < nbot) {
        const int r = n - 1 - i;
        if (fixed[r]) {
          inv_d[r] = 1.0;
        } else {
          const double d = base[static_cast<std::ptrdiff_t>(r) * S];
          if (!(d > 0.0)) return false;
          const double inv = 1.0 / d;
          inv_d[r] = inv;
          double c[M + 1], u[M + 1];  // A(r - t, r) and its U
#pragma GCC unroll 16
          for (int t = 1; t <= M; ++t) {
            c[t] = base[static_cast<std::ptrdiff_t>(r - t) * S + t];
            u[t] = c[t] * inv;
          }
          // A(r - i, r - j) -= A(r - i, r) U(r - j, r), 1 <= i <= j <= M: column r - j, entry j - i.
#pragma GCC unroll 16
          for (int j = 1; j <= M; ++j) {
            double* t = base + static_cast<std::ptrdiff_t>(r - j) * S;
#pragma GCC unroll 16
            for (int q = 1; q <= j; ++q) t[j - q] -= c[q] * u[j];
          }
#pragma GCC unroll 16
          for (int t = 1; t <= M; ++t) base[static_cast<std::ptrdiff_t>(r - t) * S + t] = u[t];
        }
      }
    }
    // The separator block, dense within the band storage (column c, entries up to row k + M - 1).
    for (int c = k; c < k + M; ++c) {
      if (fixed[c]) {
        inv_d[c] = 1.0;
        continue;
      }
      double* col = base + static_cast<std::ptrdiff_t>(c) * S;
      const double d = col[0];
      if (!(d > 0.0)) return false;
      const double inv = 1.0 / d;
      inv_d[c] = inv;
      const int qmax = k + M - 1 - c;
      for (int j = 1; j <= qmax; ++j) {
        const double l = col[j] * inv;
        double* t = col + j * S;
        for (int q = 0; q <= qmax - j; ++q) t[q] -= col[j + q] * l;
      }
      for (int j = 1; j <= qmax; ++j) col[j] *= inv;
    }
    return true;
  }

  // Substitutions of the twisted factorisation: the top's and the bottom's forward chains interleaved (each keeping
  // its window of M values in registers, as solve_band_windowed does), the separator, then both backward chains.
  template <int M>
  void solve_twisted() {
    constexpr int S = M + 1;
    const int n = n_, k = separator_row<M>(), nbot = n - k - M;
    double* y = y_.data();
    const double* inv_d = inv_d_.data();
    const double* base = band_.data();
    const int steps = std::max(k, nbot);
    // Forward. Top window a[t] = y[r + t] for its row r; bottom window w[t] = y[r - t] for its row r. The bottom's
    // loads of separator rows start from zero: its window ends holding only its updates of the separator, which
    // are added to the top's below.
    double a[M], w[M];
#pragma GCC unroll 16
    for (int t = 0; t < M; ++t) {
      a[t] = y[t];
      w[t] = y[n - 1 - t];
    }
    for (int i = 0; i < steps; ++i) {
      if (i < k) {
        const int r = i;
        const double* col = base + static_cast<std::ptrdiff_t>(r) * S;
        const double yr = a[0];
        y[r] = yr * inv_d[r];
#pragma GCC unroll 16
        for (int t = 1; t < M; ++t) a[t - 1] = a[t] - col[t] * yr;
        a[M - 1] = y[r + M] - col[M] * yr;
      }
      if (i < nbot) {
        const int r = n - 1 - i;
        const double yr = w[0];
        y[r] = yr * inv_d[r];
#pragma GCC unroll 16
        for (int t = 1; t < M; ++t) w[t - 1] = w[t] - base[static_cast<std::ptrdiff_t>(r - t) * S + t] * yr;
        const double next = r - M >= k + M ? y[r - M] : 0.0;
        w[M - 1] = next - base[static_cast<std::ptrdiff_t>(r - M) * S + M] * yr;
      }
    }
#pragma GCC unroll 16
    for (int t = 0; t < M; ++t) y[k + t] = a[t] + w[M - 1 - t];
    // The separator: forward, diagonal, backward.
    for (int c = k; c < k + M; ++c) {
      const double* col = base + static_cast<std::ptrdiff_t>(c) * S;
      const double yc = y[c];
      for (int q = 1; c + q < k + M; ++q) y[c + q] -= col[q] * yc;
      y[c] = yc * inv_d[c];
    }
    for (int c = k + M - 1; c >= k; --c) {
      const double* col = base + static_cast<std::ptrdiff_t>(c) * S;
      double s = y[c];
      for (int q = 1; c + q < k + M; ++q) s -= col[q] * y[c + q];
      y[c] = s;
    }
    // Backward. Top window a[t] = y[r + 1 + t]; bottom window w[t] = y[r - 1 - t].
#pragma GCC unroll 16
    for (int t = 0; t < M; ++t) {
      a[t] = y[k + t];
      w[t] = y[k + M - 1 - t];
    }
    for (int i = 0; i < steps; ++i) {
      if (i < k) {
        const int r = k - 1 - i;
        const double* col = base + static_cast<std::ptrdiff_t>(r) * S;
        double s0 = 0.0, s1 = 0.0;
#pragma GCC unroll 16
        for (int t = 2; t <= M; t += 2) {
          s0 += col[t] * a[t - 1];
          if (t + 1 <= M) s1 += col[t + 1] * a[t];
        }
        const double yr = (y[r] - (s0 + s1)) - col[1] * a[0];
        y[r] = yr;
#pragma GCC unroll 16
        for (int t = M - 1; t > 0; --t) a[t] = a[t - 1];
        a[0] = yr;
      }
      if (i < nbot) {
        const int r = k + M + i;
        double s0 = 0.0, s1 = 0.0;
#pragma GCC unroll 16
        for (int t = 2; t <= M; t += 2) {
          s0 += base[static_cast<std::ptrdiff_t>(r - t) * S + t] * w[t - 1];
          if (t + 1 <= M) s1 += base[static_cast<std::ptrdiff_t>(r - t - 1) * S + t + 1] * w[t];
        }
        const double yr = (y[r] - (s0 + s1)) - base[static_cast<std::ptrdiff_t>(r - 1) * S + 1] * w[0];
        y[r] = yr;
#pragma GCC unroll 16
        for (int t = M - 1; t > 0; --t) w[t] = w[t - 1];
        w[0] = yr;
      }
    }
  }

  // The border part of eliminating columns r and s = r + 1 together (factor_band's pair step): the border rows
  // w_r (wr, factor_band's w), w_s and those of the rows below them, r + 2 .. r + m + 1, and the corner; lr, ls: the
  // two columns' L.
  template <int M, int NA>
  [[gnu::always_inline]] void pair_border(double* wr, double inv, double invs, const double* lr, const double* ls) {
    const int na = NA > 0 ? NA : na_;
    double* ws = wr + na;
    for (int a = 0; a < na; ++a) ws[a] -= wr[a] * lr[1];
    for (int j = 2; j <= M; ++j) {
      double* wt = wr + j * na;
      const double a1 = lr[j], b1 = ls[j - 1];
      for (int a = 0; a < na; ++a) wt[a] -= wr[a] * a1 + ws[a] * b1;
    }
    double* wl = wr + (M + 1) * na;  // row r + m + 1
    for (int a = 0; a < na; ++a) wl[a] -= ws[a] * ls[M];
    for (int a = 0; a < na; ++a) {
      const double ra = wr[a] * inv, sa = ws[a] * invs;
      double* fr = corner_.data() + a * na;
      for (int b = 0; b <= a; ++b) fr[b] -= ra * wr[b] + sa * ws[b];
    }
    for (int a = 0; a < na; ++a) {
      wr[a] *= inv;
      ws[a] *= invs;
    }
  }

  bool factor_corner() {
    const int na = na_;
    // Dense L D L^T of the corner block.
    for (int i = 0; i < na; ++i) {
      double* ri = corner_.data() + i * na;
      for (int j = 0; j < i; ++j) {
        const double* rj = corner_.data() + j * na;
        double s = ri[j];
        for (int k = 0; k < j; ++k) s -= ri[k] * rj[k];  // ri[k] holds G = L * d for k < j
        ri[j] = s;
      }
      double d = ri[i];
      for (int j = 0; j < i; ++j) {
        const double l = ri[j] / corner_d_[j];
        d -= ri[j] * l;
        ri[j] = l;
      }
      if (!(d > 0.0)) return false;
      corner_d_[i] = d;
    }
    return true;
  }

  // Solve for a compile-time half-bandwidth. The substitutions are chains from one row to the next: the M values
  // of the sliding window y[r .. r + M] stay in registers, so each row costs one multiply-add on the chain instead
  // of a store and a reload. Rows of fixed nodes are a shift of the window (their columns and right-hand sides are
  // zero). The border's (na unknowns) sums run beside the chain.
  template <int M, bool Border, int NA>
  void solve_band_windowed() {
    const int n = n_, na = Border ? (NA > 0 ? NA : na_) : 0;
    double* y = y_.data();
    double* ya = ya_.data();
    const double* inv_d = inv_d_.data();
    const ByteFlag* fixed = fixed_.data();
    std::fill(y + n, y + n + M + 1, 0.0);
    double a[M];  // forward: y[r .. r + M - 1] with the updates of the rows above r
#pragma GCC unroll 16
    for (int t = 0; t < M; ++t) a[t] = y[t];
    // A border of compile-time size accumulates in registers (acc) rather than in ya, whose stores and reloads
    // from one row to the next would be a chain through memory beside the window's.
    constexpr int NR = Border && NA > 0 ? NA : 1;
    double acc[NR];
#pragma GCC unroll 16
    for (int k = 0; k < NR; ++k) acc[k] = NA > 0 ? ya[k] : 0.0;
    for (int r = 0; r < n; ++r) {
      const double yr = a[0];
      y[r] = yr * inv_d[r];
      if (fixed[r]) {
#pragma GCC unroll 16
        for (int t = 1; t < M; ++t) a[t - 1] = a[t];
        a[M - 1] = y[r + M];
        continue;
      }
      const double* col = column(r);
#pragma GCC unroll 16
      for (int t = 1; t < M; ++t) a[t - 1] = a[t] - col[t] * yr;
      a[M - 1] = y[r + M] - col[M] * yr;
      if constexpr (Border && NA > 0) {
        const double* w = border_.data() + static_cast<std::ptrdiff_t>(r) * NA;
#pragma GCC unroll 16
        for (int k = 0; k < NA; ++k) acc[k] -= w[k] * yr;
      } else if constexpr (Border) {
        const double* w = border_.data() + static_cast<std::ptrdiff_t>(r) * na;
        for (int k = 0; k < na; ++k) ya[k] -= w[k] * yr;
      }
    }
    if constexpr (Border && NA > 0) {
#pragma GCC unroll 16
      for (int k = 0; k < NA; ++k) ya[k] = acc[k];
    }
    if (Border) solve_corner();
    double b[M];  // backward: the solution y[r + 1 .. r + M]
#pragma GCC unroll 16
    for (int t = 0; t < M; ++t) b[t] = 0.0;
    for (int r = n - 1; r >= 0; --r) {
      if (fixed[r]) {
#pragma GCC unroll 16
        for (int t = M - 1; t > 0; --t) b[t] = b[t - 1];
        b[0] = y[r];
        continue;
      }
      const double* col = column(r);
      // The newest value, b[0] = y[r + 1], enters last: the terms before it do not wait for it.
      double s0 = 0.0, s1 = 0.0;
#pragma GCC unroll 16
      for (int t = 2; t <= M; t += 2) {
        s0 += col[t] * b[t - 1];
        if (t + 1 <= M) s1 += col[t + 1] * b[t];
      }
      if (Border) {
        // The run-time size (na_ = NA when that is set): a compile-time one lets the compiler vectorise the
        // products and add them one by one, which is slower and rounds differently.
        const double* w = border_.data() + static_cast<std::ptrdiff_t>(r) * na_;
        for (int k = 0; k < na_; ++k) s0 += w[k] * ya[k];
      }
      const double yr = (y[r] - (s0 + s1)) - col[1] * b[0];
      y[r] = yr;
#pragma GCC unroll 16
      for (int t = M - 1; t > 0; --t) b[t] = b[t - 1];
      b[0] = yr;
    }
  }

  // The border's unknowns from the corner's L D L^T (after the band's forward substitution).
  void solve_corner() {
    const int na = na_;
    double* ya = ya_.data();
    for (int i = 0; i < na; ++i) {
      const double* ri = corner_.data() + i * na;
      double s = ya[i];
      for (int j = 0; j < i; ++j) s -= ri[j] * ya[j];
      ya[i] = s;
    }
    for (int i = 0; i < na; ++i) ya[i] /= corner_d_[i];
    for (int i = na - 1; i >= 0; --i) {
      double s = ya[i];
      for (int j = i + 1; j < na; ++j) s -= corner_[j * na + i] * ya[j];
      ya[i] = s;
    }
  }

  // Solve for a run-time half-bandwidth.
  void solve_band() {
    const int m = m_, na = na_, n = n_;
    double* y = y_.data();
    double* ya = ya_.data();
    std::fill(y + n, y + n + m + 1, 0.0);
    for (int r = 0; r < n; ++r) {
      const double yr = y[r];
      if (yr == 0.0 || fixed_[r]) continue;
      const double* col = column(r);
      for (int t = 1; t <= m; ++t) y[r + t] -= col[t] * yr;
      if (na > 0) {
        const double* w = border_.data() + static_cast<std::ptrdiff_t>(r) * na;
        for (int a = 0; a < na; ++a) ya[a] -= w[a] * yr;
      }
    }
    solve_corner();
    for (int r = 0; r < n; ++r) y[r] *= inv_d_[r];
    for (int r = n - 1; r >= 0; --r) {
      if (fixed_[r]) continue;
      const double* col = column(r);
      // Four partial sums: the chain of additions, not the multiplications, bounds this loop.
      double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
      int t = 1;
      for (; t + 3 <= m; t += 4) {
        s0 += col[t] * y[r + t];
        s1 += col[t + 1] * y[r + t + 1];
        s2 += col[t + 2] * y[r + t + 2];
        s3 += col[t + 3] * y[r + t + 3];
      }
      for (; t <= m; ++t) s0 += col[t] * y[r + t];
      if (na > 0) {
        const double* w = border_.data() + static_cast<std::ptrdiff_t>(r) * na;
        int a = 0;
        for (; a + 1 < na; a += 2) {
          s1 += w[a] * ya[a];
          s3 += w[a + 1] * ya[a + 1];
        }
        if (a < na) s2 += w[a] * ya[a];
      }
      y[r] -= (s0 + s1) + (s2 + s3);
    }
  }

  // Half-bandwidths factorised two-ended when there is no border (factor_twisted), for bands of at least
  // kTwistedMinRows * M rows (each chain then has a few rows per separator row).
  template <int M>
  static constexpr bool kTwisted = M >= 2 && M <= 5;
  static constexpr int kTwistedMinRows = 8;
  // Whether the current system is factorised and solved two-ended, and the first of its M separator rows: both
  // follow from the system's sizes, so factor() and solve() take the same path by construction.
  template <int M>
  bool two_ended() const {
    return kTwisted<M> && na_ == 0 && n_ >= kTwistedMinRows * M;
  }
  template <int M>
  int separator_row() const {
    return (n_ - M) / 2;
  }

  int n_ = 0, m_ = 0, na_ = 0;
  std::vector<double> band_, border_, corner_, corner_d_, inv_d_, y_, ya_;
  std::vector<ByteFlag> fixed_;
};

}  // namespace turbodyn::reynolds

// BorderedBandLdlt (model/films/bordered_band_ldlt.h) against a dense solve of the same system: every half-bandwidth
// with a compile-time kernel and one without, borders of none, some and all of a column's nodes, fixed (identity)
// rows alone and in runs, as the film discretisation produces them.
#include "model/films/bordered_band_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

namespace turbodyn::reynolds {
namespace {

// A periodic five-point Laplacian-like grid of nc columns of m nodes (axial fastest), the last column as the border,
// with random positive couplings and a diagonal that dominates, nodes flagged fixed decoupled from the rest.
struct Grid {
  int nc, m, na;
  std::vector<std::uint8_t> fixed;  // (nc - 1) * m band nodes
  std::vector<std::uint8_t> border_fixed;
  Eigen::MatrixXd A;                // dense, all nc * m nodes (fixed nodes as identity rows)
  Eigen::VectorXd b;
};

Grid make_grid(int nc, int m, int border_free, unsigned seed, bool runs) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  Grid g{nc, m, 0, {}, {}, {}, {}};
  const int n = nc * m;
  std::vector<std::uint8_t> fx(n, 0);
  for (int k = 0; k < (nc - 1) * m; ++k) {
    const int i = k / m;
    fx[k] = runs ? (i > nc / 4 && i < nc / 2 && k % m != 0) : (rng() % 7 == 0);
  }
  for (int j = 0; j < m; ++j) fx[(nc - 1) * m + j] = j >= border_free;
  g.A = Eigen::MatrixXd::Zero(n, n);
  auto node = [&](int i, int j) { return ((i + nc) % nc) * m + j; };
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j < m; ++j) {
      const int k = node(i, j);
      if (fx[k]) continue;
      const int nb[4] = {j + 1 < m ? node(i, j + 1) : -1, j > 0 ? node(i, j - 1) : -1, node(i + 1, j), node(i - 1, j)};
      for (int q : nb)
        if (q >= 0 && !fx[q] && q > k) {
          const double c = u(rng);
          g.A(k, q) = g.A(q, k) = -c;
        }
    }
  for (int k = 0; k < n; ++k) g.A(k, k) = fx[k] ? 1.0 : 0.5 + g.A.row(k).cwiseAbs().sum() + u(rng);
  g.b = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < n; ++k)
    if (!fx[k]) g.b(k) = u(rng) - 0.6;
  g.fixed.assign(fx.begin(), fx.begin() + (nc - 1) * m);
  g.border_fixed.assign(fx.begin() + (nc - 1) * m, fx.end());
  g.na = border_free;
  return g;
}

// Solves g with the band solver (the border holds the last column's first border_free nodes) and returns the
// solution in grid order (fixed nodes 0).
Eigen::VectorXd band_solve(const Grid& g, BorderedBandLdlt& s) {
  const int nb = (g.nc - 1) * g.m, na = g.na;
  s.reserve(nb, g.m);
  s.reset(nb, g.m, na);
  for (int r = 0; r < nb; ++r) {
    double* col = s.column(r);
    s.set_fixed(r, g.fixed[r] != 0);
    if (g.fixed[r]) {
      col[0] = 1.0;
      continue;
    }
    col[0] = g.A(r, r);
    for (int t = 1; t <= g.m && r + t < nb; ++t) col[t] = g.A(r + t, r);
    for (int a = 0; a < na; ++a) s.border(r, a) = g.A(nb + a, r);
  }
  for (int a = 0; a < na; ++a)
    for (int c = 0; c <= a; ++c) s.corner(a, c) = g.A(nb + a, nb + c);
  EXPECT_TRUE(s.factor());
  for (int r = 0; r < nb; ++r) s.rhs()[r] = g.b(r);
  for (int a = 0; a < na; ++a) s.rhs_border()[a] = g.b(nb + a);
  s.solve();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(g.nc * g.m);
  for (int r = 0; r < nb; ++r) x(r) = s.rhs()[r];
  for (int a = 0; a < na; ++a) x(nb + a) = s.rhs_border()[a];
  return x;
}

TEST(BorderedBandLdlt, EqualsADenseSolveForEveryKernelBorderAndFixedPattern) {
  // 2-24: compile-time kernels; 9 and 11: the run-time one. Half-bandwidths 2, 3, 4, 5, 8 and 10 also have a kernel
  // for each border size: all of them.
  for (int m : {2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 14, 16, 20, 24}) {
    std::vector<int> borders{0, 1, m / 2, m};
    if (m == 2 || m == 3 || m == 4 || m == 5 || m == 8 || m == 10)
      for (int b = 2; b < m; ++b)
        if (b != m / 2) borders.push_back(b);
    for (int border : borders)
      for (bool runs : {false, true}) {
        SCOPED_TRACE("m = " + std::to_string(m) + ", border " + std::to_string(border) + (runs ? ", runs" : ""));
        const Grid g = make_grid(17, m, border, 100u * m + border + (runs ? 7u : 0u), runs);
        const Eigen::VectorXd x_dense = g.A.ldlt().solve(g.b);
        BorderedBandLdlt s;
        const Eigen::VectorXd x = band_solve(g, s);
        // Fixed nodes solve to their zero right-hand sides like the dense solve's identity rows.
        EXPECT_LT((x - x_dense).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + x_dense.cwiseAbs().maxCoeff()));
        EXPECT_GT(x.cwiseAbs().maxCoeff(), 1e-3);
        // A second right-hand side with the same factorisation.
        const int nb = (g.nc - 1) * g.m;
        for (int r = 0; r < nb; ++r) s.rhs()[r] = -3.0 * g.b(r);
        for (int a = 0; a < g.na; ++a) s.rhs_border()[a] = -3.0 * g.b(nb + a);
        s.solve();
        for (int r = 0; r < nb; ++r) EXPECT_NEAR(s.rhs()[r], -3.0 * x(r), 1e-12);
        for (int a = 0; a < g.na; ++a) EXPECT_NEAR(s.rhs_border()[a], -3.0 * x(nb + a), 1e-12);
      }
  }
}

TEST(BorderedBandLdlt, TwoEndedAndOneEndedEliminationsGiveTheDenseSolution) {
  // Without a border, half-bandwidths 2 to 5 eliminate from both ends at once when the band has at least 8 M rows
  // (factor_twisted): bands of 5-9 columns (4-8 band columns) take the one-ended path, longer ones the two-ended, with both parities of
  // the row count (the separator's place), fixed rows scattered and in runs (some in the separator).
  for (int m : {2, 3, 4, 5})
    for (int nc : {5, 9, 10, 11, 17, 18, 48})
      for (bool runs : {false, true}) {
        SCOPED_TRACE("m = " + std::to_string(m) + ", " + std::to_string(nc) + " columns" + (runs ? ", runs" : ""));
        const Grid g = make_grid(nc, m, 0, 31u * nc + m + (runs ? 3u : 0u), runs);
        const Eigen::VectorXd x_dense = g.A.ldlt().solve(g.b);
        BorderedBandLdlt s;
        const Eigen::VectorXd x = band_solve(g, s);
        EXPECT_LT((x - x_dense).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + x_dense.cwiseAbs().maxCoeff()));
        EXPECT_GT(x.cwiseAbs().maxCoeff(), 1e-3);
      }
}

TEST(BorderedBandLdlt, ReportsAMatrixThatIsNotPositiveDefinite) {
  Grid g = make_grid(9, 5, 2, 3u, false);
  int k = 12;
  while (g.fixed[k]) ++k;
  g.A(k, k) = -1.0;  // a free band node
  BorderedBandLdlt s;
  const int nb = (g.nc - 1) * g.m;
  s.reserve(nb, g.m);
  s.reset(nb, g.m, g.na);
  for (int r = 0; r < nb; ++r) {
    s.set_fixed(r, g.fixed[r] != 0);
    s.column(r)[0] = g.fixed[r] ? 1.0 : g.A(r, r);
  }
  for (int a = 0; a < g.na; ++a) s.corner(a, a) = 1.0;
  EXPECT_FALSE(s.factor());
  // The same in each part of the two-ended elimination (top, separator, bottom; no border, half-bandwidth 3).
  const Grid h = make_grid(17, 3, 0, 5u, false);
  const int nh = 16 * 3, split = (nh - 3) / 2;
  for (int bad : {4, split + 1, nh - 5}) {
    SCOPED_TRACE("negative pivot in row " + std::to_string(bad));
    BorderedBandLdlt t;
    t.reserve(nh, 3);
    t.reset(nh, 3, 0);
    for (int r = 0; r < nh; ++r) {
      t.set_fixed(r, false);
      t.column(r)[0] = r == bad ? -1.0 : h.A(r, r) + 1.0;
    }
    EXPECT_FALSE(t.factor());
  }
}

}  // namespace
}  // namespace turbodyn::reynolds

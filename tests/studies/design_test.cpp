#include "studies/design.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace turbodyn::studies {
namespace {

using ::testing::HasSubstr;
using Kind = Distribution::Kind;

constexpr double pi = std::numbers::pi;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

Parameter uniform(const std::string& path, double low, double high, int n_levels = 0) {
  Parameter p{path, {}};
  p.distribution.kind = Kind::Uniform;
  p.distribution.low = low;
  p.distribution.high = high;
  p.distribution.n_levels = n_levels;
  return p;
}

Parameter log_uniform(const std::string& path, double low, double high, int n_levels = 0) {
  Parameter p = uniform(path, low, high, n_levels);
  p.distribution.kind = Kind::LogUniform;
  return p;
}

Parameter levels(const std::string& path, std::vector<double> values) {
  Parameter p{path, {}};
  p.distribution.kind = Kind::Levels;
  p.distribution.levels = std::move(values);
  return p;
}

Parameter normal(const std::string& path, double mean, double std, double low = 0, double high = 0) {
  Parameter p{path, {}};
  p.distribution.kind = Kind::Normal;
  p.distribution.mean = mean;
  p.distribution.std = std;
  p.distribution.low = low;
  p.distribution.high = high;
  return p;
}

DesignSpec spec_of(DesignKind kind, std::vector<Parameter> parameters, std::size_t runs = 0, std::uint64_t seed = 1,
                   bool scramble = false) {
  DesignSpec s;
  s.kind = kind;
  s.parameters = std::move(parameters);
  s.runs = runs;
  s.seed = seed;
  s.scramble = scramble;
  return s;
}

// n unit-range parameters "x0", "x1", ... (values equal to the unit coordinates).
std::vector<Parameter> unit_cube(std::size_t n) {
  std::vector<Parameter> ps;
  for (std::size_t j = 0; j < n; ++j) ps.push_back(uniform("x" + std::to_string(j), 0.0, 1.0));
  return ps;
}

std::vector<double> column(const std::vector<std::vector<double>>& rows, std::size_t j) {
  std::vector<double> c;
  for (const auto& r : rows) c.push_back(r[j]);
  return c;
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double sd_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

// True if every stratum [k/s, (k+1)/s) holds exactly one of the values. `nudge` (relative) moves values that
// should lie exactly on a stratum's left edge k/s but were rounded below it (s not a power of 2) into it.
bool one_per_stratum(const std::vector<double>& u, std::size_t strata, double nudge = 0) {
  if (u.size() != strata) return false;
  std::vector<int> count(strata, 0);
  for (double x : u) {
    if (!(x >= 0 && x < 1)) return false;
    const double k = std::floor(x * static_cast<double>(strata) * (1 + nudge));
    if (k >= static_cast<double>(strata)) return false;
    ++count[static_cast<std::size_t>(k)];
  }
  return std::all_of(count.begin(), count.end(), [](int c) { return c == 1; });
}

// ---------------------------------------------------------------------------------------------------------------
// Distributions and the normal quantile

TEST(NormalQuantile, KnownValuesAndRoundTrip) {
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-14);
  EXPECT_NEAR(normal_quantile(0.025), -1.959963984540054, 1e-14);
  EXPECT_NEAR(normal_quantile(0.5), 0.0, 1e-16);
  EXPECT_NEAR(normal_quantile(0.8413447460685429), 1.0, 1e-13);  // Phi(1)
  EXPECT_NEAR(normal_quantile(1e-10), -6.361340902404056, 1e-11);
  EXPECT_EQ(normal_quantile(0.0), -inf);
  EXPECT_EQ(normal_quantile(1.0), inf);
  for (double p : {1e-300, 1e-100, 1e-20, 1e-8, 1e-3, 0.02, 0.03, 0.2, 0.4999, 0.6, 0.9, 0.999, 1 - 1e-9}) {
    const double z = normal_quantile(p);
    const double back = p <= 0.5 ? normal_cdf(z) : 1.0 - normal_cdf(-z);
    EXPECT_NEAR(back / p, 1.0, 1e-13) << "p = " << p;
    if (p >= 1e-3) {  // where 1 - p still carries p's digits
      EXPECT_NEAR(normal_quantile(p), -normal_quantile(1.0 - p), 1e-13) << "symmetry at p = " << p;
    }
  }
}

TEST(Distribution, QuantileOfEachKind) {
  EXPECT_EQ(levels("a", {1, 2, 5}).distribution.quantile(0.0), 1);
  EXPECT_EQ(levels("a", {1, 2, 5}).distribution.quantile(0.33), 1);   // floor(0.99) = 0
  EXPECT_EQ(levels("a", {1, 2, 5}).distribution.quantile(0.34), 2);   // floor(1.02) = 1
  EXPECT_EQ(levels("a", {1, 2, 5}).distribution.quantile(0.999), 5);
  EXPECT_DOUBLE_EQ(uniform("a", 2, 6).distribution.quantile(0.25), 3.0);
  EXPECT_DOUBLE_EQ(log_uniform("a", 1e-3, 1e3).distribution.quantile(0.5), 1.0);
  EXPECT_NEAR(log_uniform("a", 1e-3, 1e3).distribution.quantile(0.25), std::pow(10.0, -1.5), 1e-15);
  EXPECT_NEAR(normal("a", 10, 2).distribution.quantile(0.975), 10 + 2 * 1.959963984540054, 1e-12);
  // Untruncated normal at u = 0 stays finite (u clamped to 2^-53).
  EXPECT_TRUE(std::isfinite(normal("a", 0, 1).distribution.quantile(0.0)));
  // Truncated normal: u = 0 and u -> 1 give the ends; the median of the symmetric truncation is the mean.
  const Distribution t = normal("a", 1, 0.5, 0.0, 2.0).distribution;
  EXPECT_NEAR(t.quantile(0.0), 0.0, 1e-12);
  EXPECT_NEAR(t.quantile(0.5), 1.0, 1e-12);
  EXPECT_NEAR(t.quantile(1.0), 2.0, 1e-12);
  EXPECT_THROW((void)t.quantile(nan), std::invalid_argument);
  EXPECT_THROW((void)t.quantile(-0.1), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------------------
// Full factorial

TEST(FullFactorial, Properties) {
  Parameter t = normal("oil.temperature", 360, 10, 340, 400);
  t.distribution.n_levels = 2;
  const DesignSpec spec =
      spec_of(DesignKind::FullFactorial, {levels("bearings.compressor.k", {1e7, 2e7, 3e7}),
                                          uniform("disks.turbine.unbalance", 0.0, 10.0, 5),
                                          log_uniform("bearings.compressor.c", 1.0, 100.0, 3), t});
  const Design d = make_design(spec);
  ASSERT_EQ(d.paths, (std::vector<std::string>{"bearings.compressor.k", "disks.turbine.unbalance",
                                               "bearings.compressor.c", "oil.temperature"}));
  ASSERT_EQ(d.runs(), 3u * 5u * 3u * 2u);
  ASSERT_EQ(d.unit.size(), d.runs());

  // Level sets: the ends exactly, evenly (geometrically for LogUniform) spaced in between.
  std::vector<std::set<double>> seen(4);
  for (const auto& row : d.values)
    for (std::size_t j = 0; j < 4; ++j) seen[j].insert(row[j]);
  EXPECT_EQ(seen[0], (std::set<double>{1e7, 2e7, 3e7}));
  EXPECT_EQ(seen[1], (std::set<double>{0.0, 2.5, 5.0, 7.5, 10.0}));
  ASSERT_EQ(seen[2].size(), 3u);
  EXPECT_EQ(*seen[2].begin(), 1.0);
  EXPECT_NEAR(*std::next(seen[2].begin()), 10.0, 1e-12);
  EXPECT_EQ(*seen[2].rbegin(), 100.0);
  EXPECT_EQ(seen[3], (std::set<double>{340.0, 400.0}));

  // Every combination exactly once.
  std::set<std::vector<double>> combos(d.values.begin(), d.values.end());
  EXPECT_EQ(combos.size(), d.runs());

  // Order: last parameter fastest, first slowest.
  EXPECT_EQ(d.values[0], (std::vector<double>{1e7, 0.0, 1.0, 340.0}));
  EXPECT_EQ(d.values[1], (std::vector<double>{1e7, 0.0, 1.0, 400.0}));
  EXPECT_NEAR(d.values[2][2], 10.0, 1e-12);  // then the third column advances
  EXPECT_EQ(d.values[2][3], 340.0);
  EXPECT_EQ(d.values[6][1], 2.5);  // after 3 * 2 runs the second column advances
  EXPECT_EQ(d.values[30][0], 2e7);  // after 5 * 3 * 2 runs the first column advances
  EXPECT_EQ(d.values.back(), (std::vector<double>{3e7, 10.0, 100.0, 400.0}));
  for (std::size_t r = 0; r < d.runs(); ++r) {
    const std::size_t i0 = r / 30, i1 = (r / 6) % 5, i2 = (r / 2) % 3, i3 = r % 2;
    EXPECT_EQ(d.values[r][0], (std::vector<double>{1e7, 2e7, 3e7})[i0]);
    EXPECT_DOUBLE_EQ(d.values[r][1], 2.5 * static_cast<double>(i1));
    EXPECT_NEAR(d.values[r][2], std::pow(10.0, static_cast<double>(i2)), 1e-12);
    EXPECT_EQ(d.values[r][3], i3 == 0 ? 340.0 : 400.0);
    // The unit coordinate is the midpoint of the level's stratum; the quantile of a Levels column returns it.
    EXPECT_DOUBLE_EQ(d.unit[r][1], (static_cast<double>(i1) + 0.5) / 5.0);
    EXPECT_EQ(spec.parameters[0].distribution.quantile(d.unit[r][0]), d.values[r][0]);
  }
}

TEST(FullFactorial, SingleLevelAndSingleParameter) {
  const Design d = make_design(spec_of(DesignKind::FullFactorial, {levels("a", {4.0})}));
  ASSERT_EQ(d.runs(), 1u);
  EXPECT_EQ(d.values[0][0], 4.0);
  EXPECT_EQ(d.unit[0][0], 0.5);
}

// ---------------------------------------------------------------------------------------------------------------
// Latin hypercube

TEST(LatinHypercube, OnePointPerStratumValuesAreQuantilesReproducible) {
  Parameter t = normal("oil.temperature", 360, 10, 340, 400);
  const std::vector<Parameter> ps = {uniform("disks.turbine.unbalance", 0, 1e-6), normal("bearings.k", 3e7, 3e6),
                                     log_uniform("bearings.c", 10, 1000), levels("variant", {1, 2, 3, 4, 5}), t};
  for (std::size_t n : {1u, 2u, 7u, 64u, 1000u}) {
    const Design d = make_design(spec_of(DesignKind::LatinHypercube, ps, n, 42));
    ASSERT_EQ(d.runs(), n);
    for (std::size_t j = 0; j < ps.size(); ++j) {
      EXPECT_TRUE(one_per_stratum(column(d.unit, j), n)) << "n = " << n << ", column " << j;
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(d.values[i][j], ps[j].distribution.quantile(d.unit[i][j]));
    }
  }
  const Design a = make_design(spec_of(DesignKind::LatinHypercube, ps, 100, 7));
  const Design b = make_design(spec_of(DesignKind::LatinHypercube, ps, 100, 7));
  const Design c = make_design(spec_of(DesignKind::LatinHypercube, ps, 100, 8));
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.unit, b.unit);
  for (std::size_t j = 0; j < ps.size(); ++j) EXPECT_NE(column(a.unit, j), column(c.unit, j)) << "column " << j;
  // Columns are independent streams: adding a parameter at the end leaves the earlier columns unchanged.
  std::vector<Parameter> more = ps;
  more.push_back(uniform("extra", 0, 1));
  const Design e = make_design(spec_of(DesignKind::LatinHypercube, more, 100, 7));
  for (std::size_t j = 0; j < ps.size(); ++j) EXPECT_EQ(column(e.unit, j), column(a.unit, j));
}

// ---------------------------------------------------------------------------------------------------------------
// Sobol

TEST(Sobol, FirstPointsMatchPublishedSequence) {
  // Joe & Kuo (new-joe-kuo-6.21201) dims 1-3, the origin skipped: the published points 1, 2, 3, ... (also the
  // unscrambled reference values in SciPy's test suite, which uses the same direction numbers).
  const Design d = make_design(spec_of(DesignKind::Sobol, unit_cube(3), 9));
  const std::vector<std::vector<double>> expected = {
      {0.5, 0.5, 0.5},       {0.75, 0.25, 0.25},   {0.25, 0.75, 0.75},     {0.375, 0.375, 0.625},
      {0.875, 0.875, 0.125}, {0.625, 0.125, 0.875}, {0.125, 0.625, 0.375}, {0.1875, 0.3125, 0.9375},
      {0.6875, 0.8125, 0.4375}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(d.unit[i], expected[i]) << "run " << i;
    EXPECT_EQ(d.values[i], expected[i]) << "run " << i;
  }
  // The raw sequence starts at the origin.
  const auto raw = sobol_points(3, 3);
  EXPECT_EQ(raw[0], (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(raw[1], expected[0]);
  EXPECT_EQ(raw[2], expected[1]);
  // Starting in the middle of the sequence gives the same points (Gray-code fast forward).
  const auto all = sobol_points(300, 10);
  const auto tail = sobol_points(50, 10, 250);
  for (std::size_t i = 0; i < 50; ++i) EXPECT_EQ(tail[i], all[250 + i]);
}

// Every built-in dimension (the typed-in Joe-Kuo table) yields a (0,1)-sequence: the first 2^m points of each
// coordinate fill the 2^m dyadic intervals, which fails for an even m_k or one >= 2^k (a typo in the table).
TEST(Sobol, SupportsAtLeast21DimensionsAndEveryDimensionIsStratified) {
  ASSERT_GE(sobol_max_dimensions(), 21u);
  const std::size_t dims = sobol_max_dimensions();
  const auto pts = sobol_points(256, dims);
  for (std::size_t j = 0; j < dims; ++j) {
    EXPECT_EQ(pts[1][j], 0.5) << "dimension " << j + 1;
    for (std::size_t m = 1; m <= 8; ++m) {
      std::vector<double> first;
      for (std::size_t i = 0; i < (std::size_t{1} << m); ++i) first.push_back(pts[i][j]);
      EXPECT_TRUE(one_per_stratum(first, std::size_t{1} << m)) << "dimension " << j + 1 << ", m = " << m;
    }
  }
  // Distinct dimensions.
  std::set<std::vector<double>> columns;
  for (std::size_t j = 0; j < dims; ++j) columns.insert(column(pts, j));
  EXPECT_EQ(columns.size(), dims);
}

TEST(Sobol, DesignStratificationWithSkippedOrigin) {
  // Unscrambled: the origin plus the first 2^m - 1 runs fill every elementary interval of length 2^-m.
  const Design d = make_design(spec_of(DesignKind::Sobol, unit_cube(21), 255));
  for (std::size_t j = 0; j < 21; ++j)
    for (std::size_t m = 1; m <= 8; ++m) {
      std::vector<double> u = {0.0};
      for (std::size_t i = 0; i + 1 < (std::size_t{1} << m); ++i) u.push_back(d.unit[i][j]);
      EXPECT_TRUE(one_per_stratum(u, std::size_t{1} << m)) << "dimension " << j + 1 << ", m = " << m;
    }
}

TEST(Sobol, FirstTwoDimensionsFormA0m2Net) {
  // Dimensions 1 and 2 of Sobol's sequence are a (0,2)-sequence: the first 2^m points have exactly one point in
  // every dyadic box of area 2^-m. Scrambling (linear matrix scramble + digital shift) preserves this.
  for (bool scramble : {false, true}) {
    const auto pts = sobol_points(256, 2, 0, scramble, 99);
    for (std::size_t m = 1; m <= 8; ++m)
      for (std::size_t k1 = 0; k1 <= m; ++k1) {
        const std::size_t k2 = m - k1;
        std::map<std::pair<std::size_t, std::size_t>, int> boxes;
        for (std::size_t i = 0; i < (std::size_t{1} << m); ++i)
          ++boxes[{static_cast<std::size_t>(std::ldexp(pts[i][0], static_cast<int>(k1))),
                   static_cast<std::size_t>(std::ldexp(pts[i][1], static_cast<int>(k2)))}];
        EXPECT_EQ(boxes.size(), std::size_t{1} << m) << "scramble " << scramble << ", m " << m << ", k1 " << k1;
      }
  }
}

TEST(Sobol, ScrambledIsDeterministicStratifiedAndDiffersBySeed) {
  const Design a = make_design(spec_of(DesignKind::Sobol, unit_cube(8), 256, 5, true));
  const Design b = make_design(spec_of(DesignKind::Sobol, unit_cube(8), 256, 5, true));
  const Design c = make_design(spec_of(DesignKind::Sobol, unit_cube(8), 256, 6, true));
  EXPECT_EQ(a.unit, b.unit);
  EXPECT_NE(a.unit, c.unit);
  for (std::size_t j = 0; j < 8; ++j)
    for (std::size_t m = 1; m <= 8; ++m) {
      std::vector<double> u;
      for (std::size_t i = 0; i < (std::size_t{1} << m); ++i) u.push_back(a.unit[i][j]);
      EXPECT_TRUE(one_per_stratum(u, std::size_t{1} << m)) << "dimension " << j + 1 << ", m = " << m;
    }
  // Not the unscrambled sequence.
  EXPECT_NE(a.unit, make_design(spec_of(DesignKind::Sobol, unit_cube(8), 256)).unit);
}

TEST(Sobol, IntegratesSmoothFunctionFarBetterThanMonteCarlo) {
  // f(x) = exp((x_1 + ... + x_5) / 5) over the unit cube: integral (5 (e^(1/5) - 1))^5, variance
  // (5/2 (e^(2/5) - 1))^5 - integral^2 (standard deviation 0.22: Monte Carlo error ~1e-2 with 2^10 points).
  const std::size_t n = 1024, dims = 5;
  const double integral = std::pow(5 * (std::exp(0.2) - 1), 5);
  const double variance = std::pow(2.5 * (std::exp(0.4) - 1), 5) - integral * integral;
  auto error = [&](const Design& d) {
    double s = 0;
    for (const auto& row : d.values) {
      double sum = 0;
      for (double x : row) sum += x;
      s += std::exp(sum / 5);
    }
    return std::abs(s / static_cast<double>(d.runs()) - integral);
  };
  const double sobol_error = error(make_design(spec_of(DesignKind::Sobol, unit_cube(dims), n)));
  const double scrambled_error = error(make_design(spec_of(DesignKind::Sobol, unit_cube(dims), n, 3, true)));
  double mc_ms = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const double e = error(make_design(spec_of(DesignKind::MonteCarlo, unit_cube(dims), n, seed)));
    mc_ms += e * e / 20;
  }
  const double mc_se = std::sqrt(variance / static_cast<double>(n));  // 6.9e-3
  EXPECT_LT(sobol_error, 1e-3);
  EXPECT_LT(scrambled_error, 1e-3);
  EXPECT_GT(std::sqrt(mc_ms), 0.5 * mc_se);  // Monte Carlo really is at the 1e-2 level ...
  EXPECT_LT(sobol_error, 0.1 * mc_se);       // ... and Sobol far below it
  EXPECT_LT(scrambled_error, 0.1 * mc_se);
}

// ---------------------------------------------------------------------------------------------------------------
// Halton

TEST(Halton, KnownFirstValuesInBases2And3And5) {
  const Design d = make_design(spec_of(DesignKind::Halton, unit_cube(3), 8));
  const std::vector<double> base2 = {1. / 2, 1. / 4, 3. / 4, 1. / 8, 5. / 8, 3. / 8, 7. / 8, 1. / 16};
  const std::vector<double> base3 = {1. / 3, 2. / 3, 1. / 9, 4. / 9, 7. / 9, 2. / 9, 5. / 9, 8. / 9};
  const std::vector<double> base5 = {1. / 5, 2. / 5, 3. / 5, 4. / 5, 1. / 25, 6. / 25, 11. / 25, 16. / 25};
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_DOUBLE_EQ(d.unit[i][0], base2[i]) << "run " << i;
    EXPECT_DOUBLE_EQ(d.unit[i][1], base3[i]) << "run " << i;
    EXPECT_DOUBLE_EQ(d.unit[i][2], base5[i]) << "run " << i;
  }
  EXPECT_EQ(nth_prime(0), 2u);
  EXPECT_EQ(nth_prime(5), 13u);
  EXPECT_EQ(nth_prime(99), 541u);
  EXPECT_EQ(radical_inverse(0, 7), 0.0);
  EXPECT_DOUBLE_EQ(radical_inverse(1, 7), 1.0 / 7);
  EXPECT_DOUBLE_EQ(radical_inverse(8, 7), 1.0 / 7 + 1.0 / 49);
}

TEST(Halton, StratifiedInEachBaseScrambledOrNot) {
  const std::size_t dims = 4;  // bases 2, 3, 5, 7
  const std::vector<std::size_t> bases = {2, 3, 5, 7};
  const Design plain = make_design(spec_of(DesignKind::Halton, unit_cube(dims), 400));
  const Design scr = make_design(spec_of(DesignKind::Halton, unit_cube(dims), 400, 11, true));
  const Design scr2 = make_design(spec_of(DesignKind::Halton, unit_cube(dims), 400, 11, true));
  const Design scr3 = make_design(spec_of(DesignKind::Halton, unit_cube(dims), 400, 12, true));
  EXPECT_EQ(scr.unit, scr2.unit);
  EXPECT_NE(scr.unit, scr3.unit);
  EXPECT_NE(scr.unit, plain.unit);
  for (std::size_t j = 0; j < dims; ++j)
    for (std::size_t strata = bases[j]; strata <= 400; strata *= bases[j]) {
      std::vector<double> u = {0.0};  // unscrambled: the skipped origin plus the first b^m - 1 runs
      for (std::size_t i = 0; i + 1 < strata; ++i) u.push_back(plain.unit[i][j]);
      EXPECT_TRUE(one_per_stratum(u, strata, 1e-12)) << "base " << bases[j] << ", strata " << strata;
      std::vector<double> s;  // scrambled: the first b^m runs (from index 0)
      for (std::size_t i = 0; i < strata; ++i) s.push_back(scr.unit[i][j]);
      EXPECT_TRUE(one_per_stratum(s, strata, 1e-12)) << "scrambled, base " << bases[j] << ", strata " << strata;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Monte Carlo

TEST(MonteCarlo, NormalMeanAndStdWithinThreeStandardErrors) {
  const std::size_t n = 20000;
  const Design d = make_design(spec_of(DesignKind::MonteCarlo, {normal("bearings.k", 10.0, 2.0)}, n, 2024));
  const auto v = column(d.values, 0);
  const double se_mean = 2.0 / std::sqrt(static_cast<double>(n));
  const double se_sd = 2.0 / std::sqrt(2.0 * static_cast<double>(n - 1));
  EXPECT_NEAR(mean_of(v), 10.0, 3 * se_mean);
  EXPECT_NEAR(sd_of(v), 2.0, 3 * se_sd);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_TRUE(d.unit[i][0] >= 0 && d.unit[i][0] < 1);
    ASSERT_EQ(v[i], d.values[i][0]);
  }
  // Reproducible with the seed, different with another.
  EXPECT_EQ(make_design(spec_of(DesignKind::MonteCarlo, {normal("bearings.k", 10.0, 2.0)}, n, 2024)).values,
            d.values);
  EXPECT_NE(make_design(spec_of(DesignKind::MonteCarlo, {normal("bearings.k", 10.0, 2.0)}, n, 2025)).values,
            d.values);
}

TEST(MonteCarlo, TruncatedNormalStaysInBoundsWithTheAnalyticMean) {
  const std::size_t n = 20000;
  auto phi = [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * pi); };
  struct Case {
    double mean, std, low, high;
  };
  for (const Case c : {Case{0, 1, -0.5, 2}, Case{100, 5, 125, 130}, Case{0, 1, -30, -29}, Case{3, 1, -1, 3}}) {
    const Design d =
        make_design(spec_of(DesignKind::MonteCarlo, {normal("oil.viscosity", c.mean, c.std, c.low, c.high)}, n, 9));
    const auto v = column(d.values, 0);
    for (double x : v) ASSERT_TRUE(x >= c.low && x <= c.high) << x;
    const double a = (c.low - c.mean) / c.std, b = (c.high - c.mean) / c.std;
    // Mean of the truncated normal: mean + std (phi(a) - phi(b)) / (Phi(b) - Phi(a)).
    const double mass = a >= 0 ? normal_cdf(-a) - normal_cdf(-b) : normal_cdf(b) - normal_cdf(a);
    const double mu = c.mean + c.std * (phi(a) - phi(b)) / mass;
    EXPECT_NEAR(mean_of(v), mu, 4 * sd_of(v) / std::sqrt(static_cast<double>(n))) << "[" << c.low << ", " << c.high << "]";
  }
}

TEST(MonteCarlo, LogUniformStaysInBoundsAndItsLogIsUniform) {
  const std::size_t n = 20000;
  const double lo = 1e-3, hi = 1e3;
  const Design d = make_design(spec_of(DesignKind::MonteCarlo, {log_uniform("bearings.c", lo, hi)}, n, 77));
  std::vector<double> t;
  for (const auto& row : d.values) {
    ASSERT_TRUE(row[0] >= lo && row[0] <= hi);
    t.push_back((std::log(row[0]) - std::log(lo)) / (std::log(hi) - std::log(lo)));
  }
  std::sort(t.begin(), t.end());
  double ks = 0;  // Kolmogorov-Smirnov distance to U(0,1)
  for (std::size_t i = 0; i < n; ++i) {
    const double dn = static_cast<double>(n);
    ks = std::max({ks, std::abs(static_cast<double>(i + 1) / dn - t[i]), std::abs(t[i] - static_cast<double>(i) / dn)});
  }
  EXPECT_LT(ks, 1.63 / std::sqrt(static_cast<double>(n)));  // 1 % critical value
  // The median is the geometric mean of the bounds, 1 (a uniform would have 500).
  std::vector<double> v = column(d.values, 0);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2), v.end());
  EXPECT_NEAR(std::log10(v[n / 2]), 0.0, 0.05);
}

// ---------------------------------------------------------------------------------------------------------------
// Table

TEST(Table, RowsAsGivenUnitNaN) {
  DesignSpec s = spec_of(DesignKind::Table, {uniform("a", 0, 1), uniform("b", 0, 1)});
  s.table = {{1, 2}, {3, 4}, {5, 6}};
  const Design d = make_design(s);
  EXPECT_EQ(d.values, s.table);
  ASSERT_EQ(d.unit.size(), 3u);
  for (const auto& row : d.unit)
    for (double u : row) EXPECT_TRUE(std::isnan(u));
}

// ---------------------------------------------------------------------------------------------------------------
// Shards

TEST(Shards, UnionIsEveryRunExactlyOnce) {
  for (std::size_t total : {0u, 1u, 7u, 100u, 1001u})
    for (std::size_t n : {1u, 2u, 3u, 8u, 150u}) {
      std::vector<int> hits(total, 0);
      for (std::size_t k = 0; k < n; ++k) {
        const auto s = shard_indices(total, k, n);
        EXPECT_TRUE(std::is_sorted(s.begin(), s.end()));
        for (std::size_t i : s) {
          ASSERT_LT(i, total);
          EXPECT_EQ(i % n, k);
          ++hits[i];
        }
      }
      for (std::size_t i = 0; i < total; ++i) EXPECT_EQ(hits[i], 1) << "total " << total << ", n " << n << ", i " << i;
    }
  EXPECT_EQ(shard_indices(10, 2, 4), (std::vector<std::size_t>{2, 6}));
  EXPECT_THROW(shard_indices(10, 4, 4), std::invalid_argument);
  EXPECT_THROW(shard_indices(10, 0, 0), std::invalid_argument);
  const std::size_t big = std::numeric_limits<std::size_t>::max();
  EXPECT_EQ(shard_indices(big, big - 1, big), (std::vector<std::size_t>{big - 1}));  // no overflow
}

// ---------------------------------------------------------------------------------------------------------------
// Sensitivity

TEST(StandardizedRegression, LinearModelRanksAndMatchesAnalyticSRC) {
  const Design d = make_design(spec_of(DesignKind::LatinHypercube,
                                       {uniform("x1", 0, 1), uniform("x2", 0, 2), uniform("x3", -1, 1)}, 500, 3));
  std::vector<double> y;
  for (std::size_t i = 0; i < d.runs(); ++i)
    y.push_back(3 * d.values[i][0] - 1 * d.values[i][1] + 0 * d.values[i][2] +
                1e-4 * std::sin(1.7 * static_cast<double>(i)));
  const Sensitivity s = standardized_regression(d.values, y);
  ASSERT_EQ(s.src.size(), 3u);
  EXPECT_GT(std::abs(s.src[0]), std::abs(s.src[1]));
  EXPECT_GT(std::abs(s.src[1]), std::abs(s.src[2]));
  EXPECT_GT(s.r_squared, 0.99999);
  EXPECT_LE(s.r_squared, 1.0 + 1e-12);
  // Against the sample standard deviations: SRC_j = b_j sd_j / sd_y.
  const double sy = sd_of(y);
  EXPECT_NEAR(s.src[0], 3 * sd_of(column(d.values, 0)) / sy, 1e-3);
  EXPECT_NEAR(s.src[1], -1 * sd_of(column(d.values, 1)) / sy, 1e-3);
  EXPECT_NEAR(s.src[2], 0.0, 1e-3);
  // Against the population values sd1 = 1/sqrt(12), sd2 = 2/sqrt(12), sd_y = sqrt(13/12), up to the chance
  // correlation of the LHS columns (~1/sqrt(500)).
  EXPECT_NEAR(s.src[0], 3 / std::sqrt(13.0), 0.05);
  EXPECT_NEAR(s.src[1], -2 / std::sqrt(13.0), 0.05);
}

TEST(StandardizedRegression, NoisyModelRSquaredAndSkippedRuns) {
  const Design d = make_design(spec_of(DesignKind::MonteCarlo, {uniform("a", 0, 1), uniform("b", 0, 1),
                                                                 uniform("noise", -1, 1)}, 4000, 5));
  std::vector<double> y;
  for (const auto& r : d.values) y.push_back(r[0] + 2 * r[1] + r[2]);
  // The "noise" column is a parameter here, so the fit is exact; drop it to make it noise.
  std::vector<std::vector<double>> x2;
  for (const auto& r : d.values) x2.push_back({r[0], r[1]});
  const Sensitivity s = standardized_regression(x2, y);
  // Var: 1/12 + 4/12 + 4/12 = 9/12; explained 5/12 -> R^2 = 5/9.
  EXPECT_NEAR(s.r_squared, 5.0 / 9.0, 0.03);
  EXPECT_NEAR(s.src[0], std::sqrt(1.0 / 9.0), 0.03);
  EXPECT_NEAR(s.src[1], std::sqrt(4.0 / 9.0), 0.03);
  // Runs with non-finite y are skipped: same result as without them.
  std::vector<std::vector<double>> xs = x2;
  std::vector<double> ys = y;
  xs.push_back({0.5, 0.5});
  ys.push_back(nan);
  xs.insert(xs.begin(), {0.1, 0.9});
  ys.insert(ys.begin(), inf);
  const Sensitivity t = standardized_regression(xs, ys);
  EXPECT_NEAR(t.r_squared, s.r_squared, 1e-12);
  EXPECT_NEAR(t.src[0], s.src[0], 1e-12);
  EXPECT_NEAR(t.src[1], s.src[1], 1e-12);
}

TEST(StandardizedRegression, ConstantColumnAndErrors) {
  std::vector<std::vector<double>> x = {{1, 5}, {2, 5}, {3, 5}, {4, 5}, {5, 5}};
  std::vector<double> y = {2, 4.1, 5.9, 8, 10};
  const Sensitivity s = standardized_regression(x, y);
  EXPECT_EQ(s.src[1], 0.0);
  EXPECT_GT(s.src[0], 0.99);
  // Fewer usable runs than parameters + 2.
  EXPECT_THROW(standardized_regression({{1, 2}, {2, 1}, {3, 3}}, {1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(standardized_regression({{1, 2}, {2, 1}, {3, 3}, {4, 4}}, {1, 2, 3, nan}), std::invalid_argument);
  // Size mismatches and collinear columns.
  EXPECT_THROW(standardized_regression({{1}, {2}, {3}}, {1, 2}), std::invalid_argument);
  EXPECT_THROW(standardized_regression({{1}, {2, 3}, {3}}, {1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(standardized_regression({{1, 2}, {2, 4}, {3, 6}, {4, 8}, {5, 10}}, {1, 3, 2, 5, 4}),
               std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------------------
// Errors: std::invalid_argument naming the parameter and the problem.

void expect_error(const DesignSpec& spec, const std::vector<std::string>& fragments) {
  try {
    (void)make_design(spec);
    ADD_FAILURE() << "no exception, expected one mentioning " << fragments.front();
  } catch (const std::invalid_argument& e) {
    for (const auto& f : fragments) EXPECT_THAT(e.what(), HasSubstr(f));
  }
}

TEST(Errors, EveryCaseNamesTheParameterAndProblem) {
  const Parameter good = uniform("disks.turbine.unbalance", 0, 1e-6);
  expect_error(spec_of(DesignKind::MonteCarlo, {}, 10), {"no parameters"});
  expect_error(spec_of(DesignKind::MonteCarlo, {good, uniform("bearings.k", 0, 1), good}, 10),
               {"duplicate", "disks.turbine.unbalance"});
  expect_error(spec_of(DesignKind::MonteCarlo, {good, uniform("", 0, 1)}, 10), {"empty path"});
  expect_error(spec_of(DesignKind::MonteCarlo, {good, uniform("bearings.k", 2, 1)}, 10), {"bearings.k", "low >= high"});
  expect_error(spec_of(DesignKind::LatinHypercube, {uniform("bearings.k", 1, 1)}, 10), {"bearings.k", "low >= high"});
  expect_error(spec_of(DesignKind::Sobol, {log_uniform("bearings.c", 0, 1)}, 10), {"bearings.c", "low > 0"});
  expect_error(spec_of(DesignKind::Sobol, {log_uniform("bearings.c", 5, 1)}, 10), {"bearings.c", "low >= high"});
  expect_error(spec_of(DesignKind::Halton, {normal("oil.t", 300, 0)}, 10), {"oil.t", "std > 0"});
  expect_error(spec_of(DesignKind::Halton, {normal("oil.t", 300, -1)}, 10), {"oil.t", "std > 0"});
  expect_error(spec_of(DesignKind::Halton, {normal("oil.t", 300, 1, 310, 305)}, 10), {"oil.t", "low"});
  expect_error(spec_of(DesignKind::Halton, {normal("oil.t", 0, 1, 50, 60)}, 10), {"oil.t", "zero probability"});
  expect_error(spec_of(DesignKind::MonteCarlo, {levels("variant", {})}, 10), {"variant", "empty levels"});
  expect_error(spec_of(DesignKind::FullFactorial, {levels("variant", {1, 2}), uniform("bearings.k", 1, 2)}),
               {"bearings.k", "n_levels >= 2"});
  expect_error(spec_of(DesignKind::FullFactorial, {uniform("bearings.k", 1, 2, 1)}), {"bearings.k", "n_levels"});
  expect_error(spec_of(DesignKind::FullFactorial, {log_uniform("bearings.c", 1, 2, 0)}), {"bearings.c", "n_levels"});
  Parameter untruncated = normal("oil.t", 300, 5);
  untruncated.distribution.n_levels = 3;
  expect_error(spec_of(DesignKind::FullFactorial, {untruncated}), {"oil.t", "truncation"});
  for (DesignKind k : {DesignKind::LatinHypercube, DesignKind::Sobol, DesignKind::Halton, DesignKind::MonteCarlo})
    expect_error(spec_of(k, {good}, 0), {"runs", "disks.turbine.unbalance"});
  expect_error(spec_of(DesignKind::Sobol, unit_cube(sobol_max_dimensions() + 1), 10),
               {"Sobol", "x" + std::to_string(sobol_max_dimensions())});
  EXPECT_NO_THROW(make_design(spec_of(DesignKind::Sobol, unit_cube(sobol_max_dimensions()), 10)));
  // Non-finite numbers.
  expect_error(spec_of(DesignKind::MonteCarlo, {levels("variant", {1, nan})}, 10), {"variant", "not finite"});
  expect_error(spec_of(DesignKind::MonteCarlo, {uniform("bearings.k", -inf, 1)}, 10), {"bearings.k", "not finite"});
  expect_error(spec_of(DesignKind::MonteCarlo, {normal("oil.t", nan, 1)}, 10), {"oil.t", "mean"});
  expect_error(spec_of(DesignKind::MonteCarlo, {normal("oil.t", 1, inf)}, 10), {"oil.t", "std"});
  // Tables.
  DesignSpec t = spec_of(DesignKind::Table, {uniform("a.x", 0, 1), uniform("b.y", 0, 1)});
  t.table = {{1, 2}, {3}};
  expect_error(t, {"row 1", "a.x", "b.y"});
  t.table = {{1, 2}, {3, nan}};
  expect_error(t, {"row 1", "b.y", "not finite"});
  t.table = {};
  expect_error(t, {"no rows", "a.x"});
}

}  // namespace
}  // namespace turbodyn::studies

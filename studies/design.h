#pragma once
// Design of experiments for parameter sweeps of a rotor model.
//
// Each parameter is named by a path string into the model ("disks.turbine.unbalance", "bearings.compressor.k")
// and varies by a Distribution. make_design() turns a DesignSpec into a table of runs (rows) x parameters
// (columns) of SI values, together with the [0,1) "unit" coordinate every value came from (for scatter plots and
// sensitivity measures). Everything is deterministic and identical on every platform: random numbers are the raw
// 64-bit output of std::mt19937_64 (whose sequence the standard fixes) turned into doubles and integers by the
// transforms in design.cpp, never by the implementation-defined std:: distributions.
//
// Designs
//   FullFactorial   every combination of the parameters' levels, the LAST parameter varying fastest. A Levels
//                   parameter uses its list; Uniform uses n_levels evenly spaced values from low to high (both
//                   ends included); LogUniform n_levels geometrically spaced values from low to high (ends
//                   included); Normal n_levels evenly spaced values over its truncation range [low, high] (a
//                   Normal without truncation has no finite range and is rejected). The unit coordinate of
//                   level i of n is the midpoint (i + 0.5) / n of its stratum. spec.runs is ignored.
//   LatinHypercube  n = spec.runs runs; in every column the unit coordinates have exactly one point in each stratum
//                   [i/n, (i+1)/n), placed uniformly at random within the stratum, with an independent random
//                   permutation of the strata per column (McKay, Beckman & Conover 1979).
//   Sobol           Sobol' sequence, Gray-code construction (Antonov & Saleev 1979) with the direction numbers
//                   of Joe & Kuo, file new-joe-kuo-6.21201 (S. Joe and F. Y. Kuo, "Constructing Sobol sequences
//                   with better two-dimensional projections", SIAM J. Sci. Comput. 30, 2635-2654 (2008);
//                   https://web.maths.unsw.edu.au/~fkuo/sobol/), dimensions 1..sobol_max_dimensions() (53).
//                   32-bit digits: at most 2^32 points.
//   Halton          radical inverses in the first primes 2, 3, 5, 7, ... as bases, one per parameter.
//   MonteCarlo      independent uniform unit coordinates (53-bit), one random stream per column.
//   Table           the rows of spec.table as given (SI values); distributions are not used, unit is NaN.
//
// Skipping the first point (Sobol and Halton): an UNSCRAMBLED sequence starts at index 1, i.e. the origin
// (index 0, where every coordinate is 0 and an unbounded distribution's quantile is -infinity) is skipped, so
// run i is sequence point i + 1 and the published first points 1/2, 3/4, 1/4, ... (Sobol) and 1/2, 1/4, 3/4, ...
// (Halton base 2) are the first runs. Note that the stratification of the first 2^m Sobol points then holds for
// the origin plus the first 2^m - 1 runs. A SCRAMBLED sequence starts at index 0 (Owen 2020, "On dropping the
// first Sobol' point": scrambling moves the origin to a random interior point, and keeping it keeps the net
// property of the first 2^m runs).
//
// Scrambling (spec.scramble, from spec.seed, deterministic):
//   Sobol   Matousek's random linear matrix scramble (a random lower-triangular binary matrix with unit diagonal,
//           applied to the direction numbers) followed by a random digital shift (XOR), independently per
//           dimension. Every elementary-interval (net) property of the unscrambled sequence is preserved.
//   Halton  random digit permutation: for every base and every digit position an independent random permutation
//           of the digits 0..b-1 (Owen-type "random permutation" scramble of the radical inverse, using
//           floor(53 log 2 / log b) digits). Preserves the 1-D stratification in base b.
// The random streams are per column (seeded from spec.seed and the column index), so adding parameters at the
// end of a spec does not change the earlier columns.
//
// Quantiles (Distribution::quantile): inverse CDF of u in [0,1).
//   Levels      level floor(u * n) (u = 1 is taken as the last level)
//   Uniform     low + u (high - low)
//   LogUniform  exp(log low + u (log high - log low)), clamped to [low, high]
//   Normal      mean + std * Phi^-1(u), u clamped to [2^-53, 1 - 2^-53] (about +-8.1 std) when untruncated;
//               truncated to [low, high] when low < high (inverse CDF of the truncated distribution, computed in
//               the tail that keeps precision; exactly in [low, high]). low == high means "not truncated".
//   Phi^-1 is Acklam's rational approximation refined by Halley steps on erfc (relative error ~1e-15).
//
// Errors: make_design() throws std::invalid_argument naming the parameter (path) and the problem.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace turbodyn::studies {

struct Distribution {  // how one parameter varies
  enum class Kind {
    Levels,     // explicit list
    Uniform,    // [low, high]
    Normal,     // mean, std, optionally truncated to [low, high]
    LogUniform  // [low, high], low > 0
  } kind = Kind::Uniform;
  std::vector<double> levels;  // Levels
  double low = 0, high = 0;    // Uniform, LogUniform, Normal truncation (if low < high)
  double mean = 0, std = 0;    // Normal
  int n_levels = 0;            // full factorial of a continuous range: this many evenly spaced levels incl. the ends

  // Maps u in [0,1) to a value (inverse CDF; Levels: picks level floor(u * n)). Throws std::invalid_argument for
  // an invalid distribution or u outside [0, 1] / NaN.
  double quantile(double u) const;
};

struct Parameter {
  std::string path;
  Distribution distribution;
};

enum class DesignKind { FullFactorial, LatinHypercube, Sobol, Halton, MonteCarlo, Table };

struct DesignSpec {
  DesignKind kind = DesignKind::FullFactorial;
  std::vector<Parameter> parameters;
  std::size_t runs = 0;    // LHS, Sobol, Halton, MonteCarlo: number of runs (FullFactorial and Table: ignored)
  std::uint64_t seed = 1;  // LHS, MonteCarlo, and the scrambling of Sobol/Halton
  bool scramble = false;   // Sobol/Halton: see above
  std::vector<std::vector<double>> table;  // Table: rows x parameters (values in SI)
};

struct Design {
  std::vector<std::string> paths;           // parameter paths (columns)
  std::vector<std::vector<double>> values;  // runs x parameters
  std::vector<std::vector<double>> unit;    // runs x parameters: the [0,1) coordinate of each value, NaN for Table

  std::size_t runs() const { return values.size(); }
};

// Throws std::invalid_argument with a message naming the parameter and the problem: no parameters, empty or
// duplicate paths, low >= high, low <= 0 for LogUniform, std <= 0, empty levels, n_levels < 2 for a full
// factorial of a range, an untruncated Normal in a full factorial, runs == 0, too many runs or dimensions for
// Sobol, a table row length mismatch or an empty table, non-finite numbers.
Design make_design(const DesignSpec& spec);

// Deterministic slice for cluster jobs: the run indices i < total_runs with i % n == k, ascending.
// Throws std::invalid_argument for n == 0 or k >= n.
std::vector<std::size_t> shard_indices(std::size_t total_runs, std::size_t k, std::size_t n);

// Sensitivity: standardised regression coefficients (SRC) of a metric y on the parameters x, i.e. the least-squares
// coefficients after centring every variable and scaling it to unit sample standard deviation, with the R^2 of
// the fit. Runs with a non-finite y or a non-finite x value are skipped. A parameter column that is constant over
// the used runs gets SRC 0 and is left out of the fit; a constant y gives all SRC 0 and R^2 = NaN.
// Throws std::invalid_argument if x and y differ in length, the rows of x differ in length or are empty, fewer
// usable runs than parameters + 2 remain, or the (non-constant) columns are collinear.
struct Sensitivity {
  std::vector<double> src;
  double r_squared = 0;
};
Sensitivity standardized_regression(const std::vector<std::vector<double>>& x /*runs x params*/,
                                    const std::vector<double>& y /*runs*/);

// Response surface: the full quadratic polynomial in all parameters (constant, linear, squares and products),
// fitted to a metric by least squares on parameters scaled to [-1, 1] over [lo, hi] (Myers & Montgomery, Response
// Surface Methodology, ch. 2), with its R^2. Runs with a non-finite value are skipped. Throws
// std::invalid_argument if the sizes differ, lo >= hi for a parameter, or fewer usable runs than terms + 3 remain.
struct QuadraticSurface {
  std::vector<double> lo, hi;  ///< scaling of each parameter
  std::vector<double> coef;    ///< 1, u_i (i < p), u_i u_j (i <= j), in that order
  double r_squared = 0;
  std::size_t runs = 0;        ///< runs the fit used
  double operator()(const std::vector<double>& x) const;
};
QuadraticSurface fit_quadratic_surface(const std::vector<std::vector<double>>& x /*runs x params*/,
                                       const std::vector<double>& y, const std::vector<double>& lo,
                                       const std::vector<double>& hi);

// ---- Building blocks (also used by the tests) ----

// Standard normal CDF and its inverse (p <= 0 -> -inf, p >= 1 -> +inf, NaN -> NaN).
double normal_cdf(double z);
double normal_quantile(double p);

// Number of dimensions with Joe-Kuo direction numbers built in.
std::size_t sobol_max_dimensions();
// Points first_index .. first_index + n - 1 of the Sobol sequence in `dims` dimensions (n x dims, values
// k / 2^32). Index 0 is the origin when unscrambled. Throws std::invalid_argument for dims == 0, dims >
// sobol_max_dimensions() or indices beyond 2^32 - 1.
std::vector<std::vector<double>> sobol_points(std::size_t n, std::size_t dims, std::uint64_t first_index = 0,
                                              bool scramble = false, std::uint64_t seed = 1);

// The i-th prime (0 -> 2, 1 -> 3, 2 -> 5, ...).
std::uint32_t nth_prime(std::size_t i);
// Radical inverse of index in base b >= 2 (van der Corput): digits of index mirrored about the radix point.
double radical_inverse(std::uint64_t index, std::uint32_t base);
// Points first_index .. first_index + n - 1 of the Halton sequence in `dims` dimensions (bases nth_prime(0..)).
// Index 0 is the origin when unscrambled.
std::vector<std::vector<double>> halton_points(std::size_t n, std::size_t dims, std::uint64_t first_index = 0,
                                               bool scramble = false, std::uint64_t seed = 1);

}  // namespace turbodyn::studies

#include "studies/design.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/QR>

namespace turbodyn::studies {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------------------------
// Messages

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument("make_design: " + message); }

std::string who(const std::string& path) { return "parameter '" + path + "'"; }

const char* kind_name(Distribution::Kind k) {
  switch (k) {
    case Distribution::Kind::Levels: return "Levels";
    case Distribution::Kind::Uniform: return "Uniform";
    case Distribution::Kind::Normal: return "Normal";
    case Distribution::Kind::LogUniform: return "LogUniform";
  }
  return "unknown";
}

const char* design_name(DesignKind k) {
  switch (k) {
    case DesignKind::FullFactorial: return "FullFactorial";
    case DesignKind::LatinHypercube: return "LatinHypercube";
    case DesignKind::Sobol: return "Sobol";
    case DesignKind::Halton: return "Halton";
    case DesignKind::MonteCarlo: return "MonteCarlo";
    case DesignKind::Table: return "Table";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------------------------------------------
// Validation of one distribution. `subject` names the parameter ("parameter 'a.b'") in messages.

void require_finite(double v, const char* field, const std::string& subject) {
  if (!std::isfinite(v)) fail(subject + ": " + field + " is not finite (" + fmt(v) + ")");
}

// Probability mass of the truncation interval of a Normal, computed in the tail that keeps precision.
double truncated_mass(const Distribution& d) {
  const double a = (d.low - d.mean) / d.std, b = (d.high - d.mean) / d.std;
  if (a >= 0) return normal_cdf(-a) - normal_cdf(-b);
  return normal_cdf(b) - normal_cdf(a);
}

void validate(const Distribution& d, const std::string& subject, bool full_factorial) {
  const std::string kind = kind_name(d.kind);
  auto need_levels = [&] {
    if (!full_factorial) return;
    if (d.n_levels < 2)
      fail(subject + ": a full factorial of a " + kind + " range needs n_levels >= 2 (got " +
           std::to_string(d.n_levels) + ")");
  };
  switch (d.kind) {
    case Distribution::Kind::Levels:
      if (d.levels.empty()) fail(subject + ": Levels distribution has empty levels");
      for (std::size_t i = 0; i < d.levels.size(); ++i)
        if (!std::isfinite(d.levels[i]))
          fail(subject + ": level " + std::to_string(i) + " is not finite (" + fmt(d.levels[i]) + ")");
      return;
    case Distribution::Kind::Uniform:
    case Distribution::Kind::LogUniform:
      require_finite(d.low, "low", subject);
      require_finite(d.high, "high", subject);
      if (d.kind == Distribution::Kind::LogUniform && !(d.low > 0))
        fail(subject + ": LogUniform needs low > 0 (got low = " + fmt(d.low) + ")");
      if (!(d.low < d.high))
        fail(subject + ": " + kind + " needs low < high, got low >= high (low = " + fmt(d.low) + ", high = " +
             fmt(d.high) + ")");
      need_levels();
      return;
    case Distribution::Kind::Normal:
      require_finite(d.mean, "mean", subject);
      require_finite(d.std, "std", subject);
      require_finite(d.low, "low", subject);
      require_finite(d.high, "high", subject);
      if (!(d.std > 0)) fail(subject + ": Normal needs std > 0 (got std = " + fmt(d.std) + ")");
      if (d.low > d.high)
        fail(subject + ": Normal truncation needs low < high (or low == high for none), got low = " + fmt(d.low) +
             " > high = " + fmt(d.high));
      if (d.low < d.high && !(truncated_mass(d) > 0))
        fail(subject + ": Normal truncation interval [" + fmt(d.low) + ", " + fmt(d.high) +
             "] has zero probability for mean = " + fmt(d.mean) + ", std = " + fmt(d.std));
      if (full_factorial && !(d.low < d.high))
        fail(subject + ": a full factorial of a Normal needs the truncation range low < high (got low = " +
             fmt(d.low) + ", high = " + fmt(d.high) + ")");
      need_levels();
      return;
  }
  fail(subject + ": unknown distribution kind " + std::to_string(static_cast<int>(d.kind)));
}

// ---------------------------------------------------------------------------------------------------------------
// Random numbers: raw std::mt19937_64 output (fixed by the standard) and our own transforms.

std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

enum class Purpose : std::uint64_t { LatinHypercube = 1, MonteCarlo = 2, SobolScramble = 3, HaltonScramble = 4 };

// Independent stream per (seed, purpose, column).
std::mt19937_64 stream(std::uint64_t seed, Purpose purpose, std::size_t column) {
  const std::uint64_t s =
      splitmix64(splitmix64(seed ^ (static_cast<std::uint64_t>(purpose) * 0xd1b54a32d192ed03ULL)) +
                 static_cast<std::uint64_t>(column));
  return std::mt19937_64(s);
}

// Uniform in [0,1) with 53 random bits.
double uniform53(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Uniform integer in [0, n), n >= 1, by rejection (no modulo bias).
std::uint64_t below(std::mt19937_64& rng, std::uint64_t n) {
  const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
  for (;;) {
    const std::uint64_t r = rng();
    if (r >= threshold) return r % n;
  }
}

template <class T>
void shuffle(std::vector<T>& v, std::mt19937_64& rng) {  // Fisher-Yates
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[below(rng, i)]);
}

// ---------------------------------------------------------------------------------------------------------------
// Sobol direction numbers: S. Joe and F. Y. Kuo, new-joe-kuo-6.21201, dimensions 2..53 (dimension 1 is the van der
// Corput sequence in base 2, all m_i = 1). Columns: degree s of the primitive polynomial, its coefficients a
// (interior coefficients as bits, highest first), initial direction numbers m_1..m_s.
// Source: https://web.maths.unsw.edu.au/~fkuo/sobol/new-joe-kuo-6.21201 and S. Joe, F. Y. Kuo, SIAM J. Sci.
// Comput. 30 (2008) 2635-2654.

struct JoeKuo {
  unsigned s;
  unsigned a;
  std::array<std::uint32_t, 8> m;
};

constexpr JoeKuo kJoeKuo[] = {
    {1, 0, {1}},                                 // d = 2
    {2, 1, {1, 3}},                              // 3
    {3, 1, {1, 3, 1}},                           // 4
    {3, 2, {1, 1, 1}},                           // 5
    {4, 1, {1, 1, 3, 3}},                        // 6
    {4, 4, {1, 3, 5, 13}},                       // 7
    {5, 2, {1, 1, 5, 5, 17}},                    // 8
    {5, 4, {1, 1, 5, 5, 5}},                     // 9
    {5, 7, {1, 1, 7, 11, 19}},                   // 10
    {5, 11, {1, 1, 5, 1, 1}},                    // 11
    {5, 13, {1, 1, 1, 3, 11}},                   // 12
    {5, 14, {1, 3, 5, 5, 31}},                   // 13
    {6, 1, {1, 3, 3, 9, 7, 49}},                 // 14
    {6, 13, {1, 1, 1, 15, 21, 21}},              // 15
    {6, 16, {1, 3, 1, 13, 27, 49}},              // 16
    {6, 19, {1, 1, 1, 15, 7, 5}},                // 17
    {6, 22, {1, 3, 1, 15, 13, 25}},              // 18
    {6, 25, {1, 1, 5, 5, 19, 61}},               // 19
    {7, 1, {1, 3, 7, 11, 23, 15, 103}},          // 20
    {7, 4, {1, 3, 7, 13, 13, 15, 69}},           // 21
    {7, 7, {1, 1, 3, 13, 7, 35, 63}},            // 22
    {7, 8, {1, 3, 5, 9, 1, 25, 53}},             // 23
    {7, 14, {1, 3, 1, 13, 9, 35, 107}},          // 24
    {7, 19, {1, 3, 1, 5, 27, 61, 31}},           // 25
    {7, 21, {1, 1, 5, 11, 19, 41, 61}},          // 26
    {7, 28, {1, 3, 5, 3, 3, 13, 69}},            // 27
    {7, 31, {1, 1, 7, 13, 1, 19, 1}},            // 28
    {7, 32, {1, 3, 7, 5, 13, 19, 59}},           // 29
    {7, 37, {1, 1, 3, 9, 25, 29, 41}},           // 30
    {7, 41, {1, 3, 5, 13, 23, 1, 55}},           // 31
    {7, 42, {1, 3, 7, 3, 13, 59, 17}},           // 32
    {7, 50, {1, 3, 1, 3, 5, 53, 69}},            // 33
    {7, 55, {1, 1, 5, 5, 23, 33, 13}},           // 34
    {7, 56, {1, 1, 7, 7, 1, 61, 123}},           // 35
    {7, 59, {1, 1, 7, 9, 13, 61, 49}},           // 36
    {7, 62, {1, 3, 3, 5, 3, 55, 33}},            // 37
    {8, 14, {1, 3, 1, 15, 31, 13, 49, 245}},     // 38
    {8, 21, {1, 3, 5, 15, 31, 59, 63, 97}},      // 39
    {8, 22, {1, 3, 1, 11, 11, 11, 77, 249}},     // 40
    {8, 38, {1, 3, 1, 11, 27, 43, 71, 9}},       // 41
    {8, 47, {1, 1, 7, 15, 21, 11, 81, 45}},      // 42
    {8, 49, {1, 3, 7, 3, 25, 31, 65, 79}},       // 43
    {8, 50, {1, 3, 1, 1, 19, 11, 3, 205}},       // 44
    {8, 52, {1, 1, 5, 9, 19, 21, 29, 157}},      // 45
    {8, 56, {1, 3, 7, 11, 1, 33, 89, 185}},      // 46
    {8, 67, {1, 3, 3, 3, 15, 9, 79, 71}},        // 47
    {8, 70, {1, 3, 7, 11, 15, 39, 119, 27}},     // 48
    {8, 84, {1, 1, 3, 1, 11, 31, 97, 225}},      // 49
    {8, 97, {1, 1, 1, 3, 23, 43, 57, 177}},      // 50
    {8, 103, {1, 3, 7, 7, 17, 17, 37, 71}},      // 51
    {8, 115, {1, 3, 1, 5, 27, 63, 123, 213}},    // 52
    {8, 122, {1, 1, 3, 5, 11, 43, 53, 133}},     // 53
};

constexpr std::size_t kSobolDims = 1 + sizeof(kJoeKuo) / sizeof(kJoeKuo[0]);
constexpr int kSobolBits = 32;

using Directions = std::array<std::uint32_t, kSobolBits>;  // V[k] = v_{k+1} * 2^32, left aligned

Directions make_directions(std::size_t dim) {
  Directions v{};
  if (dim == 0) {
    for (int k = 0; k < kSobolBits; ++k) v[static_cast<std::size_t>(k)] = std::uint32_t{1} << (31 - k);
    return v;
  }
  const JoeKuo& jk = kJoeKuo[dim - 1];
  const std::size_t s = jk.s;
  for (std::size_t k = 0; k < s; ++k) v[k] = jk.m[k] << (31 - k);
  for (std::size_t k = s; k < static_cast<std::size_t>(kSobolBits); ++k) {
    v[k] = v[k - s] ^ (v[k - s] >> s);
    for (std::size_t j = 1; j < s; ++j)
      if ((jk.a >> (s - 1 - j)) & 1u) v[k] ^= v[k - j];
  }
  return v;
}

const std::vector<Directions>& sobol_directions() {
  static const std::vector<Directions> table = [] {
    std::vector<Directions> t;
    for (std::size_t d = 0; d < kSobolDims; ++d) t.push_back(make_directions(d));
    return t;
  }();
  return table;
}

// Matousek's linear matrix scramble: y = L x over GF(2) with L random lower triangular, unit diagonal. Digit i
// (i = 0 the most significant) is bit 31 - i. Applied to each direction number (the map is linear).
Directions scramble_directions(const Directions& v, std::mt19937_64& rng) {
  std::array<std::uint32_t, kSobolBits> rows{};
  for (int i = 0; i < kSobolBits; ++i) {
    const std::uint32_t diagonal = std::uint32_t{1} << (31 - i);
    const std::uint32_t above = i == 0 ? 0u : ~std::uint32_t{0} << (32 - i);  // digits j < i
    rows[static_cast<std::size_t>(i)] = (static_cast<std::uint32_t>(rng() >> 32) & above) | diagonal;
  }
  Directions out{};
  for (std::size_t k = 0; k < v.size(); ++k) {
    std::uint32_t y = 0;
    for (int i = 0; i < kSobolBits; ++i)
      if (std::popcount(rows[static_cast<std::size_t>(i)] & v[k]) & 1) y |= std::uint32_t{1} << (31 - i);
    out[k] = y;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Normal distribution: Acklam's approximation refined by Halley steps.

double lower_tail_quantile(double p) {  // 0 < p <= 0.5
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01, -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  double x;
  if (p < 0.02425) {
    const double q = std::sqrt(-2.0 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  // Halley's method on Phi(x) - p = 0 (third order; two steps reach full double precision).
  const double sqrt_2pi = std::sqrt(2.0 * std::numbers::pi);
  for (int it = 0; it < 2; ++it) {
    const double e = normal_cdf(x) - p;
    const double u = e * sqrt_2pi * std::exp(0.5 * x * x);
    const double step = u / (1.0 + 0.5 * x * u);
    if (!std::isfinite(step)) break;
    x -= step;
  }
  return x;
}

// ---------------------------------------------------------------------------------------------------------------
// Designs

std::vector<double> column_levels(const Distribution& d) {
  if (d.kind == Distribution::Kind::Levels) return d.levels;
  const auto n = static_cast<std::size_t>(d.n_levels);
  std::vector<double> v(n);
  const bool log_spaced = d.kind == Distribution::Kind::LogUniform;
  const double lo = log_spaced ? std::log(d.low) : d.low, hi = log_spaced ? std::log(d.high) : d.high;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n - 1);
    double x = lo + (hi - lo) * t;
    if (log_spaced) x = std::exp(x);
    v[i] = std::clamp(x, d.low, d.high);
  }
  v.front() = d.low;  // the ends exactly
  v.back() = d.high;
  return v;
}

void full_factorial(const DesignSpec& spec, Design& out) {
  const std::size_t p = spec.parameters.size();
  std::vector<std::vector<double>> levels(p);
  std::size_t runs = 1;
  for (std::size_t j = 0; j < p; ++j) {
    levels[j] = column_levels(spec.parameters[j].distribution);
    const std::size_t n = levels[j].size();
    if (runs > std::numeric_limits<std::size_t>::max() / n)
      fail("full factorial has too many runs (overflow at " + who(spec.parameters[j].path) + ")");
    runs *= n;
  }
  out.values.assign(runs, std::vector<double>(p));
  out.unit.assign(runs, std::vector<double>(p));
  for (std::size_t r = 0; r < runs; ++r) {
    std::size_t rest = r;
    for (std::size_t j = p; j-- > 0;) {  // last parameter varies fastest
      const std::size_t n = levels[j].size();
      const std::size_t i = rest % n;
      rest /= n;
      out.values[r][j] = levels[j][i];
      out.unit[r][j] = (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    }
  }
}

// Largest u' near u with floor(u' * n) == k (guards the rounding of (k + U) / n).
double into_stratum(double u, std::size_t k, std::size_t n) {
  const double dn = static_cast<double>(n), dk = static_cast<double>(k);
  while (u > 0 && std::floor(u * dn) > dk) u = std::nextafter(u, 0.0);
  while (std::floor(u * dn) < dk) u = std::nextafter(u, 1.0);
  return u;
}

void latin_hypercube(const DesignSpec& spec, Design& out) {
  const std::size_t n = spec.runs, p = spec.parameters.size();
  for (std::size_t j = 0; j < p; ++j) {
    auto rng = stream(spec.seed, Purpose::LatinHypercube, j);
    std::vector<std::size_t> perm(n);
    for (std::size_t i = 0; i < n; ++i) perm[i] = i;
    shuffle(perm, rng);
    for (std::size_t i = 0; i < n; ++i) {
      const double u = (static_cast<double>(perm[i]) + uniform53(rng)) / static_cast<double>(n);
      out.unit[i][j] = into_stratum(u, perm[i], n);
    }
  }
}

void monte_carlo(const DesignSpec& spec, Design& out) {
  for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
    auto rng = stream(spec.seed, Purpose::MonteCarlo, j);
    for (std::size_t i = 0; i < spec.runs; ++i) out.unit[i][j] = uniform53(rng);
  }
}

std::vector<std::uint32_t> first_primes(std::size_t count) {
  std::vector<std::uint32_t> primes;
  primes.reserve(count);
  for (std::uint32_t c = 2; primes.size() < count; ++c) {
    bool prime = true;
    for (std::uint32_t q : primes) {
      if (static_cast<std::uint64_t>(q) * q > c) break;
      if (c % q == 0) {
        prime = false;
        break;
      }
    }
    if (prime) primes.push_back(c);
  }
  return primes;
}

constexpr std::uint64_t kTwo53 = std::uint64_t{1} << 53;

}  // namespace

// -----------------------------------------------------------------------------------------------------------------

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

double normal_quantile(double p) {
  if (std::isnan(p)) return nan;
  if (p <= 0) return -inf;
  if (p >= 1) return inf;
  if (p > 0.5) return -lower_tail_quantile(1.0 - p);  // 1 - p is exact for p >= 0.5
  return lower_tail_quantile(p);
}

double Distribution::quantile(double u) const {
  if (!(u >= 0 && u <= 1)) throw std::invalid_argument("Distribution::quantile: u = " + fmt(u) + " outside [0, 1)");
  try {
    validate(*this, "distribution", false);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("Distribution::quantile: ") + e.what());
  }
  switch (kind) {
    case Kind::Levels: {
      const std::size_t n = levels.size();
      const auto i = static_cast<std::size_t>(std::floor(u * static_cast<double>(n)));
      return levels[std::min(i, n - 1)];
    }
    case Kind::Uniform: return std::min(low + u * (high - low), high);
    case Kind::LogUniform: {
      const double lo = std::log(low), hi = std::log(high);
      return std::clamp(std::exp(lo + u * (hi - lo)), low, high);
    }
    case Kind::Normal: {
      if (!(low < high)) {
        const double q = std::clamp(u, 0x1.0p-53, 1.0 - 0x1.0p-53);
        return mean + std * normal_quantile(q);
      }
      const double a = (low - mean) / std, b = (high - mean) / std;
      double z;
      if (a >= 0) {  // both ends in the upper tail: work with upper-tail probabilities
        const double qa = normal_cdf(-a), qb = normal_cdf(-b);
        z = -normal_quantile(qa - u * (qa - qb));
      } else {
        const double pa = normal_cdf(a), pb = normal_cdf(b);
        z = normal_quantile(pa + u * (pb - pa));
      }
      return std::clamp(mean + std * z, low, high);
    }
  }
  throw std::invalid_argument("Distribution::quantile: unknown distribution kind");
}

std::size_t sobol_max_dimensions() { return kSobolDims; }

std::vector<std::vector<double>> sobol_points(std::size_t n, std::size_t dims, std::uint64_t first_index,
                                              bool scramble, std::uint64_t seed) {
  if (dims == 0) throw std::invalid_argument("sobol_points: dims must be >= 1");
  if (dims > kSobolDims)
    throw std::invalid_argument("sobol_points: " + std::to_string(dims) + " dimensions requested, at most " +
                                std::to_string(kSobolDims) + " supported (Joe-Kuo direction numbers built in)");
  constexpr std::uint64_t max_index = (std::uint64_t{1} << kSobolBits) - 1;
  if (n > 0 && (first_index > max_index || n - 1 > max_index - first_index))
    throw std::invalid_argument("sobol_points: indices " + std::to_string(first_index) + " .. " +
                                std::to_string(first_index) + " + " + std::to_string(n) +
                                " - 1 exceed the 2^32 points of the 32-bit sequence");
  std::vector<std::vector<double>> pts(n, std::vector<double>(dims));
  const auto& table = sobol_directions();
  for (std::size_t d = 0; d < dims; ++d) {
    Directions v = table[d];
    std::uint32_t shift = 0;
    if (scramble) {
      auto rng = stream(seed, Purpose::SobolScramble, d);
      v = scramble_directions(v, rng);
      shift = static_cast<std::uint32_t>(rng() >> 32);
    }
    // Gray code: point i is the XOR of the direction numbers at the set bits of i ^ (i >> 1) ...
    std::uint64_t i = first_index;
    const std::uint64_t gray = i ^ (i >> 1);
    std::uint32_t x = 0;
    for (int k = 0; k < kSobolBits; ++k)
      if ((gray >> k) & 1u) x ^= v[static_cast<std::size_t>(k)];
    for (std::size_t r = 0; r < n; ++r, ++i) {
      if (r > 0) x ^= v[static_cast<std::size_t>(std::countr_one(i - 1))];  // ... and successive points differ in one
      pts[r][d] = static_cast<double>(x ^ shift) * 0x1.0p-32;
    }
  }
  return pts;
}

std::uint32_t nth_prime(std::size_t i) { return first_primes(i + 1).back(); }

double radical_inverse(std::uint64_t index, std::uint32_t base) {
  if (base < 2) throw std::invalid_argument("radical_inverse: base must be >= 2");
  std::uint64_t rev = 0, denom = 1, i = index;
  while (i > 0 && denom <= kTwo53 / base) {  // exact integer part: rev / denom with denom <= 2^53
    rev = rev * base + i % base;
    i /= base;
    denom *= base;
  }
  if (i == 0) return static_cast<double>(rev) / static_cast<double>(denom);
  const double u = (static_cast<double>(rev) + radical_inverse(i, base)) / static_cast<double>(denom);
  return std::min(u, std::nextafter(1.0, 0.0));
}

std::vector<std::vector<double>> halton_points(std::size_t n, std::size_t dims, std::uint64_t first_index,
                                               bool scramble, std::uint64_t seed) {
  if (dims == 0) throw std::invalid_argument("halton_points: dims must be >= 1");
  const auto primes = first_primes(dims);
  std::vector<std::vector<double>> pts(n, std::vector<double>(dims));
  for (std::size_t d = 0; d < dims; ++d) {
    const std::uint32_t b = primes[d];
    if (!scramble) {
      for (std::size_t r = 0; r < n; ++r) pts[r][d] = radical_inverse(first_index + r, b);
      continue;
    }
    // Random digit permutation per digit position, K digits with b^K <= 2^53.
    std::size_t digits = 0;
    std::uint64_t bk = 1;
    while (bk <= kTwo53 / b) {
      bk *= b;
      ++digits;
    }
    auto rng = stream(seed, Purpose::HaltonScramble, d);
    std::vector<std::vector<std::uint32_t>> perm(digits, std::vector<std::uint32_t>(b));
    for (auto& pi : perm) {
      for (std::uint32_t k = 0; k < b; ++k) pi[k] = k;
      shuffle(pi, rng);
    }
    for (std::size_t r = 0; r < n; ++r) {
      std::uint64_t i = first_index + r, num = 0;
      for (std::size_t j = 0; j < digits; ++j) {  // digit j of the index becomes digit j + 1 after the point
        num = num * b + perm[j][i % b];
        i /= b;
      }
      pts[r][d] = static_cast<double>(num) / static_cast<double>(bk);
    }
  }
  return pts;
}

Design make_design(const DesignSpec& spec) {
  const std::string design = design_name(spec.kind);
  if (design == "unknown") fail("unknown design kind " + std::to_string(static_cast<int>(spec.kind)));
  const std::size_t p = spec.parameters.size();
  if (p == 0) fail(design + " design has no parameters");

  Design out;
  std::set<std::string> seen;
  for (std::size_t j = 0; j < p; ++j) {
    const std::string& path = spec.parameters[j].path;
    if (path.empty()) fail("parameter " + std::to_string(j) + " has an empty path");
    if (!seen.insert(path).second) fail("duplicate parameter path '" + path + "' (" + who(path) + " given twice)");
    out.paths.push_back(path);
  }

  if (spec.kind == DesignKind::Table) {
    if (spec.table.empty()) fail("Table design has no rows (runs == 0); parameters: " + out.paths.front() + " ...");
    for (std::size_t r = 0; r < spec.table.size(); ++r) {
      const auto& row = spec.table[r];
      if (row.size() != p) {
        std::string names;
        for (const auto& s : out.paths) names += (names.empty() ? "" : ", ") + s;
        fail("table row " + std::to_string(r) + " has " + std::to_string(row.size()) + " values, expected " +
             std::to_string(p) + " (one per parameter: " + names + ")");
      }
      for (std::size_t j = 0; j < p; ++j)
        if (!std::isfinite(row[j]))
          fail(who(out.paths[j]) + ": table row " + std::to_string(r) + " value is not finite (" + fmt(row[j]) +
               ")");
    }
    out.values = spec.table;
    out.unit.assign(spec.table.size(), std::vector<double>(p, nan));
    return out;
  }

  for (const auto& par : spec.parameters)
    validate(par.distribution, who(par.path), spec.kind == DesignKind::FullFactorial);

  if (spec.kind == DesignKind::FullFactorial) {
    full_factorial(spec, out);
    return out;
  }

  const std::size_t n = spec.runs;
  if (n == 0) fail(design + " design needs runs > 0 (runs == 0; first parameter '" + out.paths.front() + "')");
  switch (spec.kind) {
    case DesignKind::LatinHypercube:
      out.unit.assign(n, std::vector<double>(p));
      latin_hypercube(spec, out);
      break;
    case DesignKind::MonteCarlo:
      out.unit.assign(n, std::vector<double>(p));
      monte_carlo(spec, out);
      break;
    case DesignKind::Sobol: {
      if (p > kSobolDims)
        fail("Sobol supports at most " + std::to_string(kSobolDims) + " dimensions (Joe-Kuo direction numbers), " +
             std::to_string(p) + " parameters given; first unsupported: " + who(out.paths[kSobolDims]));
      const std::uint64_t first = spec.scramble ? 0 : 1;  // unscrambled: skip the origin
      const std::uint64_t limit = (std::uint64_t{1} << kSobolBits) - first;
      if (n > limit)
        fail("Sobol design with " + std::to_string(n) + " runs exceeds the " + std::to_string(limit) +
             " points of the 32-bit sequence (parameters from '" + out.paths.front() + "')");
      out.unit = sobol_points(n, p, first, spec.scramble, spec.seed);
      break;
    }
    case DesignKind::Halton:
      out.unit = halton_points(n, p, spec.scramble ? 0 : 1, spec.scramble, spec.seed);
      break;
    default: break;
  }

  out.values.assign(n, std::vector<double>(p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < p; ++j) {
      const double v = spec.parameters[j].distribution.quantile(out.unit[i][j]);
      if (!std::isfinite(v)) fail(who(out.paths[j]) + ": non-finite value " + fmt(v) + " in run " + std::to_string(i));
      out.values[i][j] = v;
    }
  return out;
}

std::vector<std::size_t> shard_indices(std::size_t total_runs, std::size_t k, std::size_t n) {
  if (n == 0) throw std::invalid_argument("shard_indices: number of shards n must be > 0");
  if (k >= n)
    throw std::invalid_argument("shard_indices: shard k = " + std::to_string(k) + " must be < n = " +
                                std::to_string(n));
  std::vector<std::size_t> out;
  if (k < total_runs) out.reserve((total_runs - k + n - 1) / n);
  for (std::size_t i = k; i < total_runs; i += n) {
    out.push_back(i);
    if (n > total_runs - i) break;  // no overflow of i + n
  }
  return out;
}

Sensitivity standardized_regression(const std::vector<std::vector<double>>& x, const std::vector<double>& y) {
  const std::string me = "standardized_regression: ";
  if (x.size() != y.size())
    throw std::invalid_argument(me + "x has " + std::to_string(x.size()) + " runs but y has " +
                                std::to_string(y.size()));
  if (x.empty()) throw std::invalid_argument(me + "no runs");
  const std::size_t p = x.front().size();
  if (p == 0) throw std::invalid_argument(me + "no parameters (rows of x are empty)");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i].size() != p)
      throw std::invalid_argument(me + "row " + std::to_string(i) + " of x has " + std::to_string(x[i].size()) +
                                  " values, expected " + std::to_string(p));

  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i]) && std::all_of(x[i].begin(), x[i].end(), [](double v) { return std::isfinite(v); }))
      used.push_back(i);
  const std::size_t n = used.size();
  if (n < p + 2)
    throw std::invalid_argument(me + "needs at least parameters + 2 = " + std::to_string(p + 2) +
                                " runs with finite values, got " + std::to_string(n));
  const double dn = static_cast<double>(n);

  auto mean_sd = [&](auto get) {
    double m = 0;
    for (std::size_t i : used) m += get(i);
    m /= dn;
    double ss = 0;
    for (std::size_t i : used) ss += (get(i) - m) * (get(i) - m);
    return std::pair<double, double>(m, std::sqrt(ss / (dn - 1)));
  };

  Sensitivity result;
  result.src.assign(p, 0.0);
  const auto [my, sy] = mean_sd([&](std::size_t i) { return y[i]; });
  if (!(sy > 1e-300) || sy <= 1e-14 * std::abs(my)) {
    result.r_squared = nan;
    return result;
  }

  // Standardised columns of the parameters that vary.
  std::vector<std::size_t> active;
  std::vector<std::vector<double>> z;  // columns
  for (std::size_t j = 0; j < p; ++j) {
    const auto [mj, sj] = mean_sd([&](std::size_t i) { return x[i][j]; });
    if (!(sj > 1e-300) || sj <= 1e-14 * std::abs(mj)) continue;
    std::vector<double> col(n);
    for (std::size_t r = 0; r < n; ++r) col[r] = (x[used[r]][j] - mj) / sj;
    active.push_back(j);
    z.push_back(std::move(col));
  }
  std::vector<double> w(n);
  for (std::size_t r = 0; r < n; ++r) w[r] = (y[used[r]] - my) / sy;
  const double sst = dn - 1;  // sum of squares of the standardised y

  // Householder QR of z, applied to w; z[c][c..] holds R.
  const std::size_t q = active.size();
  std::vector<double> diag(q);
  for (std::size_t c = 0; c < q; ++c) {
    double sigma = 0;
    for (std::size_t r = c; r < n; ++r) sigma += z[c][r] * z[c][r];
    sigma = std::sqrt(sigma);
    if (sigma <= 1e-9 * std::sqrt(sst))
      throw std::invalid_argument(me + "parameter column " + std::to_string(active[c]) +
                                  " is collinear with the previous columns");
    const double alpha = z[c][c] > 0 ? -sigma : sigma;
    std::vector<double> v(z[c].begin() + static_cast<std::ptrdiff_t>(c), z[c].end());
    v[0] -= alpha;
    double vv = 0;
    for (double e : v) vv += e * e;
    auto reflect = [&](std::vector<double>& col) {
      double s = 0;
      for (std::size_t r = c; r < n; ++r) s += v[r - c] * col[r];
      s *= 2.0 / vv;
      for (std::size_t r = c; r < n; ++r) col[r] -= s * v[r - c];
    };
    for (std::size_t k = c + 1; k < q; ++k) reflect(z[k]);
    reflect(w);
    diag[c] = alpha;
  }
  std::vector<double> beta(q);
  for (std::size_t c = q; c-- > 0;) {
    double s = w[c];
    for (std::size_t k = c + 1; k < q; ++k) s -= z[k][c] * beta[k];
    beta[c] = s / diag[c];
  }
  double sse = 0;
  for (std::size_t r = q; r < n; ++r) sse += w[r] * w[r];
  for (std::size_t c = 0; c < q; ++c) result.src[active[c]] = beta[c];
  result.r_squared = 1.0 - sse / sst;
  return result;
}

namespace {

// The quadratic basis at parameters x scaled to [-1, 1]; writes 1 + p + p (p + 1) / 2 values into b.
void quadratic_basis(const std::vector<double>& x, const std::vector<double>& lo, const std::vector<double>& hi,
                     std::vector<double>& b) {
  const std::size_t p = x.size();
  b.assign(1, 1.0);
  std::vector<double> u(p);
  for (std::size_t i = 0; i < p; ++i) u[i] = (2.0 * x[i] - lo[i] - hi[i]) / (hi[i] - lo[i]);
  for (std::size_t i = 0; i < p; ++i) b.push_back(u[i]);
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = i; j < p; ++j) b.push_back(u[i] * u[j]);
}

}  // namespace

double QuadraticSurface::operator()(const std::vector<double>& x) const {
  std::vector<double> b;
  quadratic_basis(x, lo, hi, b);
  double v = 0.0;
  for (std::size_t k = 0; k < b.size() && k < coef.size(); ++k) v += coef[k] * b[k];
  return v;
}

QuadraticSurface fit_quadratic_surface(const std::vector<std::vector<double>>& x, const std::vector<double>& y,
                                       const std::vector<double>& lo, const std::vector<double>& hi) {
  const std::string me = "fit_quadratic_surface: ";
  if (x.size() != y.size()) throw std::invalid_argument(me + "x and y differ in length");
  const std::size_t p = lo.size();
  if (p == 0 || hi.size() != p) throw std::invalid_argument(me + "lo and hi must name every parameter");
  for (std::size_t i = 0; i < p; ++i)
    if (!(hi[i] > lo[i])) throw std::invalid_argument(me + "parameter " + std::to_string(i) + " has lo >= hi");
  const std::size_t terms = 1 + p + p * (p + 1) / 2;
  std::vector<std::size_t> used;
  for (std::size_t r = 0; r < x.size(); ++r) {
    if (x[r].size() != p) throw std::invalid_argument(me + "row " + std::to_string(r) + " has the wrong length");
    bool finite = std::isfinite(y[r]);
    for (double v : x[r]) finite = finite && std::isfinite(v);
    if (finite) used.push_back(r);
  }
  if (used.size() < terms + 3)
    throw std::invalid_argument(me + std::to_string(used.size()) + " usable runs for " + std::to_string(terms) +
                                " terms (need terms + 3)");
  Eigen::MatrixXd A(used.size(), terms);
  Eigen::VectorXd b(used.size());
  std::vector<double> row;
  for (std::size_t r = 0; r < used.size(); ++r) {
    quadratic_basis(x[used[r]], lo, hi, row);
    for (std::size_t k = 0; k < terms; ++k) A(r, k) = row[k];
    b(r) = y[used[r]];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < static_cast<Eigen::Index>(terms))
    throw std::invalid_argument(me + "the design does not determine every quadratic term (rank " +
                                std::to_string(qr.rank()) + " of " + std::to_string(terms) + ")");
  const Eigen::VectorXd c = qr.solve(b);
  QuadraticSurface s;
  s.lo = lo;
  s.hi = hi;
  s.coef.assign(c.data(), c.data() + c.size());
  s.runs = used.size();
  const double mean = b.mean();
  const double sst = (b.array() - mean).square().sum(), sse = (A * c - b).squaredNorm();
  s.r_squared = sst > 0.0 ? 1.0 - sse / sst : std::numeric_limits<double>::quiet_NaN();
  return s;
}

}  // namespace turbodyn::studies

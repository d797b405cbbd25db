#include "post/signal.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace turbodyn::signal {
namespace {

constexpr double pi = std::numbers::pi;
using cd = std::complex<double>;

// Plain complex product: std::complex's operator* goes through __muldc3 (NaN/Inf recovery) without -ffast-math.
inline cd mul(cd a, cd b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

bool is_power_of_two(std::size_t n) { return n != 0 && (n & (n - 1)) == 0; }

std::size_t next_power_of_two(std::size_t n) {
  std::size_t p = 1;
  while (p < n) p <<= 1;
  return p;
}

// In-place iterative radix-2 DFT of a fixed power-of-two length.
class Radix2 {
 public:
  explicit Radix2(std::size_t m) : m_(m), rev_(m), twiddle_(m / 2) {
    std::size_t bits = 0;
    while ((std::size_t{1} << bits) < m) ++bits;
    for (std::size_t i = 0; i < m; ++i) {
      std::size_t r = 0;
      for (std::size_t b = 0; b < bits; ++b)
        if (i & (std::size_t{1} << b)) r |= std::size_t{1} << (bits - 1 - b);
      rev_[i] = r;
    }
    for (std::size_t k = 0; k < m / 2; ++k) {
      const double angle = -2.0 * pi * static_cast<double>(k) / static_cast<double>(m);
      twiddle_[k] = {std::cos(angle), std::sin(angle)};
    }
  }

  std::size_t size() const { return m_; }

  // inverse = false: X[k] = sum x[j] e^{-2 pi i jk/m}; inverse = true: the same with +i (not divided by m).
  void transform(cd* a, bool inverse) const {
    for (std::size_t i = 0; i < m_; ++i)
      if (i < rev_[i]) std::swap(a[i], a[rev_[i]]);
    for (std::size_t len = 2; len <= m_; len <<= 1) {
      const std::size_t half = len / 2;
      const std::size_t step = m_ / len;
      for (std::size_t i = 0; i < m_; i += len) {
        for (std::size_t j = 0; j < half; ++j) {
          cd w = twiddle_[j * step];
          if (inverse) w = std::conj(w);
          const cd u = a[i + j];
          const cd v = mul(a[i + j + half], w);
          a[i + j] = u + v;
          a[i + j + half] = u - v;
        }
      }
    }
  }

 private:
  std::size_t m_;
  std::vector<std::size_t> rev_;
  std::vector<cd> twiddle_;
};

// Forward complex DFT of any length n >= 1: radix-2 for powers of two, Bluestein otherwise.
class ComplexFft {
 public:
  explicit ComplexFft(std::size_t n)
      : n_(n), bluestein_(!is_power_of_two(n)), radix2_(bluestein_ ? next_power_of_two(2 * n - 1) : n) {
    if (!bluestein_) return;
    const std::size_t m = radix2_.size();
    chirp_.resize(n);
    const std::uint64_t two_n = 2 * static_cast<std::uint64_t>(n);
    for (std::size_t k = 0; k < n; ++k) {
      // e^{-i pi k^2 / n}, with k^2 reduced mod 2n so the angle stays small and exact.
      const std::uint64_t k2 = (static_cast<std::uint64_t>(k) * k) % two_n;
      const double angle = -pi * static_cast<double>(k2) / static_cast<double>(n);
      chirp_[k] = {std::cos(angle), std::sin(angle)};
    }
    kernel_.assign(m, cd{0.0, 0.0});
    kernel_[0] = std::conj(chirp_[0]);
    for (std::size_t k = 1; k < n; ++k) kernel_[k] = kernel_[m - k] = std::conj(chirp_[k]);
    radix2_.transform(kernel_.data(), false);
    const double inv_m = 1.0 / static_cast<double>(m);
    for (cd& v : kernel_) v *= inv_m;  // folds the 1/m of the inverse transform into the kernel
    work_.resize(m);
  }

  std::size_t size() const { return n_; }

  void forward(cd* data) {
    if (!bluestein_) {
      radix2_.transform(data, false);
      return;
    }
    const std::size_t m = radix2_.size();
    for (std::size_t k = 0; k < n_; ++k) work_[k] = mul(data[k], chirp_[k]);
    std::fill(work_.begin() + static_cast<std::ptrdiff_t>(n_), work_.end(), cd{0.0, 0.0});
    radix2_.transform(work_.data(), false);
    for (std::size_t k = 0; k < m; ++k) work_[k] = mul(work_[k], kernel_[k]);
    radix2_.transform(work_.data(), true);
    for (std::size_t k = 0; k < n_; ++k) data[k] = mul(work_[k], chirp_[k]);
  }

 private:
  std::size_t n_;
  bool bluestein_;
  Radix2 radix2_;
  std::vector<cd> chirp_, kernel_, work_;
};

// DFT bins 0..n/2 of a real sequence of length n. Even n: packed into n/2 complex values.
class RealFft {
 public:
  explicit RealFft(std::size_t n) : n_(n), even_(n % 2 == 0), fft_(even_ ? n / 2 : n), buffer_(fft_.size()) {
    if (even_) {
      twiddle_.resize(n / 2 + 1);
      for (std::size_t k = 0; k <= n / 2; ++k) {
        const double angle = -2.0 * pi * static_cast<double>(k) / static_cast<double>(n);
        twiddle_[k] = {std::cos(angle), std::sin(angle)};
      }
    }
  }

  std::size_t bins() const { return n_ / 2 + 1; }

  void forward(const double* x, cd* out) {
    if (!even_) {
      for (std::size_t j = 0; j < n_; ++j) buffer_[j] = {x[j], 0.0};
      fft_.forward(buffer_.data());
      for (std::size_t k = 0; k < bins(); ++k) out[k] = buffer_[k];
      return;
    }
    const std::size_t h = n_ / 2;
    for (std::size_t j = 0; j < h; ++j) buffer_[j] = {x[2 * j], x[2 * j + 1]};
    fft_.forward(buffer_.data());
    for (std::size_t k = 0; k <= h; ++k) {
      const cd zk = buffer_[k == h ? 0 : k];
      const cd zc = std::conj(buffer_[k == 0 ? 0 : h - k]);
      const cd even = 0.5 * (zk + zc);
      const cd d = zk - zc;
      const cd odd{0.5 * d.imag(), -0.5 * d.real()};  // (zk - zc) / (2i)
      out[k] = even + mul(twiddle_[k], odd);
    }
  }

 private:
  std::size_t n_;
  bool even_;
  ComplexFft fft_;
  std::vector<cd> buffer_;
  std::vector<cd> twiddle_;
};

std::string number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void check_sample_rate(const char* function, double sample_rate) {
  if (!(sample_rate > 0.0) || !std::isfinite(sample_rate))
    throw std::invalid_argument(std::string(function) + ": sample rate must be a finite positive number of Hz, got " +
                                number(sample_rate));
}

void check_finite(const char* function, const char* what, const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw std::invalid_argument(std::string(function) + ": " + what + " sample " + std::to_string(i) +
                                  " is not finite (" + number(v[i]) + ")");
}

}  // namespace

Window window_from_string(const std::string& name) {
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "rectangular") return Window::Rectangular;
  if (lower == "hann") return Window::Hann;
  if (lower == "hamming") return Window::Hamming;
  if (lower == "blackman") return Window::Blackman;
  if (lower == "flattop") return Window::FlatTop;
  throw std::invalid_argument("unknown window '" + name +
                              "'; valid windows are: rectangular, hann, hamming, blackman, flattop");
}

std::string to_string(Window w) {
  switch (w) {
    case Window::Rectangular: return "rectangular";
    case Window::Hann: return "hann";
    case Window::Hamming: return "hamming";
    case Window::Blackman: return "blackman";
    case Window::FlatTop: return "flattop";
  }
  return "unknown";
}

namespace {

// Cosine-sum coefficients a_j of a window w = sum_j (-1)^j a_j cos(j x).
std::vector<double> cosine_sum_terms(Window w) {
  switch (w) {
    case Window::Rectangular: return {1.0};
    case Window::Hann: return {0.5, 0.5};
    case Window::Hamming: return {0.54, 0.46};
    case Window::Blackman: return {0.42, 0.5, 0.08};
    case Window::FlatTop: {
      // HFT95 (Heinzel, Ruediger & Schilling 2002), scaled to a peak of 1.
      std::vector<double> a = {1.0, 1.9383379, 1.3045202, 0.4028270, 0.0350665};
      const double peak = a[0] + a[1] + a[2] + a[3] + a[4];
      for (double& v : a) v /= peak;
      return a;
    }
  }
  return {1.0};
}

}  // namespace

std::vector<double> window_coefficients(Window w, std::size_t n) {
  if (n == 0) return {};
  if (n == 1) return {1.0};
  if (w == Window::Rectangular) return std::vector<double>(n, 1.0);
  const std::vector<double> a = cosine_sum_terms(w);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    double v = a[0];
    double sign = -1.0;
    for (std::size_t j = 1; j < a.size(); ++j, sign = -sign) {
      // cos(2 pi m / n) with m = j*i reduced mod n and folded to [0, n/2], so w[i] == w[n-i] exactly.
      std::size_t m = (j * i) % n;
      m = std::min(m, n - m);
      v += sign * a[j] * std::cos(2.0 * pi * static_cast<double>(m) / static_cast<double>(n));
    }
    out[i] = v;
  }
  return out;
}

Spectrogram stft(const std::vector<double>& signal, double sample_rate, const StftOptions& options) {
  check_sample_rate("stft", sample_rate);
  const std::size_t n = options.segment_length;
  if (n < 8) throw std::invalid_argument("stft: segment_length must be at least 8 samples, got " + std::to_string(n));
  if (!(options.overlap >= 0.0 && options.overlap < 1.0))
    throw std::invalid_argument("stft: overlap must be a fraction in [0, 1), got " + number(options.overlap));
  if (signal.size() < n)
    throw std::invalid_argument("stft: signal has " + std::to_string(signal.size()) +
                                " samples, shorter than one segment of " + std::to_string(n));
  check_finite("stft", "signal", signal);

  const auto overlap_samples = static_cast<std::size_t>(std::llround(options.overlap * static_cast<double>(n)));
  const std::size_t hop = overlap_samples >= n ? 1 : n - overlap_samples;
  const std::size_t n_segments = 1 + (signal.size() - n) / hop;

  RealFft fft(n);
  const std::size_t n_bins = fft.bins();
  const std::vector<double> window = window_coefficients(options.window, n);
  double window_sum = 0.0;
  for (double w : window) window_sum += w;
  std::vector<double> scale(n_bins, 2.0 / window_sum);
  scale[0] = 1.0 / window_sum;
  if (n % 2 == 0) scale[n_bins - 1] = 1.0 / window_sum;

  Spectrogram out;
  out.sample_rate = sample_rate;
  out.segment_length = n;
  out.hop = hop;
  out.frequencies.resize(n_bins);
  for (std::size_t k = 0; k < n_bins; ++k)
    out.frequencies[k] = static_cast<double>(k) * sample_rate / static_cast<double>(n);
  out.times.resize(n_segments);
  out.amplitude.resize(n_segments * n_bins);

  std::vector<double> segment(n);
  std::vector<cd> spectrum(n_bins);
  for (std::size_t s = 0; s < n_segments; ++s) {
    const double* x = signal.data() + s * hop;
    double mean = 0.0;
    if (options.remove_mean) {
      for (std::size_t j = 0; j < n; ++j) mean += x[j];
      mean /= static_cast<double>(n);
    }
    for (std::size_t j = 0; j < n; ++j) segment[j] = (x[j] - mean) * window[j];
    fft.forward(segment.data(), spectrum.data());
    double* row = out.amplitude.data() + s * n_bins;
    for (std::size_t k = 0; k < n_bins; ++k) row[k] = scale[k] * std::sqrt(std::norm(spectrum[k]));
    out.times[s] = (static_cast<double>(s * hop) + 0.5 * static_cast<double>(n - 1)) / sample_rate;
  }
  return out;
}

std::vector<double> values_at_segment_centres(const Spectrogram& s, const std::vector<double>& series,
                                              double sample_rate) {
  check_sample_rate("values_at_segment_centres", sample_rate);
  std::vector<double> out(s.n_segments());
  if (out.empty()) return out;
  if (series.empty()) throw std::invalid_argument("values_at_segment_centres: the series is empty");
  const double last = static_cast<double>(series.size() - 1);
  for (std::size_t i = 0; i < out.size(); ++i) {
    double x = s.times[i] * sample_rate;
    // Allow for rounding in times[i] * fs; anything beyond is a series that does not cover the spectrogram.
    if (x < -1e-6 || x > last + 1e-6)
      throw std::invalid_argument("values_at_segment_centres: segment " + std::to_string(i) + " is centred at t = " +
                                  number(s.times[i]) + " s (sample " + number(x) + "), outside the series of " +
                                  std::to_string(series.size()) + " samples at " + number(sample_rate) + " Hz");
    x = std::clamp(x, 0.0, last);
    const auto i0 = std::min(static_cast<std::size_t>(x), series.size() - 1);
    const double frac = x - static_cast<double>(i0);
    out[i] = frac > 0.0 ? series[i0] + frac * (series[i0 + 1] - series[i0]) : series[i0];
  }
  return out;
}

namespace {

// window_leakage of the window with cosine-sum terms `a` (cosine_sum_terms).
double cosine_sum_leakage(const std::vector<double>& a, std::size_t n, double nu) {
  // sum_{i<n} exp(-2 pi i mu i / n) = exp(-i pi mu (n - 1) / n) sin(pi mu) / sin(pi mu / n): the Dirichlet kernel,
  // n at mu = 0. A term cos(2 pi j i / n) of the window shifts it to mu = nu - j and nu + j, halved.
  const double nd = static_cast<double>(n);
  const auto kernel = [nd](double mu) {
    const double den = std::sin(pi * mu / nd);
    const double magnitude = std::abs(den) < 1e-14 ? nd : std::sin(pi * mu) / den;
    return std::polar(magnitude, -pi * mu * (nd - 1.0) / nd);
  };
  std::complex<double> at_nu = a[0] * kernel(nu);
  const double at_zero = a[0] * nd;  // W(0) = n a_0: the other terms sum to zero over a period
  double sign = -1.0;
  for (std::size_t j = 1; j < a.size(); ++j, sign = -sign) {
    const double jd = static_cast<double>(j);
    at_nu += 0.5 * sign * a[j] * (kernel(nu - jd) + kernel(nu + jd));
  }
  return std::abs(at_nu) / at_zero;
}

}  // namespace

double window_leakage(Window w, std::size_t n, double nu) { return cosine_sum_leakage(cosine_sum_terms(w), n, nu); }

std::size_t leakage_margin_bins(Window w, std::size_t n, double level) {
  if (n < 8) throw std::invalid_argument("leakage_margin_bins: n must be at least 8, got " + std::to_string(n));
  if (!(level > 0.0 && level < 1.0))
    throw std::invalid_argument("leakage_margin_bins: level must lie in (0, 1), got " + number(level));
  // From the far end inwards: the margin is the first whole bin above the last grid point that leaks more.
  constexpr int kSteps = 16;
  const auto last = static_cast<long>(n / 2) * kSteps;
  const std::vector<double> a = cosine_sum_terms(w);
  for (long k = last; k >= 0; --k)
    if (cosine_sum_leakage(a, n, static_cast<double>(k) / kSteps) > level)
      return static_cast<std::size_t>(k / kSteps + 1);
  return 0;
}

std::optional<SpectralLine> largest_subsynchronous_line(const Spectrogram& s,
                                                        const std::vector<double>& rotor_frequency, double sample_rate,
                                                        double frequency_max, std::size_t margin_bins,
                                                        std::size_t first_segment) {
  check_sample_rate("largest_subsynchronous_line", sample_rate);
  const std::size_t ns = s.n_segments(), n = s.segment_length;
  if (ns == 0 || first_segment >= ns) return std::nullopt;
  if (rotor_frequency.size() < (ns - 1) * s.hop + n)
    throw std::invalid_argument("largest_subsynchronous_line: the rotor frequency has " +
                                std::to_string(rotor_frequency.size()) + " samples, the spectrogram's last segment "
                                "ends at sample " + std::to_string((ns - 1) * s.hop + n));
  const std::vector<double> centre_speed = values_at_segment_centres(s, rotor_frequency, sample_rate);
  const double df = sample_rate / static_cast<double>(n);
  const double margin = static_cast<double>(margin_bins) * df;
  std::optional<SpectralLine> best;
  for (std::size_t seg = first_segment; seg < ns; ++seg) {
    double slowest = std::abs(rotor_frequency[seg * s.hop]);
    for (std::size_t i = seg * s.hop; i < seg * s.hop + n; ++i)
      slowest = std::min(slowest, std::abs(rotor_frequency[i]));
    const double top = std::min(slowest - margin, frequency_max);
    for (std::size_t k = 0; k < s.n_bins() && s.frequencies[k] <= top; ++k) {
      if (s.frequencies[k] < margin) continue;
      const double v = s.at(seg, k);
      if (!best || v > best->amplitude) best = SpectralLine{v, s.frequencies[k], s.times[seg], centre_speed[seg], seg};
    }
  }
  return best;
}

OrderTrack track_order(const std::vector<double>& signal, const std::vector<double>& rotor_angle,
                       const std::vector<double>& rotor_frequency, double sample_rate,
                       const OrderTrackOptions& options) {
  const char* fn = "track_order";
  check_sample_rate(fn, sample_rate);
  const std::size_t len = signal.size();
  if (rotor_angle.size() != len || rotor_frequency.size() != len)
    throw std::invalid_argument("track_order: signal, rotor_angle and rotor_frequency must have the same length, got " +
                                std::to_string(len) + ", " + std::to_string(rotor_angle.size()) + " and " +
                                std::to_string(rotor_frequency.size()));
  if (len < 2) throw std::invalid_argument("track_order: the signal needs at least 2 samples");
  const double n = options.order;
  const double rev = options.revolutions;
  if (!(n > 0.0) || !std::isfinite(n))
    throw std::invalid_argument("track_order: order must be a finite positive number, got " + number(n));
  if (!(rev > 0.0) || !std::isfinite(rev))
    throw std::invalid_argument("track_order: revolutions must be a finite positive number, got " + number(rev));
  if (n * rev < 1.0)
    throw std::invalid_argument("track_order: order * revolutions must be >= 1 (at least one cycle of the tracked "
                                "order per window), got " + number(n) + " * " + number(rev));
  if (options.points < 1) throw std::invalid_argument("track_order: points must be at least 1");
  if (!(options.min_speed >= 0.0) || !std::isfinite(options.min_speed))
    throw std::invalid_argument("track_order: min_speed must be a finite number >= 0 Hz, got " +
                                number(options.min_speed));
  check_finite(fn, "signal", signal);
  check_finite(fn, "rotor_angle", rotor_angle);
  check_finite(fn, "rotor_frequency", rotor_frequency);

  const double total = rotor_angle.back() - rotor_angle.front();
  if (total == 0.0) throw std::invalid_argument("track_order: the rotor angle does not change (rotor not turning)");
  const double dir = total > 0.0 ? 1.0 : -1.0;
  for (std::size_t i = 1; i < len; ++i)
    if (dir * (rotor_angle[i] - rotor_angle[i - 1]) < 0.0)
      throw std::invalid_argument("track_order: the rotor angle must be monotonic; it turns back at sample " +
                                  std::to_string(i));

  // u = dir * phi is non-decreasing.
  std::vector<double> u(len);
  for (std::size_t i = 0; i < len; ++i) u[i] = dir * rotor_angle[i];
  const double u_first = u.front(), u_last = u.back();
  const double half = pi * rev;

  auto valid = [&](std::size_t i) {
    return u[i] - u_first >= half && u_last - u[i] >= half && std::abs(rotor_frequency[i]) >= options.min_speed;
  };
  std::size_t ia = 0;
  while (ia < len && !valid(ia)) ++ia;
  if (ia == len)
    throw std::invalid_argument("track_order: no analysis window of " + number(rev) +
                                " revolutions fits in the record at a rotor speed >= " + number(options.min_speed) +
                                " Hz (the record covers " + number(std::abs(total) / (2.0 * pi)) + " revolutions)");
  std::size_t ib = len - 1;
  while (!valid(ib)) --ib;

  // cos / sin of the tracked order at every sample, once.
  std::vector<double> c(len), s(len);
  for (std::size_t i = 0; i < len; ++i) {
    const double a = n * rotor_angle[i];
    c[i] = std::cos(a);
    s[i] = std::sin(a);
  }

  OrderTrack out;
  const std::size_t points = options.points;
  out.times.reserve(points);
  out.speeds.reserve(points);
  out.amplitude.reserve(points);
  out.phase.reserve(points);
  for (std::size_t p = 0; p < points; ++p) {
    const double x = points == 1 ? 0.5 * static_cast<double>(ia + ib)
                                 : static_cast<double>(ia) + static_cast<double>(ib - ia) * static_cast<double>(p) /
                                                                 static_cast<double>(points - 1);
    const auto i0 = std::min(static_cast<std::size_t>(x), len - 1);
    const double frac = x - static_cast<double>(i0);
    const std::size_t i1 = std::min(i0 + 1, len - 1);
    const double u_c = dir * (rotor_angle[i0] + frac * (rotor_angle[i1] - rotor_angle[i0]));
    const double f_c = rotor_frequency[i0] + frac * (rotor_frequency[i1] - rotor_frequency[i0]);
    if (std::abs(f_c) < options.min_speed || n * std::abs(f_c) >= 0.5 * sample_rate) continue;

    // Window [lo_u, hi_u]; samples a..b lie strictly inside. The sums are trapezoidal-rule integrals over the
    // nodes lo_u, u_a, ..., u_b, hi_u (in angle, or in time without angle weighting); the integrand at the two
    // window ends is interpolated linearly between the neighbouring samples, which spreads the end weights onto
    // samples a-1, a and b, b+1. All weights are >= 0, so this is a weighted least-squares fit.
    const double lo_u = u_c - half, hi_u = u_c + half;
    const auto a = static_cast<std::size_t>(std::upper_bound(u.begin(), u.end(), lo_u) - u.begin());
    const auto b1 = static_cast<std::size_t>(std::lower_bound(u.begin(), u.end(), hi_u) - u.begin());
    if (a == 0 || b1 >= len || b1 < a + 4) continue;  // (cannot happen for a fitting window) or too few samples
    const std::size_t b = b1 - 1;
    const double lam_lo = (lo_u - u[a - 1]) / (u[a] - u[a - 1]);
    const double lam_hi = (hi_u - u[b]) / (u[b1] - u[b]);
    const bool by_angle = options.angle_weighting;
    auto q = [&](std::size_t i) { return by_angle ? u[i] : static_cast<double>(i); };
    const double q_lo = q(a - 1) + lam_lo * (q(a) - q(a - 1));
    const double q_hi = q(b) + lam_hi * (q(b1) - q(b));

    double s1 = 0, sc = 0, ss = 0, scc = 0, scs = 0, sss = 0, sx = 0, sxc = 0, sxs = 0;
    auto add = [&](std::size_t i, double w) {
      const double ci = c[i], si = s[i], xi = signal[i];
      const double wc = w * ci, ws = w * si;
      s1 += w;
      sc += wc;
      ss += ws;
      scc += wc * ci;
      scs += wc * si;
      sss += ws * si;
      sx += w * xi;
      sxc += wc * xi;
      sxs += ws * xi;
    };
    const double w_lo = 0.5 * (q(a) - q_lo), w_hi = 0.5 * (q_hi - q(b));
    add(a - 1, (1.0 - lam_lo) * w_lo);
    add(a, lam_lo * w_lo + 0.5 * (q(a + 1) - q_lo));
    for (std::size_t i = a + 1; i < b; ++i) add(i, 0.5 * (q(i + 1) - q(i - 1)));
    add(b, (1.0 - lam_hi) * w_hi + 0.5 * (q_hi - q(b - 1)));
    add(b1, lam_hi * w_hi);
    // Symmetric 3x3 normal equations [s1 sc ss; sc scc scs; ss scs sss] [c0 a b]' = [sx sxc sxs]', by Cramer's rule
    // (well conditioned: over >= 1 cycle of the order the three regressors are close to orthogonal).
    const double m00 = scc * sss - scs * scs;
    const double m01 = sc * sss - scs * ss;
    const double m02 = sc * scs - scc * ss;
    const double det = s1 * m00 - sc * m01 + ss * m02;
    if (!(std::abs(det) > 1e-9 * s1 * scc * sss)) continue;
    const double ca = (s1 * (sxc * sss - scs * sxs) - sx * (sc * sss - scs * ss) + ss * (sc * sxs - sxc * ss)) / det;
    const double cb = (s1 * (scc * sxs - sxc * scs) - sc * (sc * sxs - sxc * ss) + sx * (sc * scs - scc * ss)) / det;
    double phase = std::atan2(-cb, ca);
    if (phase <= -pi) phase = pi;
    out.times.push_back(x / sample_rate);
    out.speeds.push_back(f_c);
    out.amplitude.push_back(std::hypot(ca, cb));
    out.phase.push_back(phase);
  }
  return out;
}

}  // namespace turbodyn::signal

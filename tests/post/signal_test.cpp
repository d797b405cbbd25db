#include "post/signal.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace turbodyn::signal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

using std::numbers::pi;
// Hann response to a tone halfway between two bins: sinc(1/2) / (1 - 1/4) = 8 / (3 pi) = 0.8488, the largest
// scalloping loss of the window (15.1 %, 1.42 dB).
constexpr double hann_worst = 8.0 / (3.0 * pi);

// Samples of f(t) at t = i / fs, i = 0 .. n-1.
std::vector<double> sampled(std::size_t n, double fs, const std::function<double(double)>& f) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = f(static_cast<double>(i) / fs);
  return v;
}

std::size_t peak_bin(const Spectrogram& s, std::size_t segment, std::size_t from = 0) {
  std::size_t best = from;
  for (std::size_t k = from; k < s.n_bins(); ++k)
    if (s.at(segment, k) > s.at(segment, best)) best = k;
  return best;
}

// The message of the std::invalid_argument `f` throws; fails the test if it throws nothing.
std::string signal_error_of(const std::function<void()>& f) {
  try {
    f();
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

double angle_difference(double a, double b) { return std::remainder(a - b, 2.0 * pi); }

// ---------------------------------------------------------------------------------------------------------------
// Windows

// Every segment of s shows the amplitude of each (bin, amplitude) pair within tol.
void expect_in_every_segment(const Spectrogram& s, std::initializer_list<std::pair<std::size_t, double>> bins,
                             double tol) {
  for (std::size_t seg = 0; seg < s.n_segments(); ++seg)
    for (const auto& [bin, amplitude] : bins) EXPECT_NEAR(s.at(seg, bin), amplitude, tol) << "segment " << seg;
}

// STFT options with segments of n samples and window w, the rest at their defaults.
StftOptions options(std::size_t n, Window w) {
  StftOptions o;
  o.segment_length = n;
  o.window = w;
  return o;
}

TEST(Window, FromStringAcceptsTheNamesCaseInsensitively) {
  EXPECT_EQ(window_from_string("rectangular"), Window::Rectangular);
  EXPECT_EQ(window_from_string("hann"), Window::Hann);
  EXPECT_EQ(window_from_string("Hamming"), Window::Hamming);
  EXPECT_EQ(window_from_string("BLACKMAN"), Window::Blackman);
  EXPECT_EQ(window_from_string("flattop"), Window::FlatTop);
  for (Window w : {Window::Rectangular, Window::Hann, Window::Hamming, Window::Blackman, Window::FlatTop})
    EXPECT_EQ(window_from_string(to_string(w)), w);
}

TEST(Window, FromStringRejectsUnknownNamesListingTheValidOnes) {
  EXPECT_THAT(signal_error_of([] { window_from_string("hanning"); }),
              AllOf(HasSubstr("'hanning'"), HasSubstr("rectangular"), HasSubstr("hann,"), HasSubstr("hamming"),
                    HasSubstr("blackman"), HasSubstr("flattop")));
  EXPECT_THROW(window_from_string(""), std::invalid_argument);
}

TEST(Window, HannIsPeriodicWithSumHalfTheLength) {
  const std::size_t n = 16;
  const std::vector<double> w = window_coefficients(Window::Hann, n);
  ASSERT_EQ(w.size(), n);
  double sum = 0.0;
  for (double v : w) sum += v;
  EXPECT_NEAR(sum, 8.0, 1e-13);  // periodic form: sum = n/2 exactly (the symmetric form would give (n-1)/2)
  EXPECT_NEAR(w[0], 0.0, 1e-15);
  EXPECT_NEAR(w[4], 0.5, 1e-15);
  EXPECT_NEAR(w[8], 1.0, 1e-15);
  EXPECT_NEAR(w[12], 0.5, 1e-15);
  EXPECT_NEAR(w[1], 0.5 - 0.5 * std::cos(pi / 8.0), 1e-15);
  EXPECT_NEAR(w[1], 0.03806023374435663, 1e-15);
  for (std::size_t i = 1; i < n; ++i) EXPECT_DOUBLE_EQ(w[i], w[n - i]) << i;  // DFT-even: w[i] = w[n-i]
}

TEST(Window, OtherWindowsHaveTheirKnownValues) {
  const std::size_t n = 64;
  auto sum = [](const std::vector<double>& w) {
    double s = 0.0;
    for (double v : w) s += v;
    return s;
  };
  const auto rect = window_coefficients(Window::Rectangular, n);
  EXPECT_EQ(rect, std::vector<double>(n, 1.0));

  const auto hamming = window_coefficients(Window::Hamming, n);
  EXPECT_NEAR(hamming[0], 0.08, 1e-15);
  EXPECT_NEAR(hamming[n / 4], 0.54, 1e-15);
  EXPECT_NEAR(hamming[n / 2], 1.0, 1e-15);
  EXPECT_NEAR(sum(hamming), 0.54 * n, 1e-12);

  const auto blackman = window_coefficients(Window::Blackman, n);
  EXPECT_NEAR(blackman[0], 0.0, 1e-15);
  EXPECT_NEAR(blackman[n / 4], 0.34, 1e-15);  // 0.42 - 0.5 cos(pi/2) + 0.08 cos(pi)
  EXPECT_NEAR(blackman[n / 2], 1.0, 1e-15);
  EXPECT_NEAR(sum(blackman), 0.42 * n, 1e-12);

  // HFT95, peak-normalised.
  const double peak = 1.0 + 1.9383379 + 1.3045202 + 0.4028270 + 0.0350665;
  const auto flattop = window_coefficients(Window::FlatTop, n);
  EXPECT_NEAR(flattop[n / 2], 1.0, 1e-15);
  EXPECT_NEAR(flattop[0], (1.0 - 1.9383379 + 1.3045202 - 0.4028270 + 0.0350665) / peak, 1e-15);
  EXPECT_NEAR(sum(flattop), n / peak, 1e-12);

  EXPECT_TRUE(window_coefficients(Window::Hann, 0).empty());
  EXPECT_EQ(window_coefficients(Window::Hann, 1), std::vector<double>{1.0});
}

// ---------------------------------------------------------------------------------------------------------------
// stft: amplitude calibration

// fs = N Hz makes the bin spacing 1 Hz, so a tone at an integer frequency lies on a bin. The lengths exercise the
// three FFT paths: 1024 (radix-2 on 512 packed points), 1000 (Bluestein on 500 packed points), 999 (odd: Bluestein
// on the full length).
TEST(Stft, ToneOnABinIsRecoveredExactly) {
  for (std::size_t n : {1024u, 1000u, 999u}) {
    const double fs = static_cast<double>(n);
    // The last bin below Nyquist only with the rectangular window: with Hann, the tone's negative-frequency image
    // lies in the adjacent bin and leaks into it.
    const double last = std::floor((static_cast<double>(n) - 1.0) / 2.0);
    for (double f : {37.0, 120.0, last}) {
      const double A = 2.5;
      const auto x = sampled(3 * n, fs, [&](double t) { return A * std::cos(2 * pi * f * t + 0.3); });
      for (Window w : {Window::Rectangular, Window::Hann}) {
        if (f == last && w != Window::Rectangular) continue;
        SCOPED_TRACE("n = " + std::to_string(n) + ", f = " + std::to_string(f) + ", window " + to_string(w));
        StftOptions o;
        o.segment_length = n;
        o.overlap = 0.5;
        o.window = w;
        const Spectrogram s = stft(x, fs, o);
        ASSERT_EQ(s.n_bins(), n / 2 + 1);
        ASSERT_EQ(s.n_segments(), 5u);
        const auto k = static_cast<std::size_t>(f);
        EXPECT_DOUBLE_EQ(s.frequencies[k], f);
        const double tol = w == Window::Rectangular ? 1e-9 : 1e-6;
        for (std::size_t seg = 0; seg < s.n_segments(); ++seg) {
          EXPECT_EQ(peak_bin(s, seg), k);
          EXPECT_NEAR(s.at(seg, k), A, tol);
          // Everything else is zero (rectangular) or only the two neighbours carry A/2 (Hann).
          for (std::size_t j = 0; j < s.n_bins(); ++j) {
            if (j == k) continue;
            const double expected = (w == Window::Hann && (j + 1 == k || j == k + 1)) ? A / 2 : 0.0;
            EXPECT_NEAR(s.at(seg, j), expected, tol) << "bin " << j;
          }
        }
      }
    }
  }
}

// Every segment length exercises one FFT path (radix-2, Bluestein on the packed half, odd Bluestein); a direct
// O(N^2) DFT of an arbitrary signal is the reference.
TEST(Stft, MatchesADirectDftForAnyLength) {
  std::vector<std::size_t> lengths;
  for (std::size_t n = 8; n <= 40; ++n) lengths.push_back(n);
  for (std::size_t n : {64u, 97u, 250u, 256u, 1000u}) lengths.push_back(n);
  for (std::size_t n : lengths) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i)
      x[i] = std::sin(0.37 * static_cast<double>(i * i) + 1.0) + 0.1 * static_cast<double>(i % 5);
    StftOptions o = options(n, Window::Rectangular);
    o.remove_mean = false;
    const Spectrogram s = stft(x, 1.0, o);
    ASSERT_EQ(s.n_segments(), 1u);
    ASSERT_EQ(s.n_bins(), n / 2 + 1);
    for (std::size_t k = 0; k < s.n_bins(); ++k) {
      double re = 0.0, im = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        const double angle = -2.0 * pi * static_cast<double>((j * k) % n) / static_cast<double>(n);
        re += x[j] * std::cos(angle);
        im += x[j] * std::sin(angle);
      }
      const bool single = k == 0 || 2 * k == n;
      const double expected = (single ? 1.0 : 2.0) * std::hypot(re, im) / static_cast<double>(n);
      EXPECT_NEAR(s.at(0, k), expected, 1e-12) << "n = " << n << ", bin " << k;
    }
  }
}

TEST(Stft, DcAndNyquistAreNotDoubled) {
  const std::size_t n = 1000;
  std::vector<double> x(2 * n);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.7 + 1.9 * (i % 2 == 0 ? 1.0 : -1.0);
  StftOptions o = options(n, Window::Rectangular);
  o.remove_mean = false;
  const Spectrogram s = stft(x, 2000.0, o);
  ASSERT_EQ(s.n_bins(), 501u);
  EXPECT_DOUBLE_EQ(s.frequencies.back(), 1000.0);
  expect_in_every_segment(s, {{0, 0.7}, {500, 1.9}, {250, 0.0}}, 1e-12);
}

TEST(Stft, RemoveMeanTakesOutTheDcButNotTheTone) {
  const std::size_t n = 512;
  const double fs = 512.0;
  const auto x = sampled(4 * n, fs, [](double t) { return 3.0 + 0.5 * std::sin(2 * pi * 40.0 * t); });
  for (Window w : {Window::Rectangular, Window::Hann, Window::FlatTop}) {
    SCOPED_TRACE(to_string(w));
    StftOptions o = options(n, w);
    o.remove_mean = true;
    const Spectrogram with = stft(x, fs, o);
    o.remove_mean = false;
    const Spectrogram without = stft(x, fs, o);
    expect_in_every_segment(with, {{0, 0.0}, {40, 0.5}}, 1e-9);
    expect_in_every_segment(without, {{0, 3.0}, {40, 0.5}}, 1e-9);
  }
}

// A tone halfway between bins k and k+1: Hann shows (2/pi)/(1 - 1/4) = 8/(3 pi) = 0.8488 A at both (the
// 1.42 dB = 15.1 % scalloping loss); other offsets lose less. The flat top stays within 0.1 % at any offset.
TEST(Stft, OffBinTonesStayWithinTheWindowsScallopingBounds) {
  const std::size_t n = 1024;
  const double fs = 1024.0;
  const double A = 1.3;
  for (double offset : {0.1, 0.25, 0.37, 0.5}) {
    const double f = 200.0 + offset;
    SCOPED_TRACE("offset " + std::to_string(offset) + " bins");
    const auto x = sampled(2 * n, fs, [&](double t) { return A * std::cos(2 * pi * f * t + 1.0); });
    StftOptions o = options(n, Window::FlatTop);
    const Spectrogram flat = stft(x, fs, o);
    o.window = Window::Hann;
    const Spectrogram hann = stft(x, fs, o);
    for (std::size_t seg = 0; seg < flat.n_segments(); ++seg) {
      const std::size_t k = peak_bin(flat, seg);
      EXPECT_LE(std::abs(flat.frequencies[k] - f), 0.5 + 1e-12);
      EXPECT_NEAR(flat.at(seg, k), A, 1e-3 * A);

      const std::size_t kh = peak_bin(hann, seg);
      EXPECT_LE(std::abs(hann.frequencies[kh] - f), 0.5 + 1e-12);
      EXPECT_GE(hann.at(seg, kh), (hann_worst - 1e-4) * A);
      EXPECT_LE(hann.at(seg, kh), A);
      if (offset == 0.5) {
        EXPECT_NEAR(hann.at(seg, 200), hann_worst * A, 1e-4 * A);
        EXPECT_NEAR(hann.at(seg, 201), hann_worst * A, 1e-4 * A);
      }
    }
  }
}

// Hann sidelobes: on a bin, all other bins but the two neighbours are exactly zero; off a bin, the leakage of a
// tone d bins away is |sinc(d)| / (d^2 - 1), below -41.8 dB for d >= 3.5 and below -48.7 dB for d >= 4.5.
TEST(Stft, TwoTonesAreBothRecoveredWithoutLeakageBetweenThem) {
  const std::size_t n = 1024;
  const double fs = 8192.0;  // 8 Hz bins
  StftOptions o = options(n, Window::Hann);
  {  // on bins 200 and 208
    const auto x = sampled(4 * n, fs, [](double t) {
      return 1.0 * std::cos(2 * pi * 1600.0 * t + 0.2) + 0.25 * std::cos(2 * pi * 1664.0 * t - 1.0);
    });
    const Spectrogram s = stft(x, fs, o);
    for (std::size_t seg = 0; seg < s.n_segments(); ++seg) {
      EXPECT_NEAR(s.at(seg, 200), 1.0, 1e-6);
      EXPECT_NEAR(s.at(seg, 208), 0.25, 1e-6);
      for (std::size_t k = 202; k <= 206; ++k) EXPECT_LT(s.at(seg, k), 1e-9);
    }
  }
  {  // off bins: 300.4 and 310.6 bins (10.2 bins apart), amplitudes 1 and 0.3
    const double f1 = 300.4 * 8.0, f2 = 310.6 * 8.0;
    const auto x = sampled(4 * n, fs, [&](double t) {
      return 1.0 * std::cos(2 * pi * f1 * t + 0.2) + 0.3 * std::cos(2 * pi * f2 * t - 1.0);
    });
    const Spectrogram s = stft(x, fs, o);
    for (std::size_t seg = 0; seg < s.n_segments(); ++seg) {
      EXPECT_GE(s.at(seg, 300), hann_worst * 1.0);  // within the scalloping loss of the nearest bin
      EXPECT_LE(s.at(seg, 300), 1.0);
      EXPECT_GE(s.at(seg, 311), hann_worst * 0.3);
      EXPECT_LE(s.at(seg, 311), 0.3);
      for (std::size_t k = 304; k <= 307; ++k)  // >= 3.5 bins from both tones
        EXPECT_LT(s.at(seg, k), 0.01 * 1.0) << "bin " << k << ": leakage above -40 dB";
    }
  }
}

// A linear chirp f(t) = f0 + k t sweeps k T = 1 bin during one segment of T = 0.125 s (fs = 8192 Hz, N = 1024,
// 8 Hz bins). Around a segment centre t_c the phase relative to a bin frequency f_b is
//   theta(tau) = 2 pi (f(t_c) - f_b) tau + pi k tau^2  (+ const),  tau = t - t_c,
// and the bin shows A |sum w e^{i theta}| / sum w >= A sum w (1 - theta^2 / 2) / sum w (as cos x >= 1 - x^2/2).
// For the nearest bin (|f(t_c) - f_b| <= 4 Hz) this lower bound is computed per segment: its frequency-offset
// part is the Hann scalloping (<= 16 %), the chirp part (pi k T^2)^2 E_w[(tau/T)^4] / 2 = 1.3 % is the spread of
// the chirp over one segment. The peak can only be higher, and never above A.
TEST(Stft, ChirpPeakFollowsTheInstantaneousFrequency) {
  const double fs = 8192.0, f0 = 1000.0, k = 64.0, A = 0.8;
  const std::size_t n = 1024;
  const auto x = sampled(65536, fs, [&](double t) { return A * std::cos(2 * pi * (f0 * t + 0.5 * k * t * t) + 0.4); });
  StftOptions o;
  o.segment_length = n;
  o.overlap = 0.75;
  o.window = Window::Hann;
  const Spectrogram s = stft(x, fs, o);
  ASSERT_EQ(s.n_segments(), 1 + (65536 - n) / 256);
  const std::vector<double> w = window_coefficients(Window::Hann, n);
  double wsum = 0.0;
  for (double v : w) wsum += v;
  const double bin = fs / static_cast<double>(n);
  std::size_t near_bin_segments = 0;
  for (std::size_t seg = 0; seg < s.n_segments(); ++seg) {
    const double f_c = f0 + k * s.times[seg];
    const std::size_t kp = peak_bin(s, seg);
    EXPECT_LE(std::abs(s.frequencies[kp] - f_c), bin) << "segment " << seg;
    const auto kn = static_cast<std::size_t>(std::lround(f_c / bin));
    double mean_theta2 = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double tau = (static_cast<double>(j) - 0.5 * static_cast<double>(n - 1)) / fs;
      const double theta = 2 * pi * (f_c - s.frequencies[kn]) * tau + pi * k * tau * tau;
      mean_theta2 += w[j] * theta * theta;
    }
    mean_theta2 /= wsum;
    EXPECT_GE(s.at(seg, kn), A * (1.0 - 0.5 * mean_theta2)) << "segment " << seg;
    EXPECT_LE(s.at(seg, kp), A * (1.0 + 1e-6)) << "segment " << seg;
    if (std::abs(f_c - s.frequencies[kn]) <= 0.1 * bin) {  // centred on a bin: only the chirp spread is lost
      ++near_bin_segments;
      EXPECT_NEAR(s.at(seg, kp), A, 0.02 * A) << "segment " << seg;
    }
  }
  EXPECT_GT(near_bin_segments, 30u);
}

// ---------------------------------------------------------------------------------------------------------------
// stft: segmentation, resampling onto rotor speed

TEST(Stft, SegmentsAndTimes) {
  const std::vector<double> x(4196, 1.0);
  StftOptions o;
  o.segment_length = 1024;
  o.overlap = 0.75;
  const Spectrogram s = stft(x, 100.0, o);
  EXPECT_EQ(s.hop, 256u);
  EXPECT_EQ(s.segment_length, 1024u);
  EXPECT_DOUBLE_EQ(s.sample_rate, 100.0);
  ASSERT_EQ(s.n_segments(), 13u);  // 1 + (4196 - 1024) / 256
  EXPECT_EQ(s.amplitude.size(), 13u * 513u);
  for (std::size_t seg = 0; seg < s.n_segments(); ++seg)
    EXPECT_DOUBLE_EQ(s.times[seg], (256.0 * static_cast<double>(seg) + 511.5) / 100.0);
  EXPECT_DOUBLE_EQ(s.frequencies[1], 100.0 / 1024.0);
  EXPECT_DOUBLE_EQ(s.frequencies.back(), 50.0);

  o.overlap = 0.0;
  EXPECT_EQ(stft(x, 100.0, o).hop, 1024u);
  o.overlap = 0.9999;  // rounds to an overlap of the whole segment: hop clamps to 1 sample
  EXPECT_EQ(stft(x, 100.0, o).hop, 1u);
}

TEST(Stft, ValuesAtSegmentCentresInterpolateTheSeries) {
  const double fs = 1000.0;
  const std::vector<double> x(5000, 0.0);
  StftOptions o;
  o.segment_length = 1000;  // centres at half samples: 499.5 + 250 s
  const Spectrogram s = stft(x, fs, o);
  const auto speed = sampled(5000, fs, [](double t) { return 5.0 + 625.0 * t; });
  const std::vector<double> v = values_at_segment_centres(s, speed, fs);
  ASSERT_EQ(v.size(), s.n_segments());
  for (std::size_t seg = 0; seg < v.size(); ++seg) EXPECT_NEAR(v[seg], 5.0 + 625.0 * s.times[seg], 1e-9);

  EXPECT_THAT(signal_error_of([&] { values_at_segment_centres(s, std::vector<double>(3000, 1.0), fs); }),
              HasSubstr("outside the series of 3000 samples"));
  EXPECT_THAT(signal_error_of([&] { values_at_segment_centres(s, speed, 0.0); }), HasSubstr("sample rate"));
}

// A run-up as in the simulations: fs = 20 kHz, 4 s, 0 -> 2500 Hz. The spectrogram rows, placed at the rotor speed
// of their segment centre, show the 1x line at f_d. The sweep during one segment is 625 Hz/s * 0.2048 s = 128 Hz,
// so the peak lies within half of that (+ one bin) of f_d.
TEST(Stft, RunUpSpectrogramShowsTheOneTimesOrderLine) {
  const double fs = 20000.0, k = 625.0;
  const auto x = sampled(80000, fs, [&](double t) {
    const double phi = 2 * pi * 0.5 * k * t * t;
    return std::cos(phi) + 0.3 * std::cos(0.5 * phi);
  });
  const auto f_d = sampled(80000, fs, [&](double t) { return k * t; });
  const Spectrogram s = stft(x, fs);
  ASSERT_EQ(s.n_segments(), 75u);
  ASSERT_EQ(s.n_bins(), 2049u);
  const std::vector<double> speed = values_at_segment_centres(s, f_d, fs);
  const double bin = fs / 4096.0;
  for (std::size_t seg = 0; seg < s.n_segments(); ++seg) {
    if (speed[seg] < 300.0) continue;
    const auto from = static_cast<std::size_t>(0.75 * speed[seg] / bin);
    EXPECT_NEAR(s.frequencies[peak_bin(s, seg, from)], speed[seg], 64.0 + bin) << "segment " << seg;
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Window leakage and sub-synchronous lines

TEST(WindowLeakage, IsTheDiscreteFourierTransformOfTheWindow) {
  for (const Window w : {Window::Rectangular, Window::Hann, Window::Hamming, Window::Blackman, Window::FlatTop})
    for (const std::size_t n : {std::size_t{64}, std::size_t{4096}}) {
      const std::vector<double> c = window_coefficients(w, n);
      double sum = 0.0;
      for (double v : c) sum += v;
      for (const double nu : {0.0, 0.37, 1.0, 2.5, 3.75, 10.2, 31.0}) {
        std::complex<double> direct = 0.0;
        for (std::size_t i = 0; i < n; ++i)
          direct += c[i] * std::polar(1.0, -2.0 * pi * nu * static_cast<double>(i) / static_cast<double>(n));
        EXPECT_NEAR(window_leakage(w, n, nu), std::abs(direct) / sum, 1e-12)
            << to_string(w) << " n " << n << " nu " << nu;
      }
    }
}

TEST(WindowLeakage, HighestSidelobesAreHarrisValues) {
  // docs/references.md §10: Harris, "On the use of windows for harmonic analysis with the DFT", Proc. IEEE 66(1),
  // 1978, Table 1: highest sidelobe level -13 dB (rectangular), -32 dB (Hann), -43 dB (Hamming), -58 dB (Blackman).
  const auto highest_sidelobe_db = [](Window w, double from) {
    double top = 0.0;
    for (double nu = from; nu < 40.0; nu += 1.0 / 64.0) top = std::max(top, window_leakage(w, 4096, nu));
    return 20.0 * std::log10(top);
  };
  EXPECT_NEAR(highest_sidelobe_db(Window::Rectangular, 1.0), -13.26, 0.05);
  EXPECT_NEAR(highest_sidelobe_db(Window::Hann, 2.0), -31.47, 0.05);
  EXPECT_NEAR(highest_sidelobe_db(Window::Hamming, 2.0), -42.7, 0.3);
  EXPECT_NEAR(highest_sidelobe_db(Window::Blackman, 3.0), -58.1, 0.3);
  // The main lobe ends at 1, 2, 2 and 3 bins: zeros of the transform.
  EXPECT_LT(window_leakage(Window::Rectangular, 4096, 1.0), 1e-12);
  EXPECT_LT(window_leakage(Window::Hann, 4096, 2.0), 1e-12);
  EXPECT_LT(window_leakage(Window::Blackman, 4096, 3.0), 1e-12);
}

TEST(WindowLeakage, MarginIsWhereTheLeakageStaysBelowTheLevel) {
  for (const Window w : {Window::Rectangular, Window::Hann, Window::Hamming, Window::Blackman, Window::FlatTop}) {
    const std::size_t m = leakage_margin_bins(w, 4096, 1e-3);
    ASSERT_GT(m, 0u) << to_string(w);
    for (double nu = static_cast<double>(m); nu <= 2048.0; nu += 1.0 / 16.0)
      ASSERT_LE(window_leakage(w, 4096, nu), 1e-3) << to_string(w) << " at " << nu;
    double above = 0.0;
    for (double nu = static_cast<double>(m) - 1.0; nu < static_cast<double>(m); nu += 1.0 / 16.0)
      above = std::max(above, window_leakage(w, 4096, nu));
    EXPECT_GT(above, 1e-3) << to_string(w) << ": the margin is not the smallest";
  }
  EXPECT_EQ(leakage_margin_bins(Window::Hann, 4096, 1e-3), 7u);
  EXPECT_EQ(leakage_margin_bins(Window::Hamming, 4096, 1e-3), 47u);
  EXPECT_EQ(leakage_margin_bins(Window::Rectangular, 4096, 1e-3), 322u);  // 1 / (pi 321.5) < 1e-3
  EXPECT_THAT(signal_error_of([] { leakage_margin_bins(Window::Hann, 4096, 0.0); }), HasSubstr("level"));
  EXPECT_THAT(signal_error_of([] { leakage_margin_bins(Window::Hann, 4, 1e-3); }), HasSubstr("at least 8"));
}

// A run-up at 625 Hz/s (the paper's 150,000 rpm in 4 s) with a strong 1x line of amplitude 100 and, from 2 s on,
// a whirl of amplitude 0.5 at 0.42 x the rotor speed.
struct RunUpWithWhirl {
  static constexpr double fs = 20000.0, rate = 625.0;
  std::vector<double> x, f_d;
  explicit RunUpWithWhirl(double whirl) {
    x = sampled(80000, fs, [&](double t) {
      const double phi = 2 * pi * 0.5 * rate * t * t;
      return 100.0 * std::cos(phi) + (t >= 2.0 ? whirl * std::cos(0.42 * phi) : 0.0);
    });
    f_d = sampled(80000, fs, [&](double t) { return rate * t; });
  }
};

TEST(SubsynchronousLine, FindsTheWhirlBesideAStrongSynchronousLine) {
  const RunUpWithWhirl r(0.5);
  const Spectrogram s = stft(r.x, r.fs);
  const std::size_t m = leakage_margin_bins(Window::Hann, 4096, 1e-3);
  const auto line = largest_subsynchronous_line(s, r.f_d, r.fs, 1e9, m);
  ASSERT_TRUE(line.has_value());
  // The whirl sweeps 0.42 x 128 Hz in a segment: its amplitude is spread, read as at least half of it.
  EXPECT_GT(line->amplitude, 0.25);
  EXPECT_LT(line->amplitude, 0.5);
  EXPECT_GE(line->time_s, 2.0);
  EXPECT_NEAR(line->frequency_hz / line->speed_hz, 0.42, 0.03);
  EXPECT_NEAR(line->speed_hz, r.rate * line->time_s, 1e-9);
  // At the end: the last segment's whirl, at its speed.
  const auto end = largest_subsynchronous_line(s, r.f_d, r.fs, 1e9, m, s.n_segments() - 1);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->segment, s.n_segments() - 1);
  EXPECT_NEAR(end->frequency_hz / end->speed_hz, 0.42, 0.03);
  EXPECT_GT(end->amplitude, 0.25);
}

TEST(SubsynchronousLine, TheSynchronousLineAloneLeavesNothingAboveTheLeakageLevel) {
  const RunUpWithWhirl r(0.0);
  const Spectrogram s = stft(r.x, r.fs);
  const auto line = largest_subsynchronous_line(s, r.f_d, r.fs, 1e9, leakage_margin_bins(Window::Hann, 4096, 1e-3));
  ASSERT_TRUE(line.has_value());
  EXPECT_LT(line->amplitude, 100.0 * 1e-3);
  // Without the margin the 1x line's own spread counts.
  EXPECT_GT(largest_subsynchronous_line(s, r.f_d, r.fs, 1e9, 0)->amplitude, 1.0);
}

TEST(SubsynchronousLine, NoBinQualifiesBelowTwiceTheMarginOrAboveTheFrequencyRange) {
  const RunUpWithWhirl r(0.5);
  const Spectrogram s = stft(r.x, r.fs);
  const std::vector<double> slow(r.f_d.size(), 60.0);  // 60 Hz < 2 x 7 bins of 4.88 Hz
  EXPECT_FALSE(largest_subsynchronous_line(s, slow, r.fs, 1e9, 7).has_value());
  const auto capped = largest_subsynchronous_line(s, r.f_d, r.fs, 300.0, 7);
  ASSERT_TRUE(capped.has_value());
  EXPECT_LE(capped->frequency_hz, 300.0);
  EXPECT_FALSE(largest_subsynchronous_line(s, r.f_d, r.fs, 1e9, 7, s.n_segments()).has_value());
  const std::vector<double> short_speed(r.f_d.begin(), r.f_d.begin() + 79000);  // the last segment ends at 79,872
  EXPECT_THAT(signal_error_of([&] { largest_subsynchronous_line(s, short_speed, r.fs, 1e9, 7); }),
              HasSubstr("rotor frequency has 79000 samples"));
}

TEST(Stft, InvalidInputsAreRejectedWithAClearMessage) {
  const std::vector<double> x(100, 0.0);
  StftOptions o;
  o.segment_length = 32;
  EXPECT_THAT(signal_error_of([&] { stft(x, 0.0, o); }), HasSubstr("sample rate"));
  EXPECT_THAT(signal_error_of([&] { stft(x, -5.0, o); }), HasSubstr("sample rate"));
  EXPECT_THAT(signal_error_of([&] { stft(x, std::numeric_limits<double>::quiet_NaN(), o); }), HasSubstr("sample rate"));
  EXPECT_THAT(signal_error_of([&] { stft(std::vector<double>(31, 0.0), 10.0, o); }),
              AllOf(HasSubstr("31 samples"), HasSubstr("shorter than one segment of 32")));
  {
    StftOptions bad = o;
    bad.segment_length = 7;
    EXPECT_THAT(signal_error_of([&] { stft(x, 10.0, bad); }), HasSubstr("segment_length must be at least 8"));
  }
  for (double overlap : {-0.1, 1.0, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    StftOptions bad = o;
    bad.overlap = overlap;
    EXPECT_THAT(signal_error_of([&] { stft(x, 10.0, bad); }), HasSubstr("overlap must be a fraction in [0, 1)"));
  }
  std::vector<double> with_nan = x;
  with_nan[17] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(signal_error_of([&] { stft(with_nan, 10.0, o); }),
              AllOf(HasSubstr("sample 17"), HasSubstr("not finite")));
  std::vector<double> with_inf = x;
  with_inf[99] = -std::numeric_limits<double>::infinity();
  EXPECT_THAT(signal_error_of([&] { stft(with_inf, 10.0, o); }),
              AllOf(HasSubstr("sample 99"), HasSubstr("not finite")));
}

// ---------------------------------------------------------------------------------------------------------------
// Order tracking

struct RunUp {
  double fs = 20000.0;
  double k = 625.0;  // Hz/s: 0 -> 2500 Hz in 4 s
  std::size_t n = 80000;
  double p1 = 0.7, p2 = -2.1, a2 = 0.3;
  static double a1(double speed) { return 0.5 + speed / 2500.0; }  // 1x amplitude, linear in speed
  std::vector<double> x, phi, f;

  RunUp() {
    f = sampled(n, fs, [&](double t) { return k * t; });
    phi = sampled(n, fs, [&](double t) { return 2 * pi * 0.5 * k * t * t; });
    x.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      x[i] = a1(f[i]) * std::cos(phi[i] + p1) + a2 * std::cos(0.5 * phi[i] + p2);
  }
};

const RunUp& run_up() {
  static const RunUp r;
  return r;
}

TEST(TrackOrder, RecoversBothOrdersAlongARunUp) {
  const RunUp& r = run_up();
  OrderTrackOptions o;  // 1x, 8 revolutions, 200 points
  const OrderTrack one = track_order(r.x, r.phi, r.f, r.fs, o);
  ASSERT_EQ(one.times.size(), 200u);
  ASSERT_EQ(one.speeds.size(), 200u);
  ASSERT_EQ(one.amplitude.size(), 200u);
  ASSERT_EQ(one.phase.size(), 200u);
  // The first window centre is where 8 revolutions (a half window of 4 revolutions back to phi = 0) fit:
  // 0.5 k t^2 = 4 -> t = 0.113 s, 70.7 Hz. The last is 4 revolutions before the end, at 2499 Hz.
  EXPECT_NEAR(one.speeds.front(), std::sqrt(2.0 * 4.0 * r.k), 0.1);
  EXPECT_NEAR(one.speeds.back(), 2500.0 - r.k * 4.0 / 2500.0, 0.1);
  const double step = one.times[1] - one.times[0];
  for (std::size_t j = 0; j < one.times.size(); ++j) {
    SCOPED_TRACE("point " + std::to_string(j) + " at " + std::to_string(one.speeds[j]) + " Hz");
    if (j > 0) {
      EXPECT_NEAR(one.times[j] - one.times[j - 1], step, 1e-12);
    }
    EXPECT_NEAR(one.speeds[j], r.k * one.times[j], 1e-9);
    EXPECT_NEAR(one.amplitude[j], RunUp::a1(one.speeds[j]), 0.01 * RunUp::a1(one.speeds[j]));
    EXPECT_NEAR(angle_difference(one.phase[j], r.p1), 0.0, 0.01);
    EXPECT_GT(one.phase[j], -pi);
    EXPECT_LE(one.phase[j], pi);
  }

  o.order = 0.5;
  const OrderTrack half = track_order(r.x, r.phi, r.f, r.fs, o);
  ASSERT_EQ(half.times.size(), 200u);
  for (std::size_t j = 0; j < half.times.size(); ++j) {
    SCOPED_TRACE("point " + std::to_string(j) + " at " + std::to_string(half.speeds[j]) + " Hz");
    EXPECT_NEAR(half.amplitude[j], r.a2, 0.01 * r.a2);
    EXPECT_NEAR(angle_difference(half.phase[j], r.p2), 0.0, 0.01);
  }
}

// Without angle weighting every sample counts the same, so where the speed changes much within a window (the first
// windows of a run-up from standstill span 0 .. 100 Hz) the orders are no longer orthogonal and leak.
TEST(TrackOrder, AngleWeightingKeepsOrdersApartAtTheStartOfARunUp) {
  const RunUp& r = run_up();
  OrderTrackOptions o;
  o.points = 5;
  o.angle_weighting = true;
  const OrderTrack weighted = track_order(r.x, r.phi, r.f, r.fs, o);
  o.angle_weighting = false;
  const OrderTrack plain = track_order(r.x, r.phi, r.f, r.fs, o);
  ASSERT_EQ(weighted.times.size(), 5u);
  ASSERT_EQ(plain.times.size(), 5u);
  const double truth = RunUp::a1(weighted.speeds[0]);
  EXPECT_NEAR(weighted.amplitude[0], truth, 0.005 * truth);
  EXPECT_GT(std::abs(plain.amplitude[0] - truth), 0.02 * truth);
  // Higher up the speed changes little within 8 revolutions and both agree with the truth.
  for (std::size_t j = 1; j < 5; ++j) {
    const double a = RunUp::a1(plain.speeds[j]);
    EXPECT_NEAR(plain.amplitude[j], a, 0.01 * a);
    EXPECT_NEAR(weighted.amplitude[j], a, 0.01 * a);
  }
}

// Constant speed 50 Hz, fs = 5 kHz, 10 s. An interfering order 1/R away is orthogonal to the tracked one over the
// window of R revolutions; one only 0.4/R away is not separated (the 1x estimate picks up sinc(0.4) = 76 % of it).
TEST(TrackOrder, ResolutionIsOneOverRevolutions) {
  const double fs = 5000.0, speed = 50.0;
  const std::size_t n = 50000;
  const auto f = sampled(n, fs, [&](double) { return speed; });
  const auto phi = sampled(n, fs, [&](double t) { return 2 * pi * speed * t; });
  auto signal_with = [&](double other_order) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i)
      x[i] = 5.0 + std::cos(phi[i] + 1.0) + 0.5 * std::cos(other_order * phi[i] - 0.5);
    return x;
  };
  OrderTrackOptions o;
  o.points = 20;
  o.revolutions = 8.0;
  const OrderTrack separated = track_order(signal_with(1.0 + 1.0 / 8.0), phi, f, fs, o);
  ASSERT_EQ(separated.times.size(), 20u);
  for (std::size_t j = 0; j < separated.times.size(); ++j) {
    EXPECT_NEAR(separated.amplitude[j], 1.0, 1e-6);  // also unaffected by the offset 5.0
    EXPECT_NEAR(angle_difference(separated.phase[j], 1.0), 0.0, 1e-6);
  }
  const std::vector<double> close = signal_with(1.05);
  const OrderTrack mixed = track_order(close, phi, f, fs, o);
  double worst = 0.0;
  for (double a : mixed.amplitude) worst = std::max(worst, std::abs(a - 1.0));
  EXPECT_GT(worst, 0.2);
  o.revolutions = 40.0;  // 1.05 is now 2/R away
  const OrderTrack resolved = track_order(close, phi, f, fs, o);
  for (double a : resolved.amplitude) EXPECT_NEAR(a, 1.0, 1e-6);
}

TEST(TrackOrder, PhaseConventionAndRotationDirection) {
  const double fs = 4000.0, speed = 30.0;
  const std::size_t n = 8000;
  const auto f = sampled(n, fs, [&](double) { return -speed; });
  // The rotor turns backwards: phi decreases. The component is still A cos(n phi + phase).
  const auto phi = sampled(n, fs, [&](double t) { return 3.0 - 2 * pi * speed * t; });
  for (double p : {pi, -pi / 2, 0.0, 2.5, -3.0}) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = 0.2 * std::cos(2.0 * phi[i] + p);
    OrderTrackOptions o;
    o.order = 2.0;
    o.points = 7;
    const OrderTrack t = track_order(x, phi, f, fs, o);
    ASSERT_EQ(t.times.size(), 7u);
    for (std::size_t j = 0; j < t.times.size(); ++j) {
      EXPECT_NEAR(t.amplitude[j], 0.2, 1e-9);
      EXPECT_NEAR(angle_difference(t.phase[j], p), 0.0, 1e-9);
      EXPECT_GT(t.phase[j], -pi);
      EXPECT_LE(t.phase[j], pi);
      EXPECT_DOUBLE_EQ(t.speeds[j], -speed);
    }
  }
}

TEST(TrackOrder, SkipsSlowAndAliasedPoints) {
  const RunUp& r = run_up();
  OrderTrackOptions o;
  o.min_speed = 500.0;
  o.points = 50;
  const OrderTrack t = track_order(r.x, r.phi, r.f, r.fs, o);
  ASSERT_EQ(t.times.size(), 50u);
  EXPECT_NEAR(t.speeds.front(), 500.0, 0.1);  // the usable span starts where the rotor reaches min_speed
  for (double s : t.speeds) EXPECT_GE(s, 500.0);

  o.order = 5.0;  // 5 x speed reaches fs/2 = 10 kHz at 2000 Hz: the points above are aliased and skipped
  const OrderTrack aliased = track_order(r.x, r.phi, r.f, r.fs, o);
  EXPECT_LT(aliased.times.size(), 50u);
  EXPECT_GT(aliased.times.size(), 30u);
  for (double s : aliased.speeds) EXPECT_LT(s, 2000.0);
}

TEST(TrackOrder, InvalidInputsAreRejectedWithAClearMessage) {
  const std::size_t n = 1000;
  const double fs = 1000.0;
  const auto f = sampled(n, fs, [](double) { return 20.0; });
  const auto phi = sampled(n, fs, [](double t) { return 2 * pi * 20.0 * t; });
  const std::vector<double> x(n, 0.0);
  const OrderTrackOptions o;
  EXPECT_THAT(signal_error_of([&] { track_order(x, phi, f, 0.0, o); }), HasSubstr("sample rate"));
  EXPECT_THAT(signal_error_of([&] { track_order(std::vector<double>(999, 0.0), phi, f, fs, o); }),
              AllOf(HasSubstr("same length"), HasSubstr("999")));
  EXPECT_THAT(signal_error_of([&] { track_order(x, phi, std::vector<double>(5, 1.0), fs, o); }),
              HasSubstr("same length"));
  EXPECT_THAT(signal_error_of([&] { track_order({1.0}, {0.0}, {1.0}, fs, o); }), HasSubstr("at least 2 samples"));
  {
    auto bad = x;
    bad[3] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THAT(signal_error_of([&] { track_order(bad, phi, f, fs, o); }),
                AllOf(HasSubstr("signal sample 3"), HasSubstr("not finite")));
    auto bad_phi = phi;
    bad_phi[5] = std::numeric_limits<double>::infinity();
    EXPECT_THAT(signal_error_of([&] { track_order(x, bad_phi, f, fs, o); }), HasSubstr("rotor_angle sample 5"));
    auto bad_f = f;
    bad_f[7] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THAT(signal_error_of([&] { track_order(x, phi, bad_f, fs, o); }), HasSubstr("rotor_frequency sample 7"));
  }
  {
    auto back = phi;
    back[500] = back[498];
    EXPECT_THAT(signal_error_of([&] { track_order(x, back, f, fs, o); }),
                AllOf(HasSubstr("monotonic"), HasSubstr("sample 500")));
    EXPECT_THAT(signal_error_of([&] { track_order(x, std::vector<double>(n, 1.0), f, fs, o); }),
                HasSubstr("does not change"));
  }
  auto with = [&](auto change) {
    OrderTrackOptions b;
    change(b);
    return signal_error_of([&] { track_order(x, phi, f, fs, b); });
  };
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.order = 0.0; }), HasSubstr("order must be"));
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.order = -1.0; }), HasSubstr("order must be"));
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.revolutions = 0.0; }), HasSubstr("revolutions must be"));
  EXPECT_THAT(with([](OrderTrackOptions& b) {
                b.order = 0.1;
                b.revolutions = 5.0;
              }),
              HasSubstr("order * revolutions must be >= 1"));
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.points = 0; }), HasSubstr("points must be at least 1"));
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.min_speed = -1.0; }), HasSubstr("min_speed"));
  // 0.999 s at 20 Hz = 19.98 revolutions: a window of 30 does not fit; no sample turns at 25 Hz.
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.revolutions = 30.0; }),
              AllOf(HasSubstr("no analysis window of 30 revolutions"), HasSubstr("covers 19.98 revolutions")));
  EXPECT_THAT(with([](OrderTrackOptions& b) { b.min_speed = 25.0; }), HasSubstr("no analysis window"));
}

}  // namespace
}  // namespace turbodyn::signal

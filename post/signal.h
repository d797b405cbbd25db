#pragma once
// Post-processing of simulated (or measured) time series: spectrograms and order tracking.
//
// A run-up simulation produces e.g. the compressor-wheel displacement x(t), sampled at fs while the rotor speed
// f_d(t) ramps up. Engineers read such a record in two ways:
//   1. as a spectrogram, amplitude over (time or rotor speed) x (frequency), with the order lines 1x, 0.5x, ...
//      stft() cuts the record into overlapping windowed segments and returns a calibrated amplitude spectrum of
//      each; values_at_segment_centres() maps any sampled quantity (the rotor speed) onto the segment centres so
//      the same rows can be plotted against f_d.
//   2. as order tracks, amplitude and phase of the n-th order (n x rotor speed) against speed: track_order().
//
// FFT: an own implementation, no external dependency and no allocation per segment. A real segment of even
// length N is packed into a complex sequence of length N/2; complex lengths that are powers of two use an
// iterative radix-2 transform with exact (table, not recurrence) twiddle factors, any other complex length L uses
// Bluestein's chirp-z algorithm on a power-of-two radix-2 transform of length >= 2L-1. Odd N uses a full-length
// complex transform. Plans (twiddles, chirps, work buffers) are built once per stft() call and reused for every
// segment, so any segment_length >= 8 costs O(N log N) per segment.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace turbodyn::signal {

/// Data windows, all in the periodic (DFT-even) form w[i] = f(2 pi i / n), i = 0..n-1, peak 1 at i = n/2:
///   Rectangular  1
///   Hann         0.5 - 0.5 cos x
///   Hamming      0.54 - 0.46 cos x
///   Blackman     0.42 - 0.5 cos x + 0.08 cos 2x
///   FlatTop      (1 - 1.9383379 cos x + 1.3045202 cos 2x - 0.4028270 cos 3x + 0.0350665 cos 4x) / 4.6807516,
///                the HFT95 flat top of Heinzel, Ruediger & Schilling (2002, "Spectrum and spectral density
///                estimation by the DFT"): amplitude of a tone anywhere between bins within +-0.051 %, sidelobes
///                -95 dB, main lobe +-5 bins. (MATLAB flattopwin / scipy flattop coefficients would be off by up to
///                0.113 % halfway between bins, hence not used.)
/// Max. scalloping loss (tone halfway between two bins): Rectangular 36.3 % (3.92 dB), Hann 15.1 % (1.42 dB),
/// Hamming 18.3 % (1.75 dB), Blackman 11.9 % (1.10 dB), FlatTop 0.05 %.
enum class Window { Rectangular, Hann, Hamming, Blackman, FlatTop };

/// "rectangular", "hann", "hamming", "blackman", "flattop" (case-insensitive); anything else throws
/// std::invalid_argument naming the valid names.
Window window_from_string(const std::string& name);
/// Lower-case name as accepted by window_from_string.
std::string to_string(Window w);

/// The n window coefficients in periodic form (see Window). n == 0 gives an empty vector, n == 1 gives {1}.
std::vector<double> window_coefficients(Window w, std::size_t n);

struct StftOptions {
  std::size_t segment_length = 4096;  ///< samples per segment (any length >= 8; power of two not required)
  double overlap = 0.75;              ///< fraction in [0, 1); hop = max(1, N - round(overlap * N)) samples
  Window window = Window::Hann;
  bool remove_mean = true;            ///< subtract each segment's (unweighted) mean before windowing
};

struct Spectrogram {
  std::vector<double> times;        ///< centre time of each segment [s]: (start + (N - 1) / 2) / fs
  std::vector<double> frequencies;  ///< bin frequencies k fs / N [Hz], k = 0 .. N/2 (n_bins = N/2 + 1)
  std::vector<double> amplitude;    ///< n_segments x n_bins row-major: amplitude[s * n_bins + k]
  double sample_rate = 0.0;         ///< fs [Hz] of the analysed signal
  std::size_t segment_length = 0;   ///< N
  std::size_t hop = 0;              ///< samples between the starts of consecutive segments

  std::size_t n_segments() const { return times.size(); }
  std::size_t n_bins() const { return frequencies.size(); }
  double at(std::size_t segment, std::size_t bin) const { return amplitude[segment * n_bins() + bin]; }
};

/// Short-time Fourier transform amplitude spectrogram.
///
/// Segments start at s * hop, s = 0 .. n_segments - 1 with n_segments = 1 + (len - N) / hop (a trailing partial
/// segment is dropped). Each segment is (optionally) de-meaned, multiplied by the window w and transformed.
/// Amplitude scaling: single-sided amplitude spectrum with coherent-gain correction, 2 |X_k| / sum(w), the DC bin
/// (and for even N the Nyquist bin) |X_k| / sum(w). A sinusoid A cos(2 pi f t + p) whose frequency lies on a bin
/// therefore shows as A at that bin (any window); a constant c shows as c at DC (with remove_mean = false).
/// Between bins the amplitude is reduced by the window's scalloping loss (see Window).
///
/// Throws std::invalid_argument for: sample_rate <= 0 (or not finite), segment_length < 8, overlap outside [0, 1),
/// signal shorter than one segment, a non-finite sample (the message gives its index).
Spectrogram stft(const std::vector<double>& signal, double sample_rate, const StftOptions& options = {});

/// The value of a series sampled like the analysed signal (series[i] at time i / fs), linearly interpolated at
/// each segment centre of `s` (e.g. the rotor frequency f_d, to plot the spectrogram rows against speed).
/// Throws std::invalid_argument if sample_rate <= 0 or the series does not reach the last segment centre.
std::vector<double> values_at_segment_centres(const Spectrogram& s, const std::vector<double>& series,
                                              double sample_rate);

/// The leakage of a window: |W(nu)| / W(0), the magnitude of its discrete-time Fourier transform nu bins (of fs / n)
/// from its centre relative to its peak, in closed form (each cosine term is a sum of two shifted Dirichlet kernels).
/// A tone's line in a spectrogram spreads over the neighbouring bins by this factor.
double window_leakage(Window w, std::size_t n, double nu);

/// The smallest whole number of bins m beyond which a window of length n leaks at most `level` of a line's amplitude:
/// window_leakage(w, n, nu) <= level for every nu >= m up to n / 2 (checked on a grid of 1/16 bin). At level 1e-3
/// (-60 dB) and n = 4096: Hann 7 bins, Hamming 47, Blackman 5, FlatTop 5 (its main lobe), Rectangular 322.
/// Throws std::invalid_argument unless n >= 8 and 0 < level < 1.
std::size_t leakage_margin_bins(Window w, std::size_t n, double level);

/// One line of a spectrogram: a bin of one segment.
struct SpectralLine {
  double amplitude = 0.0;     ///< in the signal's unit
  double frequency_hz = 0.0;  ///< the bin's frequency
  double time_s = 0.0;        ///< the segment's centre
  double speed_hz = 0.0;      ///< the rotor frequency at the segment's centre (interpolated)
  std::size_t segment = 0;
};

/// The largest sub-synchronous line of a spectrogram taken with any window: the largest amplitude among the bins
/// that lie below the rotor speed of their segment and clear of the 1x order and of the slow drift. How the
/// vibration of a turbocharger is sorted (the oil whirl of floating rings, a rolling bearing's cage and ball-set
/// whirl, the 0.5x of a rub all lie below the rotor speed; the synchronous response to unbalance on it).
///
/// The rotor speed sweeps within a segment, and a window spreads a line over neighbouring bins, so a bin f of
/// segment s counts only if  m df <= f <= min f_d(s) - m df  and f <= frequency_max, where df = fs / N,
/// min f_d(s) is the smallest |rotor_frequency| over the segment's N samples, and m = margin_bins (of
/// leakage_margin_bins: then the 1x line's leakage into a counted bin is below its level from the edge of the
/// sweep on). Segments from `first_segment` on are searched (the last one alone: what persists at the end).
/// std::nullopt when no bin of those segments qualifies (a rotor slower than 2 m df throughout, say).
/// Throws std::invalid_argument if sample_rate <= 0 or rotor_frequency does not cover the last segment.
std::optional<SpectralLine> largest_subsynchronous_line(const Spectrogram& s,
                                                        const std::vector<double>& rotor_frequency, double sample_rate,
                                                        double frequency_max, std::size_t margin_bins,
                                                        std::size_t first_segment = 0);

struct OrderTrackOptions {
  double order = 1.0;        ///< n: tracks the component at n x rotor speed (> 0)
  double revolutions = 8.0;  ///< analysis window length R in rotor revolutions, centred on each point
  std::size_t points = 200;  ///< number of output points (evenly spaced in time over the usable span)
  double min_speed = 1.0;    ///< Hz; points where the rotor turns slower than this are skipped
  /// true: every sample is weighted by the rotor angle it spans (least squares in the angle domain, see
  /// track_order); false: every sample weighs the same (plain least squares in time).
  bool angle_weighting = true;
};

struct OrderTrack {
  std::vector<double> times;      ///< window centre [s]
  std::vector<double> speeds;     ///< rotor frequency at the window centre [Hz] (interpolated)
  std::vector<double> amplitude;  ///< A in signal units
  std::vector<double> phase;      ///< rad, of the component A cos(n phi(t) + phase), in (-pi, pi]
};

/// Order tracking by least squares over a sliding window.
///
/// Method: around each centre time t_c the window covers the rotor angles phi_c - pi R .. phi_c + pi R, i.e.
/// exactly R revolutions (so it is long at low speed and short at high speed, and during a run-up it is not
/// symmetric in time). Within it s(t) ~ c0 + a cos(n phi(t)) + b sin(n phi(t)) is fitted by weighted least squares
/// (3 x 3 normal equations); A = hypot(a, b), phase = atan2(-b, a). phi is the given (measured or integrated)
/// rotor angle, so varying speed needs no resampling. The sums of the normal equations are trapezoidal-rule
/// integrals over the window, with the integrand at the two (fractional) window ends interpolated linearly between
/// the neighbouring samples; this amounts to non-negative weights per sample, so the fit stays a weighted least
/// squares fit. With angle_weighting the integrals are over d phi (each sample weighs the rotor angle it spans),
/// the equivalent of resampling to constant angle increments (computed order tracking): orders whose difference
/// is a multiple of 1/R are orthogonal over the window and do not disturb each other even during a fast run-up.
/// Without it the integrals are over dt, which is the plain time-domain fit; it lets orders leak into each other
/// where the speed changes much within one window (e.g. the first windows of a run-up from standstill: 5 % error
/// instead of 0.2 % in the tests).
///
/// Resolution: the fit is a rectangular window of R revolutions in the angle domain, so its order resolution is
/// 1/R: two orders closer than 1/R (e.g. 1x and 1.1x with R = 8) are not separated (the estimate is a mix of
/// both); orders that are not a multiple of 1/R away leak with the sin(x)/x sidelobes of the rectangular window
/// (first sidelobe -13 dB). Larger R sharpens the order resolution but averages over a wider speed range
/// (R / f_d seconds at speed f_d), smoothing resonance peaks passed quickly. The constant c0 absorbs a mean; other
/// non-tracked content (other orders, resonances, noise) enters only through its leakage.
///
/// Output points: the usable span runs from the first to the last sample at which a window of R revolutions fits
/// in the record and the rotor turns at >= min_speed; `points` centres are spread evenly in time over it. A point
/// is skipped (so fewer may be returned) if its speed is below min_speed, or if n x speed >= fs/2 (the tracked
/// component is aliased), or if its window holds too few samples for the fit.
///
/// Requirements (std::invalid_argument otherwise): the three series have the same length >= 2 and finite values;
/// sample_rate > 0; the rotor angle is monotonic (either direction) and changes; order > 0; revolutions > 0 with
/// order * revolutions >= 1 (at least one cycle of the tracked order per window); points >= 1; min_speed >= 0; and
/// at least one window fits. Speeds are compared by magnitude.
OrderTrack track_order(const std::vector<double>& signal, const std::vector<double>& rotor_angle,
                       const std::vector<double>& rotor_frequency, double sample_rate,
                       const OrderTrackOptions& options = {});

}  // namespace turbodyn::signal

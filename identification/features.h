// Features compared between measurement and model (docs/identification.md, "Features"):
//   order1x    1x amplitude (and phase, with a phase reference) against rotor speed, by order tracking
//              (signal::track_order) of a time series, or read off processed spectra at f = f_d
//   subsync    frequency and amplitude of the largest sub-synchronous peak (band [low, high] x f_d) against speed,
//              from the STFT (signal::stft) of a time series or from processed spectra
//   resonance  the rotor speed of the largest 1x amplitude within a speed range (peak refined by a parabola
//              through the three highest points, so it moves smoothly with the parameters)
// One set of functions per data kind (time series, spectra, steady-state response); the model and the measurement
// of one study always go through the same one.
#pragma once

#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "identification/measurement.h"
#include "model/spec/enum_names.h"
#include "post/signal.h"

namespace turbodyn::identification {

enum class FeatureKind { Order1x, Subsync, Resonance };

/// The names in study files.
inline constexpr EnumName<FeatureKind> kFeatureKinds[] = {
    {FeatureKind::Order1x, "order1x"}, {FeatureKind::Subsync, "subsync"}, {FeatureKind::Resonance, "resonance"}};
inline std::string to_string(FeatureKind k) { return name_of(kFeatureKinds, k); }

struct FeatureSpec {
  std::string name;                 ///< used in features.csv and picture names
  FeatureKind kind = FeatureKind::Order1x;
  std::size_t sensor = 0;           ///< index into MeasurementSpec::sensors
  std::vector<double> speeds_hz;    ///< order1x, subsync: speeds at which the feature is compared (Hz)
  double range_min_hz = 0.0, range_max_hz = 0.0;  ///< resonance: search range (Hz)
  bool phase = true;                ///< order1x: compare the complex 1x value (amplitude and phase)
  double weight = 1.0;              ///< multiplies the feature's residuals
  double amplitude_scale = 0.0;     ///< SI; residual normalisation of amplitudes; 0 = RMS of the measured ones
  double frequency_scale = 0.0;     ///< Hz; subsync frequencies; 0 = the spectral resolution
  double speed_scale = 0.0;         ///< Hz; resonance speed; 0 = 1 % of the measured resonance speed
  double band_low = 0.05, band_high = 0.9;  ///< subsync band as fractions of f_d (and at least 5 Hz)
  double threshold = 0.0;           ///< subsync: compare frequencies only where the measured amplitude exceeds
                                    ///< this (SI); 0 = 10 % of the largest measured sub-synchronous amplitude
};

/// Signal-processing settings shared by model and measurement.
struct ProcessingSpec {
  double revolutions = 8.0;         ///< order-tracking window, rotor revolutions
  std::size_t track_points = 400;   ///< order-track points over the record (interpolated to the feature speeds)
  std::size_t segment = 1024;       ///< STFT segment length, samples
  double overlap = 0.75;            ///< STFT overlap
  signal::Window window = signal::Window::Hann;

  /// The STFT settings above, as the signal library takes them.
  signal::StftOptions stft() const {
    signal::StftOptions so;
    so.segment_length = segment;
    so.overlap = overlap;
    so.window = window;
    return so;
  }
};

/// A feature's values at its speeds (NaN where undefined).
struct FeatureTrack {
  std::vector<double> speed_hz;     ///< = FeatureSpec::speeds_hz (order1x, subsync)
  std::vector<double> amplitude;    ///< SI (1x or sub-synchronous amplitude)
  std::vector<double> phase;        ///< rad (order1x with a phase reference), else NaN
  std::vector<double> frequency;    ///< Hz (subsync)
  double resonance_hz = std::numeric_limits<double>::quiet_NaN();
  double resonance_amplitude = std::numeric_limits<double>::quiet_NaN();
  /// The 1x track the resonance was found on (for pictures).
  std::vector<double> curve_speed_hz, curve_amplitude;
};

/// Features of a uniformly sampled record (order tracking, STFT). `with_phase`: the record's angle is a phase
/// reference. Throws std::invalid_argument if the record is too short for the processing.
std::vector<FeatureTrack> features_from_record(const std::vector<FeatureSpec>& features, const ProcessingSpec& p,
                                               const Record& record, bool with_phase);

/// Features of processed spectra: 1x = the largest amplitude within +-1.5 bins of f_d (no phase).
std::vector<FeatureTrack> features_from_spectra(const std::vector<FeatureSpec>& features, const SpectraSet& s);

/// The spectra the STFT of a record gives, in the form of measured spectra (to compare with measured spectra).
SpectraSet spectra_from_record(const Record& record, const ProcessingSpec& p);

/// Features of a steady-state response: response(f_d) = complex 1x amplitudes of all sensors at rotor speed f_d
/// (x = Re(Z e^{i phi})). Only order1x and resonance (the resonance on a grid of 201 speeds, then refined).
std::vector<FeatureTrack> features_from_response(
    const std::vector<FeatureSpec>& features,
    const std::function<std::vector<std::complex<double>>(double speed_hz)>& response, bool with_phase);

}  // namespace turbodyn::identification

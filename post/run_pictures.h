// Pictures of a run-up: the spectrograms, 1x order tracks and orbits of `turbodyn run` (and `turbodyn plot`), and
// the spectrogram pieces `turbodyn optimize` and `turbodyn identify` draw theirs with, so that all of them show a
// spectrogram the same way.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/engine/integrator.h"
#include "model/spec/model_spec.h"
#include "post/plot.h"
#include "post/signal.h"

namespace turbodyn::post {

/// How values of a unit are shown in pictures and reports: lengths (SI unit "m") in µm, stiffnesses ("N/m") in N/µm,
/// everything else as it is.
struct Display {
  double factor = 1.0;  ///< shown value = SI value x factor
  std::string unit;
};
Display display_of(const std::string& si_unit);

/// `s` as a file name: every character other than a letter, a digit, '.', '-' and '_' becomes '_'.
std::string file_safe(std::string s);

/// The STFT of the [output] table (segment, overlap, window).
signal::StftOptions stft_options(const OutputSpec& out);

/// The highest frequency a run's spectrogram shows [Hz]: output.frequency_max if given, else the lower of half the
/// sample rate and 1.1 x the top rotor speed `top_speed_hz` (at least 1 Hz).
double spectrogram_frequency_max(const OutputSpec& out, double top_speed_hz);

/// A spectrogram as a heat map: rows are the bins up to `frequency_max` [Hz], columns the segments at x[s] x
/// `x_factor` (x: one value per segment, e.g. the rotor speed at its centre in Hz), cells the amplitudes x
/// `amplitude_factor`. A segment whose x does not exceed that of the last kept one by more than 1e-9 is dropped
/// (speeds repeat while the rotor stands still; a heat map needs x strictly ascending). Titles, labels, overlays and
/// the colour scale are left to the caller.
plot::Heatmap spectrogram_heatmap(const signal::Spectrogram& sg, const std::vector<double>& x, double frequency_max,
                                  double amplitude_factor, double x_factor = 1.0);

/// The leakage level of signal::leakage_margin_bins for the sub-synchronous lines of a run (-60 dB: where a bin
/// counts, a 1x whirl of 500 um leaks less than 0.5 um).
inline constexpr double kSubsynchronousLeakage = 1e-3;

/// The largest cell of a heat map (the first one in z order); value 0 when no cell is positive.
struct HeatmapPeak {
  double value = 0.0;
  std::size_t row = 0, column = 0;  ///< z[row * nx + column]: at (x[column], y[row])
};
HeatmapPeak heatmap_peak(const plot::Heatmap& map);

/// The spectrogram of column `channel` of a run, STFT and frequency range from `out`: against the rotor speed
/// f_d [Hz] with the 1x and 0.5x order lines, or with `against_time` against time [s]; amplitudes as display_of
/// shows them, logarithmic colour scale, axis labels set; no title and no colour range. std::nullopt when the run
/// has no speed channel or fewer samples than one STFT segment. It may have fewer than two columns or rows.
std::optional<plot::Heatmap> run_spectrogram(const OutputSpec& out, const RunupResult& r, std::size_t channel,
                                             bool against_time = false);

/// A slow quantity against rotor speed, one line per channel whose name ends in one of `suffixes` (e.g.
/// ".ring_speed_ratio": every floating ring's ring speed ratio): the mean over blocks of `block` samples of the
/// value + `offset` (e.g. -273.15 for K to degC) against the block's mean rotor speed f_d [Hz], so that the whirl's
/// ripple does not hide the operating point. Legend entries are the channel names. std::nullopt when no channel matches, the run has
/// no speed channel or fewer than two blocks. With `Block::Peak` each block gives its largest |value| instead of its
/// mean (an envelope, e.g. of a contact pressure), with `Block::Min` its smallest value (e.g. of a film thickness);
/// the value is multiplied by `scale` (after the offset).
enum class Block { Mean, Peak, Min };
std::optional<plot::LineChart> against_speed_chart(const RunupResult& r, const std::vector<std::string>& suffixes,
                                                   std::size_t block, double offset = 0.0, Block kind = Block::Mean,
                                                   double scale = 1.0);

/// Draws the pictures of a run into `dir`: a spectrogram of every probe (against speed while the speed does not
/// fall, else against time), the 1x order track of every x/y probe pair, the orbits of every rotor x/y pair at the
/// [output] orbit speeds (else at 1/4 .. 4/4 of the top speed), and for floating rings the operating point against
/// speed (ring_speed_ratio.png; with thermal films film_temperatures.png, film_power_loss.png). Appends the file
/// names to `written` and what was not drawn to `warnings`; `spectral` receives, per spectrogram, its largest
/// amplitude (SI) and where it lies, and its largest sub-synchronous line over the run and in the last segment
/// (signal::largest_subsynchronous_line with kSubsynchronousLeakage; "subsynchronous", "subsynchronous_at_end":
/// amplitude, frequency_hz, order, speed_hz, time_s);
/// `campbell` (rotor speed [Hz], frequency [Hz]) series are drawn on the spectrograms against speed. Throws
/// plot::PlotError when gnuplot fails.
/// `order_overlays` are drawn on the 1x order track of the probe pair named by their stem ("disk.compressor"):
/// e.g. the critical speeds at an amplitude of `turbodyn modal --amplitudes` (x rotor speed [Hz], y the amplitude in
/// SI units, scaled as the track is); one that names no track is reported in `warnings`.
struct OrderOverlay {
  std::string stem;
  std::vector<plot::Series> series;
};
void draw_run_pictures(const MachineSpec& spec, const RunupResult& r, const std::filesystem::path& dir,
                       std::vector<std::string>& written, std::vector<std::string>& warnings,
                       nlohmann::json& spectral, const std::vector<plot::Series>& campbell = {},
                       const std::vector<OrderOverlay>& order_overlays = {});

/// The `spectral` of draw_run_pictures without drawing a picture (for runs without pictures): per spectrogram its
/// largest amplitude and where it lies, and its largest sub-synchronous lines. Empty when the run has no speed channel
/// or fewer samples than one STFT segment.
nlohmann::json spectrogram_maxima(const MachineSpec& spec, const RunupResult& r);

}  // namespace turbodyn::post

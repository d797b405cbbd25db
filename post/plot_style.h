// One look for every picture: the colour of each meaning, used by every command that draws (run, plot, modal,
// response, bearing, sweep, optimize, identify), so that blue means forward whirl in the Campbell diagram and on the
// spectrograms alike. docs/output-format.md ("Pictures") lists the conventions for the reader.
//
// Meanings never drawn in the same picture may share a colour: red is backward whirl in a Campbell diagram and a
// failed or infeasible point in a study's picture.
#pragma once

namespace turbodyn::plot::style {

// Whirl direction of a natural frequency. The *OnDark variants are the same hues, lighter, for the dark
// (viridis) background of a spectrogram.
inline constexpr const char* kForward = "#1f77b4";        // blue
inline constexpr const char* kBackward = "#d62728";       // red
inline constexpr const char* kForwardOnDark = "#7cc4ff";  // light blue
inline constexpr const char* kBackwardOnDark = "#ff7070"; // light red
inline constexpr const char* kMixedWhirl = "#7f7f7f";     // grey: mixed or planar modes
inline constexpr const char* kTorsional = "#17becf";      // cyan
inline constexpr const char* kCriticalSpeed = "#9467bd";  // purple: crossing of a mode and an order line

// Order lines: 1x solid, 0.5x dashed; black and grey on white, white and light grey on a spectrogram.
inline constexpr const char* kOrder1x = "black";
inline constexpr const char* kOrderHalf = "#7f7f7f";
inline constexpr const char* kOrder1xOnDark = "white";
inline constexpr const char* kOrderHalfOnDark = "#c8c8c8";

// Measurement and model: measured points black, the fitted model orange, the initial model grey and dashed.
inline constexpr const char* kMeasured = "black";
inline constexpr const char* kFitted = "#ff7f0e";
inline constexpr const char* kInitial = "#8c8c8c";

// Studies and optimisation: complete runs and feasible designs blue/green, incomplete runs orange, failed runs and
// infeasible designs red; the best so far a black step line.
inline constexpr const char* kComplete = "#1f77b4";
inline constexpr const char* kIncomplete = "#ff7f0e";
inline constexpr const char* kFailed = "#d62728";
/// A run that ran but whose metric is undefined (nothing above a threshold, an empty window): grey, not red.
inline constexpr const char* kNoValue = "#7f7f7f";
inline constexpr const char* kFeasible = "#2ca02c";
inline constexpr const char* kInfeasible = "#d62728";
inline constexpr const char* kBestSoFar = "black";
/// Run points on a filled map (dark and light colours under them): white dots; failed runs red crosses.
inline constexpr const char* kRunOnMap = "white";

// Tornado chart: a parameter that raises the metric blue, one that lowers it orange.
inline constexpr const char* kRaises = "#1f77b4";
inline constexpr const char* kLowers = "#ff7f0e";

}  // namespace turbodyn::plot::style

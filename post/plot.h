// Engineering pictures (PNG) drawn with gnuplot: line charts (Campbell diagrams, mode shapes, amplitude against
// speed, orbits), heat maps (spectrograms: frequency against rotor speed, colour = amplitude; filled contour maps)
// and horizontal bar charts (tornado charts of sensitivities). The colours of each meaning: post/plot_style.h.
//
// One look for all: titles longer than the picture is wide are broken into lines at spaces; legends sit below the
// plot area unless a picture asks otherwise.
//
// Data and script go to a private temporary directory; gnuplot (pngcairo terminal, sans font, grid lines)
// renders there and the PNG is then moved to its destination. Rendering is safe from several threads at once.
//
// All user text (titles, axis labels, legend entries, annotations) is printed literally: no gnuplot
// "enhanced text" markup, so "f_d [Hz]" shows an underscore, and quotes, backquotes, '@', '$' are harmless.
// A '\n' in a title, axis label or annotation starts a new line (in legend entries it becomes a space).
// UTF-8 is fine ("ω [rad/s]", "µm").
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace turbodyn::plot {

struct Series {
  std::string label;            ///< legend entry; empty = no legend entry
  std::vector<double> x, y;     ///< same length
  /// Steps: horizontal from each point to the next x, then vertical (a running best holds until it improves).
  /// Crosses and Triangles are point markers (failed and incomplete runs).
  enum class Style { Lines, Points, LinesPoints, Dashed, Steps, Crosses, Triangles } style = Style::Lines;
  std::string color;            ///< gnuplot colour name or "#rrggbb"; empty = automatic
  double width = 1.5;           ///< line width / point size scale
};

/// Text centred at a data point (x, y), on an opaque background so lines behind it do not cross it.
struct Annotation {
  double x = 0.0, y = 0.0;
  std::string text;
};

struct LineChart {
  std::string title, xlabel, ylabel;  ///< labels include units, e.g. "rotor speed f_d [Hz]"
  std::vector<Series> series;
  std::optional<std::pair<double, double>> xrange, yrange;  ///< unset = automatic
  /// Logarithmic y axis; y <= 0 then breaks the line like a non-finite value.
  bool logy = false;
  std::vector<Annotation> annotations;
  /// Thin grey dashed markers (e.g. bearing positions, critical speeds); with an automatic x range the
  /// range is widened to include them, with a given x range markers outside it are not drawn.
  std::vector<double> vertical_lines;
  std::string legend_position = "below";  ///< gnuplot 'set key' position words ("below", "outside right top", ...)
  bool equal_axes = false;                   ///< 'set size ratio -1' (orbits)
};

struct Heatmap {
  std::string title, xlabel, ylabel, zlabel;  ///< zlabel: colour-bar label with unit
  std::vector<double> x;   ///< nx column centres, finite and strictly ascending (need not be evenly spaced)
  std::vector<double> y;   ///< ny row centres, finite and strictly ascending (need not be evenly spaced)
  std::vector<double> z;   ///< ny * nx values, row-major: z[j * nx + i] at (x[i], y[j]); non-finite = blank cell
  /// Logarithmic colour scale. Without zrange the colour range is [floor, max] with
  /// floor = max(smallest positive value, 1e-3 * max) (at most 60 dB); values below the lower end of the
  /// colour range (including values <= 0) are drawn in its bottom colour.
  bool logz = false;
  std::optional<std::pair<double, double>> zrange;  ///< colour range; unset = [min, max] of the finite values
  std::vector<Series> overlays;  ///< lines on top (e.g. the 1x and 0.5x order lines), with legend
  std::string legend_position = "below";  ///< gnuplot 'set key' position words for the overlay legend
  /// Number of colour bands (a filled contour map); 0 = a continuous colour scale.
  int levels = 0;
};

/// One horizontal bar from zero to `value`.
struct Bar {
  std::string label;  ///< tick label left of the plot area; '\n' starts a new line
  double value = 0.0;
  std::string color;  ///< gnuplot colour name or "#rrggbb"; empty = automatic
  std::string text;   ///< printed beside the end of the bar (e.g. the value); empty = none
};

/// Horizontal bars drawn top to bottom in the given order: sorted by size, a tornado chart.
struct BarChart {
  std::string title, xlabel;
  std::vector<Bar> bars;
  std::optional<std::pair<double, double>> xrange;  ///< unset = symmetric about 0, 30 % beyond the longest bar
  /// Legend entries (colour, text), e.g. what the colours of the bars mean.
  std::vector<std::pair<std::string, std::string>> legend;
  std::string legend_position = "below";
};

struct Size {
  int width = 1000, height = 700;
};

class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// gnuplot on PATH (or $TURBODYN_GNUPLOT) and it runs ('gnuplot --version' succeeds).
bool gnuplot_available();

/// The gnuplot executable render_png uses: $TURBODYN_GNUPLOT if set and non-empty (a path, or a bare name
/// looked up on PATH), otherwise "gnuplot" looked up on PATH. Throws PlotError if there is none.
std::filesystem::path gnuplot_executable();

/// Renders to a PNG file (missing parent directories are created; an existing file is replaced).
/// Throws PlotError naming the file and the problem for inconsistent data (size mismatch, empty data,
/// non-finite or non-ascending heat-map axes, bad ranges), a missing gnuplot, or a gnuplot failure (with
/// gnuplot's messages). Non-finite x or y values in a line chart break the line; they do not fail.
void render_png(const LineChart& chart, const std::filesystem::path& png, Size size = {});
void render_png(const Heatmap& map, const std::filesystem::path& png, Size size = {});
void render_png(const BarChart& chart, const std::filesystem::path& png, Size size = {});

/// The complete gnuplot script (data inline) that draws the picture into 'png'. Validates like render_png
/// (throws PlotError) but does not need gnuplot. Useful for debugging or for re-rendering by hand.
std::string gnuplot_script(const LineChart& chart, const std::filesystem::path& png, Size size = {});
std::string gnuplot_script(const Heatmap& map, const std::filesystem::path& png, Size size = {});
std::string gnuplot_script(const BarChart& chart, const std::filesystem::path& png, Size size = {});

/// `title` broken at spaces into lines that fit a picture `width_px` wide in the title font (existing line breaks
/// kept; a word longer than a line stays whole).
std::string fit_title(const std::string& title, int width_px);

}  // namespace turbodyn::plot

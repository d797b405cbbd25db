// Engineering pictures (PNG) drawn with gnuplot: line charts (Campbell diagrams, mode shapes, order tracking,
// orbits) and heat maps (spectrograms). Data and script go to a private temporary directory; gnuplot renders
// with the pngcairo terminal.
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
  enum class Style { Lines, Points, LinesPoints, Dashed } style = Style::Lines;
  std::string color;            ///< gnuplot colour name or "#rrggbb"; empty = automatic
  double width = 1.5;           ///< line width / point size scale
};

struct Annotation {
  double x = 0.0, y = 0.0;
  std::string text;
};

struct LineChart {
  std::string title, xlabel, ylabel;  ///< labels include units, e.g. "rotor speed f_d [Hz]"
  std::vector<Series> series;
  std::optional<std::pair<double, double>> xrange, yrange;
  bool logy = false;
  std::vector<Annotation> annotations;
  std::vector<double> vertical_lines;      ///< thin grey dashed markers
  std::string legend_position = "top left";  ///< gnuplot 'set key' position words
  bool equal_axes = false;                 ///< 'set size ratio -1' (orbits)
};

struct Heatmap {
  std::string title, xlabel, ylabel, zlabel;  ///< zlabel: colour-bar label with unit
  std::vector<double> x;   ///< nx column centres, strictly ascending
  std::vector<double> y;   ///< ny row centres, strictly ascending
  std::vector<double> z;   ///< ny * nx values, row-major: z[j * nx + i] at (x[i], y[j])
  bool logz = false;       ///< logarithmic colour scale (values <= 0 drawn at the bottom of the scale)
  std::optional<std::pair<double, double>> zrange;
  std::vector<Series> overlays;  ///< lines on top (e.g. order lines), with legend
};

struct Size {
  int width = 1000, height = 700;
};

class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// gnuplot (or $TURBODYN_GNUPLOT) can be started.
bool gnuplot_available();

/// Renders to a PNG file. Throws PlotError naming the file and the problem for inconsistent data, a missing
/// gnuplot, or a gnuplot failure (with gnuplot's messages). Non-finite y values in a line chart break the line.
void render_png(const LineChart& chart, const std::filesystem::path& png, Size size = {});
void render_png(const Heatmap& map, const std::filesystem::path& png, Size size = {});

}  // namespace turbodyn::plot

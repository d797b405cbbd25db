#include "post/plot.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>

#if __has_include(<unistd.h>)
#include <unistd.h>
#define TURBODYN_PLOT_HAVE_UNISTD 1
#endif
#if __has_include(<sys/wait.h>)
#include <sys/wait.h>
#define TURBODYN_PLOT_HAVE_WAIT 1
#endif

namespace turbodyn::plot {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------------------
// Text helpers

/// Shortest round-trip decimal form, locale-independent; "NaN" for non-finite values.
std::string num(double v) {
  if (!std::isfinite(v)) return "NaN";
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

void append_num(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "NaN";
    return;
  }
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  out.append(buf.data(), r.ptr);
}

/// A gnuplot string expression showing 's' literally. Single-quoted gnuplot strings undergo no backslash,
/// backquote or macro processing ('' stands for one quote); line breaks are joined in as "\n".
/// Other control characters are dropped (tab becomes a space).
std::string gp_string(const std::string& s, bool allow_newlines = true) {
  std::string out = "'";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'') {
      out += "''";
    } else if (c == '\n') {
      out += allow_newlines ? "'.\"\\n\".'" : " ";
    } else if (c == '\t') {
      out += ' ';
    } else if (u < 0x20 || u == 0x7f) {
      // dropped (including '\r')
    } else {
      out += c;
    }
  }
  return out + "'";
}

/// A word for /bin/sh, single-quoted.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

std::string where(const fs::path& png) { return "cannot render '" + png.string() + "': "; }

[[noreturn]] void fail(const fs::path& png, const std::string& what) { throw PlotError(where(png) + what); }

std::string series_name(std::size_t i, const Series& s) {
  std::string n = "series " + std::to_string(i + 1);
  if (!s.label.empty()) n += " ('" + s.label + "')";
  return n;
}

// ---------------------------------------------------------------------------------------------------------------
// Validation shared by both kinds of picture

void check_size(const fs::path& png, Size size) {
  if (size.width < 16 || size.height < 16 || size.width > 20000 || size.height > 20000)
    fail(png, "picture size " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                  " px is out of range (16 .. 20000 px)");
}

void check_range(const fs::path& png, const char* name, const std::optional<std::pair<double, double>>& r,
                 bool log) {
  if (!r) return;
  if (!std::isfinite(r->first) || !std::isfinite(r->second) || r->first == r->second)
    fail(png, std::string(name) + " [" + num(r->first) + ", " + num(r->second) +
                  "] must be two different finite numbers");
  if (log && (r->first <= 0 || r->second <= 0))
    fail(png, std::string(name) + " [" + num(r->first) + ", " + num(r->second) +
                  "] must be positive on a logarithmic scale");
}

void check_legend_position(const fs::path& png, const std::string& pos) {
  for (char c : pos) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == ' ' || c == ',' || c == '.' || c == '-' ||
                    c == '+';
    if (!ok) fail(png, "legend position '" + pos + "' contains the character '" + std::string(1, c) + "'");
  }
}

void check_series_shapes(const fs::path& png, const std::vector<Series>& series, const char* what) {
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    if (s.x.size() != s.y.size())
      fail(png, std::string(what) + " " + series_name(i, s) + ": size mismatch, " + std::to_string(s.x.size()) +
                    " x values but " + std::to_string(s.y.size()) + " y values");
    if (s.x.empty()) fail(png, std::string(what) + " " + series_name(i, s) + " is empty (no data points)");
    if (!std::isfinite(s.width) || s.width <= 0)
      fail(png, std::string(what) + " " + series_name(i, s) + ": width " + num(s.width) + " must be positive");
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Script pieces

const std::array<const char*, 10> kLineColors = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                 "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
// Visible on the viridis palette (dark purple .. yellow).
const std::array<const char*, 5> kOverlayColors = {"white", "#ff4040", "#40e0ff", "#ff80ff", "#ffa500"};

std::string header(const fs::path& out, Size size, const std::string& title, const std::string& xlabel,
                   const std::string& ylabel) {
  std::ostringstream s;
  s << "# turbodyn picture\n"
    << "set encoding utf8\n"
    << "set terminal pngcairo size " << size.width << "," << size.height
    << " enhanced font 'Sans,12' linewidth 1 rounded\n"
    << "set output " << gp_string(out.string(), false) << "\n";
  if (!title.empty()) s << "set title " << gp_string(fit_title(title, size.width)) << " font ',14' noenhanced\n";
  if (!xlabel.empty()) s << "set xlabel " << gp_string(xlabel) << " noenhanced\n";
  if (!ylabel.empty()) s << "set ylabel " << gp_string(ylabel) << " noenhanced\n";
  s << "set border lw 1 lc rgb '#303030'\n"
    << "set tics nomirror out scale 0.7\n"
    << "set mxtics\nset mytics\n";
  return s.str();
}

/// ' with ... lc ... title ...' for one series.
std::string style_of(const Series& s, const std::string& auto_color) {
  std::ostringstream st;
  const std::string w = num(s.width), ps = num(0.6 * s.width);
  switch (s.style) {
    case Series::Style::Lines: st << " with lines lw " << w; break;
    case Series::Style::Dashed: st << " with lines lw " << w << " dt (8,5)"; break;
    case Series::Style::Points: st << " with points pt 7 ps " << ps; break;
    case Series::Style::LinesPoints: st << " with linespoints lw " << w << " pt 7 ps " << ps; break;
    case Series::Style::Steps: st << " with steps lw " << w; break;
    case Series::Style::Crosses: st << " with points pt 2 ps " << ps << " lw 2"; break;
    case Series::Style::Triangles: st << " with points pt 9 ps " << ps; break;
  }
  st << " lc rgb " << gp_string(s.color.empty() ? auto_color : s.color, false);
  if (s.label.empty()) st << " notitle";
  else st << " title " << gp_string(s.label, false) << " noenhanced";
  return st.str();
}

/// The plot clauses of `series`, whose data blocks are $BLOCK0, $BLOCK1, ...: a series without a colour of its own
/// takes the next of `palette`. `after_another`: a clause precedes them on the plot line.
template <std::size_t N>
void plot_clauses(std::ostream& s, const std::vector<Series>& series, const std::string& block,
                  const std::array<const char*, N>& palette, bool after_another) {
  std::size_t auto_index = 0;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& se = series[i];
    const std::string color = palette[auto_index % N];
    if (se.color.empty()) ++auto_index;
    s << (i || after_another ? ", \\\n     " : "") << "$" << block << i << " using 1:2" << style_of(se, color);
  }
}

/// Inline data block of one series; a point with non-finite x or y (or y <= 0 on a log axis) becomes a blank
/// line, which breaks the line there. Returns the number of points written.
std::size_t write_series_block(std::string& out, const std::string& name, const Series& s, bool logy,
                               std::optional<double>* some_y = nullptr) {
  out += "$" + name + " << EOD\n";
  std::size_t written = 0;
  bool gap = false;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const double x = s.x[i], y = s.y[i];
    if (!std::isfinite(x) || !std::isfinite(y) || (logy && !(y > 0))) {
      if (!gap && written > 0) out += "\n";
      gap = true;
      continue;
    }
    gap = false;
    append_num(out, x);
    out += ' ';
    append_num(out, y);
    out += '\n';
    ++written;
    if (some_y && !*some_y) *some_y = y;
  }
  out += "EOD\n";
  return written;
}

/// 'set key' for a legend at 'position'. Inside the plot area it gets a box with a mostly opaque background
/// (light for line charts, dark for heat maps so that white and pale overlay lines show in it); data behind it
/// remain faintly visible. Outside the plot area a line chart's legend has no box (gnuplot 5.4 lets a boxed key
/// below the plot overlap the x label when the box has a title line), a heat map's a dark one.
std::string key_line(const std::string& position, bool dark) {
  bool outside = false;
  for (const char* word : {"out", "below", "above", "over", "under", "margin"})
    outside = outside || position.find(word) != std::string::npos;
  std::string s = "set key " + position + " Left reverse samplen 3 spacing 1.15 width 1 noenhanced";
  // A heat map's overlay lines are light (white 1x line): their legend needs a dark ground outside the plot too.
  if (outside && dark) s += " box lc rgb '#909090' opaque fc rgb '#303030' textcolor rgb 'white'";
  else if (outside) s += " nobox";
  else if (dark) s += " box lc rgb '#909090' opaque fc rgb '#1a303030' textcolor rgb 'white'";
  else s += " box lc rgb '#b0b0b0' opaque fc rgb '#30ffffff'";
  return s + "\n";
}

// ---------------------------------------------------------------------------------------------------------------
// Line chart

std::string line_chart_script(const LineChart& c, const fs::path& png, const fs::path& out, Size size) {
  check_size(png, size);
  if (c.series.empty()) fail(png, "empty data: the line chart has no series");
  check_series_shapes(png, c.series, "line chart");
  check_range(png, "x range", c.xrange, false);
  check_range(png, "y range", c.yrange, c.logy);
  check_legend_position(png, c.legend_position);
  for (double v : c.vertical_lines)
    if (!std::isfinite(v)) fail(png, "vertical line at x = " + num(v) + " is not finite");
  for (const Annotation& a : c.annotations)
    if (!std::isfinite(a.x) || !std::isfinite(a.y))
      fail(png, "annotation '" + a.text + "' at (" + num(a.x) + ", " + num(a.y) + ") is not finite");

  std::string data;
  std::optional<double> some_y;
  std::size_t points = 0;
  for (std::size_t i = 0; i < c.series.size(); ++i)
    points += write_series_block(data, "d" + std::to_string(i), c.series[i], c.logy, &some_y);
  if (points == 0)
    fail(png, std::string("no finite data points to draw (all x or y values are non-finite") +
                  (c.logy ? " or <= 0 on the logarithmic y axis)" : ")"));

  std::ostringstream s;
  s << header(out, size, c.title, c.xlabel, c.ylabel);
  s << "set grid xtics ytics mxtics mytics lt 1 lc rgb '#d8d8d8' lw 1, lt 1 lc rgb '#eeeeee' lw 1\n";
  bool any_label = false;
  for (const Series& se : c.series) any_label = any_label || !se.label.empty();
  if (any_label) s << key_line(c.legend_position, false);
  else s << "unset key\n";
  // Room for the last x tic label ("160000") when no legend takes the right margin.
  if (c.legend_position.find("right") == std::string::npos || !any_label) s << "set rmargin 5\n";
  if (c.xrange) s << "set xrange [" << num(c.xrange->first) << ":" << num(c.xrange->second) << "]\n";
  if (c.yrange) s << "set yrange [" << num(c.yrange->first) << ":" << num(c.yrange->second) << "]\n";
  if (c.logy) s << "set logscale y 10\n";
  if (c.equal_axes) s << "set size ratio -1\n";
  // Scatter plots: points on the automatic range's ends would sit on the border, half hidden.
  const bool points_only = std::all_of(c.series.begin(), c.series.end(), [](const Series& se) {
    return se.style == Series::Style::Points || se.style == Series::Style::Crosses ||
           se.style == Series::Style::Triangles;
  });
  if (points_only && !c.equal_axes)
    s << "set offsets graph " << (c.xrange ? "0, graph 0" : "0.03, graph 0.03") << ", graph "
      << (c.yrange || c.logy ? "0, graph 0" : "0.05, graph 0.05") << "\n";

  std::vector<double> vlines;
  for (double v : c.vertical_lines) {
    if (c.xrange) {
      const double lo = std::min(c.xrange->first, c.xrange->second), hi = std::max(c.xrange->first, c.xrange->second);
      if (v < lo || v > hi) continue;
    }
    vlines.push_back(v);
  }
  int tag = 1;
  for (double v : vlines)
    s << "set arrow " << tag++ << " from first " << num(v) << ", graph 0 to first " << num(v)
      << ", graph 1 nohead back lc rgb '#909090' lw 1 dt (6,4)\n";
  if (!c.annotations.empty()) s << "set style textbox opaque noborder margins 1.5,1\n";
  tag = 1;
  for (const Annotation& a : c.annotations)
    s << "set label " << tag++ << " " << gp_string(a.text) << " at first " << num(a.x) << ", first " << num(a.y)
      << " center front boxed noenhanced font ',10' textcolor rgb '#303030'\n";

  s << data;
  // Invisible points that make the automatic x range include the vertical markers.
  const bool vline_points = !c.xrange && !vlines.empty();
  if (vline_points) {
    s << "$vlines << EOD\n";
    for (double v : vlines) s << num(v) << " " << num(*some_y) << "\n";
    s << "EOD\n";
  }
  s << "plot ";
  plot_clauses(s, c.series, "d", kLineColors, false);
  if (vline_points) s << ", \\\n     $vlines using 1:2 with dots lc rgb '#ff000000' notitle";
  s << "\n";
  return s.str();
}

// ---------------------------------------------------------------------------------------------------------------
// Heat map

struct Axis {
  std::vector<double> centres;   // of the pixels written (uniform)
  std::vector<std::size_t> cell; // cell index of each pixel
  double lo = 0, hi = 0;         // plot range: outer cell edges
};

void check_axis(const fs::path& png, const char* name, const std::vector<double>& v) {
  if (v.empty()) fail(png, std::string("empty data: the heat map has no ") + name + " values");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      fail(png, std::string("heat map ") + name + "[" + std::to_string(i) + "] = " + num(v[i]) + " is not finite");
    if (i > 0 && !(v[i] > v[i - 1]))
      fail(png, std::string("heat map ") + name + " values are not strictly ascending: " + name + "[" +
                    std::to_string(i - 1) + "] = " + num(v[i - 1]) + ", " + name + "[" + std::to_string(i) +
                    "] = " + num(v[i]));
  }
}

/// The pixel grid along one axis. An evenly spaced axis is used as it is (one pixel per cell). Otherwise cells
/// span half-way to their neighbours and are sampled on a uniform grid at least as fine as the picture's pixels
/// (and 4 samples across the narrowest cell where affordable), so every cell is drawn at its true place to within
/// a screen pixel.
Axis make_axis(const std::vector<double>& c, int pixels) {
  Axis a;
  const std::size_t n = c.size();
  std::vector<double> edges(n + 1);
  if (n == 1) {
    const double h = c[0] != 0 ? 0.05 * std::abs(c[0]) : 0.5;
    edges[0] = c[0] - h;
    edges[1] = c[0] + h;
  } else {
    for (std::size_t i = 1; i < n; ++i) edges[i] = 0.5 * (c[i - 1] + c[i]);
    edges[0] = c[0] - (edges[1] - c[0]);
    edges[n] = c[n - 1] + (c[n - 1] - edges[n - 1]);
  }
  a.lo = edges.front();
  a.hi = edges.back();
  bool uniform = n >= 2;
  if (uniform) {
    const double step = (c.back() - c.front()) / static_cast<double>(n - 1);
    for (std::size_t i = 0; i < n && uniform; ++i)
      uniform = std::abs(c[i] - (c.front() + step * static_cast<double>(i))) <= 1e-3 * step;
  }
  if (uniform) {
    a.centres = c;
    a.cell.resize(n);
    for (std::size_t i = 0; i < n; ++i) a.cell[i] = i;
    return a;
  }
  double narrowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) narrowest = std::min(narrowest, edges[i + 1] - edges[i]);
  const double span = a.hi - a.lo;
  const double wanted = std::ceil(4.0 * span / narrowest);
  const double m_d = std::clamp(wanted, static_cast<double>(std::max<std::size_t>(n, 2)),
                                std::max(static_cast<double>(n), static_cast<double>(pixels)));
  const auto m = static_cast<std::size_t>(m_d);
  const double step = span / static_cast<double>(m);
  a.centres.resize(m);
  a.cell.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double x = a.lo + (static_cast<double>(k) + 0.5) * step;
    a.centres[k] = x;
    // Cell i covers [edges[i], edges[i+1]).
    const auto it = std::upper_bound(edges.begin() + 1, edges.end() - 1, x);
    a.cell[k] = static_cast<std::size_t>(it - (edges.begin() + 1));
  }
  return a;
}

std::string heatmap_script(const Heatmap& m, const fs::path& png, const fs::path& out, Size size) {
  check_size(png, size);
  check_axis(png, "x", m.x);
  check_axis(png, "y", m.y);
  const std::size_t nx = m.x.size(), ny = m.y.size();
  if (m.z.size() != nx * ny)
    fail(png, "size mismatch: heat map z has " + std::to_string(m.z.size()) + " values, expected ny * nx = " +
                  std::to_string(ny) + " * " + std::to_string(nx) + " = " + std::to_string(nx * ny));
  check_range(png, "z range", m.zrange, m.logz);
  check_series_shapes(png, m.overlays, "heat map overlay");
  check_legend_position(png, m.legend_position);
  if (m.levels < 0 || m.levels == 1 || m.levels > 256)
    fail(png, "heat map levels " + std::to_string(m.levels) + " must be 0 (continuous) or 2 .. 256");

  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin, minpos = zmin;
  for (double v : m.z) {
    if (!std::isfinite(v)) continue;
    zmin = std::min(zmin, v);
    zmax = std::max(zmax, v);
    if (v > 0) minpos = std::min(minpos, v);
  }
  if (!(zmax >= zmin)) fail(png, "heat map has no finite z values");
  double lo = 0, hi = 0;
  if (m.zrange) {
    lo = std::min(m.zrange->first, m.zrange->second);
    hi = std::max(m.zrange->first, m.zrange->second);
  } else if (m.logz) {
    if (!(zmax > 0)) fail(png, "logarithmic colour scale, but the heat map has no positive z values");
    lo = std::max(minpos, 1e-3 * zmax);
    hi = zmax;
    if (!(hi > lo)) {  // constant data
      lo = hi / 10;
      hi = hi * 10;
    }
  } else {
    lo = zmin;
    hi = zmax;
    if (!(hi > lo)) {
      const double d = zmax != 0 ? 0.1 * std::abs(zmax) : 1.0;
      lo -= d;
      hi += d;
    }
  }

  // Plot area is a little smaller than the picture; sampling at picture resolution is fine enough.
  const Axis ax = make_axis(m.x, size.width), ay = make_axis(m.y, size.height);

  std::string data = "$map << EOD\n";
  data.reserve(data.size() + ax.centres.size() * ay.centres.size() * 40);
  for (std::size_t j = 0; j < ay.centres.size(); ++j) {
    for (std::size_t i = 0; i < ax.centres.size(); ++i) {
      double v = m.z[ay.cell[j] * nx + ax.cell[i]];
      if (m.logz && std::isfinite(v) && v < lo) v = lo;
      append_num(data, ax.centres[i]);
      data += ' ';
      append_num(data, ay.centres[j]);
      data += ' ';
      append_num(data, v);
      data += '\n';
    }
    data += '\n';
  }
  data += "EOD\n";
  for (std::size_t i = 0; i < m.overlays.size(); ++i)
    write_series_block(data, "o" + std::to_string(i), m.overlays[i], false);

  std::ostringstream s;
  s << header(out, size, m.title, m.xlabel, m.ylabel);
  if (!m.zlabel.empty()) s << "set cblabel " << gp_string(m.zlabel) << " noenhanced offset 0.5,0\n";
  // Viridis (perceptually uniform, readable in grey scale and for colour-blind viewers).
  s << "set palette defined (0 '#440154', 0.1 '#482475', 0.2 '#414487', 0.3 '#355f8d', 0.4 '#2a788e', "
       "0.5 '#21918c', 0.6 '#22a884', 0.7 '#44bf70', 0.8 '#7ad151', 0.9 '#bddf26', 1 '#fde725')\n"
    << "set palette maxcolors " << std::max(0, m.levels) << "\n"
    << "set colorbox vertical\n"
    << "set cbtics out nomirror scale 0.7\n";
  if (m.logz) s << "set logscale cb 10\nset mcbtics 10\n";
  s << "set cbrange [" << num(lo) << ":" << num(hi) << "]\n"
    << "set xrange [" << num(ax.lo) << ":" << num(ax.hi) << "]\n"
    << "set yrange [" << num(ay.lo) << ":" << num(ay.hi) << "]\n"
    << "set grid front xtics ytics lt 1 lc rgb '#a0ffffff' lw 0.6 dt (3,4)\n"
    << "set border front\nset tics front\n"
    << "unset clip points\n";  // overlay points on the edge (runs at a design's bounds) drawn whole
  bool any_label = false;
  for (const Series& se : m.overlays) any_label = any_label || !se.label.empty();
  if (any_label) {
    s << key_line(m.legend_position, true);
    // gnuplot 5.4 reserves too little room for a boxed key below the x label (it overlaps the label when the tics
    // carry exponents): a bottom margin of the tics, the label and the key's rows (about three entries a row).
    if (m.legend_position.find("below") != std::string::npos) {
      std::size_t labelled = 0;
      for (const Series& se : m.overlays) labelled += !se.label.empty();
      s << "set bmargin " << 5 + (labelled + 2) / 3 << "\n";
    }
  } else {
    s << "unset key\n";
  }
  s << data;
  s << "plot $map using 1:2:3 with image notitle";
  plot_clauses(s, m.overlays, "o", kOverlayColors, true);
  s << "\n";
  return s.str();
}

// ---------------------------------------------------------------------------------------------------------------
// Bar chart

/// A colour as the integer gnuplot's 'lc rgb variable' reads; colour names other than black and white are refused
/// (bars take "#rrggbb").
long rgb_int(const fs::path& png, const std::string& color) {
  if (color == "black") return 0;
  if (color == "white") return 0xffffff;
  if (color.size() == 7 && color[0] == '#') {
    long v = 0;
    const auto r = std::from_chars(color.data() + 1, color.data() + 7, v, 16);
    if (r.ec == std::errc() && r.ptr == color.data() + 7) return v;
  }
  fail(png, "bar colour '" + color + "' must be \"#rrggbb\", \"black\" or \"white\"");
}

std::string bar_chart_script(const BarChart& c, const fs::path& png, const fs::path& out, Size size) {
  check_size(png, size);
  if (c.bars.empty()) fail(png, "empty data: the bar chart has no bars");
  check_range(png, "x range", c.xrange, false);
  check_legend_position(png, c.legend_position);
  double longest = 0.0;
  for (const Bar& b : c.bars) {
    if (!std::isfinite(b.value)) fail(png, "bar '" + b.label + "': value " + num(b.value) + " is not finite");
    longest = std::max(longest, std::abs(b.value));
  }
  const double half = longest > 0 ? 1.3 * longest : 1.0;  // room for the value beside the longest bar
  const std::pair<double, double> xr = c.xrange ? *c.xrange : std::make_pair(-half, half);
  const std::size_t n = c.bars.size();

  std::ostringstream s;
  s << header(out, size, c.title, c.xlabel, "");
  s << "set style fill solid 0.85 noborder\n"
    << "set grid xtics lt 1 lc rgb '#d8d8d8' lw 1\n"
    << "unset mytics\n"
    << "set xrange [" << num(xr.first) << ":" << num(xr.second) << "]\n"
    << "set yrange [0.4:" << num(static_cast<double>(n) + 0.6) << "]\n"
    << "set arrow 1 from first 0, graph 0 to first 0, graph 1 nohead front lc rgb '#303030' lw 1\n"
    << "set ytics scale 0 (";
  // The first bar on top.
  for (std::size_t i = 0; i < n; ++i)
    s << (i ? ", " : "") << gp_string(c.bars[i].label) << " " << n - i;
  s << ") noenhanced\n";
  int tag = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const Bar& b = c.bars[i];
    if (b.text.empty()) continue;
    s << "set label " << tag++ << " " << gp_string(b.text) << " at first " << num(b.value) << ", first " << n - i
      << (b.value < 0 ? " right offset -0.6,0" : " left offset 0.6,0") << " front noenhanced\n";
  }
  if (c.legend.empty()) s << "unset key\n";
  else s << key_line(c.legend_position, false);
  s << "$bars << EOD\n";
  std::size_t auto_index = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Bar& b = c.bars[i];
    const double y = static_cast<double>(n - i);
    const std::string color = b.color.empty() ? kLineColors[auto_index++ % kLineColors.size()] : b.color;
    s << num(b.value) << " " << num(y) << " " << num(std::min(0.0, b.value)) << " " << num(std::max(0.0, b.value))
      << " " << num(y - 0.32) << " " << num(y + 0.32) << " " << rgb_int(png, color) << "\n";
  }
  s << "EOD\n";
  s << "plot $bars using 1:2:3:4:5:6:7 with boxxyerror lc rgb variable notitle";
  for (const auto& [color, text] : c.legend)
    s << ", \\\n     keyentry with boxes fc rgb " << gp_string(color, false) << " title " << gp_string(text, false);
  s << "\n";
  return s.str();
}

// ---------------------------------------------------------------------------------------------------------------
// Running gnuplot

bool is_executable_file(const fs::path& p) {
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (ec || !fs::is_regular_file(st)) return false;
  const fs::perms x = fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec;
  return (st.permissions() & x) != fs::perms::none;
}

std::optional<fs::path> search_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    std::size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    const std::string dir = dirs.substr(start, end - start);
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
    if (is_executable_file(candidate)) return candidate;
    start = end + 1;
  }
  return std::nullopt;
}

/// The executable, or an explanation why there is none.
std::pair<std::optional<fs::path>, std::string> find_gnuplot() {
  const char* env = std::getenv("TURBODYN_GNUPLOT");
  const std::string hint = " (install gnuplot, e.g. the Debian package gnuplot-nox, or set TURBODYN_GNUPLOT to it)";
  if (env && *env) {
    const std::string name = env;
    if (name.find('/') != std::string::npos) {
      if (is_executable_file(name)) return {fs::path(name), ""};
      std::error_code ec;
      const bool exists = fs::exists(name, ec);
      return {std::nullopt, "gnuplot not found: TURBODYN_GNUPLOT = '" + name + "' " +
                                (exists ? "is not an executable file" : "does not exist") + hint};
    }
    if (auto p = search_path(name)) return {*p, ""};
    return {std::nullopt, "gnuplot not found: TURBODYN_GNUPLOT = '" + name + "' is not on PATH" + hint};
  }
  if (auto p = search_path("gnuplot")) return {*p, ""};
  return {std::nullopt, "gnuplot not found on PATH" + hint};
}

std::string read_text(const fs::path& p, std::size_t limit = 4000) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string t = ss.str();
  while (!t.empty() && (t.back() == '\n' || t.back() == ' ' || t.back() == '\r')) t.pop_back();
  while (!t.empty() && (t.front() == '\n' || t.front() == '\r')) t.erase(t.begin());
  if (t.size() > limit) t = t.substr(0, limit) + "\n[... truncated]";
  return t;
}

bool has_png_signature(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::array<char, 8> h{};
  if (!in.read(h.data(), h.size())) return false;
  static constexpr std::array<unsigned char, 8> sig = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (std::size_t i = 0; i < sig.size(); ++i)
    if (static_cast<unsigned char>(h[i]) != sig[i]) return false;
  return true;
}

long current_pid() {
#ifdef TURBODYN_PLOT_HAVE_UNISTD
  return static_cast<long>(::getpid());
#else
  return 0;
#endif
}

/// Private temporary directory (owner-only), removed with everything in it on destruction.
class TempDir {
 public:
  explicit TempDir(const fs::path& png) {
    static std::atomic<std::uint64_t> counter{0};
    std::error_code ec;
    const fs::path base = fs::temp_directory_path(ec);
    if (ec) fail(png, "no temporary directory: " + ec.message());
    for (int attempt = 0; attempt < 100; ++attempt) {
      const auto ticks = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
      const fs::path p = base / ("turbodyn-plot-" + std::to_string(current_pid()) + "-" +
                                 std::to_string(counter.fetch_add(1)) + "-" + std::to_string(ticks % 1000000007u));
      if (fs::create_directory(p, ec)) {
        path_ = p;
        fs::permissions(p, fs::perms::owner_all, fs::perm_options::replace, ec);
        return;
      }
      if (ec) fail(png, "cannot create a temporary directory in '" + base.string() + "': " + ec.message());
    }
    fail(png, "cannot create a unique temporary directory in '" + base.string() + "'");
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string describe_status(int rc) {
#ifdef TURBODYN_PLOT_HAVE_WAIT
  if (rc == -1) return "could not be started";
  if (WIFEXITED(rc)) return "exited with status " + std::to_string(WEXITSTATUS(rc));
  if (WIFSIGNALED(rc)) return "was killed by signal " + std::to_string(WTERMSIG(rc));
#endif
  return "failed (status " + std::to_string(rc) + ")";
}

void install(const fs::path& from, const fs::path& png) {
  std::error_code ec;
  if (png.has_parent_path()) {
    fs::create_directories(png.parent_path(), ec);
    if (ec) fail(png, "cannot create the directory '" + png.parent_path().string() + "': " + ec.message());
  }
  fs::rename(from, png, ec);
  if (!ec) return;
  ec.clear();
  fs::copy_file(from, png, fs::copy_options::overwrite_existing, ec);
  if (ec) fail(png, "cannot write the file: " + ec.message());
}

template <class Picture, class ScriptFn>
void render(const Picture& picture, const fs::path& png, Size size, ScriptFn make_script) {
  TempDir tmp(png);
  const fs::path out = tmp.path() / "out.png", script_file = tmp.path() / "plot.gp",
                 err_file = tmp.path() / "stderr.txt", out_file = tmp.path() / "stdout.txt";
  // Validates the data first: data errors are reported even where gnuplot is missing.
  const std::string script = make_script(picture, png, out, size);
  const auto [exe, why] = find_gnuplot();
  if (!exe) fail(png, why);
  {
    std::ofstream f(script_file, std::ios::binary);
    f << script;
    f.close();
    if (!f) fail(png, "cannot write the gnuplot script '" + script_file.string() + "'");
  }
  const std::string cmd = shell_quote(exe->string()) + " -d " + shell_quote(script_file.string()) +
                          " </dev/null >" + shell_quote(out_file.string()) + " 2>" +
                          shell_quote(err_file.string());
  const int rc = std::system(cmd.c_str());
  std::string messages = read_text(err_file);
  if (messages.empty()) messages = read_text(out_file);
  const std::string gp = "gnuplot ('" + exe->string() + "') ";
  if (rc != 0)
    fail(png, gp + describe_status(rc) + (messages.empty() ? std::string() : ":\n" + messages));
  std::error_code ec;
  const auto bytes = fs::file_size(out, ec);
  if (ec || bytes == 0 || !has_png_signature(out))
    fail(png, gp + "ran but wrote no PNG picture" + (messages.empty() ? std::string() : ":\n" + messages));
  install(out, png);
}

}  // namespace

fs::path gnuplot_executable() {
  const auto [exe, why] = find_gnuplot();
  if (!exe) throw PlotError(why);
  return *exe;
}

bool gnuplot_available() {
  const auto found = find_gnuplot();
  if (!found.first) return false;
  const std::string exe = found.first->string();
  static std::mutex mutex;
  static std::map<std::string, bool> cache;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = cache.find(exe); it != cache.end()) return it->second;
  }
  const std::string cmd = shell_quote(exe) + " --version </dev/null >/dev/null 2>&1";
  const bool ok = std::system(cmd.c_str()) == 0;
  std::lock_guard<std::mutex> lock(mutex);
  cache[exe] = ok;
  return ok;
}

std::string gnuplot_script(const LineChart& chart, const fs::path& png, Size size) {
  return line_chart_script(chart, png, png, size);
}

std::string gnuplot_script(const Heatmap& map, const fs::path& png, Size size) {
  return heatmap_script(map, png, png, size);
}

std::string gnuplot_script(const BarChart& chart, const fs::path& png, Size size) {
  return bar_chart_script(chart, png, png, size);
}

std::string fit_title(const std::string& title, int width_px) {
  // The title font (14 pt sans) takes up to about 11 px per character (measured on the pictures).
  const std::size_t max_chars = static_cast<std::size_t>(std::max(20, (width_px - 40) / 11));
  auto length = [](const std::string& t) {  // characters, not UTF-8 bytes
    std::size_t n = 0;
    for (char ch : t) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
    return n;
  };
  std::string result, line;
  std::size_t start = 0;
  while (start <= title.size()) {
    std::size_t end = title.find('\n', start);
    if (end == std::string::npos) end = title.size();
    std::istringstream words(title.substr(start, end - start));
    line.clear();
    std::string out_line;
    for (std::string w; words >> w;) {
      if (!line.empty() && length(line) + 1 + length(w) > max_chars) {
        out_line += line + "\n";
        line.clear();
      }
      line += (line.empty() ? "" : " ") + w;
    }
    result += (start ? "\n" : "") + out_line + line;
    start = end + 1;
  }
  return result;
}

void render_png(const LineChart& chart, const fs::path& png, Size size) {
  render(chart, png, size, line_chart_script);
}

void render_png(const Heatmap& map, const fs::path& png, Size size) { render(map, png, size, heatmap_script); }

void render_png(const BarChart& chart, const fs::path& png, Size size) { render(chart, png, size, bar_chart_script); }

}  // namespace turbodyn::plot

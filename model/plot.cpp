#include "model/plot.h"

#include <unistd.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace turbodyn::plot {
namespace {

std::string gnuplot_command() {
  const char* env = std::getenv("TURBODYN_GNUPLOT");
  return env && *env ? std::string(env) : std::string("gnuplot");
}

std::string number(double v) {
  if (!std::isfinite(v)) return "NaN";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A gnuplot string literal in single quotes (where only '' needs escaping).
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "''";
    else out += c;
  }
  return out + "'";
}

// Labels use '_' literally (no enhanced-text subscripts) except for a trailing "_d"-style subscript we want kept.
std::string label(const std::string& s) { return quoted(s); }

// Private temporary directory, removed on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<long> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("turbodyn-plot-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void run_gnuplot(const std::string& script, const std::filesystem::path& png, const TempDir& tmp) {
  const std::filesystem::path gp = tmp.path() / "plot.gp", err = tmp.path() / "stderr.txt";
  {
    std::ofstream out(gp);
    out << script;
  }
  std::error_code ec;
  std::filesystem::remove(png, ec);
  const std::string cmd = "\"" + gnuplot_command() + "\" \"" + gp.string() + "\" 2> \"" + err.string() + "\"";
  const int rc = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream msg;
  msg << in.rdbuf();
  if (rc != 0 || !std::filesystem::exists(png) || std::filesystem::file_size(png) == 0) {
    std::string text = msg.str();
    if (text.size() > 2000) text = text.substr(0, 2000) + "...";
    throw PlotError("cannot draw " + png.string() + ": gnuplot ('" + gnuplot_command() + "') failed" +
                    (rc == 127 * 256 || rc == 127 ? " (not found: install gnuplot-nox)" : "") +
                    (text.empty() ? "" : ": " + text));
  }
}

std::string header(const std::string& title, const std::string& xl, const std::string& yl,
                   const std::filesystem::path& png, Size size) {
  std::ostringstream s;
  s << "set terminal pngcairo size " << size.width << "," << size.height
    << " enhanced font 'DejaVu Sans,12' linewidth 1\n"
    << "set output " << quoted(png.string()) << "\n"
    << "set encoding utf8\n"
    << "set title " << label(title) << " noenhanced\n"
    << "set xlabel " << label(xl) << " noenhanced\n"
    << "set ylabel " << label(yl) << " noenhanced\n"
    << "set grid lc rgb '#dddddd'\n"
    << "set border lw 1\n";
  return s.str();
}

std::string style_of(const Series& s) {
  std::ostringstream st;
  switch (s.style) {
    case Series::Style::Lines: st << "with lines lw " << number(s.width); break;
    case Series::Style::Dashed: st << "with lines dt 2 lw " << number(s.width); break;
    case Series::Style::Points: st << "with points pt 7 ps " << number(0.5 * s.width); break;
    case Series::Style::LinesPoints: st << "with linespoints pt 7 ps " << number(0.5 * s.width) << " lw 1.5"; break;
  }
  if (!s.color.empty()) st << " lc rgb " << quoted(s.color);
  st << (s.label.empty() ? " notitle" : " title " + quoted(s.label) + " noenhanced");
  return st.str();
}

void write_block(std::ostringstream& s, const std::string& name, const Series& series) {
  s << "$" << name << " << EOD\n";
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    if (!std::isfinite(series.y[i]) || !std::isfinite(series.x[i])) {
      s << "\n";  // a blank line breaks the curve
      continue;
    }
    s << number(series.x[i]) << " " << number(series.y[i]) << "\n";
  }
  s << "EOD\n";
}

void check_series(const Series& s, const std::filesystem::path& png) {
  if (s.x.size() != s.y.size())
    throw PlotError("cannot draw " + png.string() + ": series '" + s.label + "' has " + std::to_string(s.x.size()) +
                    " x values but " + std::to_string(s.y.size()) + " y values");
}

}  // namespace

bool gnuplot_available() {
  const std::string cmd = "\"" + gnuplot_command() + "\" -e 'exit' > /dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

void render_png(const LineChart& c, const std::filesystem::path& png, Size size) {
  bool any = false;
  for (const Series& s : c.series) {
    check_series(s, png);
    any = any || !s.x.empty();
  }
  if (!any) throw PlotError("cannot draw " + png.string() + ": no data");
  TempDir tmp;
  std::ostringstream s;
  s << header(c.title, c.xlabel, c.ylabel, png, size);
  s << "set key " << c.legend_position << " box opaque samplen 2 spacing 1.1\n";
  if (c.xrange) s << "set xrange [" << number(c.xrange->first) << ":" << number(c.xrange->second) << "]\n";
  if (c.yrange) s << "set yrange [" << number(c.yrange->first) << ":" << number(c.yrange->second) << "]\n";
  if (c.logy) s << "set logscale y\nset format y '10^{%L}'\n";
  if (c.equal_axes) s << "set size ratio -1\n";
  int k = 1;
  for (double x : c.vertical_lines)
    s << "set arrow " << k++ << " from " << number(x) << ", graph 0 to " << number(x)
      << ", graph 1 nohead lc rgb '#999999' dt 3 lw 1\n";
  k = 1;
  for (const Annotation& a : c.annotations)
    s << "set label " << k++ << " " << quoted(a.text) << " at " << number(a.x) << "," << number(a.y)
      << " center noenhanced font ',10' textcolor rgb '#555555' front\n";
  for (std::size_t i = 0; i < c.series.size(); ++i) write_block(s, "d" + std::to_string(i), c.series[i]);
  s << "plot ";
  bool first = true;
  for (std::size_t i = 0; i < c.series.size(); ++i) {
    if (c.series[i].x.empty()) continue;
    s << (first ? "" : ", \\\n     ") << "$d" << i << " using 1:2 " << style_of(c.series[i]);
    first = false;
  }
  s << "\n";
  run_gnuplot(s.str(), png, tmp);
}

void render_png(const Heatmap& m, const std::filesystem::path& png, Size size) {
  const std::size_t nx = m.x.size(), ny = m.y.size();
  if (nx < 2 || ny < 2) throw PlotError("cannot draw " + png.string() + ": a heat map needs at least 2 x 2 values");
  if (m.z.size() != nx * ny)
    throw PlotError("cannot draw " + png.string() + ": " + std::to_string(m.z.size()) + " values for a " +
                    std::to_string(ny) + " x " + std::to_string(nx) + " grid");
  for (std::size_t i = 1; i < nx; ++i)
    if (!(m.x[i] > m.x[i - 1]) || !std::isfinite(m.x[i]))
      throw PlotError("cannot draw " + png.string() + ": heat-map x values must be finite and strictly ascending");
  for (std::size_t j = 1; j < ny; ++j)
    if (!(m.y[j] > m.y[j - 1]) || !std::isfinite(m.y[j]))
      throw PlotError("cannot draw " + png.string() + ": heat-map y values must be finite and strictly ascending");
  for (const Series& s : m.overlays) check_series(s, png);

  TempDir tmp;
  std::ostringstream s;
  s << header(m.title, m.xlabel, m.ylabel, png, size);
  s << "set cblabel " << label(m.zlabel) << " noenhanced\n";
  // Viridis-like, perceptually uniform.
  s << "set palette defined (0 '#440154', 1 '#482878', 2 '#3e4989', 3 '#31688e', 4 '#26828e', 5 '#1f9e89', "
       "6 '#35b779', 7 '#6ece58', 8 '#b5de2b', 9 '#fde725')\n";
  double zmin = std::numeric_limits<double>::infinity(), zmax = 0.0;
  for (double v : m.z)
    if (v > 0 && std::isfinite(v)) {
      zmin = std::min(zmin, v);
      zmax = std::max(zmax, v);
    }
  double lo = m.zrange ? m.zrange->first : (m.logz ? std::max(zmin, zmax * 1e-3) : 0.0);
  double hi = m.zrange ? m.zrange->second : zmax;
  if (!(hi > lo)) hi = lo + 1.0;
  if (m.logz) {
    if (!(lo > 0)) lo = hi * 1e-3;
    s << "set logscale cb\nset format cb '10^{%L}'\n";
  }
  s << "set cbrange [" << number(lo) << ":" << number(hi) << "]\n";
  s << "set xrange [" << number(m.x.front()) << ":" << number(m.x.back()) << "]\n";
  s << "set yrange [" << number(m.y.front()) << ":" << number(m.y.back()) << "]\n";
  s << "set key top left box opaque textcolor rgb 'black'\n";
  s << "set grid front lc rgb '#888888'\n";
  // Cells as boxes spanning half-way to the neighbours: correct on non-uniform grids (rotor speed axis).
  auto edges = [](const std::vector<double>& c) {
    std::vector<double> e(c.size() + 1);
    for (std::size_t i = 1; i < c.size(); ++i) e[i] = 0.5 * (c[i - 1] + c[i]);
    e[0] = c[0] - (e[1] - c[0]);
    e[c.size()] = c.back() + (c.back() - e[c.size() - 1]);
    return e;
  };
  const std::vector<double> ex = edges(m.x), ey = edges(m.y);
  const std::filesystem::path data = tmp.path() / "grid.dat";
  {
    std::ofstream out(data);
    // pm3d corners: (ny+1) x (nx+1) vertices; each cell coloured by corners2color c1 (its lower-left vertex value).
    for (std::size_t i = 0; i <= nx; ++i) {
      for (std::size_t j = 0; j <= ny; ++j) {
        const std::size_t ci = std::min(i, nx - 1), cj = std::min(j, ny - 1);
        double v = m.z[cj * nx + ci];
        if (m.logz && !(v > lo)) v = lo;
        out << number(ex[i]) << " " << number(ey[j]) << " " << number(v) << "\n";
      }
      out << "\n";
    }
  }
  for (std::size_t i = 0; i < m.overlays.size(); ++i) write_block(s, "o" + std::to_string(i), m.overlays[i]);
  s << "set view map\nset pm3d corners2color c1 noborder\n";
  s << "splot " << quoted(data.string()) << " using 1:2:3 with pm3d notitle";
  for (std::size_t i = 0; i < m.overlays.size(); ++i) {
    std::string st = style_of(m.overlays[i]);
    s << ", \\\n      $o" << i << " using 1:2:(" << number(hi) << ") " << st;
  }
  s << "\n";
  run_gnuplot(s.str(), png, tmp);
}

}  // namespace turbodyn::plot

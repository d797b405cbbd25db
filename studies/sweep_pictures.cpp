#include "studies/sweep_pictures.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <tuple>

#include "post/plot.h"
#include "post/plot_style.h"
#include "post/run_pictures.h"
#include "studies/table.h"

namespace turbodyn::studies {
namespace {

// The number of cells across a contour map (interpolated values), and of colour bands.
constexpr int kMapCells = 320;
constexpr int kMapLevels = 12;
constexpr int kMapPad = 12;

std::string with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " [" + unit + "]";
}

std::string param_label(const StudySpec& study, const Design& design, std::size_t p) {
  return with_unit(design.paths[p], study.parameter_units[p]);
}

std::string short_number(double v) {
  std::ostringstream os;
  os << std::setprecision(4) << v;
  return os.str();
}

// Smallest and largest value of parameter p over the design.
std::pair<double, double> span(const Design& design, std::size_t p) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& row : design.values) {
    lo = std::min(lo, row[p]);
    hi = std::max(hi, row[p]);
  }
  return {lo, hi};
}

}  // namespace

void draw_tornado(const StudySpec& study, const Design& design, std::size_t metric, const Sensitivity& s,
                  const std::filesystem::path& png) {
  std::vector<std::size_t> order(s.src.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(s.src[a]) > std::abs(s.src[b]);
  });
  plot::BarChart chart;
  chart.title = "Sensitivity of " + study.metrics[metric].name + " (R² = " + short_number(s.r_squared) + ")";
  chart.xlabel = "standardised regression coefficient [-]";
  for (std::size_t p : order) {
    const auto [lo, hi] = span(design, p);
    const std::string unit = study.parameter_units[p].empty() ? "" : " " + study.parameter_units[p];
    plot::Bar b;
    b.label = design.paths[p] + "\n" + short_number(lo) + " … " + short_number(hi) + unit;
    b.value = s.src[p];
    b.color = s.src[p] >= 0 ? plot::style::kRaises : plot::style::kLowers;
    std::ostringstream t;
    t << std::showpos << std::fixed << std::setprecision(2) << s.src[p];
    b.text = t.str();
    chart.bars.push_back(b);
  }
  chart.legend = {{plot::style::kRaises, "raises the metric"}, {plot::style::kLowers, "lowers the metric"}};
  const int height = std::max(360, 160 + 90 * static_cast<int>(chart.bars.size()));
  plot::render_png(chart, png, plot::Size{1000, height});
}

bool draw_metric_scatter(const StudySpec& study, const Design& design, const std::vector<RunRecord>& runs,
                         std::size_t metric, std::size_t parameter, const std::string& unit,
                         const std::filesystem::path& png) {
  const post::Display d = post::display_of(unit);
  plot::LineChart chart;
  chart.title = study.metrics[metric].name + " against " + design.paths[parameter];
  chart.xlabel = param_label(study, design, parameter);
  chart.ylabel = with_unit(study.metrics[metric].name, d.unit);
  plot::Series ok{"complete run", {}, {}, plot::Series::Style::Points, plot::style::kComplete, 2.0};
  plot::Series part{"incomplete run (value of the part that ran)", {}, {}, plot::Series::Style::Triangles,
                    plot::style::kIncomplete, 2.4};
  plot::Series failed{"failed run (no value; drawn at the lower edge)", {}, {}, plot::Series::Style::Crosses,
                      plot::style::kFailed, 2.4};
  plot::Series undefined{"run without a value of this metric (e.g. nothing above its threshold; drawn at the lower "
                         "edge)",
                         {}, {}, plot::Series::Style::Crosses, plot::style::kNoValue, 2.4};
  double ymin = std::numeric_limits<double>::infinity();
  for (const RunRecord& r : runs) {
    const double v = r.metrics[metric] * d.factor;
    if (!std::isfinite(v)) {
      (r.status == "failed" ? failed : undefined).x.push_back(r.parameters[parameter]);
      continue;
    }
    ymin = std::min(ymin, v);
    plot::Series& s = r.status == "ok" ? ok : part;
    s.x.push_back(r.parameters[parameter]);
    s.y.push_back(v);
  }
  if (!std::isfinite(ymin)) return false;
  failed.y.assign(failed.x.size(), ymin);
  undefined.y.assign(undefined.x.size(), ymin);
  for (plot::Series* s : {&ok, &part, &failed, &undefined})
    if (!s->x.empty()) chart.series.push_back(*s);
  plot::render_png(chart, png);
  return true;
}

double shepard(const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs, double x,
               double y, double sx, double sy) {
  double wsum = 0.0, zsum = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double dx = (x - xs[i]) / sx, dy = (y - ys[i]) / sy;
    const double r2 = dx * dx + dy * dy;
    if (r2 < 1e-24) return zs[i];
    wsum += 1.0 / r2;
    zsum += zs[i] / r2;
  }
  return zsum / wsum;
}

bool draw_metric_map(const StudySpec& study, const Design& design, const std::vector<RunRecord>& runs,
                     std::size_t metric, const std::string& unit, const std::filesystem::path& png) {
  const std::size_t n_par = design.paths.size();
  if (n_par < 2) return false;
  const post::Display d = post::display_of(unit);
  std::vector<double> xs, ys, zs;
  plot::Series ok{"complete run", {}, {}, plot::Series::Style::Points, plot::style::kRunOnMap, 2.2};
  plot::Series part{"incomplete run", {}, {}, plot::Series::Style::Triangles, plot::style::kIncomplete, 2.0};
  plot::Series failed{"failed run", {}, {}, plot::Series::Style::Crosses, plot::style::kFailed, 2.4};
  plot::Series undefined{"run without a value of this metric", {}, {}, plot::Series::Style::Crosses,
                         plot::style::kNoValue, 2.4};
  for (const RunRecord& r : runs) {
    const double v = r.metrics[metric] * d.factor;
    plot::Series& s = !std::isfinite(v) ? (r.status == "failed" ? failed : undefined) : r.status == "ok" ? ok : part;
    s.x.push_back(r.parameters[0]);
    s.y.push_back(r.parameters[1]);
    if (!std::isfinite(v)) continue;
    xs.push_back(r.parameters[0]);
    ys.push_back(r.parameters[1]);
    zs.push_back(v);
  }
  if (zs.size() < 3) return false;
  const auto [x0, x1] = span(design, 0);
  const auto [y0, y1] = span(design, 1);
  if (!(x1 > x0) || !(y1 > y0)) return false;
  // More than two parameters: the map is a quadratic response surface in all of them, drawn over the first two
  // with the others at the centre of their ranges; the runs are shown at their first two parameters.
  QuadraticSurface surface;
  std::vector<double> at(n_par);
  if (n_par > 2) {
    std::vector<std::vector<double>> xs_all;
    std::vector<double> ys_all;
    std::vector<double> lo(n_par), hi(n_par);
    for (std::size_t p = 0; p < n_par; ++p) {
      std::tie(lo[p], hi[p]) = span(design, p);
      if (!(hi[p] > lo[p])) return false;
      at[p] = 0.5 * (lo[p] + hi[p]);
    }
    for (const RunRecord& r : runs) {
      xs_all.push_back(r.parameters);
      ys_all.push_back(r.metrics[metric] * d.factor);
    }
    try {
      surface = fit_quadratic_surface(xs_all, ys_all, lo, hi);
    } catch (const std::invalid_argument&) {
      return false;  // too few runs for the quadratic terms: no map
    }
  }

  plot::Heatmap hm;
  hm.title = study.metrics[metric].name + " over " + design.paths[0] + " and " + design.paths[1];
  if (n_par > 2) {
    std::ostringstream os;
    os << std::setprecision(2) << std::fixed << surface.r_squared;
    hm.title += " (quadratic response surface of " + std::to_string(surface.runs) + " runs, R² " + os.str() +
                "; other parameters at the centre of their ranges)";
  }
  hm.xlabel = param_label(study, design, 0);
  hm.ylabel = param_label(study, design, 1);
  hm.zlabel = with_unit(study.metrics[metric].name, d.unit);
  hm.levels = kMapLevels;
  // The design's box and a blank margin of kMapPad cells around it, so that runs on its edges show whole.
  for (int i = -kMapPad; i < kMapCells + kMapPad; ++i) {
    hm.x.push_back(x0 + (x1 - x0) * (i + 0.5) / kMapCells);
    hm.y.push_back(y0 + (y1 - y0) * (i + 0.5) / kMapCells);
  }
  hm.z.resize(hm.x.size() * hm.y.size());

  // A complete full-factorial grid: bilinear between the grid's runs.
  std::vector<double> gx = xs, gy = ys;
  std::sort(gx.begin(), gx.end());
  gx.erase(std::unique(gx.begin(), gx.end()), gx.end());
  std::sort(gy.begin(), gy.end());
  gy.erase(std::unique(gy.begin(), gy.end()), gy.end());
  std::vector<double> grid(gx.size() * gy.size(), NAN);
  for (std::size_t k = 0; k < zs.size(); ++k) {
    const std::size_t i = std::lower_bound(gx.begin(), gx.end(), xs[k]) - gx.begin();
    const std::size_t j = std::lower_bound(gy.begin(), gy.end(), ys[k]) - gy.begin();
    grid[j * gx.size() + i] = zs[k];
  }
  const bool full_grid = study.design.kind == DesignKind::FullFactorial && gx.size() >= 2 && gy.size() >= 2 &&
                         std::all_of(grid.begin(), grid.end(), [](double v) { return std::isfinite(v); });
  for (std::size_t j = 0; j < hm.y.size(); ++j)
    for (std::size_t i = 0; i < hm.x.size(); ++i) {
      const double x = hm.x[i], y = hm.y[j];
      double v = NAN;
      if (x < x0 || x > x1 || y < y0 || y > y1) {
        hm.z[j * hm.x.size() + i] = v;
        continue;
      }
      if (n_par > 2) {
        at[0] = x;
        at[1] = y;
        v = surface(at);
      } else if (full_grid) {
        const std::size_t a = std::clamp<std::size_t>(std::upper_bound(gx.begin(), gx.end(), x) - gx.begin(), 1,
                                                       gx.size() - 1);
        const std::size_t b = std::clamp<std::size_t>(std::upper_bound(gy.begin(), gy.end(), y) - gy.begin(), 1,
                                                       gy.size() - 1);
        const double tx = (x - gx[a - 1]) / (gx[a] - gx[a - 1]), ty = (y - gy[b - 1]) / (gy[b] - gy[b - 1]);
        const std::size_t n = gx.size();
        v = (1 - ty) * ((1 - tx) * grid[(b - 1) * n + a - 1] + tx * grid[(b - 1) * n + a]) +
            ty * ((1 - tx) * grid[b * n + a - 1] + tx * grid[b * n + a]);
      } else {
        v = shepard(xs, ys, zs, x, y, x1 - x0, y1 - y0);
      }
      hm.z[j * hm.x.size() + i] = v;
    }
  // White dots with a black rim: seen on the dark and the light colours of the map and on the blank margin.
  if (!ok.x.empty()) hm.overlays.push_back({"", ok.x, ok.y, plot::Series::Style::Points, "black", 2.9});
  for (plot::Series* s : {&ok, &part, &failed, &undefined})
    if (!s->x.empty()) hm.overlays.push_back(*s);
  plot::render_png(hm, png);
  return true;
}

}  // namespace turbodyn::studies

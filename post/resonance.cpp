#include "post/resonance.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace turbodyn::post {

namespace {

constexpr double kHalfPowerRatio = 0.70710678118654752440;  // 1 / sqrt(2)
constexpr double kBracketTolerance = 1e-10;                 // of the speed: where the searches stop

// Where the curve crosses `level` walking from (x0, y0), the peak, in direction dir (+1 up, -1 down) over the samples
// beyond x0: the first sample below the level and the point before it (the peak or a sample), which straddle the
// crossing. found = false: the range ends first; dominated = true: a sample rises above `peak` first.
struct Walk {
  bool found = false, dominated = false;
  double x_in = 0.0, y_in = 0.0, x_out = 0.0, y_out = 0.0;
};

Walk walk(const std::vector<double>& xs, const std::vector<double>& ys, double x0, double y0, int dir, double level,
          double peak) {
  Walk w;
  w.x_in = x0;
  w.y_in = y0;
  const long n = static_cast<long>(xs.size());
  long j = dir > 0 ? 0 : n - 1;
  while (j >= 0 && j < n && (dir > 0 ? xs[j] <= x0 : xs[j] >= x0)) j += dir;  // the first sample beyond x0
  for (; j >= 0 && j < n; j += dir) {
    if (ys[j] > peak) {
      w.dominated = true;
      return w;
    }
    if (ys[j] < level) {
      w.found = true;
      w.x_out = xs[j];
      w.y_out = ys[j];
      return w;
    }
    w.x_in = xs[j];
    w.y_in = ys[j];
  }
  return w;
}

// The maximum of f on [a, b] by golden section, never below the sample (xk, yk) inside the bracket.
void golden_maximum(const std::function<double(double)>& f, double a, double b, double xk, double yk, double& x_c,
                    double& y_c) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  const double stop = kBracketTolerance * std::max(std::abs(a), std::abs(b));
  for (int it = 0; it < 200 && b - a > stop; ++it) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  x_c = fc > fd ? c : d;
  y_c = std::max(fc, fd);
  if (yk > y_c) {
    x_c = xk;
    y_c = yk;
  }
}

// The vertex of the parabola through the three samples about k (clamped to their span), never below the sample.
void parabola_maximum(const std::vector<double>& xs, const std::vector<double>& ys, std::size_t k, double& x_c,
                      double& y_c) {
  x_c = xs[k];
  y_c = ys[k];
  const double x0 = xs[k - 1], x1 = xs[k], x2 = xs[k + 1], y0 = ys[k - 1], y1 = ys[k], y2 = ys[k + 1];
  const double num = (x1 - x0) * (x1 - x0) * (y1 - y2) - (x1 - x2) * (x1 - x2) * (y1 - y0);
  const double den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0);
  if (!(den != 0.0) || !std::isfinite(num / den)) return;
  const double xv = std::min(std::max(x1 - 0.5 * num / den, x0), x2);
  // Lagrange form of the parabola at xv.
  const double yv = y0 * (xv - x1) * (xv - x2) / ((x0 - x1) * (x0 - x2)) +
                    y1 * (xv - x0) * (xv - x2) / ((x1 - x0) * (x1 - x2)) +
                    y2 * (xv - x0) * (xv - x1) / ((x2 - x0) * (x2 - x1));
  if (yv > y_c) {
    x_c = xv;
    y_c = yv;
  }
}

// The crossing of `level` between the walk's two points: bisection on the curve, or a straight line between them.
double crossing(const Walk& w, double level, const std::function<double(double)>& curve_at) {
  if (!curve_at) return w.x_in + (level - w.y_in) * (w.x_out - w.x_in) / (w.y_out - w.y_in);
  double in = w.x_in, out = w.x_out;
  const double stop = kBracketTolerance * std::max(std::abs(in), std::abs(out));
  for (int it = 0; it < 200 && std::abs(out - in) > stop; ++it) {
    const double mid = 0.5 * (in + out);
    (curve_at(mid) >= level ? in : out) = mid;
  }
  return 0.5 * (in + out);
}

}  // namespace

std::vector<Resonance> find_resonances(const std::vector<double>& xs, const std::vector<double>& ys,
                                       const std::function<double(double)>& curve_at) {
  if (xs.size() != ys.size())
    throw std::invalid_argument("find_resonances: " + std::to_string(xs.size()) + " speeds but " +
                                std::to_string(ys.size()) + " amplitudes");
  if (xs.size() < 3) throw std::invalid_argument("find_resonances: needs at least three samples");
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!std::isfinite(xs[i]) || (i > 0 && !(xs[i] > xs[i - 1])))
      throw std::invalid_argument("find_resonances: the speeds must be finite and increasing (sample " +
                                  std::to_string(i) + ")");
    if (!std::isfinite(ys[i]) || ys[i] < 0.0)
      throw std::invalid_argument("find_resonances: amplitude " + std::to_string(i) + " is negative or not finite");
  }
  std::vector<Resonance> out;
  for (std::size_t k = 1; k + 1 < xs.size(); ++k) {
    if (!(ys[k] > ys[k - 1] && ys[k] >= ys[k + 1])) continue;  // the first sample of a peak (or plateau)
    // On the samples: does the curve fall to the half-power level on a side before it rises above the peak?
    const double sample_level = kHalfPowerRatio * ys[k];
    const Walk down = walk(xs, ys, xs[k], ys[k], -1, sample_level, ys[k]);
    const Walk up = walk(xs, ys, xs[k], ys[k], +1, sample_level, ys[k]);
    if (down.dominated || up.dominated || (!down.found && !up.found)) continue;
    Resonance r;
    if (curve_at)
      golden_maximum(curve_at, xs[k - 1], xs[k + 1], xs[k], ys[k], r.speed, r.peak);
    else
      parabola_maximum(xs, ys, k, r.speed, r.peak);
    r.refined = static_cast<bool>(curve_at);
    // The band about the found peak (its level is at least the samples', so it closes no later than theirs).
    const double level = kHalfPowerRatio * r.peak;
    const Walk lo = walk(xs, ys, r.speed, r.peak, -1, level, r.peak);
    const Walk hi = walk(xs, ys, r.speed, r.peak, +1, level, r.peak);
    if (lo.found) r.lower = crossing(lo, level, curve_at);
    if (hi.found) r.upper = crossing(hi, level, curve_at);
    if (lo.found && hi.found) r.amplification_factor = r.speed / (r.upper - r.lower);
    out.push_back(r);
  }
  return out;
}

}  // namespace turbodyn::post

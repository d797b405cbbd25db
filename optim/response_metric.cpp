#include "optim/response_metric.h"

#include <cmath>
#include <stdexcept>

#include "model/rotor/response.h"
#include "model/spec/constants.h"

namespace turbodyn::optim {
namespace {

constexpr double kGoldenTolerance = 1e-10;  // relative speed tolerance of the refined peak

// Which quantity of the steady response a probe names.
struct Probe {
  bool disk = true;
  int index = 0;       ///< disk or bearing index
  int component = -1;  ///< -1: major semi-axis, 0: x, 1: y
};

Probe find_probe(const std::string& name, const Rotor& rotor) {
  auto component = [&](const std::string& rest, bool disk) {
    if (rest.empty()) return -1;
    if (rest == (disk ? ".x" : ".fx")) return 0;
    if (rest == (disk ? ".y" : ".fy")) return 1;
    return -2;
  };
  for (std::size_t i = 0; i < rotor.disks.size(); ++i) {
    const std::string stem = "disk." + rotor.disks[i].name;
    if (name.rfind(stem, 0) == 0) {
      const int c = component(name.substr(stem.size()), true);
      if (c > -2) return {true, static_cast<int>(i), c};
    }
  }
  for (std::size_t i = 0; i < rotor.bearings.size(); ++i) {
    const std::string stem = "bearing." + rotor.bearings[i].name;
    if (name.rfind(stem, 0) == 0) {
      const int c = component(name.substr(stem.size()), false);
      if (c > -2) return {false, static_cast<int>(i), c};
    }
  }
  throw std::invalid_argument("the steady-state response has no probe '" + name + "'");
}

double amplitude(const Rotor& rotor, const Probe& p, double speed) {
  const SteadyResponse r = unbalance_response(rotor, speed);
  std::complex<double> x, y;
  if (p.disk) {
    const int node = rotor.disks[p.index].node;
    x = r.q(rotor.dof(node, kX));
    y = r.q(rotor.dof(node, kY));
  } else {
    x = r.bearing_fx[p.index];
    y = r.bearing_fy[p.index];
  }
  if (p.component == 0) return std::abs(x);
  if (p.component == 1) return std::abs(y);
  return major_semi_axis(x, y);
}

}  // namespace

double response_metric(const studies::MetricSpec& m, int points, const Rotor& rotor) {
  const Probe p = find_probe(m.probe, rotor);
  if (points < 3 || !(m.speed_max > m.speed_min)) throw std::invalid_argument("response metric: bad speed grid");
  std::vector<double> w(points), a(points);
  std::size_t best = 0;
  for (int i = 0; i < points; ++i) {
    w[i] = m.speed_min + (m.speed_max - m.speed_min) * i / (points - 1);
    a[i] = w[i] > 0.0 ? amplitude(rotor, p, w[i]) : 0.0;
    if (a[i] > a[best]) best = i;
  }
  double peak = a[best], at = w[best];
  if (best > 0 && best + 1 < w.size()) {
    // Golden-section search for the maximum between the grid neighbours.
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    double lo = w[best - 1], hi = w[best + 1];
    double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
    double f1 = amplitude(rotor, p, x1), f2 = amplitude(rotor, p, x2);
    while (hi - lo > kGoldenTolerance * hi) {
      if (f1 > f2) {
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - phi * (hi - lo);
        f1 = amplitude(rotor, p, x1);
      } else {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + phi * (hi - lo);
        f2 = amplitude(rotor, p, x2);
      }
    }
    for (auto [f, x] : {std::pair{f1, x1}, std::pair{f2, x2}})
      if (f > peak) {
        peak = f;
        at = x;
      }
  }
  return m.kind == "response_peak_speed" ? at * kRadPerSToRpm : peak;
}

}  // namespace turbodyn::optim

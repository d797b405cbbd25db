#include "identification/residuals.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace turbodyn::identification {
namespace {

constexpr double kAutoThreshold = 0.1;      // subsync: frequencies compared above 10 % of the largest measured peak
constexpr double kAutoSpeedScale = 0.01;    // resonance: 1 % of the measured resonance speed

double rms(const std::vector<double>& v) {
  double s = 0.0;
  std::size_t n = 0;
  for (double x : v)
    if (std::isfinite(x)) {
      s += x * x;
      ++n;
    }
  return n ? std::sqrt(s / static_cast<double>(n)) : 0.0;
}

}  // namespace

Residuals::Residuals(const std::vector<FeatureSpec>& features, const std::vector<FeatureTrack>& measured,
                     double resolution_hz)
    : features_(features), measured_(measured) {
  for (std::size_t f = 0; f < features.size(); ++f) {
    const FeatureSpec& fs = features[f];
    const FeatureTrack& m = measured[f];
    double sa = fs.amplitude_scale > 0.0 ? fs.amplitude_scale : rms(m.amplitude);
    if (!(sa > 0.0)) sa = 1.0;
    amplitude_scale_.push_back(sa);
    double th = fs.threshold;
    if (fs.kind == FeatureKind::Subsync && !(th > 0.0)) {
      double mx = 0.0;
      for (double a : m.amplitude)
        if (std::isfinite(a)) mx = std::max(mx, a);
      th = kAutoThreshold * mx;
    }
    threshold_.push_back(th);
    switch (fs.kind) {
      case FeatureKind::Order1x:
        for (std::size_t k = 0; k < m.speed_hz.size(); ++k) {
          if (!std::isfinite(m.amplitude[k])) continue;
          if (fs.phase && std::isfinite(m.phase[k])) {
            rows_.push_back({f, k, "re", sa, fs.weight});
            rows_.push_back({f, k, "im", sa, fs.weight});
          } else {
            rows_.push_back({f, k, "amplitude", sa, fs.weight});
          }
        }
        break;
      case FeatureKind::Subsync: {
        const double sf = fs.frequency_scale > 0.0 ? fs.frequency_scale : resolution_hz;
        for (std::size_t k = 0; k < m.speed_hz.size(); ++k) {
          if (!std::isfinite(m.amplitude[k])) continue;
          rows_.push_back({f, k, "amplitude", sa, fs.weight});
          if (m.amplitude[k] > th && std::isfinite(m.frequency[k])) rows_.push_back({f, k, "frequency", sf, fs.weight});
        }
        break;
      }
      case FeatureKind::Resonance:
        if (std::isfinite(m.resonance_hz)) {
          const double sn = fs.speed_scale > 0.0 ? fs.speed_scale : kAutoSpeedScale * m.resonance_hz;
          rows_.push_back({f, 0, "resonance_speed", sn, fs.weight});
        }
        break;
    }
  }
}

bool Residuals::evaluate(const std::vector<FeatureTrack>& model, double* r) const {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const ResidualRow& row = rows_[i];
    const FeatureTrack& m = measured_[row.feature];
    const FeatureTrack& d = model[row.feature];
    double diff = 0.0;
    if (row.quantity == "re" || row.quantity == "im") {
      const std::complex<double> zm = std::polar(m.amplitude[row.point], m.phase[row.point]);
      const std::complex<double> zd = std::polar(d.amplitude[row.point], d.phase[row.point]);
      const std::complex<double> dz = zd - zm;
      diff = row.quantity == "re" ? dz.real() : dz.imag();
    } else if (row.quantity == "amplitude") {
      diff = d.amplitude[row.point] - m.amplitude[row.point];
    } else if (row.quantity == "frequency") {
      diff = d.frequency[row.point] - m.frequency[row.point];
    } else {
      diff = d.resonance_hz - m.resonance_hz;
    }
    if (!std::isfinite(diff)) return false;
    r[i] = row.weight * diff / row.scale;
  }
  return true;
}

}  // namespace turbodyn::identification

#include "identification/features.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/spec/constants.h"

namespace turbodyn::identification {
namespace {

constexpr double kMinSubsyncHz = 5.0;       // lowest frequency taken as sub-synchronous (drift, DC leakage below)
constexpr int kResonanceGrid = 201;         // response method: speeds scanned for the 1x peak
constexpr double kOneXBins = 1.5;           // spectra: the 1x line is the largest bin within this many bins of f_d

// Index k with x[k] <= xi <= x[k+1] in an ascending (or mostly ascending) sequence, or -1.
int bracket(const std::vector<double>& x, double xi) {
  for (std::size_t k = 0; k + 1 < x.size(); ++k)
    if ((x[k] <= xi && xi <= x[k + 1]) || (x[k] >= xi && xi >= x[k + 1])) return static_cast<int>(k);
  return -1;
}

double lerp(const std::vector<double>& x, const std::vector<double>& y, double xi) {
  const int k = bracket(x, xi);
  if (k < 0) return kNaN;
  const double d = x[k + 1] - x[k];
  const double a = d == 0.0 ? 0.0 : (xi - x[k]) / d;
  return y[k] + a * (y[k + 1] - y[k]);
}

// Vertex of the parabola through (x0,y0), (x1,y1), (x2,y2); x1 if degenerate.
std::pair<double, double> parabola_peak(double x0, double y0, double x1, double y1, double x2, double y2) {
  const double d0 = (x0 - x1) * (x0 - x2), d1 = (x1 - x0) * (x1 - x2), d2 = (x2 - x0) * (x2 - x1);
  if (d0 == 0.0 || d1 == 0.0 || d2 == 0.0) return {x1, y1};
  const double a = y0 / d0 + y1 / d1 + y2 / d2;
  const double b = -(y0 * (x1 + x2) / d0 + y1 * (x0 + x2) / d1 + y2 * (x0 + x1) / d2);
  const double c = y0 * x1 * x2 / d0 + y1 * x0 * x2 / d1 + y2 * x0 * x1 / d2;
  if (!(a < 0.0)) return {x1, y1};
  const double xv = std::clamp(-b / (2.0 * a), std::min(x0, x2), std::max(x0, x2));
  return {xv, (a * xv + b) * xv + c};
}

// Largest value of y over x in [lo, hi], refined by a parabola.
void find_resonance(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi,
                    FeatureTrack& t) {
  int best = -1;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] >= lo && x[i] <= hi && std::isfinite(y[i]) && (best < 0 || y[i] > y[best])) best = static_cast<int>(i);
  t.curve_speed_hz.clear();
  t.curve_amplitude.clear();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] >= lo && x[i] <= hi) {
      t.curve_speed_hz.push_back(x[i]);
      t.curve_amplitude.push_back(y[i]);
    }
  if (best < 0) return;
  t.resonance_hz = x[best];
  t.resonance_amplitude = y[best];
  if (best > 0 && best + 1 < static_cast<int>(x.size()) && x[best - 1] >= lo && x[best + 1] <= hi) {
    const auto [xv, yv] = parabola_peak(x[best - 1], y[best - 1], x[best], y[best], x[best + 1], y[best + 1]);
    t.resonance_hz = xv;
    t.resonance_amplitude = yv;
  }
}

// Per spectrum: the 1x amplitude and the largest sub-synchronous peak (frequency refined by a parabola).
struct SpectrumFeatures {
  double one_x = kNaN, sub_amplitude = kNaN, sub_frequency = kNaN;
};

SpectrumFeatures analyse_spectrum(const std::vector<double>& f, const std::vector<double>& a, double fd, double low,
                                  double high) {
  SpectrumFeatures out;
  if (f.empty()) return out;
  double df = 0.0;
  for (std::size_t k = 1; k < f.size(); ++k) df = std::max(df, f[k] - f[k - 1]);
  if (f.size() == 1) df = std::abs(fd);
  // 1x: largest bin within kOneXBins bins of f_d (for a spectrum with one line per speed: that line).
  for (std::size_t k = 0; k < f.size(); ++k)
    if (std::abs(f[k] - fd) <= kOneXBins * df) out.one_x = std::isnan(out.one_x) ? a[k] : std::max(out.one_x, a[k]);
  int best = -1;
  const double lo = std::max(kMinSubsyncHz, low * fd), hi = high * fd;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (f[k] >= lo && f[k] <= hi && (best < 0 || a[k] > a[best])) best = static_cast<int>(k);
  if (best >= 0) {
    out.sub_amplitude = a[best];
    out.sub_frequency = f[best];
    if (best > 0 && best + 1 < static_cast<int>(f.size())) {
      const auto [xv, yv] = parabola_peak(f[best - 1], a[best - 1], f[best], a[best], f[best + 1], a[best + 1]);
      out.sub_frequency = xv;
      out.sub_amplitude = yv;
    }
  }
  return out;
}

FeatureTrack empty_track(const FeatureSpec& fs) {
  FeatureTrack t;
  t.speed_hz = fs.speeds_hz;
  t.amplitude.assign(fs.speeds_hz.size(), kNaN);
  t.phase.assign(fs.speeds_hz.size(), kNaN);
  t.frequency.assign(fs.speeds_hz.size(), kNaN);
  return t;
}

}  // namespace

SpectraSet spectra_from_record(const Record& r, const ProcessingSpec& p) {
  SpectraSet s;
  const signal::StftOptions so = p.stft();
  s.amplitude.resize(r.channels.size());
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const signal::Spectrogram sg = signal::stft(r.channels[c], r.sample_rate, so);
    if (c == 0) {
      s.speed_hz = signal::values_at_segment_centres(sg, r.speed_hz, r.sample_rate);
      s.frequency_hz.assign(sg.n_segments(), sg.frequencies);
    }
    s.amplitude[c].resize(sg.n_segments());
    for (std::size_t seg = 0; seg < sg.n_segments(); ++seg)
      s.amplitude[c][seg].assign(sg.amplitude.begin() + seg * sg.n_bins(),
                                 sg.amplitude.begin() + (seg + 1) * sg.n_bins());
  }
  return s;
}

std::vector<FeatureTrack> features_from_spectra(const std::vector<FeatureSpec>& features, const SpectraSet& s) {
  std::vector<FeatureTrack> out;
  for (const FeatureSpec& fs : features) {
    FeatureTrack t = empty_track(fs);
    const std::size_t n = s.speed_hz.size();
    std::vector<double> one_x(n), sub_a(n), sub_f(n);
    for (std::size_t i = 0; i < n; ++i) {
      const SpectrumFeatures sf =
          analyse_spectrum(s.frequency_hz[i], s.amplitude[fs.sensor][i], s.speed_hz[i], fs.band_low, fs.band_high);
      one_x[i] = sf.one_x;
      sub_a[i] = sf.sub_amplitude;
      sub_f[i] = sf.sub_frequency;
    }
    for (std::size_t k = 0; k < fs.speeds_hz.size(); ++k) {
      if (fs.kind == FeatureKind::Order1x) t.amplitude[k] = lerp(s.speed_hz, one_x, fs.speeds_hz[k]);
      if (fs.kind == FeatureKind::Subsync) {
        t.amplitude[k] = lerp(s.speed_hz, sub_a, fs.speeds_hz[k]);
        t.frequency[k] = lerp(s.speed_hz, sub_f, fs.speeds_hz[k]);
      }
    }
    if (fs.kind == FeatureKind::Resonance) find_resonance(s.speed_hz, one_x, fs.range_min_hz, fs.range_max_hz, t);
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<FeatureTrack> features_from_record(const std::vector<FeatureSpec>& features, const ProcessingSpec& p,
                                               const Record& r, bool with_phase) {
  std::vector<FeatureTrack> out;
  std::vector<signal::OrderTrack> tracks(r.channels.size());
  std::vector<bool> tracked(r.channels.size(), false);
  SpectraSet spectra;
  bool have_spectra = false;
  for (const FeatureSpec& fs : features) {
    FeatureTrack t = empty_track(fs);
    if (fs.kind == FeatureKind::Subsync) {
      if (!have_spectra) spectra = spectra_from_record(r, p);
      have_spectra = true;
      t = features_from_spectra({fs}, spectra).front();
      out.push_back(std::move(t));
      continue;
    }
    if (!tracked[fs.sensor]) {
      signal::OrderTrackOptions oo;
      oo.revolutions = p.revolutions;
      oo.points = p.track_points;
      tracks[fs.sensor] = signal::track_order(r.channels[fs.sensor], r.angle, r.speed_hz, r.sample_rate, oo);
      tracked[fs.sensor] = true;
    }
    const signal::OrderTrack& ot = tracks[fs.sensor];
    if (fs.kind == FeatureKind::Order1x) {
      // Interpolate the complex 1x value (no phase unwrapping needed).
      std::vector<double> re(ot.amplitude.size()), im(ot.amplitude.size());
      for (std::size_t i = 0; i < re.size(); ++i) {
        re[i] = ot.amplitude[i] * std::cos(ot.phase[i]);
        im[i] = ot.amplitude[i] * std::sin(ot.phase[i]);
      }
      for (std::size_t k = 0; k < fs.speeds_hz.size(); ++k) {
        if (with_phase) {
          const double a = lerp(ot.speeds, re, fs.speeds_hz[k]), b = lerp(ot.speeds, im, fs.speeds_hz[k]);
          t.amplitude[k] = std::hypot(a, b);
          t.phase[k] = std::atan2(b, a);
        } else {
          t.amplitude[k] = lerp(ot.speeds, ot.amplitude, fs.speeds_hz[k]);
        }
      }
    } else {
      find_resonance(ot.speeds, ot.amplitude, fs.range_min_hz, fs.range_max_hz, t);
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<FeatureTrack> features_from_response(
    const std::vector<FeatureSpec>& features,
    const std::function<std::vector<std::complex<double>>(double speed_hz)>& response, bool with_phase) {
  std::vector<FeatureTrack> out;
  for (const FeatureSpec& fs : features) {
    FeatureTrack t = empty_track(fs);
    if (fs.kind == FeatureKind::Subsync)
      throw std::invalid_argument("feature '" + fs.name + "': the steady-state response has no sub-synchronous content");
    if (fs.kind == FeatureKind::Order1x) {
      for (std::size_t k = 0; k < fs.speeds_hz.size(); ++k) {
        const std::complex<double> z = response(fs.speeds_hz[k])[fs.sensor];
        t.amplitude[k] = std::abs(z);
        if (with_phase) t.phase[k] = std::arg(z);
      }
    } else {
      std::vector<double> x(kResonanceGrid), y(kResonanceGrid);
      for (int i = 0; i < kResonanceGrid; ++i) {
        x[i] = fs.range_min_hz + (fs.range_max_hz - fs.range_min_hz) * i / (kResonanceGrid - 1);
        y[i] = std::abs(response(x[i])[fs.sensor]);
      }
      find_resonance(x, y, fs.range_min_hz, fs.range_max_hz, t);
    }
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace turbodyn::identification

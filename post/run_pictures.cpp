#include "post/run_pictures.h"

#include "post/plot_style.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace turbodyn::post {
namespace {

std::string pretty_name(const ProbeChannel& c) { return c.description.empty() ? c.name : c.description; }

// Name shared by an x/y channel pair: "disk.compressor.x" -> "disk.compressor", "bearing.turbine.fx" ->
// "bearing.turbine.force".
std::string pair_stem(const std::string& name) {
  std::string stem = name.substr(0, name.size() - 1);
  if (!stem.empty() && stem.back() == '.') return stem.substr(0, stem.size() - 1);
  if (stem.size() > 2 && stem.compare(stem.size() - 2, 2, ".f") == 0) return stem + "orce";
  return stem;
}

// Index of the sample where the speed first reaches `speed_hz` (or the last sample).
std::size_t sample_at_speed(const std::vector<double>& speed_hz, double target) {
  for (std::size_t i = 0; i < speed_hz.size(); ++i)
    if (speed_hz[i] >= target) return i;
  return speed_hz.empty() ? 0 : speed_hz.size() - 1;
}

int column_of(const RunupResult& r, ProbeChannel::Kind kind) {
  for (std::size_t c = 0; c < r.channels.size(); ++c)
    if (r.channels[c].kind == kind) return static_cast<int>(c);
  return -1;
}

}  // namespace

Display display_of(const std::string& si_unit) {
  if (si_unit == "m") return {1e6, "µm"};
  if (si_unit == "N/m") return {1e-6, "N/µm"};
  if (si_unit == "Pa") return {1e-6, "MPa"};  // film and contact pressures
  return {1.0, si_unit};
}

std::string file_safe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return s;
}

signal::StftOptions stft_options(const OutputSpec& out) {
  signal::StftOptions so;
  so.segment_length = static_cast<std::size_t>(out.spectrogram_segment);
  so.overlap = out.spectrogram_overlap;
  so.window = signal::window_from_string(to_string(out.spectrogram_window));
  return so;
}

double spectrogram_frequency_max(const OutputSpec& out, double top_speed_hz) {
  return out.frequency_max > 0 ? out.frequency_max
                               : std::min(out.sample_rate / 2.0, 1.1 * std::max(top_speed_hz, 1.0));
}

plot::Heatmap spectrogram_heatmap(const signal::Spectrogram& sg, const std::vector<double>& x, double frequency_max,
                                  double amplitude_factor, double x_factor) {
  plot::Heatmap hm;
  std::size_t nb = 0;
  while (nb < sg.n_bins() && sg.frequencies[nb] <= frequency_max) ++nb;
  hm.y.assign(sg.frequencies.begin(), sg.frequencies.begin() + static_cast<std::ptrdiff_t>(nb));
  std::vector<std::size_t> keep;
  for (std::size_t s = 0; s < x.size(); ++s)
    if (keep.empty() || x[s] > x[keep.back()] + 1e-9) keep.push_back(s);
  for (std::size_t s : keep) hm.x.push_back(x[s] * x_factor);
  hm.z.resize(nb * keep.size());
  for (std::size_t j = 0; j < nb; ++j)
    for (std::size_t i = 0; i < keep.size(); ++i) hm.z[j * keep.size() + i] = sg.at(keep[i], j) * amplitude_factor;
  return hm;
}

HeatmapPeak heatmap_peak(const plot::Heatmap& map) {
  HeatmapPeak p;
  const std::size_t nx = map.x.size();
  for (std::size_t k = 0; k < map.z.size(); ++k)
    if (map.z[k] > p.value) p = {map.z[k], k / nx, k % nx};
  return p;
}

namespace {

// run_spectrogram's picture from the channel's STFT `sg` (taken with stft_options(out)); the run has a speed channel.
plot::Heatmap spectrogram_picture(const OutputSpec& out, const RunupResult& r, std::size_t channel,
                                  const signal::Spectrogram& sg, bool against_time) {
  const std::vector<double>& speed_hz = r.columns[static_cast<std::size_t>(column_of(r, ProbeChannel::Kind::Speed))];
  const double top = *std::max_element(speed_hz.begin(), speed_hz.end());
  const Display disp = display_of(r.channels[channel].unit);
  plot::Heatmap hm = spectrogram_heatmap(
      sg, against_time ? sg.times : signal::values_at_segment_centres(sg, speed_hz, out.sample_rate),
      spectrogram_frequency_max(out, top), disp.factor);
  hm.zlabel = "amplitude [" + disp.unit + "]";
  hm.ylabel = "frequency f [Hz]";
  hm.xlabel = against_time ? "time [s]" : "rotor speed f_d [Hz]";
  hm.logz = true;
  if (!against_time && !hm.x.empty()) {
    const double x0 = hm.x.front(), x1 = hm.x.back();
    hm.overlays.push_back({"1x", {x0, x1}, {x0, x1}, plot::Series::Style::Lines, plot::style::kOrder1xOnDark, 1.0});
    hm.overlays.push_back(
        {"0.5x", {x0, x1}, {0.5 * x0, 0.5 * x1}, plot::Series::Style::Dashed, plot::style::kOrderHalfOnDark, 1.0});
  }
  return hm;
}

nlohmann::json spectral_line_json(const signal::SpectralLine& l) {
  return {{"amplitude", l.amplitude},
          {"frequency_hz", l.frequency_hz},
          {"order", l.frequency_hz / l.speed_hz},
          {"speed_hz", l.speed_hz},
          {"time_s", l.time_s}};
}

// A probe's limit as a dashed black line at y across the chart's first series (a pressure or a film thickness
// against speed).
void add_limit_line(plot::LineChart& chart, double y, std::string label) {
  plot::Series limit;
  limit.label = std::move(label);
  limit.style = plot::Series::Style::Dashed;
  limit.color = "black";
  limit.x = {chart.series.front().x.front(), chart.series.front().x.back()};
  limit.y = {y, y};
  chart.series.push_back(std::move(limit));
}

// Whether a run's channel gets a spectrogram: not the speed and angle, not powers and losses (W), which are read
// as time series, not as vibration (they stay in the file), and not a probe with a limit or a film's thinnest point,
// read as their level (against the limit: the contact-pressure and film-thickness pictures).
bool gets_spectrogram(const ProbeChannel& ch) {
  return ch.kind != ProbeChannel::Kind::Speed && ch.kind != ProbeChannel::Kind::Angle && ch.unit != "W" &&
         !std::isfinite(ch.limit) && !ch.name.ends_with(kMinFilmProbeSuffix);
}

// What every spectrogram of a run shares: the rotor speed, whether it never falls (the spectrograms are then drawn
// against it, else against time), the frequency range, the STFT and the leakage margin of the sub-synchronous lines.
struct RunSpectrograms {
  const std::vector<double>& speed_hz;
  bool ascending = true;
  double top_speed = 0.0;  // Hz
  double fmax = 0.0;
  signal::StftOptions stft;
  std::size_t margin = 0;

  RunSpectrograms(const OutputSpec& out, const RunupResult& r)
      : speed_hz(r.columns[static_cast<std::size_t>(column_of(r, ProbeChannel::Kind::Speed))]),
        stft(stft_options(out)) {
    for (std::size_t i = 1; i < speed_hz.size(); ++i) ascending = ascending && speed_hz[i] >= speed_hz[i - 1];
    top_speed = *std::max_element(speed_hz.begin(), speed_hz.end());
    fmax = spectrogram_frequency_max(out, top_speed);
    margin = signal::leakage_margin_bins(stft.window, stft.segment_length, kSubsynchronousLeakage);
  }
};

// The spectrogram `hm` (with its largest cell `peak`) of channel `ch`, from the STFT `sg`: its largest amplitude
// (SI) and where it lies, and its largest sub-synchronous line over the run and in its last segment, into
// spectral[ch.name]; nothing when no cell is positive.
void add_spectral_maxima(const RunSpectrograms& run, double sample_rate, const ProbeChannel& ch,
                         const signal::Spectrogram& sg, const plot::Heatmap& hm, const HeatmapPeak& peak,
                         nlohmann::json& spectral) {
  if (!(peak.value > 0.0)) return;
  spectral[ch.name] = {{"amplitude", peak.value / display_of(ch.unit).factor},
                       {"unit", ch.unit},
                       {"frequency_hz", hm.y[peak.row]},
                       {run.ascending ? "speed_hz" : "time_s", hm.x[peak.column]}};
  // The largest sub-synchronous line, over the run and in its last segment (what persists at the end).
  if (const auto l = signal::largest_subsynchronous_line(sg, run.speed_hz, sample_rate, run.fmax, run.margin))
    spectral[ch.name]["subsynchronous"] = spectral_line_json(*l);
  if (const auto l = signal::largest_subsynchronous_line(sg, run.speed_hz, sample_rate, run.fmax, run.margin,
                                                         sg.n_segments() - 1))
    spectral[ch.name]["subsynchronous_at_end"] = spectral_line_json(*l);
}

}  // namespace

std::optional<plot::Heatmap> run_spectrogram(const OutputSpec& out, const RunupResult& r, std::size_t channel,
                                             bool against_time) {
  const signal::StftOptions so = stft_options(out);
  if (column_of(r, ProbeChannel::Kind::Speed) < 0 || r.time.size() < so.segment_length) return std::nullopt;
  return spectrogram_picture(out, r, channel, signal::stft(r.columns[channel], out.sample_rate, so), against_time);
}

nlohmann::json spectrogram_maxima(const MachineSpec& spec, const RunupResult& r) {
  nlohmann::json spectral = nlohmann::json::object();
  const OutputSpec& out = spec.output;
  if (column_of(r, ProbeChannel::Kind::Speed) < 0 || r.time.size() < stft_options(out).segment_length)
    return spectral;
  const RunSpectrograms run(out, r);
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    if (!gets_spectrogram(r.channels[c])) continue;
    const signal::Spectrogram sg = signal::stft(r.columns[c], out.sample_rate, run.stft);
    const plot::Heatmap hm = spectrogram_picture(out, r, c, sg, !run.ascending);
    add_spectral_maxima(run, out.sample_rate, r.channels[c], sg, hm, heatmap_peak(hm), spectral);
  }
  return spectral;
}

std::optional<plot::LineChart> against_speed_chart(const RunupResult& r, const std::vector<std::string>& suffixes,
                                                   std::size_t block, double offset, Block kind, double scale) {
  const int speed_col = column_of(r, ProbeChannel::Kind::Speed);
  if (speed_col < 0 || block == 0 || r.time.size() < 2 * block) return std::nullopt;
  const std::vector<double>& speed_hz = r.columns[speed_col];
  plot::LineChart chart;
  chart.xlabel = "rotor speed f_d [Hz]";
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const std::string& name = r.channels[c].name;
    const bool match = std::any_of(suffixes.begin(), suffixes.end(), [&](const std::string& s) {
      return name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    });
    if (!match) continue;
    plot::Series s;
    s.label = name;
    for (std::size_t i0 = 0; i0 + block <= r.time.size(); i0 += block) {
      double w = 0.0, v = 0.0;
      if (kind == Block::Min) v = r.columns[c][i0];
      for (std::size_t i = i0; i < i0 + block; ++i) {
        w += speed_hz[i];
        if (kind == Block::Mean) v += r.columns[c][i];
        else if (kind == Block::Peak) v = std::max(v, std::abs(r.columns[c][i]));
        else v = std::min(v, r.columns[c][i]);
      }
      s.x.push_back(w / static_cast<double>(block));
      s.y.push_back(((kind == Block::Mean ? v / static_cast<double>(block) : v) + offset) * scale);
    }
    chart.series.push_back(std::move(s));
  }
  if (chart.series.empty()) return std::nullopt;
  return chart;
}

void draw_run_pictures(const MachineSpec& spec, const RunupResult& r, const std::filesystem::path& dir,
                       std::vector<std::string>& written, std::vector<std::string>& warnings,
                       nlohmann::json& spectral, const std::vector<plot::Series>& campbell,
                       const std::vector<OrderOverlay>& order_overlays) {
  const OutputSpec& out = spec.output;
  const double fs = out.sample_rate;
  const RunSpectrograms run(out, r);
  const std::vector<double>& speed_hz = run.speed_hz;
  const std::vector<double>& angle = r.columns[static_cast<std::size_t>(column_of(r, ProbeChannel::Kind::Angle))];
  const double top_speed = run.top_speed;
  const bool ascending = run.ascending;
  const double fmax = run.fmax;

  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const ProbeChannel& ch = r.channels[c];
    if (!gets_spectrogram(ch)) continue;
    // Spectrogram against rotor speed (paper Figs. 4-6), with the 1x and 0.5x order lines.
    if (r.time.size() < run.stft.segment_length) {
      warnings.push_back("no spectrogram of " + ch.name + ": the run has fewer samples than one STFT segment");
      continue;
    }
    const signal::Spectrogram sg = signal::stft(r.columns[c], fs, run.stft);
    plot::Heatmap hm = spectrogram_picture(out, r, c, sg, !ascending);
    hm.title = "Spectrogram: " + pretty_name(ch);
    const HeatmapPeak peak = heatmap_peak(hm);
    add_spectral_maxima(run, fs, ch, sg, hm, peak, spectral);
    if (hm.x.size() < 2 || peak.value <= 0.0) {
      warnings.push_back("no spectrogram of " + ch.name + ": nothing to show");
      continue;
    }
    hm.zrange = std::make_pair(peak.value * 1e-3, peak.value);
    if (ascending) {
      const double x0 = hm.x.front(), x1 = hm.x.back();
      for (const plot::Series& m : campbell) {
        plot::Series s = m;
        s.x.clear();
        s.y.clear();
        for (std::size_t i = 0; i < m.x.size(); ++i)
          if (m.x[i] >= x0 && m.x[i] <= x1 && m.y[i] <= fmax) s.x.push_back(m.x[i]), s.y.push_back(m.y[i]);
        if (!s.x.empty()) hm.overlays.push_back(s);
      }
    }
    const std::string file = "spectrogram_" + ch.name + ".png";
    plot::render_png(hm, dir / file);
    written.push_back(file);
  }

  // Order tracking of 1x: amplitude against speed, x and y of each probe pair in one picture.
  std::vector<std::string> drawn_overlays;
  signal::OrderTrackOptions oo;
  oo.order = 1.0;
  oo.points = 300;
  oo.min_speed = std::max(1.0, 0.01 * top_speed);
  for (std::size_t c = 0; c + 1 < r.channels.size(); ++c) {
    const ProbeChannel& a = r.channels[c];
    const ProbeChannel& b = r.channels[c + 1];
    const bool pair = a.name.size() == b.name.size() && a.name.substr(0, a.name.size() - 1) ==
                                                            b.name.substr(0, b.name.size() - 1);
    if (!pair || a.kind == ProbeChannel::Kind::Speed || a.kind == ProbeChannel::Kind::Angle) continue;
    const Display disp = display_of(a.unit);
    plot::LineChart chart;
    const std::string stem = pair_stem(a.name);
    chart.title = "1x order tracking: " + stem;
    chart.xlabel = "rotor speed f_d [Hz]";
    chart.ylabel = "1x amplitude [" + disp.unit + "]";
    try {
      for (const ProbeChannel* ch : {&a, &b}) {
        const std::size_t col = ch == &a ? c : c + 1;
        const signal::OrderTrack t = signal::track_order(r.columns[col], angle, speed_hz, fs, oo);
        std::vector<double> amp = t.amplitude;
        for (double& v : amp) v *= disp.factor;
        chart.series.push_back({ch->name, t.speeds, amp, plot::Series::Style::Lines, "", 1.5});
      }
      // Overlays up to 1.5 times the track's largest amplitude, so that the track keeps the picture's scale.
      double track_max = 0.0;
      for (const plot::Series& s : chart.series)
        for (double v : s.y) track_max = std::max(track_max, v);
      for (const OrderOverlay& o : order_overlays) {
        if (o.stem != stem) continue;
        drawn_overlays.push_back(o.stem);
        for (const plot::Series& s : o.series) {
          plot::Series shown = s;
          shown.x.clear();
          shown.y.clear();
          for (std::size_t i = 0; i < s.x.size() && s.y[i] * disp.factor <= 1.5 * track_max; ++i) {
            shown.x.push_back(s.x[i]);
            shown.y.push_back(s.y[i] * disp.factor);
          }
          if (!shown.x.empty()) chart.series.push_back(std::move(shown));
        }
      }
      const std::string file = "order1x_" + stem + ".png";
      plot::render_png(chart, dir / file);
      written.push_back(file);
    } catch (const std::invalid_argument& e) {
      warnings.push_back("no order tracking of " + stem + ": " + e.what());
    }
    ++c;  // skip the partner
  }

  for (const OrderOverlay& o : order_overlays)
    if (std::find(drawn_overlays.begin(), drawn_overlays.end(), o.stem) == drawn_overlays.end())
      warnings.push_back("the overlay for " + o.stem + " was not drawn: the run has no 1x order track of it");

  // Orbits of each disk at chosen speeds: 5 revolutions around the sample where the speed is reached.
  std::vector<double> orbit_hz;
  for (double w : out.orbit_speeds) orbit_hz.push_back(w / (2 * M_PI));
  if (orbit_hz.empty())
    for (int k = 1; k <= 4; ++k) orbit_hz.push_back(top_speed * k / 4.0);
  for (std::size_t c = 0; c + 1 < r.channels.size(); ++c) {
    const ProbeChannel& a = r.channels[c];
    if (a.kind != ProbeChannel::Kind::RotorDof || a.name.back() != 'x') continue;
    const std::string stem = pair_stem(a.name);
    plot::LineChart chart;
    chart.title = "Orbits: " + stem;
    chart.xlabel = "x [µm]";
    chart.ylabel = "y [µm]";
    chart.equal_axes = true;
    chart.legend_position = "outside right top";
    for (double f : orbit_hz) {
      if (f <= 0) continue;
      const std::size_t mid = sample_at_speed(speed_hz, f);
      const std::size_t half = static_cast<std::size_t>(2.5 * fs / f);
      const std::size_t i0 = mid > half ? mid - half : 0, i1 = std::min(r.time.size(), mid + half);
      if (i1 <= i0 + 2) continue;
      plot::Series s;
      std::ostringstream label;
      label << std::llround(speed_hz[mid] * 60) << " rpm";
      s.label = label.str();
      for (std::size_t i = i0; i < i1; ++i) {
        s.x.push_back(r.columns[c][i] * 1e6);
        s.y.push_back(r.columns[c + 1][i] * 1e6);
      }
      chart.series.push_back(s);
    }
    if (chart.series.empty()) continue;
    const std::string file = "orbits_" + stem + ".png";
    plot::render_png(chart, dir / file, plot::Size{900, 800});
    written.push_back(file);
  }

  // Floating rings' operating point against speed, as turbocharger rigs report it: block means over 10 ms.
  if (!ascending) return;
  const std::size_t block = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.01 * fs)));
  struct Slow {
    std::vector<std::string> suffixes;
    double offset;
    const char *title, *ylabel, *file;
  };
  const Slow slow[] = {
      {{".ring_speed_ratio"}, 0.0, "Ring speed ratio against rotor speed (10-ms means)",
       "ring speed / rotor speed [1]", "ring_speed_ratio.png"},
      {{".inner_temperature", ".outer_temperature"}, -273.15, "Film temperatures against rotor speed",
       "film temperature [°C]", "film_temperatures.png"},
      {{".inner_power_loss", ".outer_power_loss"}, 0.0, "Film power losses against rotor speed (10-ms means)",
       "power loss [W]", "film_power_loss.png"}};
  for (const Slow& q : slow) {
    std::optional<plot::LineChart> chart = against_speed_chart(r, q.suffixes, block, q.offset);
    if (!chart) continue;
    chart->title = q.title;
    chart->ylabel = q.ylabel;
    plot::render_png(*chart, dir / q.file);
    written.push_back(q.file);
  }
  // Ball bearings' largest contact pressure, 10-ms peaks, against the limit their probe carries (ISO 76's).
  const std::string pressure = ".max_contact_pressure";
  if (std::optional<plot::LineChart> chart = against_speed_chart(r, {pressure}, block, 0.0, Block::Peak, 1e-6)) {
    chart->title = "Largest ball-race contact pressure against rotor speed (10-ms peaks)";
    chart->ylabel = "Hertz pressure p_0 [MPa]";
    for (const ProbeChannel& ch : r.channels) {
      if (!std::isfinite(ch.limit) || !ch.name.ends_with(pressure)) continue;
      add_limit_line(*chart, ch.limit * 1e-6, "static limit (ISO 76)");
      break;  // one line: every ball bearing has the same limit
    }
    plot::render_png(*chart, dir / "contact_pressure.png");
    written.push_back("contact_pressure.png");
  }
  // Fluid films' thinnest points, 10-ms minima, against each bearing's permissible minimum film thickness if the
  // model file gives one.
  if (std::optional<plot::LineChart> chart =
          against_speed_chart(r, {std::string(kMinFilmProbeSuffix)}, block, 0.0, Block::Min, 1e6)) {
    chart->title = "Thinnest oil film against rotor speed (10-ms minima)";
    chart->ylabel = "minimum film thickness h_min [µm]";
    std::vector<double> drawn;
    for (const ProbeChannel& ch : r.channels) {
      if (!std::isfinite(ch.limit) || !ch.name.ends_with(kMinFilmProbeSuffix) ||
          std::find(drawn.begin(), drawn.end(), ch.limit) != drawn.end())
        continue;
      drawn.push_back(ch.limit);
      std::ostringstream label;
      label << "permissible minimum " << std::fixed << std::setprecision(1) << ch.limit * 1e6
            << " µm (film_thickness_limit)";
      add_limit_line(*chart, ch.limit * 1e6, label.str());
    }
    plot::render_png(*chart, dir / "film_thickness.png");
    written.push_back("film_thickness.png");
  }
}

}  // namespace turbodyn::post

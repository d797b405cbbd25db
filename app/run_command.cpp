#include "app/run_command.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "post/plot.h"
#include "model/io/run_summary.h"
#include "model/engine/integrator.h"
#include "post/signal.h"
#include "model/io/timeseries_file.h"

namespace turbodyn::app {
namespace {

constexpr double kRadPerSToRpm = 60.0 / (2.0 * M_PI);
constexpr int kExitIncomplete = 3;
constexpr int kExitInterrupted = 130;

std::atomic<bool> g_interrupted{false};
extern "C" void on_sigint(int) { g_interrupted.store(true); }

std::string format_duration(double s) {
  std::ostringstream os;
  if (s < 120) os << std::fixed << std::setprecision(1) << s << " s";
  else os << std::fixed << std::setprecision(1) << s / 60.0 << " min";
  return os.str();
}

// Display scaling: displacements in micrometres, everything else as it is.
struct Display {
  double factor = 1.0;
  std::string unit;
};
Display display_of(const ProbeChannel& c) {
  if (c.unit == "m") return {1e6, "µm"};
  return {1.0, c.unit};
}

std::string pretty_name(const ProbeChannel& c) {
  std::string s = c.description.empty() ? c.name : c.description;
  return s;
}

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

// Natural frequencies of a linearised model (campbell.csv of `turbodyn modal`) as point series against rotor speed
// in Hz, one per whirl direction, for the spectrograms.
std::vector<plot::Series> read_campbell_overlay(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ModelError(file.string() + ": cannot be read");
  std::string line;
  std::getline(in, line);
  if (line.rfind("speed_rad_s,speed_rpm,mode,frequency_hz,damping_ratio,whirl", 0) != 0)
    throw ModelError(file.string() + ": not a campbell.csv of turbodyn modal (header '" + line + "')");
  plot::Series fwd{"forward modes (linear model)", {}, {}, plot::Series::Style::Points, "#ff5050", 1.2};
  plot::Series bwd{"backward modes (linear model)", {}, {}, plot::Series::Style::Points, "#40a0ff", 1.2};
  int row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
    double rpm = 0.0, hz = 0.0;
    try {
      if (f.size() != 6) throw std::invalid_argument("fields");
      rpm = std::stod(f[1]);
      hz = std::stod(f[3]);
    } catch (const std::exception&) {
      throw ModelError(file.string() + ":" + std::to_string(row) + ": expected 6 fields with numbers, got '" + line + "'");
    }
    plot::Series* s = f[5] == "forward" ? &fwd : f[5] == "backward" ? &bwd : nullptr;
    if (!s) continue;  // planar, mixed, torsional: no whirl direction to draw
    s->x.push_back(rpm / 60.0);
    s->y.push_back(hz);
  }
  std::vector<plot::Series> out;
  for (plot::Series* s : {&fwd, &bwd})
    if (!s->x.empty()) out.push_back(*s);
  if (out.empty()) throw ModelError(file.string() + ": no forward or backward modes");
  return out;
}

// Draws the pictures of a run. `spectral` receives, for every spectrogram drawn, its largest amplitude and where it
// lies (the colour-scale maximum a reader takes off such a picture, as the paper quotes its maxima); `campbell`
// point series are drawn on the spectrograms against rotor speed.
void draw_pictures(const MachineSpec& spec, const RunupResult& r, const std::filesystem::path& dir,
                   std::vector<std::string>& written, std::vector<std::string>& warnings, nlohmann::json& spectral,
                   const std::vector<plot::Series>& campbell = {}) {
  const OutputSpec& out = spec.output;
  const double fs = out.sample_rate;
  int speed_col = -1, angle_col = -1;
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    if (r.channels[c].kind == ProbeChannel::Kind::Speed) speed_col = static_cast<int>(c);
    if (r.channels[c].kind == ProbeChannel::Kind::Angle) angle_col = static_cast<int>(c);
  }
  const std::vector<double>& speed_hz = r.columns[speed_col];
  const std::vector<double>& angle = r.columns[angle_col];
  const double top_speed = *std::max_element(speed_hz.begin(), speed_hz.end());
  bool ascending = true;
  for (std::size_t i = 1; i < speed_hz.size(); ++i) ascending = ascending && speed_hz[i] >= speed_hz[i - 1];

  signal::StftOptions so;
  so.segment_length = static_cast<std::size_t>(out.spectrogram_segment);
  so.overlap = out.spectrogram_overlap;
  so.window = signal::window_from_string(to_string(out.spectrogram_window));
  const double fmax = out.frequency_max > 0 ? out.frequency_max : std::min(fs / 2.0, 1.1 * std::max(top_speed, 1.0));

  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const ProbeChannel& ch = r.channels[c];
    if (ch.kind == ProbeChannel::Kind::Speed || ch.kind == ProbeChannel::Kind::Angle) continue;
    const Display disp = display_of(ch);
    // Spectrogram against rotor speed (paper Figs. 4-6), with the 1x and 0.5x order lines.
    if (r.time.size() < so.segment_length) {
      warnings.push_back("no spectrogram of " + ch.name + ": the run has fewer samples than one STFT segment");
    } else {
      signal::Spectrogram sg = signal::stft(r.columns[c], fs, so);
      plot::Heatmap hm;
      hm.title = "Spectrogram: " + pretty_name(ch);
      hm.zlabel = "amplitude [" + disp.unit + "]";
      hm.ylabel = "frequency f [Hz]";
      std::size_t nb = 0;
      while (nb < sg.n_bins() && sg.frequencies[nb] <= fmax) ++nb;
      hm.y.assign(sg.frequencies.begin(), sg.frequencies.begin() + nb);
      if (ascending) {
        hm.x = signal::values_at_segment_centres(sg, speed_hz, fs);
        hm.xlabel = "rotor speed f_d [Hz]";
      } else {
        hm.x = sg.times;
        hm.xlabel = "time [s]";
      }
      // Speeds repeat while the rotor stands still: keep x strictly ascending by dropping repeats.
      std::vector<std::size_t> keep;
      for (std::size_t s = 0; s < hm.x.size(); ++s)
        if (keep.empty() || hm.x[s] > hm.x[keep.back()] + 1e-9) keep.push_back(s);
      std::vector<double> xs;
      for (std::size_t s : keep) xs.push_back(hm.x[s]);
      hm.x = xs;
      hm.z.resize(nb * keep.size());
      double zmax = 0.0;
      std::size_t jmax = 0, imax = 0;
      for (std::size_t j = 0; j < nb; ++j)
        for (std::size_t i = 0; i < keep.size(); ++i) {
          const double a = sg.at(keep[i], j) * disp.factor;
          hm.z[j * keep.size() + i] = a;
          if (a > zmax) zmax = a, jmax = j, imax = i;
        }
      if (zmax > 0.0)
        spectral[ch.name] = {{"amplitude", zmax / disp.factor}, {"unit", ch.unit}, {"frequency_hz", hm.y[jmax]},
                             {ascending ? "speed_hz" : "time_s", hm.x[imax]}};
      if (keep.size() < 2 || zmax <= 0.0) {
        warnings.push_back("no spectrogram of " + ch.name + ": nothing to show");
      } else {
        hm.logz = true;
        hm.zrange = std::make_pair(zmax * 1e-3, zmax);
        if (ascending) {
          const double x0 = hm.x.front(), x1 = hm.x.back();
          hm.overlays.push_back({"1x", {x0, x1}, {x0, x1}, plot::Series::Style::Dashed, "white", 1.0});
          hm.overlays.push_back({"0.5x", {x0, x1}, {0.5 * x0, 0.5 * x1}, plot::Series::Style::Dashed, "#bbbbbb", 1.0});
          for (const plot::Series& c : campbell) {
            plot::Series s = c;
            s.x.clear();
            s.y.clear();
            for (std::size_t i = 0; i < c.x.size(); ++i)
              if (c.x[i] >= x0 && c.x[i] <= x1 && c.y[i] <= fmax) s.x.push_back(c.x[i]), s.y.push_back(c.y[i]);
            if (!s.x.empty()) hm.overlays.push_back(s);
          }
        }
        const std::string file = "spectrogram_" + ch.name + ".png";
        plot::render_png(hm, dir / file);
        written.push_back(file);
      }
    }
  }

  // Order tracking of 1x: amplitude against speed, x and y of each probe pair in one picture.
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
    const Display disp = display_of(a);
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
      const std::string file = "order1x_" + stem + ".png";
      plot::render_png(chart, dir / file);
      written.push_back(file);
    } catch (const std::invalid_argument& e) {
      warnings.push_back("no order tracking of " + stem + ": " + e.what());
    }
    ++c;  // skip the partner
  }

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
}

}  // namespace

int run_plot_command(const PlotCommandOptions& options) {
  // The overlay file first: a bad one is reported before the model and the time series are read.
  const std::vector<plot::Series> campbell =
      options.campbell_csv.empty() ? std::vector<plot::Series>{} : read_campbell_overlay(options.campbell_csv);
  const std::filesystem::path summary_file = options.run_dir / "summary.json";
  std::ifstream in(summary_file);
  if (!in) throw ModelError(summary_file.string() + ": cannot be read (not the output directory of turbodyn run?)");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw ModelError(summary_file.string() + ": not a summary.json: " + e.what());
  }
  if (!j.contains("model") || !j["model"].contains("source") || !j.contains("overrides"))
    throw ModelError(summary_file.string() + ": no model.source or overrides (not written by turbodyn run)");
  std::vector<Override> overrides;
  for (const auto& o : j["overrides"]) overrides.push_back(parse_override(o.get<std::string>()));
  overrides.insert(overrides.end(), options.overrides.begin(), options.overrides.end());
  const MachineSpec spec = load_model(j["model"]["source"].get<std::string>(), overrides);
  const std::unique_ptr<RunupModel> model = make_runup_model(spec);
  const TimeSeriesData data = read_hdf5_timeseries(options.run_dir / "timeseries.h5");

  // The run's channels in the model's order, matched by name with the file's.
  RunupResult r;
  r.time = data.time;
  r.complete = data.complete;
  for (const ProbeChannel& c : model->channels()) {
    std::size_t k = 0;
    while (k < data.channels.size() && data.channels[k].name != c.name) ++k;
    if (k == data.channels.size())
      throw ModelError((options.run_dir / "timeseries.h5").string() + ": no channel '" + c.name + "' of the model " +
                       j["model"]["source"].get<std::string>() + " (the run was made with another model)");
    r.channels.push_back(c);
    r.columns.push_back(data.columns[k]);
  }
  std::vector<std::string> pictures, warnings;
  nlohmann::json spectral = nlohmann::json::object();
  if (r.time.size() > 1) draw_pictures(spec, r, options.run_dir, pictures, warnings, spectral, campbell);
  j["pictures"] = pictures;
  j["spectrogram_maxima"] = spectral;
  j["warnings"] = warnings;
  nlohmann::json plot_overrides = nlohmann::json::array();
  for (const Override& o : options.overrides) plot_overrides.push_back(o.path + "=" + o.value);
  j["plot_overrides"] = plot_overrides;  // the pictures were drawn with these on top of `overrides`
  {
    std::ofstream out(summary_file);
    out << std::setw(1) << j << "\n";
  }
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  std::cout << "Redrew " << pictures.size() << " pictures of " << options.run_dir.string()
            << (r.complete ? "" : " (the run is incomplete)") << "\n";
  return 0;
}

int run_run_command(const RunCommandOptions& options) {
  MachineSpec spec = load_model(options.model_file, options.overrides);
  if (!(spec.speed.duration > 0.0))
    throw ModelError(options.model_file.string() + ": [speed]: the run-up needs a speed profile ([speed] with "
                                                   "end and duration)");
  const std::unique_ptr<RunupModel> model = make_runup_model(spec);
  std::filesystem::create_directories(options.output_dir);

  RunupOptions ro = runup_options(spec);
  ro.cancel = &g_interrupted;

  std::vector<Channel> channels;
  for (const ProbeChannel& c : model->channels()) channels.push_back({c.name, c.unit, c.description});
  Hdf5TimeSeriesWriter writer(options.output_dir / "timeseries.h5", channels);
  writer.set_attribute("model", spec.name);
  writer.set_attribute("model_file", spec.source.string());
  ro.sink = [&](double t, const double* v) { writer.append(t, v); };
  const bool tty = isatty(STDERR_FILENO);
  const double t_end = model->speed().duration();
  ro.progress = [&](double t, double speed, double wall) {
    const double frac = t / t_end;
    const double eta = frac > 0 ? wall * (1 - frac) / frac : 0.0;
    std::ostringstream os;
    os << "t = " << std::fixed << std::setprecision(3) << t << " s (" << std::setprecision(0) << 100 * frac
       << " %), " << std::llround(speed * kRadPerSToRpm) << " rpm, wall " << format_duration(wall) << ", left ~"
       << format_duration(eta);
    if (tty) std::cerr << "\r" << os.str() << "   " << std::flush;
    else std::cerr << os.str() << "\n";
  };

  g_interrupted.store(false);
  auto previous = std::signal(SIGINT, on_sigint);
  const RunupResult r = simulate_runup(*model, ro);
  std::signal(SIGINT, previous);
  if (tty) std::cerr << "\n";
  writer.finish(r.complete);

  if (spec.output.csv) {
    std::vector<Channel> ch;
    for (const ProbeChannel& c : r.channels) ch.push_back({c.name, c.unit, c.description});
    write_csv(options.output_dir / "timeseries.csv", ch, r.time, r.columns);
  }

  // summary.json (docs/output-format.md).
  nlohmann::json j = run_summary(spec, *model, ro, r, options.overrides);
  const nlohmann::json& probes = j["probes"];

  std::vector<std::string> pictures, warnings;
  nlohmann::json spectral = nlohmann::json::object();
  if (options.plots && r.time.size() > 1) {
    try {
      draw_pictures(spec, r, options.output_dir, pictures, warnings, spectral);
    } catch (const std::exception& e) {
      warnings.push_back(std::string("pictures: ") + e.what());
    }
  }
  j["pictures"] = pictures;
  j["spectrogram_maxima"] = spectral;
  j["warnings"] = warnings;
  {
    std::ofstream out(options.output_dir / "summary.json");
    out << std::setw(1) << j << "\n";
  }

  std::cout << spec.name << ": " << (r.complete ? "complete" : "INCOMPLETE") << ", " << r.stats.steps << " steps, "
            << r.stats.rhs_calls << " rhs calls, wall " << format_duration(r.stats.wall_time) << "\n";
  for (auto& [name, p] : probes.items()) {
    const Display d = display_of(ProbeChannel{name, p["unit"], "", ProbeChannel::Kind::RotorDof, 0, 0});
    std::cout << "  max |" << name << "| = " << std::setprecision(4) << p["max_abs"].get<double>() * d.factor << " "
              << d.unit << " at " << std::setprecision(0) << std::fixed << p["speed_at_max_rpm"].get<double>()
              << " rpm\n"
              << std::defaultfloat;
  }
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  std::cout << "Wrote " << (options.output_dir / "timeseries.h5").string() << ", summary.json"
            << (spec.output.csv ? ", timeseries.csv" : "") << ", " << pictures.size() << " pictures\n";
  if (!r.complete) {
    std::cerr << "error: " << options.model_file.string() << ": run-up " << r.message
              << "; the results up to that point are written and marked incomplete\n";
    return g_interrupted.load() ? kExitInterrupted : kExitIncomplete;
  }
  return 0;
}

}  // namespace turbodyn::app

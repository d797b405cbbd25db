#include "app/run_command.h"
#include "app/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <algorithm>
#include <cmath>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "post/plot.h"
#include "post/plot_style.h"
#include "post/report.h"
#include "app/command_line.h"
#include "model/io/run_summary.h"
#include "model/io/output_file.h"
#include "model/engine/integrator.h"
#include "model/engine/remaining_time.h"
#include "post/run_pictures.h"
#include "model/io/timeseries_file.h"
#include "model/spec/constants.h"

namespace turbodyn::app {
namespace {

// Natural frequencies of a linearised model (campbell.csv of `turbodyn modal`) as point series against rotor speed
// in Hz, one per whirl direction, for the spectrograms.
std::vector<plot::Series> read_campbell_overlay(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ModelError(file.string() + ": cannot be read");
  std::string line;
  std::getline(in, line);
  if (line.rfind("speed_rad_s,speed_rpm,mode,frequency_hz,damping_ratio,whirl", 0) != 0)
    throw ModelError(file.string() + ": not a campbell.csv of turbodyn modal (header '" + line + "')");
  plot::Series fwd{"forward modes (linear model)", {}, {}, plot::Series::Style::Points, plot::style::kForwardOnDark, 1.2};
  plot::Series bwd{"backward modes (linear model)", {}, {}, plot::Series::Style::Points, plot::style::kBackwardOnDark,
                   1.2};
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

// A JSON result file of `kind` ("summary.json"); `hint` follows "cannot be read" (e.g. what the directory should be).
nlohmann::json read_json(const std::filesystem::path& file, const std::string& kind, const std::string& hint) {
  std::ifstream in(file);
  if (!in) throw ModelError(file.string() + ": cannot be read" + hint);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw ModelError(file.string() + ": not a " + kind + ": " + e.what());
  }
  return j;
}

// The overlay of the 1x order track `stem` in `out`, added if there is none yet.
post::OrderOverlay& overlay_of(std::vector<post::OrderOverlay>& out, const std::string& stem) {
  auto it = std::find_if(out.begin(), out.end(), [&](const post::OrderOverlay& o) { return o.stem == stem; });
  if (it == out.end()) it = out.insert(out.end(), post::OrderOverlay{stem, {}});
  return *it;
}

// The critical speeds at an amplitude of `turbodyn modal --amplitudes` (its modal.json) as lines of amplitude against
// rotor speed in Hz, one overlay per disk the branches were measured at, for that disk's 1x order track.
std::vector<post::OrderOverlay> read_backbone_overlays(const std::filesystem::path& file) {
  const nlohmann::json j = read_json(file, "modal.json", "");
  if (!j.contains("backbones") || !j["backbones"].contains("branches"))
    throw ModelError(file.string() + ": not a modal.json of turbodyn modal --amplitudes (no \"backbones\")");
  std::vector<post::OrderOverlay> out;
  const char* colors[] = {"#9467bd", "#8c564b", "#e377c2", "#17becf"};
  try {
    for (const auto& b : j["backbones"]["branches"]) {
      const std::string at = b.at("amplitude_at").get<std::string>();
      if (at.rfind("disks.", 0) != 0)
        throw ModelError(file.string() + ": its amplitudes were measured at " + at +
                         "; a run has order tracks of the disks' displacements only (turbodyn modal --amplitude-at "
                         "disks.NAME)");
      const int branch = b.at("branch").get<int>();
      plot::Series s{"critical speed at the amplitude, branch " + std::to_string(branch + 1) + " (turbodyn modal)",
                     {}, {}, plot::Series::Style::LinesPoints, colors[branch % 4], 1.2};
      for (const auto& p : b.at("points")) {
        s.x.push_back(p.at("speed_rad_s").get<double>() / (2 * M_PI));
        s.y.push_back(p.at("amplitude_m").get<double>());
      }
      if (s.x.empty()) continue;
      overlay_of(out, "disk." + at.substr(6)).series.push_back(std::move(s));
    }
  } catch (const nlohmann::json::exception& e) {
    throw ModelError(file.string() + ": backbones: " + e.what());
  }
  if (out.empty()) throw ModelError(file.string() + ": its backbones have no points");
  return out;
}

// The nonlinear steady states of `turbodyn response --nonlinear` as overlays of the disks' 1x order tracks: one line
// per piece of the curve and disk.
std::vector<post::OrderOverlay> read_response_overlays(const std::filesystem::path& file) {
  const nlohmann::json j = read_json(file, "response.json", "");
  if (!j.contains("nonlinear") || !j["nonlinear"].contains("pieces"))
    throw ModelError(file.string() + ": not a response.json of turbodyn response --nonlinear (no \"nonlinear\")");
  std::vector<post::OrderOverlay> out;
  constexpr const char* kColor = "#444444";
  const std::string suffix = ".radius_m";
  try {
    const nlohmann::json& pieces = j["nonlinear"]["pieces"];
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const nlohmann::json& cols = pieces[k].at("columns");
      std::vector<double> hz;
      for (const auto& v : cols.at("speed_hz")) hz.push_back(v.get<double>());
      for (const auto& [name, values] : cols.items()) {
        if (name.rfind("disk.", 0) != 0 || name.size() <= suffix.size() ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
          continue;
        const std::string stem = name.substr(0, name.size() - suffix.size());
        plot::Series s{k == 0 ? "steady state (turbodyn response --nonlinear)" : "", hz, {},
                       plot::Series::Style::Lines, kColor, 1.2};
        for (const auto& v : values) s.y.push_back(v.get<double>());
        if (s.y.size() != s.x.size())
          throw ModelError(file.string() + ": nonlinear piece " + std::to_string(k + 1) + ": " + name +
                           " and speed_hz differ in length");
        if (!s.x.empty()) overlay_of(out, stem).series.push_back(std::move(s));
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw ModelError(file.string() + ": nonlinear: " + e.what());
  }
  if (out.empty()) throw ModelError(file.string() + ": its nonlinear response has no points");
  return out;
}

// The result files of a run directory besides the pictures, for the report's links.
std::vector<std::string> run_files(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  for (const char* f : {"summary.json", "timeseries.h5", "timeseries.csv"})
    if (std::filesystem::exists(dir / f)) files.push_back(f);
  return files;
}

}  // namespace

int run_plot_command(const PlotCommandOptions& options) {
  // The overlay file first: a bad one is reported before the model and the time series are read.
  const std::vector<plot::Series> campbell =
      options.campbell_csv.empty() ? std::vector<plot::Series>{} : read_campbell_overlay(options.campbell_csv);
  std::vector<post::OrderOverlay> order_overlays;
  for (const std::filesystem::path& f : options.backbone_json)
    for (post::OrderOverlay& o : read_backbone_overlays(f)) order_overlays.push_back(std::move(o));
  for (const std::filesystem::path& f : options.response_json)
    for (post::OrderOverlay& o : read_response_overlays(f)) order_overlays.push_back(std::move(o));
  const std::filesystem::path summary_file = options.run_dir / "summary.json";
  nlohmann::json j = read_json(summary_file, "summary.json", " (not the output directory of turbodyn run?)");
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
                       j["model"]["source"].get<std::string>() + " (the run was made with another model, or by an "
                       "older turbodyn that did not write this probe yet: run it again)");
    r.channels.push_back(c);
    r.columns.push_back(data.columns[k]);
  }
  std::vector<std::string> pictures, warnings = probe_limit_warnings(j);
  nlohmann::json spectral = nlohmann::json::object();
  if (r.time.size() > 1) post::draw_run_pictures(spec, r, options.run_dir, pictures, warnings, spectral, campbell,
                                                   order_overlays);
  j["pictures"] = pictures;
  j["spectrogram_maxima"] = spectral;
  j["warnings"] = warnings;
  nlohmann::json plot_overrides = nlohmann::json::array();
  for (const Override& o : options.overrides) plot_overrides.push_back(o.path + "=" + o.value);
  j["plot_overrides"] = plot_overrides;  // the pictures were drawn with these on top of `overrides`
  write_output_file(summary_file, j.dump(1) + "\n");
  post::write_run_report(options.run_dir, j, {command_line(), {}, run_files(options.run_dir), {}});
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
  ro.cancel = InterruptGuard::flag();
  ro.threads = options.threads;

  std::vector<Channel> channels;
  for (const ProbeChannel& c : model->channels()) channels.push_back({c.name, c.unit, c.description});
  Hdf5TimeSeriesWriter writer(options.output_dir / "timeseries.h5", channels);
  writer.set_attribute("model", spec.name);
  writer.set_attribute("model_file", spec.source.string());
  // Flushed about once a second of wall time, so that a killed run keeps all but its last second of samples.
  auto last_flush = std::chrono::steady_clock::now();
  ro.sink = [&](double t, const double* v) {
    writer.append(t, v);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_flush > std::chrono::seconds(1)) {
      writer.flush();
      last_flush = now;
    }
  };
  // A summary from the start, marked incomplete: a run killed before its end leaves a directory that `turbodyn
  // plot` redraws (from the flushed samples). The run's own summary replaces it.
  {
    RunupResult pending;
    pending.complete = false;
    pending.message = "running, or killed before its end: this summary is written when the run starts and replaced "
                      "when it ends";
    write_output_file(options.output_dir / "summary.json",
                      run_summary(spec, *model, ro, pending, options.overrides).dump(1) + "\n");
  }
  const bool tty = isatty(STDERR_FILENO);
  const double t_end = model->speed().duration();
  // The time left from the cost so far against the rotor speed and the ramp still to go (remaining_time.h).
  RemainingTimeEstimate remaining(model->speed(), ro.t_start, t_end);
  ro.progress = [&](double t, double speed, double wall) {
    const double frac = t / t_end;
    const double eta = remaining.update(t, wall);
    std::ostringstream os;
    os << "t = " << std::fixed << std::setprecision(3) << t << " s (" << std::setprecision(0) << 100 * frac
       << " %), " << std::llround(speed * kRadPerSToRpm) << " rpm, wall " << format_duration(wall) << ", left ~"
       << format_duration(eta);
    if (tty) std::cerr << "\r" << os.str() << "   " << std::flush;
    else std::cerr << os.str() << "\n";
  };

  const RunupResult r = [&] {
    const InterruptGuard guard;
    return simulate_runup(*model, ro);
  }();
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

  std::vector<std::string> pictures, warnings = probe_limit_warnings(j);
  nlohmann::json spectral = nlohmann::json::object();
  if (options.plots && r.time.size() > 1) {
    try {
      post::draw_run_pictures(spec, r, options.output_dir, pictures, warnings, spectral);
    } catch (const std::exception& e) {
      warnings.push_back(std::string("pictures: ") + e.what());
    }
  } else if (r.time.size() > 1) {
    // Without pictures the spectrograms' maxima and sub-synchronous lines are still measured.
    try {
      spectral = post::spectrogram_maxima(spec, r);
    } catch (const std::exception& e) {
      warnings.push_back(std::string("spectrogram maxima: ") + e.what());
    }
  }
  j["pictures"] = pictures;
  j["spectrogram_maxima"] = spectral;
  j["warnings"] = warnings;
  j["command"] = command_line();
  write_output_file(options.output_dir / "summary.json", j.dump(1) + "\n");
  post::write_run_report(options.output_dir, j, {"", {}, run_files(options.output_dir), {}});

  std::cout << spec.name << ": " << (r.complete ? "complete" : "INCOMPLETE") << ", " << r.stats.steps << " steps, "
            << r.stats.rhs_calls << " rhs calls, wall " << format_duration(r.stats.wall_time) << "\n";
  for (auto& [name, p] : probes.items()) {
    const post::Display d = post::display_of(p["unit"].get<std::string>());
    std::cout << "  max |" << name << "| = " << std::setprecision(4) << p["max_abs"].get<double>() * d.factor << " "
              << d.unit << " at " << std::setprecision(0) << std::fixed << p["speed_at_max_rpm"].get<double>()
              << " rpm\n"
              << std::defaultfloat;
  }
  // What persists below the rotor speed at the end (the rotor's probes; every spectrogram's in summary.json).
  for (const ProbeChannel& c : r.channels) {
    if (c.kind != ProbeChannel::Kind::RotorDof || !spectral.contains(c.name) ||
        !spectral[c.name].contains("subsynchronous_at_end"))
      continue;
    const nlohmann::json& l = spectral[c.name]["subsynchronous_at_end"];
    const post::Display d = post::display_of(c.unit);
    std::cout << "  largest sub-synchronous line at the end, " << c.name << ": " << std::setprecision(4)
              << l["amplitude"].get<double>() * d.factor << " " << d.unit << " at " << l["frequency_hz"].get<double>()
              << " Hz (" << std::setprecision(2) << l["order"].get<double>() << "x)\n"
              << std::defaultfloat;
  }
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  std::cout << "Wrote " << (options.output_dir / "timeseries.h5").string() << ", summary.json, report.html"
            << (spec.output.csv ? ", timeseries.csv" : "") << ", " << pictures.size() << " pictures\n";
  if (!r.complete) {
    std::cerr << "error: " << options.model_file.string() << ": run-up " << r.message
              << "; the results up to that point are written and marked incomplete\n";
    return InterruptGuard::interrupted() ? kExitInterrupted : kExitIncomplete;
  }
  return 0;
}

}  // namespace turbodyn::app

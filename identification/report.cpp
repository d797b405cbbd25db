#include "identification/report.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "post/plot.h"
#include "post/plot_style.h"
#include "post/run_pictures.h"
#include "post/signal.h"
#include "studies/study.h"
#include "studies/table.h"

namespace turbodyn::identification {
namespace {

using studies::json_number;

constexpr double kHzToRpm = 60.0;

// Display scaling of a sensor's quantity.
using post::Display;
Display display_of(Quantity q) {
  switch (q) {
    case Quantity::Displacement: return {1e6, "µm"};
    case Quantity::Acceleration: return {1.0, "m/s²"};
    case Quantity::Force: return {1.0, "N"};
  }
  return {};
}
std::string si_unit(Quantity q) { return q == Quantity::Displacement ? "m" : q == Quantity::Acceleration ? "m/s^2" : "N"; }

template <class Picture>
void try_render(const Picture& c, const std::filesystem::path& png, std::vector<std::string>& files,
                std::vector<std::string>& warnings) {
  try {
    plot::render_png(c, png);
    files.push_back(png.filename().string());
  } catch (const plot::PlotError& e) {
    warnings.push_back(std::string("picture ") + png.filename().string() + " not drawn: " + e.what());
  }
}

void spectrogram_picture(const Record& r, std::size_t sensor, const ProcessingSpec& p, const std::string& title,
                         const Display& disp, double fmax, const std::filesystem::path& png,
                         std::vector<std::string>& files, std::vector<std::string>& warnings) {
  if (r.time.size() < p.segment) {
    warnings.push_back(png.filename().string() + " not drawn: the record is shorter than one STFT segment");
    return;
  }
  const signal::StftOptions so = p.stft();
  const signal::Spectrogram sg = signal::stft(r.channels[sensor], r.sample_rate, so);
  plot::Heatmap hm = post::spectrogram_heatmap(sg, signal::values_at_segment_centres(sg, r.speed_hz, r.sample_rate),
                                               fmax, disp.factor, kHzToRpm);
  if (hm.x.size() < 2 || hm.y.size() < 2) {
    warnings.push_back(png.filename().string() + " not drawn: too few spectra");
    return;
  }
  hm.title = title;
  hm.xlabel = "rotor speed [rpm]";
  hm.ylabel = "frequency [Hz]";
  hm.zlabel = "amplitude [" + disp.unit + "]";
  hm.logz = true;
  plot::Series one;
  one.label = "1x";
  one.x = {hm.x.front(), hm.x.back()};
  one.y = {hm.x.front() / kHzToRpm, hm.x.back() / kHzToRpm};
  one.color = plot::style::kOrder1xOnDark;
  plot::Series half;
  half.label = "0.5x";
  half.x = one.x;
  half.y = {0.5 * one.y[0], 0.5 * one.y[1]};
  half.color = plot::style::kOrderHalfOnDark;
  half.style = plot::Series::Style::Dashed;
  hm.overlays = {one, half};
  try_render(hm, png, files, warnings);
}

}  // namespace

nlohmann::json estimates_json(const IdentifyStudy& study, const IdentifyResult& r) {
  nlohmann::json params = nlohmann::json::array();
  for (std::size_t i = 0; i < study.parameters.size(); ++i) {
    const ParameterSpec& p = study.parameters[i];
    nlohmann::json j{{"name", p.name},
                     {"paths", p.paths},
                     {"unit", p.unit},
                     {"start", p.start},
                     {"lower", p.lower},
                     {"upper", p.upper},
                     {"estimate", r.estimate[i]},
                     {"std_dev", json_number(r.std_dev[i])},
                     {"relative_std_dev", json_number(r.std_dev[i] / std::abs(r.estimate[i]))},
                     {"at_bound", r.estimate[i] <= p.lower || r.estimate[i] >= p.upper}};
    if (std::isfinite(p.truth)) {
      j["true"] = p.truth;
      j["error"] = r.estimate[i] - p.truth;
      j["error_in_std_devs"] = json_number((r.estimate[i] - p.truth) / r.std_dev[i]);
    }
    params.push_back(j);
  }
  auto matrix = [](const Eigen::MatrixXd& m) {
    nlohmann::json a = nlohmann::json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      nlohmann::json row = nlohmann::json::array();
      for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(json_number(m(i, j)));
      a.push_back(row);
    }
    return a;
  };
  double rms = 0.0;
  std::size_t cnt = 0;
  for (double v : r.fitted_residuals)
    if (std::isfinite(v)) {
      rms += v * v;
      ++cnt;
    }
  rms = cnt ? std::sqrt(rms / static_cast<double>(cnt)) : NAN;
  const SolverSpec& s = study.solver;
  return {{"turbodyn_version", turbodyn_version()},
          {"study", study.name},
          {"study_file", study.source.string()},
          {"model", study.model.string()},
          {"model_digest", studies::base_model_digest(study)},
          {"method", study.method == Method::Response ? "response" : "runup"},
          {"measurement", study.measurement.file.string()},
          {"parameters", params},
          {"covariance_ok", r.covariance_ok},
          {"covariance_message", r.covariance_message},
          {"covariance", matrix(r.covariance)},
          {"correlation", matrix(r.correlation)},
          {"residuals", {{"count", r.n_residuals}, {"variance", json_number(r.residual_variance)}, {"rms", json_number(rms)}}},
          {"cost", {{"initial", r.initial_cost}, {"final", r.final_cost}}},
          {"iterations", r.iterations},
          {"converged", r.converged},
          {"cancelled", r.cancelled},
          {"termination", r.termination},
          {"model_runs", r.model_runs},
          {"threads", r.threads},
          {"wall_time_s", r.wall_time},
          {"solver",
           {{"loss", to_string(s.loss)},
            {"loss_scale", s.loss_scale},
            {"max_iterations", s.max_iterations},
            {"step", s.step},
            {"differences", s.central ? "central" : "forward"},
            {"scaling", s.scaling == Scaling::Start ? "start" : "bounds"},
            {"function_tolerance", s.function_tolerance},
            {"parameter_tolerance", s.parameter_tolerance},
            {"gradient_tolerance", s.gradient_tolerance}}},
          {"warnings", r.warnings}};
}

std::vector<std::string> write_identify_results(const IdentifyStudy& study, const IdentifyResult& r,
                                                const std::filesystem::path& dir, bool plots,
                                                std::vector<std::string>& warnings) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> files;
  {
    write_output_file(dir / "estimates.json", estimates_json(study, r).dump(2) + "\n");
    files.push_back("estimates.json");
  }
  {
    write_output_file(dir / "ceres_summary.txt", r.full_report);
    files.push_back("ceres_summary.txt");
  }
  {
    std::vector<Override> o = study.fixed;
    o.insert(o.end(), r.added_fixed.begin(), r.added_fixed.end());
    std::ostringstream header;
    header << "Fitted by `turbodyn identify " << study.source.string() << "` from " << study.model.string() << "\n"
           << "Estimates:\n";
    for (std::size_t i = 0; i < study.parameters.size(); ++i) {
      const ParameterSpec& p = study.parameters[i];
      header << "  " << p.name << " = " << format_value(r.estimate[i], p.unit);
      if (std::isfinite(r.std_dev[i])) header << " +- " << format_value(r.std_dev[i], p.unit);
      header << "\n";
      for (const std::string& path : p.paths) o.push_back({path, format_value(r.estimate[i], p.unit)});
    }
    header << "Sample run:\n  turbodyn run " << (dir / "fitted.toml").string() << " -o out/fitted";
    studies::write_patched_base_model(study, o, header.str(), dir / "fitted.toml");
    files.push_back("fitted.toml");
  }
  {
    studies::CsvWriter out(dir / "features.csv");
    out.texts({"feature", "kind", "sensor", "quantity", "speed_rpm", "measured", "initial", "fitted", "unit"}).end_row();
    for (std::size_t f = 0; f < study.features.size(); ++f) {
      const FeatureSpec& fs = study.features[f];
      const SensorSpec& sensor = study.measurement.sensors[fs.sensor];
      const FeatureTrack& m = r.measured_features[f];
      const FeatureTrack* i0 = r.initial_features.empty() ? nullptr : &r.initial_features[f];
      const FeatureTrack& fi = r.fitted_features[f];
      auto row = [&](const std::string& q, double speed_hz, double a, double b, double c, const std::string& unit) {
        out.text(fs.name).text(to_string(fs.kind)).text(sensor.name).text(q).number(speed_hz * kHzToRpm);
        out.number(a).number(b).number(c).text(unit).end_row();
      };
      const double nan = NAN;
      if (fs.kind == FeatureKind::Resonance) {
        row("resonance_speed_rpm", nan, m.resonance_hz * kHzToRpm, i0 ? i0->resonance_hz * kHzToRpm : nan,
            fi.resonance_hz * kHzToRpm, "rpm");
        row("resonance_amplitude", nan, m.resonance_amplitude, i0 ? i0->resonance_amplitude : nan,
            fi.resonance_amplitude, si_unit(sensor.quantity));
        continue;
      }
      for (std::size_t k = 0; k < m.speed_hz.size(); ++k) {
        row("amplitude", m.speed_hz[k], m.amplitude[k], i0 ? i0->amplitude[k] : nan, fi.amplitude[k], si_unit(sensor.quantity));
        if (fs.kind == FeatureKind::Order1x && fs.phase)
          row("phase", m.speed_hz[k], m.phase[k], i0 ? i0->phase[k] : nan, fi.phase[k], "rad");
        if (fs.kind == FeatureKind::Subsync)
          row("frequency", m.speed_hz[k], m.frequency[k], i0 ? i0->frequency[k] : nan, fi.frequency[k], "Hz");
      }
    }
    files.push_back("features.csv");
  }
  if (!plots) return files;

  for (std::size_t f = 0; f < study.features.size(); ++f) {
    const FeatureSpec& fs = study.features[f];
    const SensorSpec& sensor = study.measurement.sensors[fs.sensor];
    const Display disp = display_of(sensor.quantity);
    const FeatureTrack& m = r.measured_features[f];
    const FeatureTrack* i0 = r.initial_features.empty() ? nullptr : &r.initial_features[f];
    const FeatureTrack& fi = r.fitted_features[f];
    auto series = [&](const std::string& label, const std::vector<double>& x, const std::vector<double>& y,
                      double factor, plot::Series::Style style, const std::string& color) {
      plot::Series s;
      s.label = label;
      s.style = style;
      s.color = color;
      for (std::size_t k = 0; k < x.size(); ++k) {
        s.x.push_back(x[k] * kHzToRpm);
        s.y.push_back(y[k] * factor);
      }
      return s;
    };
    auto chart = [&](const std::string& what, const std::vector<double> FeatureTrack::*member, double factor,
                     const std::string& unit, const std::string& file) {
      plot::LineChart c;
      c.title = fs.name + ": " + what + " (" + sensor.name + ", " + sensor.probe + ")";
      c.xlabel = "rotor speed [rpm]";
      c.ylabel = what + " [" + unit + "]";
      c.series.push_back(series("measured", m.speed_hz, m.*member, factor, plot::Series::Style::Points, plot::style::kMeasured));
      if (i0) c.series.push_back(series("initial model", i0->speed_hz, i0->*member, factor, plot::Series::Style::Dashed, plot::style::kInitial));
      c.series.push_back(series("fitted model", fi.speed_hz, fi.*member, factor, plot::Series::Style::Lines, plot::style::kFitted));
      try_render(c, dir / file, files, warnings);
    };
    const std::string stem = "feature_" + post::file_safe(fs.name);
    if (fs.kind == FeatureKind::Order1x) {
      chart("1x amplitude", &FeatureTrack::amplitude, disp.factor, disp.unit, stem + "_amplitude.png");
      if (fs.phase) chart("1x phase", &FeatureTrack::phase, 180.0 / M_PI, "deg", stem + "_phase.png");
    } else if (fs.kind == FeatureKind::Subsync) {
      chart("sub-synchronous amplitude", &FeatureTrack::amplitude, disp.factor, disp.unit, stem + "_amplitude.png");
      chart("sub-synchronous frequency", &FeatureTrack::frequency, 1.0, "Hz", stem + "_frequency.png");
    } else {
      plot::LineChart c;
      c.title = fs.name + ": 1x resonance (" + sensor.name + ")";
      c.xlabel = "rotor speed [rpm]";
      c.ylabel = "1x amplitude [" + disp.unit + "]";
      c.series.push_back(series("measured", m.curve_speed_hz, m.curve_amplitude, disp.factor, plot::Series::Style::Points, plot::style::kMeasured));
      if (i0) c.series.push_back(series("initial model", i0->curve_speed_hz, i0->curve_amplitude, disp.factor, plot::Series::Style::Dashed, plot::style::kInitial));
      c.series.push_back(series("fitted model", fi.curve_speed_hz, fi.curve_amplitude, disp.factor, plot::Series::Style::Lines, plot::style::kFitted));
      for (double v : {m.resonance_hz, fi.resonance_hz})
        if (std::isfinite(v)) c.vertical_lines.push_back(v * kHzToRpm);
      try_render(c, dir / (stem + ".png"), files, warnings);
    }
  }
  // Spectrograms of the measured and the fitted signals (time-series measurements, run-up method).
  if (r.measured.format == MeasurementFormat::TimeSeries && !r.fitted_record.time.empty()) {
    double top = 0.0;
    for (double v : r.measured.record.speed_hz) top = std::max(top, v);
    const double fmax = std::min(0.5 * r.measured.record.sample_rate, 1.2 * top);
    for (std::size_t s = 0; s < study.measurement.sensors.size(); ++s) {
      const SensorSpec& sensor = study.measurement.sensors[s];
      const Display disp = display_of(sensor.quantity);
      spectrogram_picture(r.measured.record, s, study.processing, "Measured: " + sensor.name, disp, fmax,
                          dir / ("spectrogram_measured_" + post::file_safe(sensor.name) + ".png"), files, warnings);
      spectrogram_picture(r.fitted_record, s, study.processing, "Fitted model: " + sensor.name + " (" + sensor.probe + ")",
                          disp, fmax, dir / ("spectrogram_fitted_" + post::file_safe(sensor.name) + ".png"), files, warnings);
    }
  }
  return files;
}

}  // namespace turbodyn::identification

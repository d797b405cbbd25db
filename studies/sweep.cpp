#include "studies/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <mutex>
#include <sstream>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "post/plot.h"
#include "model/io/run_summary.h"
#include "model/engine/integrator.h"
#include "model/engine/speed_profile.h"
#include "studies/metrics.h"

namespace turbodyn::studies {
namespace {

constexpr const char* kRunsFile = "runs.jsonl";

// Identifies the study a runs.jsonl belongs to: same parameters, design and metrics.
nlohmann::json fingerprint(const StudySpec& s, const Design& d) {
  nlohmann::json metrics = nlohmann::json::array();
  for (const MetricSpec& m : s.metrics) metrics.push_back(m.name + ":" + m.kind + ":" + m.probe);
  return {{"study", s.name}, {"model", s.model.filename().string()}, {"paths", d.paths},
          {"units", s.parameter_units}, {"runs", d.values.size()}, {"values", d.values}, {"metrics", metrics}};
}

nlohmann::json to_json(const RunRecord& r) {
  auto numbers = [](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : v) a.push_back(std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr));
    return a;
  };
  return {{"index", r.index}, {"parameters", numbers(r.parameters)}, {"metrics", numbers(r.metrics)},
          {"status", r.status}, {"error", r.error}, {"wall_time_s", r.wall_time}};
}

RunRecord from_json(const nlohmann::json& j) {
  RunRecord r;
  r.index = j.at("index").get<std::size_t>();
  for (const auto& v : j.at("parameters")) r.parameters.push_back(v.is_null() ? NAN : v.get<double>());
  for (const auto& v : j.at("metrics")) r.metrics.push_back(v.is_null() ? NAN : v.get<double>());
  r.status = j.at("status").get<std::string>();
  r.error = j.value("error", "");
  r.wall_time = j.value("wall_time_s", 0.0);
  return r;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}

std::string file_safe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return s;
}

}  // namespace

RunRecord evaluate_run(const StudySpec& study, const std::vector<Override>& overrides,
                       const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  RunRecord rec;
  rec.metrics.assign(study.metrics.size(), NAN);
  try {
    const MachineSpec spec = load_model(study.model, overrides);
    const auto model = make_runup_model(spec);
    RunupOptions ro = runup_options(spec);
    ro.cancel = cancel;
    if (study.speed_window_min > 0.0) ro.t_start = time_at_speed(spec.speed, study.speed_window_min);
    if (study.speed_window_max > 0.0) ro.t_end = time_at_speed(spec.speed, study.speed_window_max);
    const RunupResult r = simulate_runup(*model, ro);
    const nlohmann::json summary = run_summary(spec, *model, ro, r, overrides);
    for (std::size_t m = 0; m < study.metrics.size(); ++m)
      rec.metrics[m] = evaluate_metric(study.metrics[m], r, summary, ro.sample_rate);
    rec.status = r.complete ? "ok" : (cancel && cancel->load()) ? "cancelled" : "incomplete";
    rec.error = r.message;
  } catch (const std::exception& e) {
    rec.status = "failed";
    rec.error = e.what();
  }
  rec.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rec;
}

namespace {

// One run of the design: the run's overrides, evaluate_run.
RunRecord execute(const StudySpec& study, const Design& design, std::size_t i, const std::atomic<bool>* cancel) {
  RunRecord rec = evaluate_run(study, run_overrides(study, design, i), cancel);
  rec.index = i;
  rec.parameters = design.values[i];
  return rec;
}

}  // namespace

double time_at_speed(const SpeedProfile& profile, double speed) {
  const SpeedFunction f(profile);
  const double T = f.duration();
  if (f.speed(0.0) >= speed) return 0.0;
  double lo = 0.0, hi = T;
  if (f.speed(hi) < speed) return T;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * std::max(1.0, T); ++it) {
    const double mid = 0.5 * (lo + hi);
    (f.speed(mid) >= speed ? hi : lo) = mid;
  }
  return hi;
}

std::vector<RunRecord> read_runs(const StudySpec& study, const std::filesystem::path& dir) {
  const Design design = make_design(study.design);
  std::vector<RunRecord> runs;
  std::ifstream in(dir / kRunsFile);
  if (!in) return runs;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      continue;  // a line cut short by a kill: that run is redone
    }
    if (header) {
      if (j != fingerprint(study, design))
        throw ModelError((dir / kRunsFile).string() + ": holds the runs of a different study (parameters, design or "
                                                     "metrics differ); choose another output directory");
      header = false;
      continue;
    }
    try {
      runs.push_back(from_json(j));
    } catch (const nlohmann::json::exception&) {
      continue;
    }
  }
  return runs;
}

SweepResult run_sweep(const StudySpec& study, const SweepOptions& options) {
  SweepResult result;
  result.design = make_design(study.design);
  const Design& design = result.design;
  const std::size_t total = design.values.size();
  if (options.shard_n == 0 || options.shard_k >= options.shard_n)
    throw ModelError("--shard K/N: K must lie in 0 .. N-1");
  const std::vector<std::size_t> shard = shard_indices(total, options.shard_k, options.shard_n);

  // Check the study against the model once, before any run: overrides apply, probes exist.
  {
    const MachineSpec spec = load_model(study.model, run_overrides(study, design, shard.empty() ? 0 : shard[0]));
    check_metrics(study, make_runup_model(spec)->channels());
  }

  std::filesystem::create_directories(options.output_dir);
  std::vector<RunRecord> previous = read_runs(study, options.output_dir);
  std::map<std::size_t, RunRecord> finished;
  for (RunRecord& r : previous) finished[r.index] = std::move(r);
  const bool fresh = !std::filesystem::exists(options.output_dir / kRunsFile) ||
                     std::filesystem::file_size(options.output_dir / kRunsFile) == 0;
  std::ofstream log(options.output_dir / kRunsFile, std::ios::app);
  if (!log) throw ModelError((options.output_dir / kRunsFile).string() + ": cannot write");
  if (fresh) log << fingerprint(study, design).dump() << "\n" << std::flush;

  std::vector<std::size_t> pending;
  for (std::size_t i : shard)
    if (finished.count(i)) ++result.resumed;
    else pending.push_back(i);

  const int threads = options.threads > 0 ? options.threads : study.threads;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(threads));
  std::mutex mutex;
  SweepProgress progress;
  progress.total = shard.size();
  progress.resumed = result.resumed;
  progress.done = result.resumed;
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t done_here = 0;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pending.size(), 1), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      if (options.cancel && options.cancel->load()) return;
      RunRecord rec = execute(study, design, pending[k], options.cancel);
      if (rec.status == "cancelled") return;  // not recorded: a resumed study runs it again
      const std::lock_guard<std::mutex> lock(mutex);
      log << to_json(rec).dump() << "\n" << std::flush;  // recorded before anything else can fail
      ++progress.done;
      ++done_here;
      if (rec.status == "failed") ++progress.failed;
      progress.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::size_t left = progress.total - progress.done;
      progress.eta = progress.wall_time / static_cast<double>(done_here) * static_cast<double>(left);
      finished[rec.index] = std::move(rec);
      if (options.progress) options.progress(progress);
    }
  });
  for (std::size_t i : shard)
    if (finished.count(i)) result.runs.push_back(finished[i]);
  result.complete = result.runs.size() == shard.size();
  return result;
}

std::vector<std::string> write_results(const StudySpec& study, const Design& design, std::vector<RunRecord> runs,
                                       const std::filesystem::path& dir, bool plots) {
  std::sort(runs.begin(), runs.end(), [](const RunRecord& a, const RunRecord& b) { return a.index < b.index; });
  std::filesystem::create_directories(dir);
  std::vector<std::string> files;
  std::vector<std::string> metric_units;
  {
    // Units of the metrics need the channel list: build the base model once.
    const MachineSpec spec = load_model(study.model, study.base_overrides);
    const auto model = make_runup_model(spec);
    for (const MetricSpec& m : study.metrics) metric_units.push_back(metric_unit(m, model->channels()));
  }
  auto param_label = [&](std::size_t p) {
    return design.paths[p] + (study.parameter_units[p].empty() ? "" : " [" + study.parameter_units[p] + "]");
  };
  auto metric_label = [&](std::size_t m) {
    return study.metrics[m].name + (metric_units[m].empty() ? "" : " [" + metric_units[m] + "]");
  };
  {
    std::ofstream csv(dir / "results.csv");
    csv << "run";
    for (std::size_t p = 0; p < design.paths.size(); ++p) csv << "," << csv_field(param_label(p));
    for (std::size_t m = 0; m < study.metrics.size(); ++m) csv << "," << csv_field(metric_label(m));
    csv << ",status,error,wall_time_s\n";
    for (const RunRecord& r : runs) {
      csv << r.index;
      for (double v : r.parameters) csv << "," << number(v);
      for (double v : r.metrics) csv << "," << number(v);
      csv << "," << r.status << "," << csv_field(r.error) << "," << number(r.wall_time) << "\n";
    }
    files.push_back("results.csv");
  }
  nlohmann::json j;
  j["study"] = study.name;
  j["model"] = study.model.string();
  j["parameters"] = nlohmann::json::array();
  for (std::size_t p = 0; p < design.paths.size(); ++p)
    j["parameters"].push_back({{"path", design.paths[p]}, {"unit", study.parameter_units[p]}});
  j["metrics"] = nlohmann::json::array();
  for (std::size_t m = 0; m < study.metrics.size(); ++m)
    j["metrics"].push_back({{"name", study.metrics[m].name},
                            {"kind", study.metrics[m].kind},
                            {"probe", study.metrics[m].probe},
                            {"unit", metric_units[m]}});
  j["runs"] = nlohmann::json::array();
  std::size_t failed = 0;
  for (const RunRecord& r : runs) {
    j["runs"].push_back(to_json(r));
    if (r.status == "failed") ++failed;
  }
  j["runs_total"] = design.values.size();
  j["runs_recorded"] = runs.size();
  j["runs_failed"] = failed;

  // Sensitivity: standardised regression coefficients where the design gives enough runs.
  nlohmann::json sens = nlohmann::json::object();
  std::vector<std::vector<double>> x;
  for (const RunRecord& r : runs) x.push_back(r.parameters);
  {
    std::ofstream csv(dir / "sensitivity.csv");
    csv << "metric,parameter,src,r_squared\n";
    for (std::size_t m = 0; m < study.metrics.size(); ++m) {
      std::vector<double> y;
      for (const RunRecord& r : runs) y.push_back(r.metrics[m]);
      try {
        const Sensitivity s = standardized_regression(x, y);
        nlohmann::json e = {{"r_squared", s.r_squared}, {"src", s.src}};
        sens[study.metrics[m].name] = e;
        for (std::size_t p = 0; p < s.src.size(); ++p)
          csv << csv_field(study.metrics[m].name) << "," << csv_field(design.paths[p]) << "," << number(s.src[p])
              << "," << number(s.r_squared) << "\n";
        if (plots) {
          plot::LineChart chart;
          chart.title = "Sensitivity of " + study.metrics[m].name + " (standardised regression, R^2 = " +
                        number(std::round(s.r_squared * 1000) / 1000) + ")";
          chart.xlabel = "parameter";
          chart.ylabel = "standardised regression coefficient [-]";
          for (std::size_t p = 0; p < s.src.size(); ++p) {
            chart.series.push_back({design.paths[p], {double(p + 1), double(p + 1)}, {0.0, s.src[p]},
                                    plot::Series::Style::Lines, "", 12.0});
          }
          chart.xrange = std::make_pair(0.0, double(s.src.size() + 1));
          chart.legend_position = "outside right top";
          const std::string f = "sensitivity_" + file_safe(study.metrics[m].name) + ".png";
          plot::render_png(chart, dir / f);
          files.push_back(f);
        }
      } catch (const std::invalid_argument&) {
        // too few runs for a regression: no entry
      }
    }
    files.push_back("sensitivity.csv");
  }
  j["sensitivity"] = sens;
  {
    std::ofstream out(dir / "results.json");
    out << std::setw(1) << j << "\n";
    files.push_back("results.json");
  }
  if (!plots || runs.empty()) return files;

  // Metric against each parameter.
  for (std::size_t m = 0; m < study.metrics.size(); ++m) {
    for (std::size_t p = 0; p < design.paths.size(); ++p) {
      plot::LineChart chart;
      chart.title = study.metrics[m].name + " against " + design.paths[p];
      chart.xlabel = param_label(p);
      chart.ylabel = metric_label(m);
      plot::Series ok{"runs", {}, {}, plot::Series::Style::Points, "#1f77b4", 2.0};
      plot::Series bad{"incomplete runs", {}, {}, plot::Series::Style::Points, "#d62728", 2.0};
      for (const RunRecord& r : runs) {
        if (!std::isfinite(r.metrics[m])) continue;
        plot::Series& s = r.status == "ok" ? ok : bad;
        s.x.push_back(r.parameters[p]);
        s.y.push_back(r.metrics[m]);
      }
      if (ok.x.empty() && bad.x.empty()) continue;
      if (!ok.x.empty()) chart.series.push_back(ok);
      if (!bad.x.empty()) chart.series.push_back(bad);
      const std::string f = "metric_" + file_safe(study.metrics[m].name) + "_vs_" + file_safe(design.paths[p]) + ".png";
      plot::render_png(chart, dir / f);
      files.push_back(f);
    }
  }
  // Two-parameter full factorial: a map per metric.
  if (study.design.kind == DesignKind::FullFactorial && design.paths.size() == 2) {
    std::vector<double> xs, ys;
    for (const auto& row : design.values) {
      if (std::find(xs.begin(), xs.end(), row[0]) == xs.end()) xs.push_back(row[0]);
      if (std::find(ys.begin(), ys.end(), row[1]) == ys.end()) ys.push_back(row[1]);
    }
    std::sort(xs.begin(), xs.end());
    std::sort(ys.begin(), ys.end());
    for (std::size_t m = 0; m < study.metrics.size() && xs.size() >= 2 && ys.size() >= 2; ++m) {
      plot::Heatmap hm;
      hm.title = study.metrics[m].name;
      hm.xlabel = param_label(0);
      hm.ylabel = param_label(1);
      hm.zlabel = metric_label(m);
      hm.x = xs;
      hm.y = ys;
      hm.z.assign(xs.size() * ys.size(), NAN);
      bool any = false;
      for (const RunRecord& r : runs) {
        const std::size_t i = std::find(xs.begin(), xs.end(), r.parameters[0]) - xs.begin();
        const std::size_t jy = std::find(ys.begin(), ys.end(), r.parameters[1]) - ys.begin();
        hm.z[jy * xs.size() + i] = r.metrics[m];
        any = any || std::isfinite(r.metrics[m]);
      }
      // A map with holes would paint missing runs as some value: draw it only when every run is there.
      if (!any || std::any_of(hm.z.begin(), hm.z.end(), [](double v) { return !std::isfinite(v); })) continue;
      double zmin = INFINITY, zmax = -INFINITY;
      for (double v : hm.z)
        if (std::isfinite(v)) {
          zmin = std::min(zmin, v);
          zmax = std::max(zmax, v);
        }
      for (double& v : hm.z)
        if (!std::isfinite(v)) v = zmin;
      if (zmax > zmin) hm.zrange = std::make_pair(zmin, zmax);
      const std::string f = "map_" + file_safe(study.metrics[m].name) + ".png";
      plot::render_png(hm, dir / f);
      files.push_back(f);
    }
  }
  return files;
}

}  // namespace turbodyn::studies

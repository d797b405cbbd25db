#include "studies/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "post/plot.h"
#include "post/run_pictures.h"
#include "model/engine/integrator.h"
#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "studies/metrics.h"
#include "studies/stability_metrics.h"
#include "studies/parallel.h"
#include "studies/run_log.h"
#include "studies/sweep_pictures.h"
#include "studies/table.h"

namespace turbodyn::studies {
namespace {

constexpr const char* kRunsFile = "runs.jsonl";
constexpr const char* kOtherStudy =
    "holds the runs of a different study (parameters, design or metrics differ, or the model file has changed "
    "since); choose another output directory";

// Identifies the study a runs.jsonl belongs to: same model file (name and content), parameters, design and metrics.
nlohmann::json fingerprint(const StudySpec& s, const Design& d) {
  nlohmann::json metrics = nlohmann::json::array();
  // A metric's window, threshold, band and a stability metric's speeds and rotor share are part of it (the first three
  // only where set, so that a log of a study without them still resumes).
  const MetricSpec plain;
  for (const MetricSpec& m : s.metrics) {
    std::ostringstream id;
    id.precision(17);
    id << m.name << ":" << m.kind << ":" << m.probe;
    if (m.speed_min != plain.speed_min || m.speed_max != plain.speed_max)
      id << ":window=" << m.speed_min << "," << m.speed_max;
    if (m.threshold != plain.threshold) id << ":threshold=" << m.threshold;
    if (m.order_min != plain.order_min || m.order_max != plain.order_max)
      id << ":order_band=" << m.order_min << "," << m.order_max;
    if (is_stability_metric(m.kind)) {
      id << ":speed_count=" << m.speed_count << ":min_rotor_share=" << m.min_rotor_share;
      if (m.frequency_max != plain.frequency_max) id << ":frequency_max=" << m.frequency_max;
      if (m.continuation_steps != plain.continuation_steps) id << ":continuation_steps=" << m.continuation_steps;
    }
    metrics.push_back(id.str());
  }
  return {{"study", s.name}, {"model", s.model.filename().string()}, {"model_digest", base_model_digest(s)},
          {"paths", d.paths}, {"units", s.parameter_units}, {"also", s.parameter_also},
          {"runs", d.values.size()}, {"values", d.values}, {"metrics", metrics}};
}

nlohmann::json to_json(const RunRecord& r) {
  return {{"index", r.index}, {"parameters", json_numbers(r.parameters)}, {"metrics", json_numbers(r.metrics)},
          {"status", r.status}, {"error", r.error}, {"note", r.note}, {"wall_time_s", r.wall_time}};
}

RunRecord from_json(const nlohmann::json& j) {
  RunRecord r;
  r.index = j.at("index").get<std::size_t>();
  r.parameters = from_json_numbers(j.at("parameters"));
  r.metrics = from_json_numbers(j.at("metrics"));
  r.status = j.at("status").get<std::string>();
  r.error = j.value("error", "");
  r.note = j.value("note", "");
  r.wall_time = j.value("wall_time_s", 0.0);
  return r;
}

// The run records among a log's lines; a line that is not one (written by a newer version, say) is passed over.
std::vector<RunRecord> records(const std::vector<nlohmann::json>& lines) {
  std::vector<RunRecord> runs;
  for (const nlohmann::json& j : lines) {
    try {
      runs.push_back(from_json(j));
    } catch (const nlohmann::json::exception&) {
      continue;
    }
  }
  return runs;
}

// One run of the design: the run's overrides, evaluate_run.
RunRecord execute(const StudySpec& study, const Design& design, std::size_t i, const std::atomic<bool>* cancel) {
  RunRecord rec = evaluate_run(study, study.metrics, run_overrides(study, design, i), cancel);
  rec.index = i;
  rec.parameters = design.values[i];
  return rec;
}

}  // namespace

std::vector<RunRecord> read_runs(const StudySpec& study, const std::filesystem::path& dir) {
  return records(read_run_log(dir / kRunsFile, fingerprint(study, make_design(study.design)), kOtherStudy).records);
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
    const std::vector<Override> overrides = run_overrides(study, design, shard.empty() ? 0 : shard[0]);
    const MachineSpec spec = load_study_model(study, overrides);
    std::vector<std::pair<std::string, std::string>> paths;
    for (std::size_t p = 0; p < design.paths.size(); ++p) {
      paths.emplace_back("parameters[" + std::to_string(p) + "].path", design.paths[p]);
      if (p < study.parameter_also.size())
        for (const std::string& also : study.parameter_also[p])
          paths.emplace_back("parameters[" + std::to_string(p) + "].also", also);
    }
    check_varied_paths(study, overrides, paths);
    check_speed_window(study, spec.speed);
    const std::unique_ptr<RunupModel> model = make_runup_model(spec);
    check_metrics(study, model->channels(), summary_template(spec, *model));
    check_stability_metrics(study, study.metrics, spec);
  }

  std::filesystem::create_directories(options.output_dir);
  RunLog log(options.output_dir / kRunsFile, fingerprint(study, design), kOtherStudy);
  std::map<std::size_t, RunRecord> finished;
  for (RunRecord& r : records(log.records())) finished[r.index] = std::move(r);

  std::vector<std::size_t> pending;
  for (std::size_t i : shard)
    if (finished.count(i)) ++result.resumed;
    else pending.push_back(i);

  std::mutex mutex;
  SweepProgress progress;
  progress.total = shard.size();
  progress.resumed = result.resumed;
  progress.done = result.resumed;
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t done_here = 0;
  parallel_runs(pending.size(), run_threads(options.threads, study.threads), [&](std::size_t k) {
    if (options.cancel && options.cancel->load()) return;
    RunRecord rec = execute(study, design, pending[k], options.cancel);
    if (rec.status == "cancelled") return;  // not recorded: a resumed study runs it again
    const std::lock_guard<std::mutex> lock(mutex);
    log.append(to_json(rec));
    ++progress.done;
    ++done_here;
    if (rec.status == "failed") ++progress.failed;
    progress.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::size_t left = progress.total - progress.done;
    progress.eta = progress.wall_time / static_cast<double>(done_here) * static_cast<double>(left);
    finished[rec.index] = std::move(rec);
    if (options.progress) options.progress(progress);
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
    // Units of the metrics need the channel list: build the model of the first run once (the fixed overrides
    // alone need not make a valid model, e.g. an end seal's length fixed while the design varies its gap).
    const MachineSpec spec =
        load_study_model(study, design.values.empty() ? study.fixed : run_overrides(study, design, 0));
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
    CsvWriter csv(dir / "results.csv");
    csv.text("run");
    for (std::size_t p = 0; p < design.paths.size(); ++p) csv.text(param_label(p));
    for (std::size_t m = 0; m < study.metrics.size(); ++m) csv.text(metric_label(m));
    csv.texts({"status", "error", "note", "wall_time_s"}).end_row();
    for (const RunRecord& r : runs) {
      csv.integer(r.index).numbers(r.parameters).numbers(r.metrics);
      csv.text(r.status).text(r.error).text(r.note).number(r.wall_time).end_row();
    }
    files.push_back("results.csv");
  }
  nlohmann::json j;
  j["turbodyn_version"] = turbodyn_version();
  j["study"] = study.name;
  j["model"] = study.model.string();
  j["model_digest"] = base_model_digest(study);
  j["parameters"] = nlohmann::json::array();
  for (std::size_t p = 0; p < design.paths.size(); ++p)
    j["parameters"].push_back({{"path", design.paths[p]}, {"unit", study.parameter_units[p]}});
  j["metrics"] = nlohmann::json::array();
  for (std::size_t m = 0; m < study.metrics.size(); ++m) {
    const MetricSpec& spec = study.metrics[m];
    nlohmann::json e = {{"name", spec.name}, {"kind", spec.kind}, {"probe", spec.probe}, {"unit", metric_units[m]}};
    e.update(stability_grid_json(spec));  // the speeds a stability metric analysed
    j["metrics"].push_back(e);
  }
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
    CsvWriter csv(dir / "sensitivity.csv");
    csv.texts({"metric", "parameter", "src", "r_squared"}).end_row();
    for (std::size_t m = 0; m < study.metrics.size(); ++m) {
      std::vector<double> y;
      for (const RunRecord& r : runs) y.push_back(r.metrics[m]);
      try {
        const Sensitivity s = standardized_regression(x, y);
        nlohmann::json e = {{"r_squared", s.r_squared}, {"src", s.src}};
        sens[study.metrics[m].name] = e;
        for (std::size_t p = 0; p < s.src.size(); ++p)
          csv.text(study.metrics[m].name).text(design.paths[p]).number(s.src[p]).number(s.r_squared).end_row();
        if (plots) {
          const std::string f = "sensitivity_" + post::file_safe(study.metrics[m].name) + ".png";
          draw_tornado(study, design, m, s, dir / f);
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
    write_output_file(dir / "results.json", j.dump(1) + "\n");
    files.push_back("results.json");
  }
  if (!plots || runs.empty()) return files;

  // Metric against each parameter; for two parameters a map per metric.
  for (std::size_t m = 0; m < study.metrics.size(); ++m) {
    for (std::size_t p = 0; p < design.paths.size(); ++p) {
      const std::string f =
          "metric_" + post::file_safe(study.metrics[m].name) + "_vs_" + post::file_safe(design.paths[p]) + ".png";
      if (draw_metric_scatter(study, design, runs, m, p, metric_units[m], dir / f)) files.push_back(f);
    }
    const std::string f = "map_" + post::file_safe(study.metrics[m].name) + ".png";
    if (draw_metric_map(study, design, runs, m, metric_units[m], dir / f)) files.push_back(f);
  }
  return files;
}

}  // namespace turbodyn::studies

#include "optim/evaluation_log.h"

#include <cmath>

#include "studies/stability_metrics.h"
#include "studies/table.h"

namespace turbodyn::optim {
namespace {

using studies::from_json_numbers;
using studies::json_numbers;

nlohmann::json overrides_json(const std::vector<Override>& o) {
  nlohmann::json a = nlohmann::json::array();
  for (const Override& x : o) a.push_back(x.path + "=" + x.value);
  return a;
}

}  // namespace

nlohmann::json fingerprint(const OptimizationSpec& s) {
  nlohmann::json vars = nlohmann::json::array(), cases = nlohmann::json::array(), metrics = nlohmann::json::array();
  for (const Variable& v : s.variables) {
    std::string paths;
    for (const std::string& p : v.paths) paths += (paths.empty() ? "" : ",") + p;
    vars.push_back(paths + " [" + v.unit + "]");
  }
  for (const OperatingCase& c : s.cases) cases.push_back(overrides_json(c.overrides));
  const studies::MetricSpec plain;
  for (const Metric& m : s.metrics) {
    metrics.push_back({{"name", m.spec.name}, {"kind", m.spec.kind}, {"probe", m.spec.probe},
                       {"window", {m.spec.speed_min, m.spec.speed_max}}, {"threshold", m.spec.threshold},
                       {"points", m.points}});
    // The band only where set, so that a cache written before it existed still resumes.
    if (m.spec.order_min != plain.order_min || m.spec.order_max != plain.order_max)
      metrics.back()["order_band"] = nlohmann::json::array({m.spec.order_min, m.spec.order_max});
    if (studies::is_stability_metric(m.spec.kind)) {
      metrics.back()["speed_count"] = m.spec.speed_count;
      metrics.back()["min_rotor_share"] = m.spec.min_rotor_share;
      if (m.spec.frequency_max > 0.0) metrics.back()["frequency_max"] = m.spec.frequency_max;
    }
  }
  return {{"model", s.model.filename().string()}, {"model_digest", studies::base_model_digest(s)},
          {"fixed", overrides_json(s.fixed)},
          {"speed_window", {s.speed_window_min, s.speed_window_max}}, {"variables", vars}, {"cases", cases},
          {"metrics", metrics}};
}

nlohmann::json to_json(const Evaluation& e) {
  nlohmann::json cases = nlohmann::json::array();
  for (const CaseResult& c : e.cases)
    cases.push_back({{"metrics", json_numbers(c.metrics)}, {"status", c.status}, {"error", c.error},
                     {"wall_time_s", c.wall_time}});
  return {{"id", e.id}, {"design", json_numbers(e.design)}, {"cases", cases}, {"wall_time_s", e.wall_time}};
}

Evaluation evaluation_from_json(const nlohmann::json& j) {
  Evaluation e;
  e.id = j.at("id").get<std::size_t>();
  e.design = from_json_numbers(j.at("design"));
  for (const auto& c : j.at("cases")) {
    CaseResult r;
    r.metrics = from_json_numbers(c.at("metrics"));
    r.status = c.at("status").get<std::string>();
    r.error = c.value("error", "");
    r.wall_time = c.value("wall_time_s", 0.0);
    e.cases.push_back(r);
  }
  e.wall_time = j.value("wall_time_s", 0.0);
  return e;
}

EvaluationLog::EvaluationLog(const nlohmann::json& fp, const std::filesystem::path& file) : file_(file) {
  if (file_.empty()) return;
  log_ = std::make_unique<studies::RunLog>(
      file_, nlohmann::json{{"fingerprint", fp}},
      "holds the evaluations of a different problem (model, fixed overrides, speed window, variables, cases or "
      "metrics differ, or the model file has changed since); choose another output directory or delete the file");
  for (const nlohmann::json& j : log_->records()) {
    try {
      Evaluation e = evaluation_from_json(j);
      next_id_ = std::max(next_id_, e.id + 1);
      std::vector<double> key = e.design;
      cache_[key] = std::make_unique<Evaluation>(std::move(e));
    } catch (const nlohmann::json::exception&) {
      continue;
    }
  }
  loaded_ = cache_.size();
}

const Evaluation* EvaluationLog::find(const std::vector<double>& design) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = cache_.find(design);
  return it == cache_.end() ? nullptr : it->second.get();
}

const Evaluation* EvaluationLog::record(Evaluation e, const nlohmann::json& info) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (const auto it = cache_.find(e.design); it != cache_.end()) return it->second.get();
  if (log_) {
    nlohmann::json line = to_json(e);
    if (info.is_object()) line.update(info);
    log_->append(line);
  }
  std::vector<double> key = e.design;
  auto& slot = cache_[key];
  slot = std::make_unique<Evaluation>(std::move(e));
  return slot.get();
}

std::size_t EvaluationLog::reserve_ids(std::size_t n) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t first = next_id_;
  next_id_ += n;
  return first;
}

std::size_t EvaluationLog::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return cache_.size();
}

}  // namespace turbodyn::optim

#include "optim/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "model/rotor/rotor.h"
#include "optim/response_metric.h"
#include "studies/parallel.h"
#include "studies/run_evaluation.h"

namespace turbodyn::optim {
namespace {

// One case of one design: the run-up metrics through the studies layer, the response metrics from the linear rotor.
CaseResult evaluate_case(const OptimizationSpec& spec, const std::vector<studies::MetricSpec>& runup_specs,
                         const std::vector<std::size_t>& runup_metrics, const std::vector<Override>& overrides,
                         const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  CaseResult c;
  c.metrics.assign(spec.metrics.size(), NAN);
  if (!runup_metrics.empty()) {
    const studies::RunRecord r = studies::evaluate_run(spec, runup_specs, overrides, cancel);
    for (std::size_t k = 0; k < runup_metrics.size(); ++k) c.metrics[runup_metrics[k]] = r.metrics[k];
    c.status = r.status;
    c.error = r.error;
  }
  const bool any_response =
      std::any_of(spec.metrics.begin(), spec.metrics.end(), [](const Metric& m) { return m.response(); });
  if (any_response && c.status == "ok") {
    try {
      const Rotor rotor = build_rotor(studies::load_base_model(spec, overrides));
      for (std::size_t m = 0; m < spec.metrics.size(); ++m)
        if (spec.metrics[m].response()) c.metrics[m] = response_metric(spec.metrics[m].spec, spec.metrics[m].points, rotor);
    } catch (const std::exception& e) {
      c.status = "failed";
      c.error = e.what();
    }
  }
  c.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

}  // namespace

bool Evaluation::ok() const {
  return std::all_of(cases.begin(), cases.end(), [](const CaseResult& c) { return c.status == "ok"; });
}

Evaluator model_evaluator(const OptimizationSpec& spec) {
  std::vector<studies::MetricSpec> runup;
  std::vector<std::size_t> runup_metrics;
  for (std::size_t m = 0; m < spec.metrics.size(); ++m)
    if (!spec.metrics[m].response()) {
      runup.push_back(spec.metrics[m].spec);
      runup_metrics.push_back(m);
    }
  return [spec, runup, runup_metrics](const std::vector<double>& design, const std::atomic<bool>* cancel) {
    std::vector<CaseResult> out(spec.cases.size());
    studies::parallel_runs(spec.cases.size(), 0, [&](std::size_t c) {
      out[c] = evaluate_case(spec, runup, runup_metrics, run_overrides(spec, design, &spec.cases[c]), cancel);
    });
    return out;
  };
}

Assessment assess(const OptimizationSpec& spec, const Evaluation& e, double failure_objective) {
  Assessment a;
  const std::size_t nc = spec.cases.size();
  a.case_objectives.assign(nc, NAN);
  std::string why;
  for (std::size_t c = 0; c < nc && c < e.cases.size(); ++c) {
    const CaseResult& r = e.cases[c];
    if (r.status != "ok") {
      if (why.empty()) why = spec.cases[c].name + ": run " + r.status + (r.error.empty() ? "" : ": " + r.error);
      continue;
    }
    double j = 0.0;
    for (const ObjectiveTerm& t : spec.objective.terms) j += t.weight * r.metrics[t.metric];
    if (!std::isfinite(j) && why.empty()) why = spec.cases[c].name + ": an objective metric is undefined";
    a.case_objectives[c] = j;
  }
  a.failed = !why.empty() || e.cases.size() != nc;
  if (e.cases.size() != nc && why.empty()) why = "the evaluation has the wrong number of cases";
  if (!a.failed) {
    if (spec.objective.cases == CaseAggregate::Max) {
      a.objective = *std::max_element(a.case_objectives.begin(), a.case_objectives.end());
    } else {
      double sw = 0.0, s = 0.0;
      for (std::size_t c = 0; c < nc; ++c) {
        s += spec.cases[c].weight * a.case_objectives[c];
        sw += spec.cases[c].weight;
      }
      a.objective = s / sw;
    }
  } else {
    a.objective = failure_objective;
  }
  for (const Constraint& k : spec.constraints)
    for (std::size_t c = 0; c < nc; ++c) {
      const double v = c < e.cases.size() && e.cases[c].status == "ok" ? e.cases[c].metrics[k.metric] : NAN;
      a.constraint_values.push_back(v);
      if (!std::isfinite(v)) {
        a.g.push_back(1.0);
        if (why.empty()) why = spec.cases[c].name + ": constraint metric " + k.name + " is undefined";
        a.failed = true;
        continue;
      }
      const double scale = k.bound != 0.0 ? std::abs(k.bound) : 1.0;
      a.g.push_back(k.upper ? (v - k.bound) / scale : (k.bound - v) / scale);
    }
  if (a.failed) a.objective = failure_objective;
  for (double g : a.g) a.max_violation = std::max(a.max_violation, g);
  a.feasible = !a.failed && a.max_violation <= spec.algorithm.constraint_tolerance;
  a.note = why;
  return a;
}

}  // namespace turbodyn::optim

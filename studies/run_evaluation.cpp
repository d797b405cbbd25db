#include "studies/run_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "model/engine/speed_profile.h"
#include "model/io/run_summary.h"
#include "studies/metrics.h"
#include "studies/stability_metrics.h"

namespace turbodyn::studies {

RunupRun run_runup(const StudyCommon& study, const std::vector<Override>& overrides,
                   const std::atomic<bool>* cancel) {
  RunupRun run;
  run.spec = load_base_model(study, overrides);
  run.model = make_runup_model(run.spec);
  run.options = runup_options(run.spec);
  run.options.cancel = cancel;
  if (study.speed_window_min > 0.0) run.options.t_start = time_at_speed(run.spec.speed, study.speed_window_min);
  if (study.speed_window_max > 0.0) run.options.t_end = time_at_speed(run.spec.speed, study.speed_window_max);
  run.result = simulate_runup(*run.model, run.options);
  return run;
}

RunRecord evaluate_run(const StudyCommon& study, const std::vector<MetricSpec>& metrics,
                       const std::vector<Override>& overrides, const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  RunRecord rec;
  rec.metrics.assign(metrics.size(), NAN);
  const bool any_runup = std::any_of(metrics.begin(), metrics.end(),
                                     [](const MetricSpec& m) { return !is_stability_metric(m.kind); });
  const bool any_stability = std::any_of(metrics.begin(), metrics.end(),
                                         [](const MetricSpec& m) { return is_stability_metric(m.kind); });
  try {
    rec.status = "ok";
    if (any_runup) {
      const RunupRun run = run_runup(study, overrides, cancel);
      const RunupResult& r = run.result;
      const nlohmann::json summary = run_summary(run.spec, *run.model, run.options, r, overrides);
      for (std::size_t m = 0; m < metrics.size(); ++m)
        if (!is_stability_metric(metrics[m].kind))
          rec.metrics[m] = evaluate_metric(metrics[m], r, summary, run.options.sample_rate);
      rec.status = r.complete ? "ok" : (cancel && cancel->load()) ? "cancelled" : "incomplete";
      rec.error = r.message;
      rec.note = probe_limit_note(summary);
    }
    // The stability metrics analyse the model itself (no run-up): after a complete run, or alone.
    if (any_stability && rec.status == "ok") {
      std::string error, note;
      const std::vector<double> v =
          evaluate_stability_metrics(load_base_model(study, overrides), metrics, &error, cancel, &note);
      if (!note.empty()) rec.note += (rec.note.empty() ? "" : "; ") + note;
      for (std::size_t m = 0; m < metrics.size(); ++m)
        if (is_stability_metric(metrics[m].kind)) rec.metrics[m] = v[m];
      if (!error.empty()) {
        rec.status = (cancel && cancel->load()) ? "cancelled" : "incomplete";
        rec.error = error;
      }
    }
  } catch (const std::exception& e) {
    rec.status = "failed";
    rec.error = e.what();
  }
  rec.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rec;
}

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

}  // namespace turbodyn::studies

// One run of a batch (a sweep's design row, an optimiser's design in one operating case, an identification's
// parameter values): the base model with the run's overrides, run up over the study's speed window, and the
// metrics of that run-up. Thread-safe: every call builds its own model and workspace.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "model/engine/integrator.h"
#include "model/io/model_file.h"
#include "studies/study.h"

namespace turbodyn::studies {

struct RunRecord {
  std::size_t index = 0;             ///< row of the design
  std::vector<double> parameters;    ///< in the units of the study file
  std::vector<double> metrics;       ///< NaN where undefined
  std::string status;                ///< "ok", "incomplete" (integrator gave up, or a stability analysis found no
                                     ///< steady state at a speed; metrics from the partial run), "failed"
  std::string error;                 ///< why, for incomplete and failed runs
  /// What a run's metrics need said: probes past their limit (probe_limit_note, e.g. a ball bearing's contact
  /// pressure above ISO 76's), a stability analysis's restart; "; " between them.
  std::string note;
  double wall_time = 0.0;            ///< s
};

/// A run-up as the study asks for it, with what it ran on (the summary and the metrics need all of it).
struct RunupRun {
  MachineSpec spec;
  std::unique_ptr<RunupModel> model;
  RunupOptions options;
  RunupResult result;
};

/// The run-up of the study's base model with `overrides` (the complete list, the study's fixed ones first), from
/// where the ramp reaches study.speed_window_min to where it reaches speed_window_max. Throws what loading or building
/// the model throws; an integrator that gives up or a cancel leaves result.complete false.
RunupRun run_runup(const StudyCommon& study, const std::vector<Override>& overrides,
                   const std::atomic<bool>* cancel = nullptr);

/// run_runup and the `metrics` of it (NaN where undefined), status ("ok", "incomplete", "cancelled", "failed"),
/// error and wall time. Never throws for a failing run; index and parameters are left empty.
RunRecord evaluate_run(const StudyCommon& study, const std::vector<MetricSpec>& metrics,
                       const std::vector<Override>& overrides, const std::atomic<bool>* cancel = nullptr);

/// Time (s) at which the speed profile first reaches `speed` (rad/s); the profile's end if never.
double time_at_speed(const SpeedProfile& profile, double speed);

}  // namespace turbodyn::studies

// One evaluated design: the metrics of each operating case, and the objective and constraints assembled from them.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "optim/optimization.h"

namespace turbodyn::optim {

/// The runs of one operating case for one design.
struct CaseResult {
  std::vector<double> metrics;  ///< one per OptimizationSpec::metrics, in the metric's unit; NaN where undefined
  std::string status = "ok";    ///< "ok", "incomplete" (integrator gave up), "failed", "cancelled"
  std::string error;            ///< why, when not ok
  double wall_time = 0.0;       ///< s
};

/// One design evaluated in all operating cases (the unit of the cache and the log).
struct Evaluation {
  std::size_t id = 0;               ///< order of first evaluation in the log (0, 1, ...)
  std::vector<double> design;       ///< variable values in the study's units
  std::vector<CaseResult> cases;    ///< one per OptimizationSpec::cases
  double wall_time = 0.0;           ///< s, elapsed for all cases
  bool ok() const;                  ///< every case ran to its end
};

/// Evaluates one design in every operating case. Must be thread-safe (designs of a finite-difference stencil run
/// in parallel) and must not throw for a failing run (report it in CaseResult::status instead).
using Evaluator = std::function<std::vector<CaseResult>(const std::vector<double>& design,
                                                        const std::atomic<bool>* cancel)>;

/// The evaluator of a study: each case one run-up of the base model with the design's overrides (studies'
/// evaluate_run) for the run-up metrics, and/or the steady-state response for the response metrics; the cases run
/// in parallel with TBB.
Evaluator model_evaluator(const OptimizationSpec& spec);

/// Objective and constraints of one evaluation.
struct Assessment {
  double objective = 0.0;               ///< minimised; `failure_objective` for a failed evaluation
  std::vector<double> case_objectives;  ///< J_c per case (NaN when undefined)
  std::vector<double> constraint_values;///< metric value per constraint and case (constraint-major), metric's unit
  std::vector<double> g;                ///< normalised constraints, same order; <= tolerance is feasible
  bool failed = false;                  ///< a run failed or a needed metric is undefined
  bool feasible = false;                ///< not failed and every g <= tolerance
  double max_violation = 0.0;           ///< largest g (0 when none is positive)
  std::string note;                     ///< why it failed
};

/// Assembles objective and constraints. A failed evaluation gets `failure_objective` and g = 1 (violated by 100 %)
/// for every constraint whose value is missing.
Assessment assess(const OptimizationSpec& spec, const Evaluation& e, double failure_objective);

}  // namespace turbodyn::optim

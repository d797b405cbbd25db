// The NLopt driver: runs an optimisation study with a given evaluator (the model's run-ups, or an analytic function
// in the tests), on design variables scaled to [0, 1], with finite-difference gradients whose runs execute in
// parallel, every evaluation cached and logged (a restart replays the cached ones: NLopt's algorithms are
// deterministic for given function values and seed, so it follows the same path and continues where it stopped).
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "optim/evaluation.h"

namespace turbodyn::optim {

/// One design the optimiser asked for (or a finite-difference point of its gradient).
struct HistoryEntry {
  std::size_t request = 0;      ///< 0, 1, ... in the order of the requests
  Evaluation evaluation;
  Assessment assessment;
  bool cached = false;          ///< not run now: found in the log (earlier invocation or an earlier request)
  bool gradient_point = false;  ///< a finite-difference point, not a design the optimiser proposed
};

struct OptimizationProgress {
  std::size_t requests = 0, new_evaluations = 0, cached_evaluations = 0;
  double best_objective = NAN;  ///< best feasible so far (NaN: none yet)
  double wall_time = 0.0;       ///< s
};

struct OptimizerOptions {
  std::filesystem::path log_file;               ///< evaluations.jsonl; empty = cache in memory only
  int threads = 0;                              ///< 0: the study's setting, else all cores
  const std::atomic<bool>* cancel = nullptr;    ///< set to stop (Ctrl-C): runs in flight are abandoned, not logged
  std::function<void(const HistoryEntry&, const OptimizationProgress&)> progress;  ///< after every request
};

struct OptimizationResult {
  std::vector<HistoryEntry> history;
  /// Index into history of the best design: the lowest objective among the feasible entries (earliest on ties);
  /// without a feasible one the least infeasible; empty when every evaluation failed.
  std::optional<std::size_t> best;
  bool best_feasible = false;
  int nlopt_code = 0;           ///< nlopt_result
  std::string nlopt_result;     ///< "XTOL_REACHED", ...
  std::string reason;           ///< in words
  std::string algorithm;        ///< as run, e.g. "NLOPT_LN_COBYLA" or "NLOPT_AUGLAG + NLOPT_LN_BOBYQA"
  std::string note;             ///< e.g. why AUGLAG wraps the algorithm
  std::size_t new_evaluations = 0, cached_evaluations = 0;
  bool interrupted = false;
  double wall_time = 0.0;       ///< s
};

/// Runs the optimisation. Throws ModelError for settings NLopt rejects or a log of another problem; exceptions of
/// the evaluator are passed on. Results do not depend on the thread count.
OptimizationResult optimize(const OptimizationSpec& spec, const Evaluator& evaluate, const OptimizerOptions& options);

/// NLopt's name of a result code ("XTOL_REACHED") and its meaning in words.
std::string result_name(int nlopt_code);
std::string result_reason(int nlopt_code);

}  // namespace turbodyn::optim

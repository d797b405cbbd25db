// The cache of evaluated designs and its log file (JSON lines): every evaluation is appended and flushed as it
// finishes, and read back when the optimisation starts again, so designs evaluated before (also by an interrupted or
// killed optimisation, or with another algorithm) are not run again.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include <nlohmann/json.hpp>

#include "optim/evaluation.h"
#include "studies/run_log.h"

namespace turbodyn::optim {

/// Identifies what an evaluation depends on: model (file name and content), fixed overrides, speed window, variables
/// (paths and units), cases and metrics. Bounds, start, algorithm, objective and constraints are not part of it: changing them keeps
/// the cached evaluations valid.
nlohmann::json fingerprint(const OptimizationSpec& spec);

nlohmann::json to_json(const Evaluation& e);
Evaluation evaluation_from_json(const nlohmann::json& j);

/// Thread-safe cache keyed by the exact design values (JSON numbers round-trip doubles exactly).
class EvaluationLog {
 public:
  /// Without a file: cache only. With one: reads it (throws ModelError if it holds another problem's evaluations;
  /// a line cut short by a kill is skipped) and appends new evaluations to it.
  EvaluationLog(const nlohmann::json& fingerprint, const std::filesystem::path& file = {});

  /// The cached evaluation of `design`, or nullptr. The pointer stays valid for the life of the log.
  const Evaluation* find(const std::vector<double>& design) const;
  /// Reserves `n` consecutive ids for evaluations about to run (assigned in request order, so the ids do not
  /// depend on which parallel run finishes first); returns the first.
  std::size_t reserve_ids(std::size_t n);
  /// Stores a new evaluation (with an id from reserve_ids), writes and flushes its line; returns the stored one.
  /// `info` (e.g. objective and constraint values, for the reader of the file) is written with it, not read back.
  const Evaluation* record(Evaluation e, const nlohmann::json& info = {});

  std::size_t size() const;
  std::size_t loaded() const { return loaded_; }  ///< evaluations read from the file at construction
  const std::filesystem::path& file() const { return file_; }

 private:
  mutable std::mutex mutex_;
  std::map<std::vector<double>, std::unique_ptr<Evaluation>> cache_;
  std::filesystem::path file_;
  std::unique_ptr<studies::RunLog> log_;
  std::size_t next_id_ = 0, loaded_ = 0;
};

}  // namespace turbodyn::optim

// Running a study: every run of the design is a run-up of the base model with the run's parameter overrides,
// executed in parallel with TBB (one run per task; each run owns its model and workspace), recorded as soon as it
// finishes (runs.jsonl, so an interrupted study resumes without redoing finished runs), then tabulated and plotted.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "studies/design.h"
#include "studies/run_evaluation.h"
#include "studies/study.h"

namespace turbodyn::studies {

struct SweepProgress {
  std::size_t done = 0, failed = 0, total = 0, resumed = 0;
  double wall_time = 0.0;            ///< s since the start of this invocation
  double eta = 0.0;                  ///< s, estimated time left
};

struct SweepOptions {
  std::filesystem::path output_dir;
  int threads = 0;                   ///< 0: the study's setting, else all cores
  std::size_t shard_k = 0, shard_n = 1;  ///< run only design rows i with i % n == k
  std::function<void(const SweepProgress&)> progress;  ///< called after every run (serialised)
  const std::atomic<bool>* cancel = nullptr;            ///< stop starting new runs when set
};

struct SweepResult {
  Design design;
  std::vector<RunRecord> runs;       ///< all recorded runs of this shard, by index
  std::size_t resumed = 0;           ///< runs found finished in runs.jsonl and not redone
  bool complete = false;             ///< every run of the shard is recorded
};

/// Runs (or resumes) the study into options.output_dir/runs.jsonl. Throws ModelError for a bad study (checked on
/// the first run's model before anything runs) or an output directory holding another study's runs.
SweepResult run_sweep(const StudySpec& study, const SweepOptions& options);

/// Reads the run records of one output directory (throws ModelError if they belong to another study).
std::vector<RunRecord> read_runs(const StudySpec& study, const std::filesystem::path& dir);

/// Writes results.csv, results.json, sensitivity.csv and the pictures for `runs` into dir; returns the files.
std::vector<std::string> write_results(const StudySpec& study, const Design& design, std::vector<RunRecord> runs,
                                       const std::filesystem::path& dir, bool plots);

}  // namespace turbodyn::studies

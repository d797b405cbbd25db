// `turbodyn optimize STUDY`: design optimisation with NLopt on run-up (or steady-state) metrics
// (docs/optimization.md).
#pragma once

#include <filesystem>

namespace turbodyn::app {

struct OptimizeCommandOptions {
  std::filesystem::path study_file;
  std::filesystem::path output_dir = "out/optimize";
  int threads = 0;     ///< 0: the study's setting, else all cores
  int maxeval = 0;     ///< > 0: replaces the study's [algorithm] maxeval (a quick trial of a study)
  bool plots = true;   ///< convergence plot and the spectrograms of the initial and the best design
};

/// Runs (or restarts from DIR/evaluations.jsonl) an optimisation and writes history.csv, evaluations.jsonl,
/// result.json, best.toml, convergence.png and the spectrograms. Exit code 0 with a feasible best design, 4 when
/// no evaluated design satisfies the constraints (outputs still written), 130 when interrupted, 2 for a bad study.
int run_optimize_command(const OptimizeCommandOptions& options);

}  // namespace turbodyn::app

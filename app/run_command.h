// `turbodyn run`: the run-up simulation with its outputs (time series, summary, pictures).
#pragma once

#include <filesystem>
#include <vector>

#include "model/model_file.h"

namespace turbodyn::app {

struct RunCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::filesystem::path output_dir = "out/run";
  bool plots = true;
};

/// Runs the run-up and writes timeseries.h5 (and .csv), summary.json and PNG pictures into the output directory.
/// Returns 0 on success, 3 if the integrator gave up, 130 if interrupted (results up to then are written).
int run_run_command(const RunCommandOptions& options);

}  // namespace turbodyn::app

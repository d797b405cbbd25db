// `turbodyn identify STUDY`: fit model parameters to a measured run-up (docs/identification.md).
#pragma once

#include <filesystem>

namespace turbodyn::app {

struct IdentifyCommandOptions {
  std::filesystem::path study_file;
  std::filesystem::path output_dir = "out/identify";
  int threads = 0;    ///< parallel model runs; 0 = the study's setting, else all cores
  bool plots = true;
};

/// Runs the identification and writes its results; exit code 0 when Ceres converged or stopped at its iteration
/// limit with a usable solution, 130 when interrupted (results of the last iteration are written), 2 for a bad study
/// or measured file.
int run_identify_command(const IdentifyCommandOptions& options);

}  // namespace turbodyn::app

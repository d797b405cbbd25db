// `turbodyn sweep STUDY` and `turbodyn merge STUDY DIR...`: parameter studies (docs/studies.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace turbodyn::app {

struct SweepCommandOptions {
  std::filesystem::path study_file;
  std::filesystem::path output_dir = "out/sweep";
  int threads = 0;
  std::string shard;  ///< "K/N" or ""
  bool plots = true;
};

/// Runs or resumes a study; exit code 0 when every run of the shard is recorded (failed runs included),
/// 130 when interrupted, 2 for a bad study.
int run_sweep_command(const SweepCommandOptions& options);

/// Joins the runs.jsonl of several shard directories into one results set in output_dir.
int run_merge_command(const std::filesystem::path& study_file, const std::vector<std::filesystem::path>& dirs,
                      const std::filesystem::path& output_dir, bool plots);

}  // namespace turbodyn::app

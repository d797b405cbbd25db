// `turbodyn response`: steady-state synchronous unbalance response of the linear rotor against speed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"

namespace turbodyn::app {

struct ResponseCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::string speeds;  ///< "" = from [modal] (or the speed profile)
  std::filesystem::path output_dir = "out/response";
  bool plots = true;
};

/// Writes response.json, response.csv and response.png. Returns the exit code.
int run_response_command(const ResponseCommandOptions& options);

}  // namespace turbodyn::app

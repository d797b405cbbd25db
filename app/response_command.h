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
  /// Also the nonlinear steady state on the ball bearings' quasi-static reaction (model/engine/unbalance_whirl.h).
  bool nonlinear = false;
};

/// Writes response.json, response.csv and response.png (with `nonlinear` also response_nonlinear.csv and the curve in
/// response.json and the picture). Returns the exit code: 3 if the nonlinear response leaves part of the speed range
/// without a steady state (written so far).
int run_response_command(const ResponseCommandOptions& options);

}  // namespace turbodyn::app

// `turbodyn stability`: eigenvalues of the whole run-up model (rotor, balls, cages, every contact law) linearised
// about its steady turning state at constant speeds (model/engine/stability.h; docs/ball-bearing.md,
// "Linearised stability").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"

namespace turbodyn::app {

struct StabilityCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::string speeds;                       ///< "" = 11 speeds over [modal]; "A:B:N" or "A, B, C" with units
  double min_rotor_share = 0.01;            ///< modes with less of their motion in the rotor are the balls' own
  double continuation_step_factor = 1.0;    ///< StabilityOptions::continuation_step_factor, in (0, 1]
  std::filesystem::path output_dir = "out/stability";
  bool plots = true;
};

/// Writes stability.json, stability.csv and (plots) stability_frequencies.png, stability_damping.png into the
/// output directory. Throws ModelError for a model the analysis does not cover or a steady state not found.
int run_stability_command(const StabilityCommandOptions& options);

}  // namespace turbodyn::app

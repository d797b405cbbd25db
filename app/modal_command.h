// `turbodyn modal`: complex modes, Campbell diagram and critical speeds of the linearised rotor.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"
#include "model/rotor/modal.h"

namespace turbodyn::app {

struct ModalCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::string speeds;                    ///< "" = from the model file; "A:B:N" or "A, B, C" with units
  std::filesystem::path output_dir = "out/modal";
  int n_modes = 0;                       ///< 0 = from the model file
  Frame frame = Frame::Inertial;
  bool plots = true;
};

/// Runs the analysis and writes modal.json, campbell.csv, campbell.png and modes_*.png into the output directory.
/// Returns the process exit code.
int run_modal_command(const ModalCommandOptions& options);

/// Speeds of a linear analysis: the --speeds option if given, else `count` speeds over [modal] speed_min to
/// speed_max (default: the speed profile's end). Throws ModelError when neither gives a range.
std::vector<double> analysis_speeds(const MachineSpec& spec, const std::string& option, int count);

/// Throws ModelError if the machine has supports the linear analyses do not model: nonlinear bearings (ball
/// bearings and floating-ring bearings are accepted if `nonlinear_bearings`: modal linearises them), squeeze-film
/// dampers, pedestal masses.
void require_linear_supports(const MachineSpec& spec, bool nonlinear_bearings = false);

/// Parses a speed list: "0:150000 rpm:31" (start:end:count, units on the numbers) or "0, 50000 rpm, 2500 Hz".
/// Throws ModelError naming the option.
std::vector<double> parse_speed_list(const std::string& text);

}  // namespace turbodyn::app

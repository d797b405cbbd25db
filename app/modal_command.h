// `turbodyn modal`: complex modes, Campbell diagram and critical speeds of the linearised rotor.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"
#include "model/rotor/modal.h"
#include "model/spec/units.h"

namespace turbodyn::app {

struct ModalCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::string speeds;                    ///< "" = from the model file; "A:B:N" or "A, B, C" with units
  std::filesystem::path output_dir = "out/modal";
  int n_modes = 0;                       ///< 0 = from the model file
  Frame frame = Frame::Inertial;
  bool plots = true;
  /// "" = none; else the whirl amplitudes of the critical speeds at an amplitude ("0.1:500 um:25", a comma list)
  std::string amplitudes;
  /// where the amplitude is measured: "disks.NAME" or "bearings.NAME"; "" = for each branch the disk that moves
  /// most in its linearised mode
  std::string amplitude_at;
};

/// Runs the analysis and writes modal.json, campbell.csv, campbell.png and modes_*.png into the output directory;
/// with amplitudes also the synchronous critical speeds at each amplitude (model/engine/backbone.h): backbone.csv,
/// backbone.png and modal.json's "backbones".
/// Returns the process exit code.
int run_modal_command(const ModalCommandOptions& options);

/// Speeds of a linear analysis: the --speeds option if given, else `count` speeds over [modal] speed_min to
/// speed_max (default: the speed profile's end). Throws ModelError when neither gives a range.
std::vector<double> analysis_speeds(const MachineSpec& spec, const std::string& option, int count);

/// Throws ModelError if the machine has supports the linear analyses do not model: nonlinear bearings (ball
/// bearings and floating-ring bearings are accepted if `nonlinear_bearings`: modal linearises them), squeeze-film
/// dampers, pedestal masses.
void require_linear_supports(const MachineSpec& spec, bool nonlinear_bearings = false);

/// Parses a list option of quantities of dimension `d`: "START:END:COUNT" (units on the numbers, "0:150000 rpm:31")
/// or a comma list ("0, 50000 rpm, 2500 Hz"); a bare number takes the unit of the items written with one, SI units
/// without any. Values plausible for `d`, not negative, increasing, at most `max_count`. Throws ModelError naming
/// `option` ("--speeds"), with `noun` ("speeds") in its messages.
std::vector<double> parse_quantity_list(const std::string& text, const std::string& option, const Dimension& d,
                                        const std::string& noun, long max_count);

/// Parses a speed list (parse_quantity_list for --speeds, rad/s).
std::vector<double> parse_speed_list(const std::string& text);

}  // namespace turbodyn::app

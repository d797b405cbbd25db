// `turbodyn bearing`: the quasi-static equilibrium of one ball bearing of a model under static loads at rotor
// speeds, with its stiffness and damping (model/elements/ball/ball_bearing_quasistatic.h; docs/ball-bearing.md),
// or the steady operating points of one floating-ring bearing: ring speed, eccentricities, film temperatures,
// power losses, oil flows and the linearised films (model/elements/floating_ring_steady.h;
// docs/thermal-films.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"

namespace turbodyn::app {

struct BearingCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::string bearing;                      ///< "" = the model's first ball or floating-ring bearing
  std::string speeds;                       ///< "" = 11 speeds over [modal]; "A:B:N" or "A, B, C" with units
  std::string load = "0, 0";                ///< "Fx,Fy[,Fz]" on the inner ring, units allowed ("100 N")
  /// Ball bearings: "" = none; "START:END:COUNT" or "A, B, C" (lengths, units allowed, "0:60 um:31"): the inner
  /// ring's radial travels of a load-deflection curve at each speed (without --load).
  std::string radial_travel;
  std::filesystem::path output_dir = "out/bearing";
  bool plots = true;
};

/// Ball bearings: writes bearing.json, bearing.csv, bearing_balls.csv and (plots) stiffness.png, tilt_stiffness.png,
/// with --radial-travel also load_deflection.csv and (plots) load_deflection.png;
/// floating-ring bearings: bearing.json, bearing.csv and (plots) ring_speed_ratio.png, eccentricity.png,
/// power_loss.png, temperatures.png; into the output directory.
/// Throws ModelError for a bad bearing name, option or geometry and for a load without equilibrium.
int run_bearing_command(const BearingCommandOptions& options);

/// Parses "Fx,Fy" or "Fx,Fy,Fz" (N, units allowed). Throws ModelError naming --load.
std::vector<double> parse_load(const std::string& text);

/// Parses --radial-travel (parse_quantity_list for lengths, "0:60 um:31"; at most 10,000 values). Throws ModelError
/// naming --radial-travel.
std::vector<double> parse_travel_list(const std::string& text);

}  // namespace turbodyn::app

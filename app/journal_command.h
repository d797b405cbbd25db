// `turbodyn journal`: one plain journal bearing evaluated at a given state (docs/output-format.md).
#pragma once

#include <string>

namespace turbodyn::app {

struct JournalCommandOptions {
  std::string diameter = "10 mm", length = "", clearance = "15 um";
  double ld = 0.0;                    ///< L/D, alternative to length
  std::string viscosity = "", temperature = "90 degC";
  std::string speed = "60000 rpm", outer_speed = "0 rpm";
  double eccentricity = 0.5;          ///< e/c
  std::string attitude = "0 deg";     ///< direction of the eccentricity vector from +x towards +y
  std::string cavitation = "gumbel";
  int n_circ = 60, n_axial = 12;
  std::string supply_pressure = "0 Pa", hole_diameter = "0 mm";
  std::string groove_width = "0 mm";  ///< full circumferential feed groove at mid-width, instead of the hole
};

/// Prints the JSON result to stdout; returns the exit code.
int run_journal_command(const JournalCommandOptions& o);

}  // namespace turbodyn::app

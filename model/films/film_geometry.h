// The film geometry of a plain film spec, shared by the journal bearing and both damper elements.
#pragma once

#include "model/films/reynolds.h"

namespace turbodyn {

/// Film geometry and solver options of a plain film spec (JournalBearingSpec, DamperSpec: diameter, length,
/// clearance, grid, feed hole or central feed groove, cavitation; end seals for dampers).
template <class Film>
reynolds::FilmGeometry film_geometry(const Film& f, reynolds::SolverOptions& options) {
  reynolds::FilmGeometry g;
  g.radius = 0.5 * f.diameter;
  g.length = f.length;
  g.clearance = f.clearance;
  g.n_circ = f.n_circ;
  g.n_axial = f.n_axial;
  if (f.feed_hole_diameter > 0.0) g.holes.push_back({f.feed_hole_angle, 0.0, f.feed_hole_diameter, f.supply_pressure});
  if (f.feed_groove_width > 0.0) g.grooves.push_back({0.0, f.feed_groove_width, f.supply_pressure});
  if constexpr (requires { f.end_seal_gap; }) {  // dampers
    g.end_seal_gap = f.end_seal_gap;
    g.end_seal_length = f.end_seal_length;
  }
  options.cavitation = f.cavitation;
  options.axial_grading = f.axial_grading;
  return g;
}

}  // namespace turbodyn

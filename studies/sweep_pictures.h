// The pictures of a parameter study (docs/studies.md, "Results"): a tornado chart of the standardised sensitivities
// per metric, each metric against each parameter with incomplete and failed runs marked, and for two-parameter
// designs a filled contour map of each metric with the runs on it. Values in the units the pictures use for their
// quantity (post::display_of: displacements in µm); parameters in the study's units.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "studies/design.h"
#include "studies/study.h"
#include "studies/run_evaluation.h"

namespace turbodyn::studies {

/// Tornado chart of one metric into `png`: one horizontal bar per parameter, sorted by the size of its standardised
/// regression coefficient, labelled with the parameter and the range it spans in the design.
void draw_tornado(const StudySpec& study, const Design& design, std::size_t metric, const Sensitivity& s,
                  const std::filesystem::path& png);

/// Metric `metric` (SI unit `unit`) against parameter `parameter`: complete runs as dots, incomplete runs (the
/// integrator gave up or a stability analysis stopped; the metric covers the part that ran) as triangles, failed
/// runs (no value) as crosses on the lower edge of the data. Returns false when no run has a value (nothing drawn).
bool draw_metric_scatter(const StudySpec& study, const Design& design, const std::vector<RunRecord>& runs,
                         std::size_t metric, std::size_t parameter, const std::string& unit,
                         const std::filesystem::path& png);

/// Filled contour map of metric `metric` over the two parameters of a two-parameter design, with the runs on it.
/// A full factorial grid is interpolated bilinearly; other designs by inverse-distance weighting (Shepard, power 2)
/// on axes scaled to the design's ranges, which honours every run's value. Needs three runs with a value; returns
/// false otherwise (nothing drawn).
bool draw_metric_map(const StudySpec& study, const Design& design, const std::vector<RunRecord>& runs,
                     std::size_t metric, const std::string& unit, const std::filesystem::path& png);

/// The value at (x, y) of the inverse-distance-weighted interpolation (power 2) of the points (xs, ys, zs) on
/// axes scaled by `sx`, `sy` (exact at a point). Exposed for the tests.
double shepard(const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs, double x,
               double y, double sx, double sy);

}  // namespace turbodyn::studies

// What an optimisation writes: the history table, the result summary and the convergence plot.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "optim/optimizer.h"

namespace turbodyn::optim {

/// history.csv: one row per request (design values in the study's units, metrics per case, objective, constraint
/// values and normalised g per case, feasible, status, wall time).
void write_history_csv(const OptimizationSpec& spec, const OptimizationResult& r, const std::filesystem::path& file);

/// The content of result.json: algorithm as run, NLopt result and reason, counts, the initial and the best design
/// with objective, constraints and metrics.
nlohmann::json result_json(const OptimizationSpec& spec, const OptimizationResult& r);

/// convergence.png: objective of every proposed design and the best feasible objective so far against the request.
void write_convergence_plot(const OptimizationSpec& spec, const OptimizationResult& r, const std::filesystem::path& png);

}  // namespace turbodyn::optim

// The summary of a run-up (summary.json, docs/output-format.md), shared by `turbodyn run` and the studies.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/io/model_file.h"
#include "model/engine/integrator.h"

namespace turbodyn {

/// Everything of summary.json except the pictures and warnings: model, overrides, options, statistics, energy
/// balance, and per probe the maximum absolute value with the time and speed where it occurs.
nlohmann::json run_summary(const MachineSpec& spec, const RunupModel& model, const RunupOptions& options,
                           const RunupResult& result, const std::vector<Override>& overrides);

/// One warning per probe of `summary` (run_summary's) that passes its limit (ProbeInfo::limit): the probe, the limit,
/// the speed and time it is first passed, the largest value and what passing it means.
std::vector<std::string> probe_limit_warnings(const nlohmann::json& summary);

/// The same in one line for a study's run (`note` of results.csv): each such probe, the limit, the speed where it is
/// first passed and its largest value, joined by "; "; empty if none passes its limit.
std::string probe_limit_note(const nlohmann::json& summary);

}  // namespace turbodyn

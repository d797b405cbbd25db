// The results of an identification on disk (docs/identification.md, "Results"): estimates.json, ceres_summary.txt,
// fitted.toml (the base model with the fixed overrides and the estimates applied: a ready-to-run model file that keeps
// the comments of the base model where the values can be patched in place, see write_patched_model),
// features.csv and the pictures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "identification/identify.h"
#include "model/io/overrides.h"

namespace turbodyn::identification {

/// estimates.json as a JSON value.
nlohmann::json estimates_json(const IdentifyStudy& study, const IdentifyResult& result);

/// Writes every result file into dir (created if needed); returns the names of the files written. Pictures that
/// cannot be drawn (no gnuplot) are skipped with a warning added to `warnings`.
std::vector<std::string> write_identify_results(const IdentifyStudy& study, const IdentifyResult& result,
                                                const std::filesystem::path& dir, bool plots,
                                                std::vector<std::string>& warnings);

}  // namespace turbodyn::identification

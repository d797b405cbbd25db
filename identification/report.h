// The results of an identification on disk (docs/identification.md, "Results"): estimates.json, ceres_summary.txt,
// fitted.toml (the base model with the fixed overrides and the estimates applied: a ready-to-run model file),
// features.csv and the pictures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "identification/identify.h"
#include "model/io/model_file.h"

namespace turbodyn::identification {

/// estimates.json as a JSON value.
nlohmann::json estimates_json(const IdentifyStudy& study, const IdentifyResult& result);

/// Writes the base model file with `overrides` applied to `file` (TOML; comments of the base file are not kept) and
/// checks that it loads. Paths use the --set syntax (dotted keys, name[i]); missing tables are created.
void write_model_with_overrides(const std::filesystem::path& base, const std::vector<Override>& overrides,
                                const std::filesystem::path& file, const std::string& header_comment);

/// Writes every result file into dir (created if needed); returns the names of the files written. Pictures that
/// cannot be drawn (no gnuplot) are skipped with a warning added to `warnings`.
std::vector<std::string> write_identify_results(const IdentifyStudy& study, const IdentifyResult& result,
                                                const std::filesystem::path& dir, bool plots,
                                                std::vector<std::string>& warnings);

}  // namespace turbodyn::identification

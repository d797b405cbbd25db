// Reading a machine from a TOML model file (docs/model-format.md), with command-line overrides.
//
// Every error names where the problem is (file:line:column, or "--set" for an override), the full key path and
// what was expected; unknown keys are errors with a "did you mean" suggestion.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/io/overrides.h"
#include "model/spec/errors.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

/// Reads and validates a model file, applying the overrides first (so they are validated like file values).
MachineSpec load_model(const std::filesystem::path& file, const std::vector<Override>& overrides = {});

/// Same, from TOML text; `source_name` is used in messages and as MachineSpec::source.
MachineSpec load_model_from_string(const std::string& toml_text, const std::string& source_name,
                                   const std::vector<Override>& overrides = {});

/// Every key the loader accepts, in generic form: the key paths it asks for while loading every model file in
/// `examples_dir` (a TOML file with a [[shaft]] array; study, optimisation and identification files are skipped) and
/// a built-in model that visits the tables the examples leave out. Named entries read as NAME and array entries as
/// [] (`materials.NAME.E`, `shaft[].length`, `disks.NAME.unbalance`, `bearings.NAME.damper.clearance`); a bearing's
/// own keys carry its type (`bearings.NAME[type=ball].preload`). Sorted, without duplicates; for the test that
/// docs/model-format.md documents them all. Throws ModelError if a model does not load.
std::vector<std::string> accepted_model_keys(const std::filesystem::path& examples_dir);

/// The key paths the loader reads as numbers from `file` with `overrides` applied, in --set syntax
/// ("shaft[2].length", "bearings.compressor.kxx", "bearings.turbine.damper.clearance"), present in the file or not:
/// the keys a study, an optimisation or an identification may vary. Throws ModelError if the model does not load.
std::vector<std::string> numeric_model_keys(const std::filesystem::path& file, const std::vector<Override>& overrides);
/// Same, from TOML text (`source_name` as for load_model_from_string).
std::vector<std::string> numeric_model_keys_from_string(const std::string& toml_text, const std::string& source_name,
                                                        const std::vector<Override>& overrides);

/// Levenshtein distance (for "did you mean" suggestions).
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The closest candidate to `word` if it is close enough to be a plausible typo, else "".
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace turbodyn

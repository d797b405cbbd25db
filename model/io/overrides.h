// Command-line overrides (`--set PATH=VALUE`): their grammar, and the model file with overrides applied as a file
// of its own (best.toml of `turbodyn optimize`, fitted.toml of `turbodyn identify`).
//
// The model loader applies overrides to the parsed TOML tree (model/io/overrides_toml.h); this header keeps
// toml++ out of the many files that only pass overrides around.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/spec/errors.h"

namespace turbodyn {

/// One `--set PATH=VALUE` override. PATH uses the model-file key syntax: dotted table keys, and `name[i]` (0-based)
/// for the i-th entry of an array of tables, e.g. `bearings.compressor.kxx`, `shaft[2].outer_diameter`.
/// VALUE is read as a TOML value (number, boolean, quoted string, array); anything that is not valid TOML is taken
/// as a plain string, so `--set disks.turbine.unbalance=580 mg*mm` needs no quotes.
struct Override {
  std::string path;
  std::string value;
};

/// Splits "PATH=VALUE"; throws ModelError when there is no '=' or the path is empty.
Override parse_override(const std::string& assignment);

/// One step of an override's PATH: a table key, or with `index` the entry of the array of tables `key`.
struct OverrideStep {
  std::string key;
  std::optional<std::size_t> index;  ///< 0-based, for `key[index]`
};

/// The steps of `o.path`. Throws ModelError naming the override ("--set PATH=VALUE") and the cause for an empty
/// key, an unclosed bracket, or an index that is not a whole number >= 0. Whether an index lies within its array
/// is checked where the override is applied.
std::vector<OverrideStep> override_steps(const Override& o);

/// The model file `base` with `overrides` applied, preceded by `header` (every line written as a comment, then an
/// empty line). Values the file holds on one line are replaced in place and keys it lacks are added as a line of
/// their table, so comments and layout stay; where that is not possible (a table the file lacks, an inline table,
/// a whole table or array replaced, an edit that would not give the same TOML tree) the whole tree is written out
/// by toml++ instead (comments lost, values identical). Overrides apply as in load_model (the last of the same key
/// wins). The result is checked with the model loader: throws ModelError if it does not load or an override does
/// not apply.
std::string patched_model(const std::filesystem::path& base, const std::vector<Override>& overrides,
                          const std::string& header);

/// Same from model text; `source_name` names it in messages.
std::string patched_model_text(const std::string& text, const std::string& source_name,
                               const std::vector<Override>& overrides, const std::string& header);

/// Writes patched_model(base, overrides, header) to `file`; throws ModelError if it cannot be written.
void write_patched_model(const std::filesystem::path& base, const std::vector<Override>& overrides,
                         const std::string& header, const std::filesystem::path& file);
/// Same from model text (patched_model_text).
void write_patched_model_text(const std::string& text, const std::string& source_name,
                              const std::vector<Override>& overrides, const std::string& header,
                              const std::filesystem::path& file);

}  // namespace turbodyn

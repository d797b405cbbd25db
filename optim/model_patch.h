// A ready-to-run model file with overrides applied: how the optimiser writes its best design (best.toml).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"

namespace turbodyn::optim {

/// The text of `base` with `overrides` (--set syntax) applied, preceded by `header` (each line written as a
/// comment). Values that exist in the file on one line are replaced in place and keys the file lacks are added as
/// a line in their table, so comments and layout stay; where that is not possible (a new table, an inline table,
/// or an edit that would not give the same TOML tree) the whole tree is written out by toml++ instead (comments
/// lost, values identical). The result is checked with the model loader; throws
/// ModelError if it does not load.
std::string patched_model(const std::filesystem::path& base, const std::vector<Override>& overrides,
                          const std::string& header);

}  // namespace turbodyn::optim

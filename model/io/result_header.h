// The fields every result file of a model command begins with (docs/output-format.md): the program's version, the
// model's name and source file, and the `--set` overrides applied to it.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "model/io/overrides.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

/// The version of this build, "MAJOR.MINOR.PATCH" (CMake's project version).
const char* turbodyn_version();

/// {"turbodyn_version": ..., "model": {"name", "source"}, "overrides": ["path=value", ...]}; callers add their own
/// entries to "model" and the rest of the file.
nlohmann::json result_header(const MachineSpec& spec, const std::vector<Override>& overrides);

}  // namespace turbodyn

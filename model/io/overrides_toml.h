// Overrides applied to a parsed TOML tree, for the readers of model/io (the only users of toml++; see overrides.h).
#pragma once

#include <toml++/toml.h>

#include "model/io/model_file.h"  // closest_match, which toml_reader.h uses
#include "model/io/overrides.h"
#include "model/io/toml_reader.h"

namespace turbodyn {

/// Sets the value of `o` at its path in `root`, creating missing tables. Errors are ModelErrors that start with
/// "--set PATH=VALUE: ": a malformed path (override_steps), an index into something that is not an array, an index
/// out of range, a step through a value. With `sources`, every node the override puts into the tree is recorded
/// there, so that the loader's messages name the override instead of a file position.
void apply_override(toml::table& root, const Override& o, input::Sources* sources = nullptr);

}  // namespace turbodyn

// The command line the program was started with, for the reports (report.html shows what made the results).
#pragma once

#include <string>

namespace turbodyn::app {

/// Records argv; main() calls it first.
void set_command_line(int argc, const char* const* argv);

/// "turbodyn run examples/reference_linear.toml -o out/run": the program's base name and the arguments, each
/// argument that a shell would split or expand single-quoted.
const std::string& command_line();

}  // namespace turbodyn::app

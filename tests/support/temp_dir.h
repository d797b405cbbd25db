// Scratch directories for tests that write files.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace turbodyn::testing {

/// An empty directory TMPDIR/turbodyn_NAME for a test's files (what an earlier run left there is removed first).
inline std::filesystem::path fresh_temp_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("turbodyn_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The whole content of the file at `path` ("" if it cannot be read).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace turbodyn::testing

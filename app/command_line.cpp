#include "app/command_line.h"

#include <filesystem>

namespace turbodyn::app {
namespace {

std::string g_command_line = "turbodyn";

std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                        "0123456789_-.,/:=+@%") == std::string::npos;
  if (plain) return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void set_command_line(int argc, const char* const* argv) {
  std::string s = argc > 0 ? std::filesystem::path(argv[0]).filename().string() : "turbodyn";
  for (int i = 1; i < argc; ++i) s += " " + shell_word(argv[i]);
  g_command_line = s;
}

const std::string& command_line() { return g_command_line; }

}  // namespace turbodyn::app

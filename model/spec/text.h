#pragma once
// Small text helpers for the readers of options, studies and measurement files.

#include <string>
#include <string_view>

namespace turbodyn {

/// `s` without the spaces, tabs, carriage returns and line feeds at its ends ("" if it has nothing else).
inline std::string trim_blanks(std::string_view s) {
  constexpr std::string_view kBlanks = " \t\r\n";
  const std::size_t a = s.find_first_not_of(kBlanks);
  if (a == std::string_view::npos) return {};
  return std::string(s.substr(a, s.find_last_not_of(kBlanks) - a + 1));
}

}  // namespace turbodyn

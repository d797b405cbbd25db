#pragma once
// An enum's names in one table, so that printing a value and reading a name cannot disagree:
//   constexpr EnumName<Loss> kLosses[] = {{Loss::None, "none"}, {Loss::Huber, "huber"}};
//   name_of(kLosses, Loss::Huber) == "huber";  value_of(kLosses, "none", loss) sets loss and returns true.
// input::Reader::enumeration reads a key whose value must be one of the names.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace turbodyn {

template <class Enum>
using EnumName = std::pair<Enum, std::string_view>;

/// The name of `value`, "unknown" for a value the table does not hold.
template <class Enum, std::size_t N>
std::string name_of(const EnumName<Enum> (&names)[N], Enum value) {
  for (const auto& [v, name] : names)
    if (v == value) return std::string(name);
  return "unknown";
}

/// Sets `value` to the enum called `name`; false (value untouched) if no entry has that name.
template <class Enum, std::size_t N>
bool value_of(const EnumName<Enum> (&names)[N], std::string_view name, Enum& value) {
  for (const auto& [v, n] : names)
    if (n == name) {
      value = v;
      return true;
    }
  return false;
}

/// All names, in table order (for "expected one of ..." messages).
template <class Enum, std::size_t N>
std::vector<std::string> names_of(const EnumName<Enum> (&names)[N]) {
  std::vector<std::string> out;
  for (const auto& entry : names) out.emplace_back(entry.second);
  return out;
}

}  // namespace turbodyn

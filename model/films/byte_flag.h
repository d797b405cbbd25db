// A one-byte flag for per-node arrays in the films' inner loops.
#pragma once

#include <cstdint>

namespace turbodyn::reynolds {

// Holds 0..255 like std::uint8_t and converts to and from int, but is not a character type. A store through an
// unsigned char may alias any object, so in a loop that writes a std::vector<std::uint8_t> GCC reloads the data
// pointer of every other vector and every member it reads after each store, and cannot vectorise the loop. A store
// to this struct does not alias a double, an int or a pointer, so those stay in registers. Same values, same
// arithmetic: results are bit for bit those of std::uint8_t (bench/README.md, "Issue 19: the films' flag arrays").
struct ByteFlag {
  std::uint8_t v = 0;
  constexpr ByteFlag(int x = 0) : v(static_cast<std::uint8_t>(x)) {}  // NOLINT: implicit, as for std::uint8_t
  constexpr operator int() const { return v; }                         // NOLINT
};
static_assert(sizeof(ByteFlag) == 1);

}  // namespace turbodyn::reynolds

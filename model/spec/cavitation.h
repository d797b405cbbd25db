// The cavitation models of a hydrodynamic film, as the specs name them and the Reynolds solver (model/films/reynolds.h)
// applies them. In a header of its own so that the solver does not depend on the machine specs.
#pragma once

#include <string>
#include <string_view>

namespace turbodyn {

enum class Cavitation {
  None,           ///< full Sommerfeld: p may go below the cavitation pressure (and negative)
  Gumbel,         ///< p >= p_cav as a complementarity problem (Swift-Stieber / Reynolds conditions), not a clamp
  MassConserving  ///< JFO (Elrod-Adams): p >= p_cav, film fraction 0 <= theta <= 1, p_cav < p only where theta = 1
};

/// Model-file and command-line name: "none", "gumbel", "mass-conserving".
std::string to_string(Cavitation c);
/// Sets c from its model-file name; false (c untouched) for any other name.
bool from_string(std::string_view name, Cavitation& c);

}  // namespace turbodyn

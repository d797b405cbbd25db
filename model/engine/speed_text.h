// A rotor speed as the engine's messages write it.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "model/spec/constants.h"

namespace turbodyn {

/// "123456 rpm" for a speed in rad/s.
inline std::string rpm_text(double speed) {
  std::ostringstream os;
  os << std::llround(speed * kRadPerSToRpm) << " rpm";
  return os.str();
}

}  // namespace turbodyn

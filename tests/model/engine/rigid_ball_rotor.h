// The test rotor of the closed-form checks of the synchronous whirl (backbone_test.cpp, unbalance_whirl_test.cpp):
// examples/reference_ball.toml made a rigid rotor symmetric about its middle (equal wheels, mirrored bearings), with
// a shaft of 14 mm and 1e14 Pa (476 times steel's modulus) that leaves the bending at the 1e-3 level.
#pragma once

#include <string>
#include <vector>

#include "model/io/model_file.h"
#include "model/io/overrides.h"
#include "tests/support/test_support.h"

namespace turbodyn::testing {

/// `extra` overrides are applied after the rotor's own.
inline MachineSpec rigid_symmetric_ball_rotor(const std::vector<std::string>& extra = {}) {
  std::vector<Override> o;
  for (const char* s : {"materials.steel.E=1e14 Pa", "shaft[0].outer_diameter=14 mm", "disks.compressor.z=35 mm",
                        "disks.turbine.z=105 mm", "disks.turbine.mass=0.119 kg",
                        "disks.turbine.polar_inertia=2.5e-5 kg*m^2", "disks.turbine.diametral_inertia=1.6e-5 kg*m^2",
                        "bearings.compressor.z=47.5 mm", "bearings.turbine.z=92.5 mm"})
    o.push_back(parse_override(s));
  for (const std::string& s : extra) o.push_back(parse_override(s));
  return load_model(source_dir() + "/examples/reference_ball.toml", o);
}

}  // namespace turbodyn::testing

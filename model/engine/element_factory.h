// The force elements of a machine: one per bearing, chosen by the bearing's type.
#pragma once

#include <memory>
#include <vector>

#include "model/elements/force_element.h"
#include "model/rotor/rotor.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

/// One force element per bearing of spec, attached to the rotor's DOFs: the rotor's linear bearings first (on a
/// pedestal or in a squeeze-film damper as the spec says), then the nonlinear bearings in the spec's order.
std::vector<std::unique_ptr<ForceElement>> make_force_elements(const MachineSpec& spec, const Rotor& rotor);

}  // namespace turbodyn

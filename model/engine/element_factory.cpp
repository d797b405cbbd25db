#include "model/engine/element_factory.h"

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_damper_element.h"
#include "model/elements/damper_element.h"
#include "model/elements/floating_ring_element.h"
#include "model/elements/journal_bearing_element.h"
#include "model/elements/linear_bearing_element.h"

namespace turbodyn {

std::vector<std::unique_ptr<ForceElement>> make_force_elements(const MachineSpec& spec, const Rotor& rotor) {
  std::vector<std::unique_ptr<ForceElement>> elements;
  for (const LinearBearing& b : rotor.bearings) {
    Pedestal pedestal;
    const DamperSpec* damper = nullptr;
    for (const BearingSpec& bs : spec.bearings)
      if (bs.name == b.name) {
        pedestal = Pedestal{bs.pedestal_mass, bs.pedestal_stiffness, bs.pedestal_damping};
        if (bs.damper.enabled) damper = &bs.damper;
      }
    if (damper)
      elements.push_back(std::make_unique<DamperElement>(b, rotor.dof(b.node, kX), *damper, spec.oil, spec.gravity));
    else
      elements.push_back(std::make_unique<LinearBearingElement>(b, rotor.dof(b.node, kX), pedestal, spec.gravity));
  }
  for (const BearingSpec& b : spec.bearings) {
    const int dof = rotor.dof(rotor.node_at(b.z), kX);
    switch (b.type) {
      case BearingType::Linear: break;  // built above from the rotor's linear bearings
      case BearingType::Journal:
        elements.push_back(std::make_unique<JournalBearingElement>(b.name, b.journal, spec.oil, dof));
        break;
      case BearingType::FloatingRing:
        elements.push_back(std::make_unique<FloatingRingElement>(b.name, b.ring, spec.oil, dof, spec.gravity));
        break;
      case BearingType::Ball:
        if (b.damper.enabled)
          elements.push_back(
              std::make_unique<BallDamperElement>(b.name, b.ball, b.damper, spec.oil, dof, spec.gravity));
        else
          elements.push_back(std::make_unique<BallBearingElement>(b.name, b.ball, dof, spec.gravity));
        break;
    }
  }
  return elements;
}

}  // namespace turbodyn

#include "model/engine/element_factory.h"

#include <stdexcept>
#include <string>

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_damper_element.h"
#include "model/elements/damper_element.h"
#include "model/elements/floating_ring_element.h"
#include "model/elements/journal_bearing_element.h"
#include "model/elements/linear_bearing_element.h"
#include "model/spec/errors.h"

namespace turbodyn {
namespace {

// An element refuses inconsistent input with std::invalid_argument ("reynolds::FilmSolver: grid must be ..."); the
// model loader's checks should have caught it, but if one slips through the user still learns which bearing of
// which file it is.
template <class Make>
void add_element(std::vector<std::unique_ptr<ForceElement>>& out, const MachineSpec& spec, const std::string& name,
                 Make make) {
  try {
    out.push_back(make());
  } catch (const std::invalid_argument& e) {
    throw ModelError(spec.source.string() + ": bearings." + name + ": " + e.what());
  }
}

}  // namespace

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
    add_element(elements, spec, b.name, [&]() -> std::unique_ptr<ForceElement> {
      if (damper) return std::make_unique<DamperElement>(b, rotor.dof(b.node, kX), *damper, spec.oil, spec.gravity);
      return std::make_unique<LinearBearingElement>(b, rotor.dof(b.node, kX), pedestal, spec.gravity);
    });
  }
  for (const BearingSpec& b : spec.bearings) {
    const int dof = rotor.dof(rotor.node_at(b.z), kX);
    switch (b.type) {
      case BearingType::Linear: break;  // built above from the rotor's linear bearings
      case BearingType::Journal:
        add_element(elements, spec, b.name,
                    [&] { return std::make_unique<JournalBearingElement>(b.name, b.journal, spec.oil, dof); });
        break;
      case BearingType::FloatingRing:
        add_element(elements, spec, b.name, [&] {
          return std::make_unique<FloatingRingElement>(b.name, b.ring, spec.oil, dof, spec.gravity);
        });
        break;
      case BearingType::Ball:
        add_element(elements, spec, b.name, [&]() -> std::unique_ptr<ForceElement> {
          if (b.damper.enabled)
            return std::make_unique<BallDamperElement>(b.name, b.ball, b.damper, spec.oil, dof, spec.gravity);
          return std::make_unique<BallBearingElement>(b.name, b.ball, dof, spec.gravity);
        });
        break;
    }
  }
  return elements;
}

}  // namespace turbodyn

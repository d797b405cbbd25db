// A general state of the floating-ring element, shared by its tests.
#pragma once

#include <algorithm>

#include "model/elements/floating_ring_element.h"

namespace turbodyn::testing {

/// Journal off-centre, moving and tilted in the ring; the ring off-centre, moving, tilted and spinning (angle 0).
/// z holds FloatingRingElement::kMaxStates values; the film temperatures (thermal films only) are left at 0.
inline void general_ring_state(double* q, double* v, double* z) {
  using E = FloatingRingElement;
  const double qq[4] = {4e-6, -3e-6, 2e-4, -1.5e-4}, vv[4] = {2e-3, 1e-3, 0.05, -0.08};
  std::copy(qq, qq + 4, q);
  std::copy(vv, vv + 4, v);
  std::fill(z, z + E::kMaxStates, 0.0);
  z[E::kX] = 1e-5;
  z[E::kY] = -6e-6;
  z[E::kVx] = -1e-3;
  z[E::kVy] = 3e-3;
  z[E::kAx] = 1e-4;
  z[E::kAy] = 5e-5;
  z[E::kWx] = 0.02;
  z[E::kWy] = -0.03;
  z[E::kSpin] = 900.0;
}

}  // namespace turbodyn::testing

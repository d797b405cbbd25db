// The reference ball bearing and a plain evaluator of its element, shared by the ball-bearing tests.
#pragma once

#include <cmath>
#include <memory>

#include "model/elements/ball/ball_bearing.h"

namespace turbodyn::testing {

inline constexpr double kRpm = 2.0 * M_PI / 60.0;  // rad/s per rpm

// The reference bearing of docs/reference-machine.md, variant II (the spec defaults).
inline BallBearingSpec reference_bearing() { return BallBearingSpec{}; }

// Element state derivatives with the shaft held at (q, v) and spinning at `speed`.
struct Evaluator {
  const BallBearingElement& e;
  std::unique_ptr<ElementWorkspace> ws;
  explicit Evaluator(const BallBearingElement& el) : e(el), ws(el.make_workspace()) {}
  void operator()(double speed, const double* q, const double* v, const double* z, double* f, double* zdot) {
    for (int i = 0; i < 4; ++i) f[i] = 0.0;
    e.calc_and_add_forces(SpinState{0.0, speed, 0.0, 0.0}, q, v, z, *ws, f, zdot);
  }
};

}  // namespace turbodyn::testing

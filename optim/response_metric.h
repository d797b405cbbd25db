// Steady-state metrics of the linear rotor: the largest synchronous unbalance response over a speed window, from
// the frequency-domain solution of model/rotor/response.h. Smooth in the parameters and far cheaper than a run-up, so an
// optimiser can use them where a linear model suffices (and where a closed form exists to test against).
#pragma once

#include "model/rotor/rotor.h"
#include "studies/study.h"

namespace turbodyn::optim {

/// Probe of a response metric: "disk.NAME" (major semi-axis of the 1x orbit, m), "disk.NAME.x"/".y" (amplitude,
/// m), "bearing.NAME" (major semi-axis of the transmitted force, N), "bearing.NAME.fx"/".fy" (amplitude, N).
/// Kind "response_peak": the largest value over [m.speed_min, m.speed_max]; "response_peak_speed": the speed
/// where it occurs, in rpm. The peak is found on an even grid of `points` speeds and then refined by golden-section
/// search between the neighbours of the largest grid value (to a relative speed tolerance of 1e-10).
/// Throws std::invalid_argument for an unknown probe, std::runtime_error for a singular dynamic stiffness.
double response_metric(const studies::MetricSpec& m, int points, const Rotor& rotor);

}  // namespace turbodyn::optim

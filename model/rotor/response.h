// Steady-state synchronous unbalance response of the linear rotor (frequency domain).
//
// At constant speed Omega the unbalance U at angle beta gives F = U Omega^2 (cos(Omega t + beta),
// sin(Omega t + beta)); with q = Re(Q e^{i Omega t}):
//   (K + K_b - Omega^2 M + i Omega (D + C_b + Omega G)) Q = F,   F_x = U Omega^2 e^{i beta}, F_y = -i F_x.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Dense>

#include "model/rotor/rotor.h"

namespace turbodyn {

struct SteadyResponse {
  double speed = 0.0;         ///< rad/s
  Eigen::VectorXcd q;         ///< complex amplitudes of all DOFs (x = Re(Q_x e^{i Omega t}))
  /// Per bearing: complex amplitudes of the force transmitted to the housing, x and y.
  std::vector<std::complex<double>> bearing_fx, bearing_fy;
};

/// Response at one speed; throws std::runtime_error if the dynamic stiffness is singular.
SteadyResponse unbalance_response(const Rotor& rotor, double speed);

/// Amplitude of the 1x orbit's major semi-axis from the complex amplitudes of x and y.
double major_semi_axis(std::complex<double> x, std::complex<double> y);

}  // namespace turbodyn

#include "model/rotor/response.h"

#include <cmath>
#include <stdexcept>

namespace turbodyn {

SteadyResponse unbalance_response(const Rotor& rotor, double speed) {
  const int n = rotor.n_dof;
  Eigen::MatrixXd K = rotor.K, C = rotor.D;
  rotor.add_bearings(speed, K, C);
  const std::complex<double> I(0.0, 1.0);
  Eigen::MatrixXcd Z = (K - speed * speed * rotor.M).cast<std::complex<double>>() +
                       I * speed * (C + speed * rotor.G).cast<std::complex<double>>();
  Eigen::VectorXcd F = Eigen::VectorXcd::Zero(n);
  for (const RigidDisk& d : rotor.disks) {
    const std::complex<double> fx = d.unbalance * speed * speed * std::exp(I * d.unbalance_phase);
    F(rotor.dof(d.node, kX)) += fx;
    F(rotor.dof(d.node, kY)) += -I * fx;
  }
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Z);
  SteadyResponse r;
  r.speed = speed;
  r.q = lu.solve(F);
  if (!r.q.allFinite()) throw std::runtime_error("the dynamic stiffness matrix is singular at this speed");
  // A bearing's force on all 4 DOFs of its node (a ball bearing's linearisation couples translation and tilt; a
  // table has zeros outside the x, y block).
  Eigen::Matrix4d k, c;
  for (const LinearBearing& b : rotor.bearings) {
    b.coefficients(speed, k, c);
    const int i = rotor.dof(b.node, kX);
    const Eigen::Vector4cd u = r.q.segment<4>(i);
    const Eigen::Vector4cd f = (k.cast<std::complex<double>>() + I * speed * c.cast<std::complex<double>>()) * u;
    r.bearing_fx.push_back(f(0));
    r.bearing_fy.push_back(f(1));
  }
  return r;
}

double major_semi_axis(std::complex<double> x, std::complex<double> y) {
  const double p = std::norm(x) + std::norm(y);
  const double q = std::abs(x * x + y * y);
  return std::sqrt(0.5 * (p + q));
}

}  // namespace turbodyn

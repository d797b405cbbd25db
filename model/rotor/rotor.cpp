#include "model/rotor/rotor.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/spec/errors.h"
#include "model/spec/limits.h"

namespace turbodyn {
namespace {

constexpr double kNodeMergeTolerance = 1e-9;  // m: positions closer than this are one node

double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (ys.size() == 1 || x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  const std::size_t j = static_cast<std::size_t>(it - xs.begin());
  const double t = (x - xs[j - 1]) / (xs[j] - xs[j - 1]);
  return ys[j - 1] + t * (ys[j] - ys[j - 1]);
}

double shear_factor_for(const MachineSpec& spec, const ShaftSection& s, std::size_t index) {
  const Material& mat = spec.materials.at(s.material);
  const double ratio = s.inner_diameter / s.outer_diameter;
  switch (spec.mesh.shear_factor_formula) {
    case ShearFactorFormula::Given: return spec.mesh.shear_factor;
    case ShearFactorFormula::Cowper: return cowper_shear_factor(mat.poisson_ratio, ratio);
    case ShearFactorFormula::Hutchinson:
      if (ratio > 0.0)
        throw ModelError(spec.source.string() + ": mesh.shear_factor: the Hutchinson formula is implemented for solid "
                         "sections only, but shaft[" + std::to_string(index) + "] is hollow; use \"cowper\" or a number");
      return hutchinson_shear_factor_solid(mat.poisson_ratio);
  }
  return 1.0;
}

}  // namespace

void LinearBearing::coefficients(double speed, Eigen::Matrix2d& k, Eigen::Matrix2d& c) const {
  if (linearisation) {
    Eigen::Matrix4d k4, c4;
    linearisation(speed, k4, c4);
    k = k4.topLeftCorner<2, 2>();
    c = c4.topLeftCorner<2, 2>();
    return;
  }
  for (int i = 0; i < 4; ++i) {
    k(i / 2, i % 2) = interpolate(table.speeds, table.k[i], speed);
    c(i / 2, i % 2) = interpolate(table.speeds, table.c[i], speed);
  }
}

int Rotor::node_at(double z) const {
  for (std::size_t i = 0; i < node_z.size(); ++i)
    if (std::abs(node_z[i] - z) <= kNodeMergeTolerance) return static_cast<int>(i);
  throw std::out_of_range("no node at z = " + std::to_string(z) + " m");
}

void LinearBearing::coefficients(double speed, Eigen::Matrix4d& k, Eigen::Matrix4d& c) const {
  if (linearisation) {
    linearisation(speed, k, c);
    return;
  }
  Eigen::Matrix2d k2, c2;
  coefficients(speed, k2, c2);
  k.setZero();
  c.setZero();
  k.topLeftCorner<2, 2>() = k2;
  c.topLeftCorner<2, 2>() = c2;
}

void Rotor::add_bearings(double speed, Eigen::MatrixXd& K_total, Eigen::MatrixXd& D_total) const {
  for (const LinearBearing& b : bearings) {
    const int i = dof(b.node, kX);
    if (b.linearisation) {
      Eigen::Matrix4d k, c;
      b.linearisation(speed, k, c);
      K_total.block<4, 4>(i, i) += k;
      D_total.block<4, 4>(i, i) += c;
    } else {  // a table: only the x, y block, exactly as before the 4-DOF coefficients
      Eigen::Matrix2d k, c;
      b.coefficients(speed, k, c);
      K_total.block<2, 2>(i, i) += k;
      D_total.block<2, 2>(i, i) += c;
    }
  }
}

Eigen::MatrixXd Rotor::quarter_turn() const {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n_dof, n_dof);
  for (int i = 0; i < n_dof; i += 2) {
    J(i + 1, i) = 1.0;
    J(i, i + 1) = -1.0;
  }
  return J;
}

Eigen::MatrixXd Rotor::rotating_frame_gyroscopic() const { return G + 2.0 * M * quarter_turn(); }

Eigen::MatrixXd Rotor::spin_softening() const { return -M + G * quarter_turn(); }

Rotor build_rotor(const MachineSpec& spec) {
  if (spec.shaft.empty()) throw ModelError(spec.source.string() + ": the model has no shaft sections");
  Rotor r;
  const double length = spec.shaft_length();

  // Key positions: section ends, disks, bearings; then subdivide to the maximum element length.
  std::vector<double> keys{0.0};
  for (const ShaftSection& s : spec.shaft) keys.push_back(s.z_start + s.length);
  for (const DiskSpec& d : spec.disks) keys.push_back(std::clamp(d.z, 0.0, length));
  for (const BearingSpec& b : spec.bearings) keys.push_back(std::clamp(b.z, 0.0, length));
  std::sort(keys.begin(), keys.end());
  std::vector<double> unique;
  for (double z : keys)
    if (unique.empty() || z - unique.back() > kNodeMergeTolerance) unique.push_back(z);
  double elements = 0.0;
  for (std::size_t i = 1; i < unique.size(); ++i)
    elements += std::max(1.0, std::ceil((unique[i] - unique[i - 1]) / spec.mesh.max_element_length - 1e-9));
  if (!(elements <= static_cast<double>(limits::kMaxShaftElements)))
    throw ModelError(spec.source.string() + ": mesh.max_element_length: the mesh would have about " +
                     std::to_string(elements) + " elements, more than the limit of " +
                     std::to_string(limits::kMaxShaftElements));
  r.node_z.push_back(unique.front());
  for (std::size_t i = 1; i < unique.size(); ++i) {
    const double span = unique[i] - unique[i - 1];
    const int n = std::max(1, static_cast<int>(std::ceil(span / spec.mesh.max_element_length - 1e-9)));
    for (int j = 1; j <= n; ++j) r.node_z.push_back(j == n ? unique[i] : unique[i - 1] + span * j / n);
  }
  const int n_nodes = static_cast<int>(r.node_z.size());
  r.n_dof = kDofPerNode * n_nodes;
  r.M = Eigen::MatrixXd::Zero(r.n_dof, r.n_dof);
  r.M_torsion = Eigen::MatrixXd::Zero(n_nodes, n_nodes);
  r.K_torsion = Eigen::MatrixXd::Zero(n_nodes, n_nodes);
  r.G = Eigen::MatrixXd::Zero(r.n_dof, r.n_dof);
  r.K = Eigen::MatrixXd::Zero(r.n_dof, r.n_dof);

  for (int e = 0; e + 1 < n_nodes; ++e) {
    const double zmid = 0.5 * (r.node_z[e] + r.node_z[e + 1]);
    std::size_t s = 0;
    while (s + 1 < spec.shaft.size() && zmid > spec.shaft[s].z_start + spec.shaft[s].length) ++s;
    const ShaftSection& sec = spec.shaft[s];
    const Material& mat = spec.materials.at(sec.material);
    BeamElement el;
    el.node1 = e;
    el.section = static_cast<int>(s);
    BeamProperties& p = el.properties;
    p.length = r.node_z[e + 1] - r.node_z[e];
    p.outer_diameter = sec.outer_diameter;
    p.inner_diameter = sec.inner_diameter;
    p.youngs_modulus = mat.youngs_modulus;
    p.shear_modulus = mat.shear_modulus;
    p.density = mat.density;
    p.shear_factor = shear_factor_for(spec, sec, s);
    p.shear_deformation = spec.mesh.shear_deformation;
    p.rotary_inertia = spec.mesh.rotary_inertia;
    const BeamElementMatrices m = beam_element(p);
    const int i0 = r.dof(e, kX);
    r.M.block<8, 8>(i0, i0) += m.mass;
    if (spec.mesh.gyroscopic) r.G.block<8, 8>(i0, i0) += m.gyroscopic;
    r.K.block<8, 8>(i0, i0) += m.stiffness;
    // Torsion: polar second moment J = 2I; K = G J / L [1 -1; -1 1], consistent M = rho J L / 6 [2 1; 1 2].
    const double J = 2.0 * p.second_moment();
    const double kt = p.shear_modulus * J / p.length, mt = p.density * J * p.length / 6.0;
    r.K_torsion.block<2, 2>(e, e) += kt * (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
    r.M_torsion.block<2, 2>(e, e) += mt * (Eigen::Matrix2d() << 2, 1, 1, 2).finished();
    r.elements.push_back(el);
  }

  for (const DiskSpec& d : spec.disks) {
    RigidDisk disk{d.name, r.node_at(std::clamp(d.z, 0.0, length)), d.mass, d.polar_inertia, d.diametral_inertia,
                   d.unbalance, d.unbalance_phase};
    const int i = r.dof(disk.node, kX);
    r.M(i + kX, i + kX) += disk.mass;
    r.M(i + kY, i + kY) += disk.mass;
    r.M(i + kThetaX, i + kThetaX) += disk.diametral_inertia;
    r.M(i + kThetaY, i + kThetaY) += disk.diametral_inertia;
    r.M_torsion(disk.node, disk.node) += disk.polar_inertia;
    if (spec.mesh.gyroscopic) {
      // Angular momentum Ip Omega (theta_y, -theta_x, 1): d/dt gives +Ip Omega theta_y' in the x-moment equation.
      r.G(i + kThetaX, i + kThetaY) += disk.polar_inertia;
      r.G(i + kThetaY, i + kThetaX) -= disk.polar_inertia;
    }
    r.disks.push_back(disk);
  }
  for (const BearingSpec& b : spec.bearings) {
    if (b.type != BearingType::Linear) continue;  // nonlinear bearings are force elements of the run-up
    r.bearings.push_back(LinearBearing{b.name, r.node_at(std::clamp(b.z, 0.0, length)), b.linear, {}});
  }

  r.D = spec.damping.alpha * r.M + spec.damping.beta * r.K;

  Eigen::VectorXd ex = Eigen::VectorXd::Zero(r.n_dof), ey = Eigen::VectorXd::Zero(r.n_dof);
  for (int n = 0; n < n_nodes; ++n) {
    ex(r.dof(n, kX)) = 1.0;
    ey(r.dof(n, kY)) = 1.0;
  }
  r.total_mass = ex.dot(r.M * ex);
  r.gravity_force = -spec.gravity * (r.M * ey);
  return r;
}

}  // namespace turbodyn

namespace turbodyn {

double OilSpec::viscosity_at(double T) const {
  if (viscosity > 0.0) return viscosity;
  return vogel_a * std::exp(vogel_b / ((T - 273.15) + vogel_c));
}

}  // namespace turbodyn

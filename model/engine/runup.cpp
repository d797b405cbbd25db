#include "model/engine/runup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/engine/element_factory.h"
#include "model/engine/runup_workspace.h"
#include "model/spec/errors.h"

namespace turbodyn {

RunupModel::~RunupModel() = default;

RunupModel::RunupModel(const MachineSpec& spec, Rotor rotor, std::vector<std::unique_ptr<ForceElement>> elements,
                       double reduction_cutoff)
    : spec_(spec), rotor_(std::move(rotor)), speed_(spec.speed), elements_(std::move(elements)) {
  const int N = rotor_.n_dof;
  // Boundary (kept exactly): the translations force elements act on, and the disks' x and y where the unbalance
  // acts, so that the static response to every applied force is exact. Rotations that elements read (journal
  // tilt) are interpolated through the basis: kept as coordinates of their own, the small rotary inertia of a
  // bearing node against the film's moment stiffness makes fast local modes that cost steps and no accuracy.
  std::vector<bool> boundary(N, false);
  for (const auto& e : elements_)
    for (int d : e->dofs())
      if (d % kDofPerNode == kX || d % kDofPerNode == kY) boundary[d] = true;
  for (const RigidDisk& d : rotor_.disks) {
    boundary[rotor_.dof(d.node, kX)] = true;
    boundary[rotor_.dof(d.node, kY)] = true;
  }
  std::vector<int> B, I;
  for (int i = 0; i < N; ++i) (boundary[i] ? B : I).push_back(i);

  if (reduction_cutoff > 0.0 && !B.empty() && !I.empty()) {
    const int nb = static_cast<int>(B.size()), ni = static_cast<int>(I.size());
    Eigen::MatrixXd Kii(ni, ni), Mii(ni, ni), Kib(ni, nb);
    for (int a = 0; a < ni; ++a) {
      for (int b = 0; b < ni; ++b) {
        Kii(a, b) = rotor_.K(I[a], I[b]);
        Mii(a, b) = rotor_.M(I[a], I[b]);
      }
      for (int b = 0; b < nb; ++b) Kib(a, b) = rotor_.K(I[a], B[b]);
    }
    const Eigen::LLT<Eigen::MatrixXd> kll(Kii);
    // Held at the translations of one node only, the shaft still tilts about it: singular in exact arithmetic,
    // though round-off may let the factorisation pass.
    const bool one_node = std::all_of(B.begin(), B.end(), [&](int d) { return d / kDofPerNode == B[0] / kDofPerNode; });
    if (kll.info() != Eigen::Success || one_node)
      throw ModelError(spec.source.string() + ": solver.reduction_cutoff: the Craig-Bampton reduction holds the rotor at the " +
                       std::to_string(nb) + " translations its bearings and disks act on, and it can still move "
                       "as a rigid body there (a rotor on one bearing tilts freely): give it bearings at two places "
                       "or more, or set solver.reduction_cutoff = 0 to simulate the unreduced model");
    const Eigen::MatrixXd Psi = -kll.solve(Kib);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kii, Mii);
    const double wmax = 2.0 * M_PI * reduction_cutoff;
    int nk = 0;
    while (nk < ni && es.eigenvalues()(nk) < wmax * wmax) ++nk;
    cutoff_ = nk < ni ? std::sqrt(es.eigenvalues()(nk)) / (2.0 * M_PI) : 0.0;
    n_coordinates_ = nb + nk;
    T_.setZero(N, n_coordinates_);
    for (int b = 0; b < nb; ++b) T_(B[b], b) = 1.0;
    for (int a = 0; a < ni; ++a) {
      T_.row(I[a]).head(nb) = Psi.row(a);
      T_.row(I[a]).tail(nk) = es.eigenvectors().row(a).head(nk);
    }
  } else {
    n_coordinates_ = N;
    T_ = Eigen::MatrixXd::Identity(N, N);
  }
  M_ = T_.transpose() * rotor_.M * T_;
  K_ = T_.transpose() * rotor_.K * T_;
  D_ = T_.transpose() * rotor_.D * T_;
  G_ = T_.transpose() * rotor_.G * T_;
  M_ = 0.5 * (M_ + M_.transpose());
  K_ = 0.5 * (K_ + K_.transpose());
  gravity_ = T_.transpose() * rotor_.gravity_force;
  M_inverse_ = M_.llt().solve(Eigen::MatrixXd::Identity(n_coordinates_, n_coordinates_));

  // Each element DOF is a row of T: u_e = R_e q, and its forces act as R_e' f_e.
  for (const auto& e : elements_) {
    Eigen::MatrixXd R(e->dofs().size(), n_coordinates_);
    for (std::size_t i = 0; i < e->dofs().size(); ++i) R.row(i) = T_.row(e->dofs()[i]);
    element_rows_.push_back(R);
  }
  for (const RigidDisk& d : rotor_.disks)
    disk_rows_.push_back({T_.row(rotor_.dof(d.node, kX)), T_.row(rotor_.dof(d.node, kY))});

  int offset = 2 * n_coordinates_;
  for (const auto& e : elements_) {
    state_offsets_.push_back(offset);
    offset += e->n_states();
    n_element_states_ += e->n_states();
  }

  channels_.push_back({"speed", "Hz", "rotor speed f_d", ProbeChannel::Kind::Speed, 0, 0});
  channels_.push_back({"spin_angle", "rad", "rotor spin angle", ProbeChannel::Kind::Angle, 0, 0});
  for (const RigidDisk& d : rotor_.disks) {
    channels_.push_back({"disk." + d.name + ".x", "m", "horizontal displacement of disk '" + d.name + "'",
                         ProbeChannel::Kind::RotorDof, rotor_.dof(d.node, kX), 0});
    channels_.push_back({"disk." + d.name + ".y", "m", "vertical displacement of disk '" + d.name + "'",
                         ProbeChannel::Kind::RotorDof, rotor_.dof(d.node, kY), 0});
  }
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const std::vector<ProbeInfo> probes = elements_[k]->probes();
    for (std::size_t p = 0; p < probes.size(); ++p)
      channels_.push_back({"bearing." + elements_[k]->name() + "." + probes[p].name, probes[p].unit,
                           probes[p].description, ProbeChannel::Kind::Element, static_cast<int>(k),
                           static_cast<int>(p), probes[p].limit, probes[p].limit_note, probes[p].limit_below});
  }
}

void RunupWorkspaceDeleter::operator()(RunupWorkspace* ws) const { delete ws; }

RunupWorkspace::Element::Element(const ForceElement& e, int n) {
  const int d = static_cast<int>(e.dofs().size()), m = e.n_states();
  workspace = e.make_workspace();
  q.setZero(d);
  v.setZero(d);
  f.setZero(d);
  jacobian.setZero(d + m, 2 * d + m);
  fd_in.setZero(2 * d + m);
  fd_out0.setZero(d + m);
  fd_out1.setZero(d + m);
  lu = BlockArrowLU(m, e.independent_state_blocks(), std::max(d, 1), e.kinematic_states_per_block());
  Y.setZero(m, d);
  T.setZero(m, d);
  JY.setZero(d, d);
  RJY.setZero(n, d);
  w.setZero(m);
  w0.setZero(m);
  u.setZero(d);
}

RunupWorkspacePtr RunupModel::make_workspace(int threads) const {
  RunupWorkspacePtr ws(new RunupWorkspace);
  if (threads > 1 && elements_.size() > 1)
    ws->team = std::make_unique<ElementTeam>(std::min(threads, static_cast<int>(elements_.size())));
  const int n = n_coordinates_, m = n_element_states_;
  ws->f.setZero(n);
  ws->tmp.setZero(n);
  ws->elements.reserve(elements_.size());
  for (const auto& e : elements_) ws->elements.emplace_back(*e, n);
  ws->Fq.setZero(n, n);
  ws->Fv.setZero(n, n);
  ws->Fz.setZero(n, m);
  ws->Gq.setZero(m, n);
  ws->Gv.setZero(m, n);
  ws->Gz.setZero(m, m);
  ws->A.setZero(n, n);
  ws->lu = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
  ws->rhs.setZero(n);
  ws->sol.setZero(n);
  return ws;
}

SpinState RunupModel::spin(double t) const {
  return SpinState{t, speed_.speed(t), speed_.acceleration(t), speed_.angle(t)};
}

void RunupModel::Gather(const ForceElement& e, const double* q, const double* v, RunupWorkspace& ws, int k) const {
  (void)e;
  const int n = n_coordinates_;
  ws.elements[k].q.noalias() = element_rows_[k] * Eigen::Map<const Eigen::VectorXd>(q, n);
  ws.elements[k].v.noalias() = element_rows_[k] * Eigen::Map<const Eigen::VectorXd>(v, n);
}

void RunupModel::Rhs(double t, const double* y, double* ydot, RunupWorkspace& ws) const {
  ++ws.rhs_calls;
  const int n = n_coordinates_;
  const SpinState s = spin(t);
  const Eigen::Map<const Eigen::VectorXd> q(y, n), v(y + n, n);
  Eigen::Map<Eigen::VectorXd> qdot(ydot, n), vdot(ydot + n, n);

  Eigen::VectorXd& f = ws.f;
  f = gravity_;
  f.noalias() -= K_ * q;
  f.noalias() -= D_ * v;
  f.noalias() -= s.speed * (G_ * v);
  f.noalias() -= s.acceleration * (G_ * q);

  // Unbalance: mass U at angle psi = phi + beta; force on the rotor U (Omega^2 cos psi + Omega' sin psi, ...).
  double unbalance_power = 0.0;
  const double w2 = s.speed * s.speed;
  for (std::size_t k = 0; k < rotor_.disks.size(); ++k) {
    const RigidDisk& d = rotor_.disks[k];
    if (d.unbalance == 0.0) continue;
    const double psi = s.angle + d.unbalance_phase, c = std::cos(psi), sn = std::sin(psi);
    const double fx = d.unbalance * (w2 * c + s.acceleration * sn), fy = d.unbalance * (w2 * sn - s.acceleration * c);
    f.noalias() += fx * disk_rows_[k].x.transpose();
    f.noalias() += fy * disk_rows_[k].y.transpose();
    unbalance_power += fx * disk_rows_[k].x.dot(v) + fy * disk_rows_[k].y.dot(v);
  }

  // The elements one by one, or side by side on the workspace's team; their results are added up in element
  // order below, so the numbers do not depend on the thread count.
  struct Task {
    const RunupModel* model;
    const SpinState* s;
    const double* y;
    double* ydot;
    RunupWorkspace* ws;
  } task{this, &s, y, ydot, &ws};
  const auto evaluate = [](void* context, int k) {
    const Task& c = *static_cast<const Task*>(context);
    const ForceElement& e = *c.model->elements_[k];
    RunupWorkspace::Element& we = c.ws->elements[k];
    c.model->Gather(e, c.y, c.y + c.model->n_coordinates_, *c.ws, k);
    we.f.setZero();
    const double* z = c.y + c.model->state_offsets_[k];
    e.calc_and_add_forces(*c.s, we.q.data(), we.v.data(), z, *we.workspace, we.f.data(),
                          c.ydot + c.model->state_offsets_[k]);
    if (c.ws->energy) {
      we.dissipation = e.dissipated_power(*c.s, we.q.data(), we.v.data(), z, *we.workspace);
      we.drive = e.drive_power(*c.s, we.q.data(), we.v.data(), z, *we.workspace);
    }
  };
  ws.for_each_element(static_cast<int>(elements_.size()), evaluate, &task);
  double element_dissipation = 0.0, drive_power = 0.0;
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const RunupWorkspace::Element& we = ws.elements[k];
    ++ws.element_calls;
    f.noalias() += element_rows_[k].transpose() * we.f;
    if (ws.energy) {
      element_dissipation += we.dissipation;
      drive_power += we.drive;
    }
  }

  qdot = v;
  vdot.noalias() = M_inverse_ * f;

  double* energy = ydot + 2 * n + n_element_states_;
  if (ws.energy) {
    // Work in: unbalance forces, the spin-acceleration gyroscopic term -Omega' G q and the elements' drag torques
    // (the drive's share).
    ws.tmp.noalias() = G_ * q;
    energy[0] = unbalance_power - s.acceleration * v.dot(ws.tmp) + drive_power;
    ws.tmp.noalias() = D_ * v;
    energy[1] = v.dot(ws.tmp) + element_dissipation;
  } else {
    energy[0] = energy[1] = 0.0;
  }
}

void RunupModel::Probes(double t, const double* y, RunupWorkspace& ws, double* out) const {
  const int n = n_coordinates_;
  const Eigen::Map<const Eigen::VectorXd> q(y, n);
  const SpinState s = spin(t);
  std::size_t c = 0;
  for (const ProbeChannel& ch : channels_) {
    switch (ch.kind) {
      case ProbeChannel::Kind::Speed: out[c] = s.speed / (2.0 * M_PI); break;
      case ProbeChannel::Kind::Angle: out[c] = s.angle; break;
      case ProbeChannel::Kind::RotorDof: out[c] = T_.row(ch.index).dot(q); break;
      case ProbeChannel::Kind::Element: break;  // filled below, one evaluation per element
    }
    ++c;
  }
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const ForceElement& e = *elements_[k];
    const std::size_t np = e.probes().size();
    if (np == 0) continue;
    Gather(e, y, y + n, ws, static_cast<int>(k));
    double values[16];
    std::vector<double> big;
    double* buf = values;
    if (np > 16) {
      big.resize(np);
      buf = big.data();
    }
    RunupWorkspace::Element& we = ws.elements[k];
    e.eval_probes(s, we.q.data(), we.v.data(), y + state_offsets_[k], *we.workspace, buf);
    for (std::size_t i = 0; i < channels_.size(); ++i)
      if (channels_[i].kind == ProbeChannel::Kind::Element && channels_[i].index == static_cast<int>(k))
        out[i] = buf[channels_[i].element_probe];
  }
}

void RunupModel::Jacobian(double t, const double* y, RunupWorkspace& ws) const {
  ++ws.jacobian_evaluations;
  const int n = n_coordinates_;
  const SpinState s = spin(t);
  ws.jac_t = t;
  ws.jac_spin = s;
  ws.Fq = -K_ - s.acceleration * G_;
  ws.Fv = -D_ - s.speed * G_;
  ws.Fz.setZero();
  ws.Gq.setZero();
  ws.Gv.setZero();
  ws.Gz.setZero();
  // Each element's own Jacobian, one by one or side by side on the workspace's team; assembled in element order.
  struct Task {
    const RunupModel* model;
    const SpinState* s;
    const double* y;
    RunupWorkspace* ws;
  } task{this, &s, y, &ws};
  const auto differentiate = [](void* context, int k) {
    const Task& c = *static_cast<const Task*>(context);
    const ForceElement& e = *c.model->elements_[k];
    const int d = static_cast<int>(e.dofs().size()), m = e.n_states();
    const int zoff = c.model->state_offsets_[k];
    RunupWorkspace::Element& we = c.ws->elements[k];
    Eigen::MatrixXd& J = we.jacobian;
    J.setZero();
    c.model->Gather(e, c.y, c.y + c.model->n_coordinates_, *c.ws, k);
    if (e.has_jacobian()) {
      e.add_jacobian(*c.s, we.q.data(), we.v.data(), c.y + zoff, *we.workspace, J.data());
      we.calls = e.jacobian_evaluations();
    } else {
      // Forward differences in the element's own inputs: 2d + m evaluations of the element alone.
      Eigen::VectorXd& in = we.fd_in;
      in << we.q, we.v, Eigen::Map<const Eigen::VectorXd>(c.y + zoff, m);
      auto eval = [&](Eigen::VectorXd& out) {
        out.setZero();
        e.calc_and_add_forces(*c.s, in.data(), in.data() + d, in.data() + 2 * d, *we.workspace, out.data(),
                              out.data() + d);
      };
      eval(we.fd_out0);
      for (int j = 0; j < 2 * d + m; ++j) {
        const double saved = in(j);
        const double h = e.fd_step(j, d, saved);
        in(j) = saved + h;
        eval(we.fd_out1);
        in(j) = saved;
        J.col(j) = (we.fd_out1 - we.fd_out0) / h;
      }
      we.calls = 1 + 2 * d + m;
    }
  };
  ws.for_each_element(static_cast<int>(elements_.size()), differentiate, &task);
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const ForceElement& e = *elements_[k];
    const int d = static_cast<int>(e.dofs().size()), m = e.n_states();
    const int zoff = state_offsets_[k];
    RunupWorkspace::Element& we = ws.elements[k];
    const Eigen::MatrixXd& J = we.jacobian;
    ws.element_calls += we.calls;
    const Eigen::MatrixXd& Rk = element_rows_[k];
    const int zs = zoff - 2 * n;  // offset among the element states
    ws.Fq.noalias() += Rk.transpose() * J.block(0, 0, d, d) * Rk;
    ws.Fv.noalias() += Rk.transpose() * J.block(0, d, d, d) * Rk;
    if (m > 0) {
      ws.Fz.middleCols(zs, m).noalias() += Rk.transpose() * J.block(0, 2 * d, d, m);
      ws.Gq.middleRows(zs, m).noalias() += J.block(d, 0, m, d) * Rk;
      ws.Gv.middleRows(zs, m).noalias() += J.block(d, d, m, d) * Rk;
      ws.Gz.block(zs, zs, m, m) += J.block(d, 2 * d, m, m);
    }
  }
}

void RunupModel::RespinJacobian(double t, RunupWorkspace& ws) const {
  const SpinState s = spin(t);
  ws.Fq -= (s.acceleration - ws.jac_spin.acceleration) * G_;
  ws.Fv -= (s.speed - ws.jac_spin.speed) * G_;
  ws.jac_t = t;
  ws.jac_spin = s;
}

bool RunupModel::FactorNewton(double gamma, RunupWorkspace& ws) const {
  const double g = gamma;
  ws.A = M_ - g * ws.Fv - (g * g) * ws.Fq;
  bool regular = true;
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const int d = static_cast<int>(elements_[k]->dofs().size()), m = elements_[k]->n_states();
    if (m == 0) continue;
    RunupWorkspace::Element& we = ws.elements[k];
    const Eigen::MatrixXd& J = we.jacobian;  // rows [f (d); z' (m)], columns [q (d), v (d), z (m)]
    regular = we.lu.compute(J.block(d, 2 * d, m, m), -g, 1.0) && regular;  // I - g G_zz
    // Y = A_k^-1 (-g (G_zv + g G_zq)) in the element's local DOFs; the Schur term -(-g F_z) Y enters as g R' F_z Y R.
    we.T = -g * J.block(d, d, m, d) - (g * g) * J.block(d, 0, m, d);
    we.Y = we.T;
    we.lu.solve_in_place(we.Y);
    // Small products (d = 4): coefficient-wise, without the packing of Eigen's general products.
    we.JY.noalias() = J.block(0, 2 * d, d, m).lazyProduct(we.Y);
    we.RJY.noalias() = element_rows_[k].transpose().lazyProduct(we.JY);
    ws.A.noalias() += g * we.RJY.lazyProduct(element_rows_[k]);
  }
  ws.lu.compute(ws.A);
  ++ws.factorisations;
  return regular && HasRegularPivots(ws.lu);
}

void RunupModel::SolveNewton(double gamma, const double* b, double* x, RunupWorkspace& ws) const {
  const int n = n_coordinates_;
  const double g = gamma;
  const Eigen::Map<const Eigen::VectorXd> rq(b, n), rv(b + n, n);
  ws.rhs.noalias() = M_ * rv;
  ws.rhs.noalias() += g * (ws.Fq * rq);
  // Forward elimination of each element's states: w_k = A_k^-1 (r_z + g G_zq r_q), rhs -= (-g F_z) w_k.
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const int d = static_cast<int>(elements_[k]->dofs().size()), m = elements_[k]->n_states();
    if (m == 0) continue;
    RunupWorkspace::Element& we = ws.elements[k];
    const Eigen::MatrixXd& J = we.jacobian;
    const int zoff = state_offsets_[k];
    we.u.noalias() = element_rows_[k] * rq;
    we.w0 = Eigen::Map<const Eigen::VectorXd>(b + zoff, m);
    we.w0.noalias() += g * (J.block(d, 0, m, d) * we.u);
    we.w = we.w0;
    we.lu.solve_in_place(we.w);
    we.u.noalias() = J.block(0, 2 * d, d, m) * we.w;
    ws.rhs.noalias() += g * (element_rows_[k].transpose() * we.u);
  }
  ws.sol = ws.lu.solve(ws.rhs);
  Eigen::Map<Eigen::VectorXd> dq(x, n), dv(x + n, n);
  dv = ws.sol;
  dq = rq + g * dv;
  // Back substitution: dz_k = w_k - Y_k R_k dv.
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const int m = elements_[k]->n_states();
    if (m == 0) continue;
    const int zoff = state_offsets_[k];
    RunupWorkspace::Element& we = ws.elements[k];
    we.u.noalias() = element_rows_[k] * ws.sol;
    Eigen::Map<Eigen::VectorXd> dz(x + zoff, m);
    dz = we.w;
    dz.noalias() -= we.Y * we.u;
  }
  // Energy-accounting states: their equations do not depend on y through the Newton matrix.
  const int ny = n_states();
  x[ny - 2] = b[ny - 2];
  x[ny - 1] = b[ny - 1];
}

Eigen::VectorXd RunupModel::AbsoluteTolerances(double atol, bool scaled) const {
  Eigen::VectorXd a = Eigen::VectorXd::Constant(n_states(), atol);
  if (!scaled) return a;
  const int n = n_coordinates_;
  constexpr double kDisp = ForceElement::kTypicalDisplacement, kVel = ForceElement::kTypicalVelocity;
  a.segment(n, n).setConstant(atol * kVel / kDisp);
  for (std::size_t k = 0; k < elements_.size(); ++k)
    for (int i = 0; i < elements_[k]->n_states(); ++i) {
      const double typical = elements_[k]->tolerance_scale(i);
      a(state_offsets_[k] + i) = atol * (typical > 0.0 ? typical : kDisp) / kDisp;
    }
  a.tail(2).setConstant(atol / kDisp);  // energy accounts (J)
  return a;
}

bool RunupModel::HasStateDependentTolerances() const {
  for (const auto& e : elements_)
    if (e->has_state_dependent_tolerances()) return true;
  return false;
}

void RunupModel::AbsoluteToleranceFactors(const double* y, double* f) const {
  std::fill(f, f + n_states(), 1.0);
  for (std::size_t k = 0; k < elements_.size(); ++k)
    if (elements_[k]->has_state_dependent_tolerances())
      elements_[k]->absolute_tolerance_factors(y + state_offsets_[k], f + state_offsets_[k]);
}

Eigen::MatrixXd RunupModel::JacobianMatrix(double t, const double* y, RunupWorkspace& ws) const {
  Jacobian(t, y, ws);
  const int n = n_coordinates_, m = n_element_states_;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n_states(), n_states());
  J.block(0, n, n, n).setIdentity();
  J.block(n, 0, n, n) = M_inverse_ * ws.Fq;
  J.block(n, n, n, n) = M_inverse_ * ws.Fv;
  J.block(n, 2 * n, n, m) = M_inverse_ * ws.Fz;
  J.block(2 * n, 0, m, n) = ws.Gq;
  J.block(2 * n, n, m, n) = ws.Gv;
  J.block(2 * n, 2 * n, m, m) = ws.Gz;
  return J;
}

double RunupModel::MechanicalEnergy(double t, const double* y) const {
  (void)t;
  const int n = n_coordinates_;
  const Eigen::Map<const Eigen::VectorXd> q(y, n), v(y + n, n);
  double e = 0.5 * v.dot(M_ * v) + 0.5 * q.dot(K_ * q) - gravity_.dot(q);
  std::vector<double> eq;
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const ForceElement& el = *elements_[k];
    eq.resize(el.dofs().size());
    Eigen::Map<Eigen::VectorXd>(eq.data(), eq.size()) = element_rows_[k] * q;
    e += el.potential_energy(eq.data(), y + state_offsets_[k]) + el.kinetic_energy(y + state_offsets_[k]);
  }
  return e;
}

void RunupModel::InitialState(double t, bool static_equilibrium, double* y, RunupWorkspace& ws) const {
  const int n = n_coordinates_, m = n_element_states_;
  std::fill(y, y + n_states(), 0.0);
  const double speed = spin(t).speed;
  for (std::size_t k = 0; k < elements_.size(); ++k) elements_[k]->initial_states_at_speed(speed, y + state_offsets_[k]);
  if (!static_equilibrium) return;
  // Newton on [f(q, 0, z); g(q, 0, z)] = 0 with the exact rotor Jacobian and the element blocks.
  std::vector<double> ydot(n_states());
  Eigen::MatrixXd J(n + m, n + m);
  Eigen::VectorXd r(n + m);
  const bool energy = ws.energy;
  ws.energy = false;
  constexpr int kMaxIterations = 50;
  constexpr double kTolerance = 1e-12;  // relative change of [q; z]
  constexpr const char* kHint = "set static_start = false to let the run settle from rest instead";
  // An iterate an element cannot take (a film closed, say) ends the search with a message that says what was being
  // done and what to change: a squeeze-film damper without a centring spring, for one, has no static stiffness and
  // hence no static equilibrium.
  const auto element_call = [&](int it, const auto& call) {
    try {
      call();
    } catch (const ModelError&) {
      ws.energy = energy;
      throw;  // bad input is said as it is
    } catch (const std::runtime_error& e) {
      ws.energy = energy;
      throw std::runtime_error(std::string("the static equilibrium under gravity was not found (Newton iteration ") +
                               std::to_string(it + 1) + ": " + e.what() + "); " + kHint);
    }
  };
  for (int it = 0; it < kMaxIterations; ++it) {
    element_call(it, [&] { Rhs(t, y, ydot.data(), ws); });
    r.head(n) = ws.f;  // the full generalised force at v = 0
    for (int i = 0; i < m; ++i) r(n + i) = ydot[2 * n + i];
    element_call(it, [&] { Jacobian(t, y, ws); });
    J.topLeftCorner(n, n) = ws.Fq;
    J.topRightCorner(n, m) = ws.Fz;
    J.bottomLeftCorner(m, n) = ws.Gq;
    J.bottomRightCorner(m, m) = ws.Gz;
    const Eigen::VectorXd dx = J.fullPivLu().solve(-r);
    if (!dx.allFinite()) break;
    for (int i = 0; i < n; ++i) y[i] += dx(i);
    for (int i = 0; i < m; ++i) y[2 * n + i] += dx(n + i);
    double scale = 0.0;
    for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(y[i]));
    if (dx.lpNorm<Eigen::Infinity>() <= kTolerance * std::max(scale, 1e-9)) {
      ws.energy = energy;
      return;
    }
  }
  ws.energy = energy;
  throw std::runtime_error(std::string("the static equilibrium under gravity was not found (Newton's method did not "
                                       "converge in 50 iterations); ") + kHint);
}

std::unique_ptr<RunupModel> make_runup_model(const MachineSpec& spec) {
  Rotor rotor = build_rotor(spec);
  std::vector<std::unique_ptr<ForceElement>> elements = make_force_elements(spec, rotor);
  // The bearings act through the elements; the rotor's own matrices stay bearing-free.
  double cutoff = spec.solver.reduction_cutoff;
  if (cutoff < 0.0) {  // automatic: three times the highest rotor frequency, at least 5 kHz
    const double top = std::max(spec.speed.end, spec.speed.start) / (2.0 * M_PI);
    cutoff = std::max(3.0 * top, 5000.0);
  }
  return std::make_unique<RunupModel>(spec, std::move(rotor), std::move(elements), cutoff);
}

}  // namespace turbodyn

#include "model/rotor/modal.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <stdexcept>
#include <tuple>

#include <Eigen/Eigenvalues>

namespace turbodyn {

std::string to_string(Whirl w) {
  switch (w) {
    case Whirl::Forward: return "forward";
    case Whirl::Backward: return "backward";
    case Whirl::Mixed: return "mixed";
    case Whirl::Planar: return "planar";
    case Whirl::Torsional: return "torsional";
  }
  return "?";
}

Whirl classify_whirl(const Rotor& rotor, const Eigen::VectorXcd& shape, std::vector<int>* node_whirl) {
  // Node orbit x = Re(a e^{i w t}), y = Re(b e^{i w t}). It runs in the spin direction (x towards y, forward) when
  // Im(conj(a) b) < 0. Orbits whose minor/major axis ratio is below kPlanar, or nodes moving less than kSmall of
  // the largest orbit, do not vote.
  constexpr double kPlanar = 1e-3;
  constexpr double kSmall = 1e-2;
  const int n_nodes = rotor.n_dof / kDofPerNode;
  std::vector<double> size(n_nodes), signed_area(n_nodes);
  double largest = 0.0;
  for (int n = 0; n < n_nodes; ++n) {
    const std::complex<double> a = shape(rotor.dof(n, kX)), b = shape(rotor.dof(n, kY));
    size[n] = std::norm(a) + std::norm(b);
    signed_area[n] = -(std::conj(a) * b).imag();  // = major * minor semi-axis product, sign = direction
    largest = std::max(largest, size[n]);
  }
  int forward = 0, backward = 0;
  if (node_whirl) node_whirl->assign(n_nodes, 0);
  for (int n = 0; n < n_nodes; ++n) {
    if (largest == 0.0 || size[n] < kSmall * kSmall * largest) continue;
    // 2|major*minor| / (major^2 + minor^2) >= ratio-ish; small values mean a nearly straight-line orbit.
    if (2.0 * std::abs(signed_area[n]) < kPlanar * size[n]) continue;
    const int dir = signed_area[n] > 0 ? 1 : -1;
    (dir > 0 ? forward : backward)++;
    if (node_whirl) (*node_whirl)[n] = dir;
  }
  if (forward == 0 && backward == 0) return Whirl::Planar;
  if (backward == 0) return Whirl::Forward;
  if (forward == 0) return Whirl::Backward;
  return Whirl::Mixed;
}

Eigen::VectorXd balance_for_eigenvalues(Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  Eigen::VectorXd s = Eigen::VectorXd::Ones(n);
  constexpr double kRadix = 2.0, kConverged = 0.95;
  // A few sweeps suffice for any matrix of a plausible rotor; the cap keeps absurd magnitudes (which the model
  // loader refuses, docs/model-format.md "Limits") from cycling for ever.
  constexpr int kMaxSweeps = 200;
  int sweeps = 0;
  for (bool changed = true; changed && sweeps < kMaxSweeps; ++sweeps) {
    changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double c = A.col(i).norm(), r = A.row(i).norm();
      const double cd = std::sqrt(std::max(0.0, c * c - A(i, i) * A(i, i)));
      const double rd = std::sqrt(std::max(0.0, r * r - A(i, i) * A(i, i)));
      if (cd == 0.0 || rd == 0.0) continue;
      double f = 1.0, cc = cd, rr = rd;
      const double total = cd + rd;
      while (cc < rr / kRadix) {
        cc *= kRadix;
        rr /= kRadix;
        f *= kRadix;
      }
      while (cc >= rr * kRadix) {
        cc /= kRadix;
        rr *= kRadix;
        f /= kRadix;
      }
      if (cc + rr < kConverged * total) {
        changed = true;
        s(i) *= f;
        A.col(i) *= f;
        A.row(i) /= f;
      }
    }
  }
  return s;
}

namespace {

ModalResult modes_at(const Rotor& rotor, double speed, const ModalOptions& options) {
  const int n = rotor.n_dof;
  Eigen::MatrixXd K = rotor.K, C = rotor.D;
  rotor.add_bearings(speed, K, C);
  Eigen::MatrixXd Cg = C + speed * rotor.G;
  if (options.frame == Frame::Rotating) {
    const Eigen::MatrixXd J = rotor.quarter_turn();
    constexpr double kSymmetryTolerance = 1e-9;
    Eigen::MatrixXd Kb = K - rotor.K, Cb = C - rotor.D;
    if ((Kb * J - J * Kb).norm() > kSymmetryTolerance * (1.0 + Kb.norm()) ||
        (Cb * J - J * Cb).norm() > kSymmetryTolerance * (1.0 + Cb.norm()))
      throw std::runtime_error(
          "the rotating-frame form of Eq. (9) has constant coefficients only on isotropic bearings "
          "(kxx = kyy, kxy = -kyx, likewise c); this model's bearings are anisotropic");
    // Damping acting on inertial velocities q' = R (q_r' + Omega J q_r) adds Omega C J to the stiffness.
    Cg = C + speed * rotor.rotating_frame_gyroscopic();
    K += speed * speed * rotor.spin_softening() + speed * C * J;
  }
  // Floating rings: two coordinates each (the ring's x, y) after the rotor's, the inner film between the journal's
  // x, y and the ring, the outer film between the ring and the housing.
  Eigen::MatrixXd Mx = rotor.M;
  const int nr = 2 * static_cast<int>(rotor.rings.size());
  if (nr > 0) {
    if (options.frame == Frame::Rotating)
      throw std::runtime_error("floating-ring bearings are analysed in the inertial frame only");
    const int nt = n + nr;
    auto grow = [&](Eigen::MatrixXd& A) {
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(nt, nt);
      B.topLeftCorner(n, n) = A;
      A = std::move(B);
    };
    grow(Mx);
    grow(K);
    grow(Cg);
    for (std::size_t r = 0; r < rotor.rings.size(); ++r) {
      const FloatingRingLinearisation& ring = rotor.rings[r];
      Eigen::Matrix2d ki, ci, ko, co;
      ring.films(speed, ki, ci, ko, co);
      const int j = rotor.dof(ring.node, kX), b = n + 2 * static_cast<int>(r);
      Mx.block<2, 2>(b, b) = ring.ring_mass * Eigen::Matrix2d::Identity();
      for (auto [A, a, o] : {std::tuple<Eigen::MatrixXd*, const Eigen::Matrix2d*, const Eigen::Matrix2d*>{&K, &ki, &ko},
                             {&Cg, &ci, &co}}) {
        A->block<2, 2>(j, j) += *a;
        A->block<2, 2>(j, b) -= *a;
        A->block<2, 2>(b, j) -= *a;
        A->block<2, 2>(b, b) += *a + *o;
      }
    }
  }
  const int nx = n + nr;
  // First-order form z = [q; q'], z' = A z with A = [0 I; -M^-1 K, -M^-1 Cg].
  const Eigen::LLT<Eigen::MatrixXd> llt(Mx);
  if (llt.info() != Eigen::Success) throw std::runtime_error("the mass matrix is not positive definite");
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * nx, 2 * nx);
  A.topRightCorner(nx, nx).setIdentity();
  A.bottomLeftCorner(nx, nx) = -llt.solve(K);
  A.bottomRightCorner(nx, nx) = -llt.solve(Cg);
  if (!A.allFinite()) throw std::runtime_error("the rotor's matrices are not finite (check masses and stiffnesses)");
  // Rotations, displacements and velocities differ by many orders of magnitude in A; without balancing the
  // low eigenvalues lose all accuracy (errors ~ eps * ||A||).
  const Eigen::VectorXd scale = balance_for_eigenvalues(A);
  Eigen::EigenSolver<Eigen::MatrixXd> es(A, true);
  if (es.info() != Eigen::Success) throw std::runtime_error("the eigenvalue solver did not converge");

  const Eigen::VectorXcd lambda = es.eigenvalues();
  std::vector<int> index;
  // Eigenvalues with a (relatively) positive imaginary part are oscillating modes; their conjugates are dropped.
  constexpr double kOscillatory = 1e-9;
  for (int i = 0; i < lambda.size(); ++i)
    if (lambda(i).imag() > kOscillatory * std::max(1.0, std::abs(lambda(i)))) index.push_back(i);
  std::sort(index.begin(), index.end(), [&](int a, int b) { return lambda(a).imag() < lambda(b).imag(); });
  if (static_cast<int>(index.size()) > options.n_modes) index.resize(options.n_modes);

  ModalResult result;
  result.speed = speed;
  for (int i : index) {
    Mode m;
    m.eigenvalue = lambda(i);
    m.frequency = lambda(i).imag() / (2.0 * M_PI);
    m.damping_ratio = -lambda(i).real() / std::abs(lambda(i));
    m.shape = scale.head(n).cast<std::complex<double>>().cwiseProduct(es.eigenvectors().col(i).head(n));
    // Normalise: largest translation 1 and real.
    int imax = 0;
    double amax = -1.0;
    for (int k = 0; k < n; ++k) {
      if (k % kDofPerNode >= 2) continue;
      if (std::abs(m.shape(k)) > amax) {
        amax = std::abs(m.shape(k));
        imax = k;
      }
    }
    if (amax > 0.0) m.shape /= m.shape(imax);
    m.whirl = classify_whirl(rotor, m.shape, &m.node_whirl);
    result.modes.push_back(std::move(m));
  }
  if (options.torsion) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ts(rotor.K_torsion, rotor.M_torsion);
    if (ts.info() != Eigen::Success) throw std::runtime_error("the torsional eigenvalue solver did not converge");
    const double largest = ts.eigenvalues().maxCoeff();
    constexpr double kRigidBody = 1e-10;  // relative size below which an eigenvalue is the free rigid rotation
    for (Eigen::Index i = 0; i < ts.eigenvalues().size(); ++i) {
      if (ts.eigenvalues()(i) <= kRigidBody * largest) continue;
      Mode m;
      const double w = std::sqrt(ts.eigenvalues()(i));
      m.eigenvalue = {0.0, w};
      m.frequency = w / (2.0 * M_PI);
      m.whirl = Whirl::Torsional;
      m.shape = Eigen::VectorXcd::Zero(n);
      m.twist = ts.eigenvectors().col(i);
      m.twist /= m.twist.cwiseAbs().maxCoeff();
      result.modes.push_back(std::move(m));
    }
    std::stable_sort(result.modes.begin(), result.modes.end(),
                     [](const Mode& a, const Mode& b) { return a.frequency < b.frequency; });
    if (static_cast<int>(result.modes.size()) > options.n_modes) result.modes.resize(options.n_modes);
  }
  return result;
}

}  // namespace

ModalResult modal_analysis(const Rotor& rotor, double speed, const ModalOptions& options) {
  ModalResult result = modes_at(rotor, speed, options);
  if (speed != 0.0 || options.frame != Frame::Inertial || result.modes.empty() || rotor.G.isZero(0.0)) return result;
  // At standstill the forward and backward whirl of an axisymmetric rotor have one frequency, and any combination
  // of the two circular orbits is a mode: the eigen-solver's pick, and so its label, is arbitrary (both members of
  // a pair could come out "backward"). Name each mode by its limit at a small speed, where the gyroscopic terms
  // split the pair: the shape and whirl of that limit, the frequency and damping at standstill. The small speed is
  // a 1e-4 fraction of the lowest lateral frequency, far above the eigen-solver's rounding, far below any change
  // of the frequencies that matters.
  constexpr double kSmallSpeedFraction = 1e-4;
  double lowest = 0.0;
  for (const Mode& m : result.modes)
    if (m.whirl != Whirl::Torsional && m.frequency > 0.0) {
      lowest = 2.0 * M_PI * m.frequency;
      break;
    }
  if (!(lowest > 0.0)) return result;
  const ModalResult limit = modes_at(rotor, kSmallSpeedFraction * lowest, options);
  if (limit.modes.size() != result.modes.size()) return result;
  constexpr double kSameMode = 1e-3;  // relative frequency difference within which limit and standstill mode match
  for (std::size_t i = 0; i < result.modes.size(); ++i) {
    Mode& m = result.modes[i];
    const Mode& l = limit.modes[i];
    if (m.whirl == Whirl::Torsional || l.whirl == Whirl::Torsional) continue;
    if (std::abs(l.frequency - m.frequency) > kSameMode * m.frequency) continue;
    m.whirl = l.whirl;
    m.node_whirl = l.node_whirl;
    m.shape = l.shape;
  }
  return result;
}

namespace {

// Frequency (Hz) of the `branch`-th mode of whirl class `whirl` at `speed`, NaN if absent.
double branch_frequency(const ModalResult& r, Whirl whirl, int branch) {
  int k = 0;
  for (const Mode& m : r.modes) {
    if (m.whirl != whirl) continue;
    if (k++ == branch) return m.frequency;
  }
  return std::nan("");
}

// Frequency (Hz) of the mode of whirl class `whirl` nearest `frequency`, NaN if none: the branch followed across a
// small change of speed by continuity (the branch index may change where modes reorder).
double nearest_frequency(const ModalResult& r, Whirl whirl, double frequency) {
  double best = std::nan("");
  for (const Mode& m : r.modes)
    if (m.whirl == whirl && !(std::abs(m.frequency - frequency) >= std::abs(best - frequency))) best = m.frequency;
  return best;
}

const Mode* branch_mode(const ModalResult& r, Whirl whirl, int branch) {
  int k = 0;
  for (const Mode& m : r.modes)
    if (m.whirl == whirl && k++ == branch) return &m;
  return nullptr;
}

}  // namespace

RampPassage ramp_passage(double lambda, double zeta) {
  if (!(lambda > 0.0 && lambda < 0.1) || !(zeta >= 0.0 && zeta < 0.5))
    throw std::invalid_argument("ramp_passage: needs 0 < lambda < 0.1 (a ramp slow against the mode) and 0 <= zeta < "
                                "0.5, not lambda = " + std::to_string(lambda) + ", zeta = " + std::to_string(zeta));
  const double steady = zeta > 0.0 ? 1.0 / (2.0 * zeta * std::sqrt(1.0 - zeta * zeta)) : 0.0;
  RampPassage out;
  constexpr double kQuasiSteady = 1e-5;
  if (lambda < kQuasiSteady) {
    if (zeta == 0.0) throw std::invalid_argument("ramp_passage: an undamped mode needs lambda >= 1e-5");
    out.speed_ratio = 1.0 / std::sqrt(1.0 - 2.0 * zeta * zeta);
    out.peak = steady;
    return out;
  }
  // From W0 = 0.5 on the steady response there, x = Re(X e^{i phi}), X = W0^2 / (1 - W0^2 + 2 i zeta W0).
  const double w0 = 0.5, w_end = 1.0 + std::max(0.5, 10.0 * std::sqrt(lambda));
  double t = w0 / lambda;
  const std::complex<double> X = w0 * w0 / std::complex<double>(1.0 - w0 * w0, 2.0 * zeta * w0);
  const std::complex<double> e0 = std::polar(1.0, 0.5 * lambda * t * t);
  double x = std::real(X * e0), v = std::real(std::complex<double>(0.0, w0) * X * e0);
  auto acc = [&](double tt, double xx, double vv) {
    const double w = lambda * tt;
    return w * w * std::cos(0.5 * lambda * tt * tt) - 2.0 * zeta * vv - xx;
  };
  const double dt = 2.0 * M_PI / 400.0;
  const double t_end = w_end / lambda;
  while (t < t_end) {
    const double a1 = acc(t, x, v);
    const double x2 = x + 0.5 * dt * v, v2 = v + 0.5 * dt * a1, a2 = acc(t + 0.5 * dt, x2, v2);
    const double x3 = x + 0.5 * dt * v2, v3 = v + 0.5 * dt * a2, a3 = acc(t + 0.5 * dt, x3, v3);
    const double x4 = x + dt * v3, v4 = v + dt * a3, a4 = acc(t + dt, x4, v4);
    x += dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    t += dt;
    if (std::abs(x) > out.peak) {
      out.peak = std::abs(x);
      out.speed_ratio = lambda * t;
    }
  }
  out.peak_fraction = zeta > 0.0 ? out.peak / steady : 0.0;
  return out;
}

Campbell campbell_diagram(const Rotor& rotor, const std::vector<double>& speeds, const std::vector<double>& orders,
                          const ModalOptions& options) {
  Campbell c;
  for (double s : speeds) c.points.push_back(modal_analysis(rotor, s, options));

  constexpr double kRelativeSpeedTolerance = 1e-6;
  for (double order : orders) {
    for (Whirl whirl : {Whirl::Forward, Whirl::Backward}) {
      for (int branch = 0; branch < options.n_modes; ++branch) {
        auto residual = [&](const ModalResult& r) {
          return branch_frequency(r, whirl, branch) - order * r.speed / (2.0 * M_PI);
        };
        for (std::size_t i = 1; i < c.points.size(); ++i) {
          double lo = speeds[i - 1], hi = speeds[i];
          double flo = residual(c.points[i - 1]), fhi = residual(c.points[i]);
          if (!(std::isfinite(flo) && std::isfinite(fhi)) || flo * fhi > 0.0 || (flo == 0.0 && i > 1)) continue;
          // Bisection on the branch frequency minus the order line.
          ModalResult mid_r = c.points[i];
          double f_lo = branch_frequency(c.points[i - 1], whirl, branch), f_hi = branch_frequency(mid_r, whirl, branch);
          for (int it = 0; it < 100 && hi - lo > kRelativeSpeedTolerance * std::max(1.0, hi); ++it) {
            const double mid = 0.5 * (lo + hi);
            mid_r = modal_analysis(rotor, mid, options);
            const double fm = residual(mid_r);
            if (!std::isfinite(fm)) break;
            if ((fm > 0.0) == (flo > 0.0)) {
              lo = mid;
              flo = fm;
              f_lo = branch_frequency(mid_r, whirl, branch);
            } else {
              hi = mid;
              f_hi = branch_frequency(mid_r, whirl, branch);
            }
          }
          // A branch that jumps across the order line (its index passing to another mode where a mode appears or
          // changes its whirl, as the floating rings' heavily damped ones do) crosses nothing: its frequency differs
          // on the two sides of the final bracket by far more than a crossing branch moves in it.
          const double f_line = order * 0.5 * (lo + hi) / (2.0 * M_PI);
          if (!(std::abs(f_hi - f_lo) <= 0.01 * f_line + 0.5)) continue;
          CriticalSpeed cs;
          cs.order = order;
          cs.branch = branch;
          cs.whirl = whirl;
          cs.speed = 0.5 * (lo + hi);
          cs.frequency = order * cs.speed / (2.0 * M_PI);
          if (const Mode* m = branch_mode(mid_r, whirl, branch)) cs.damping_ratio = m->damping_ratio;
          // The branch's slope at the crossing, and the amplification factor it and the damping ratio give.
          constexpr double kSlopeStep = 1e-4;  // of the speed
          const double dw = kSlopeStep * cs.speed;
          if (dw > 0.0) {
            const double f_c = cs.frequency;  // the branch's frequency at the crossing
            const double f_up = nearest_frequency(modal_analysis(rotor, cs.speed + dw, options), whirl, f_c);
            const double f_down = nearest_frequency(modal_analysis(rotor, cs.speed - dw, options), whirl, f_c);
            cs.branch_slope = (f_up - f_down) / (2.0 * dw / (2.0 * M_PI));
            if (std::isfinite(cs.branch_slope) && cs.damping_ratio > 0.0) {
              const double af = std::abs(order - cs.branch_slope) / (2.0 * order * cs.damping_ratio);
              cs.critically_damped = af < kCriticallyDampedAmplification;
              if (!cs.critically_damped) cs.amplification_factor = af;
            }
          }
          c.critical.push_back(cs);
        }
      }
    }
  }
  std::sort(c.critical.begin(), c.critical.end(),
            [](const CriticalSpeed& a, const CriticalSpeed& b) { return a.speed < b.speed; });
  return c;
}

}  // namespace turbodyn

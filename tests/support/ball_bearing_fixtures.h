// The reference ball bearing, a plain evaluator of its element and a CVODE integrator of its states, shared by
// the ball-bearing tests.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "model/elements/ball/ball_bearing.h"

namespace turbodyn::testing {

inline constexpr double kRpm = 2.0 * M_PI / 60.0;  // rad/s per rpm

// The reference bearing of docs/reference-machine.md, variant II (the spec defaults).
inline BallBearingSpec reference_bearing() { return BallBearingSpec{}; }

// The deep-groove reference of docs/references.md §5: Z = 7, D = 11.5 mm, d_m = 43.5 mm, f = 0.52 / 0.53 (the
// spec's defaults), zero clearance (free contact angle 0), E = 210 GPa, nu = 0.3, no preload, the outer ring held
// axially by a stiff spring.
inline BallBearingSpec deep_groove_reference() {
  BallBearingSpec s;
  s.n_balls = 7;
  s.ball_diameter = 11.5e-3;
  s.pitch_diameter = 43.5e-3;
  s.contact_angle = 0.0;
  s.ball_youngs_modulus = s.ring_youngs_modulus = 210e9;
  s.ball_poisson_ratio = s.ring_poisson_ratio = 0.3;
  s.preload = 0.0;
  s.preload_stiffness = 1e12;
  return s;
}

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

// CVODE (BDF, dense direct solver with CVODE's own difference-quotient Jacobian) on the element's states with
// the shaft held at (q, v) and spinning at a constant speed.
class ElementIntegrator {
 public:
  // With `powers`, two more states integrate the drive power (-torque on the shaft x speed) and the dissipated
  // power, so that an energy balance is as accurate as the integration itself.
  ElementIntegrator(const BallBearingElement& e, double speed, const Eigen::Vector4d& q, std::vector<double> z0,
             double rtol, double atol_factor, bool powers = false)
      : e_(e), ws_(e.make_workspace()), speed_(speed), q_(q), n_(e.n_states()), powers_(powers) {
    SUNContext_Create(nullptr, &ctx_);
    const int n = n_ + (powers ? 2 : 0);
    y_ = N_VNew_Serial(n, ctx_);
    atol_ = N_VNew_Serial(n, ctx_);
    for (int i = 0; i < n; ++i) {
      NV_Ith_S(y_, i) = i < n_ ? z0[i] : 0.0;
      NV_Ith_S(atol_, i) = i < n_ ? atol_factor * e.state_scale(i) : 1e-12;
    }
    mem_ = CVodeCreate(CV_BDF, ctx_);
    CVodeInit(mem_, &ElementIntegrator::Rhs, 0.0, y_);
    CVodeSetUserData(mem_, this);
    CVodeSVtolerances(mem_, rtol, atol_);
    A_ = SUNDenseMatrix(n, n, ctx_);
    ls_ = SUNLinSol_Dense(y_, A_, ctx_);
    CVodeSetLinearSolver(mem_, ls_, A_);
    CVodeSetMaxNumSteps(mem_, 10000000);
  }
  ~ElementIntegrator() {
    CVodeFree(&mem_);
    SUNLinSolFree(ls_);
    SUNMatDestroy(A_);
    N_VDestroy(y_);
    N_VDestroy(atol_);
    SUNContext_Free(&ctx_);
  }
  bool advance(double t_out) {
    double t = 0.0;
    return CVode(mem_, t_out, y_, &t, CV_NORMAL) >= 0;
  }
  const double* z() const { return N_VGetArrayPointer(y_); }
  double drive_work() const { return z()[n_]; }    ///< J, with `powers`
  double dissipated() const { return z()[n_ + 1]; }  ///< J, with `powers`
  long steps() const {
    long s = 0;
    CVodeGetNumSteps(mem_, &s);
    return s;
  }

 private:
  static int Rhs(sunrealtype, N_Vector y, N_Vector ydot, void* user) {
    auto* self = static_cast<ElementIntegrator*>(user);
    double f[4] = {0, 0, 0, 0};
    const double v[4] = {0, 0, 0, 0};
    const SpinState s{0.0, self->speed_, 0.0, 0.0};
    const double* z = N_VGetArrayPointer(y);
    double* zdot = N_VGetArrayPointer(ydot);
    if (!self->powers_) {
      self->e_.calc_and_add_forces(s, self->q_.data(), v, z, *self->ws_, f, zdot);
      return 0;
    }
    BallBearingLoads loads;
    self->e_.calc_bearing(s, self->q_.data(), v, z, OuterRingKinematics{}, loads, zdot);
    zdot[self->n_] = -loads.shaft_torque * self->speed_;
    zdot[self->n_ + 1] = self->e_.dissipated_power(s, self->q_.data(), v, z, *self->ws_);
    return 0;
  }
  const BallBearingElement& e_;
  std::unique_ptr<ElementWorkspace> ws_;
  double speed_;
  Eigen::Vector4d q_;
  int n_;
  bool powers_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr, atol_ = nullptr;
  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
};

}  // namespace turbodyn::testing

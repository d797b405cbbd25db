#include "model/engine/integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "model/engine/runup_workspace.h"
#include "model/engine/serial_vector_ops.h"

namespace turbodyn {

namespace {

struct Integration {
  const RunupModel* model = nullptr;
  RunupWorkspace* ws = nullptr;
  void* cvode = nullptr;
  double gamma_factored = -1.0;
  std::string last_error;
  const std::atomic<bool>* cancel = nullptr;  // RunupOptions::cancel
  bool cancelled = false;       // a right-hand side saw the cancel flag and stopped the integrator
  bool have_jacobian = false;   // the elements' Jacobians have been computed at least once
  long jacobian_step = 0;       // integrator step count at the last Jacobian
  long jacobian_failures = 0;   // nonlinear-solver failures counted at the last Jacobian
  // Newton convergence monitor (ls_solve): the attempt (step count and time) of the last solve, its iteration,
  // the weighted norm of its correction, and whether an iteration since the last Jacobian converged slowly.
  N_Vector weights = nullptr;
  long attempt_steps = -1;
  double attempt_t = 0.0;
  int iteration = 0;
  double last_correction = 0.0;
  bool slow = false;
  // State-dependent absolute tolerances (RunupModel::HasStateDependentTolerances): the error weights
  // 1 / (rtol |y_i| + f_i atol_i), f from RunupModel::AbsoluteToleranceFactors (CVODE's own weights otherwise).
  double rtol = 0.0;
  std::vector<double> atol, atol_factors;
};

int error_weights(N_Vector y, N_Vector ewt, void* user) {
  auto* in = static_cast<Integration*>(user);
  const double* yy = N_VGetArrayPointer(y);
  double* w = N_VGetArrayPointer(ewt);
  in->model->AbsoluteToleranceFactors(yy, in->atol_factors.data());
  const std::size_t n = in->atol.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double tol = in->rtol * std::abs(yy[i]) + in->atol_factors[i] * in->atol[i];
    if (!(tol > 0.0)) return -1;
    w[i] = 1.0 / tol;
  }
  return 0;
}

int rhs_callback(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* in = static_cast<Integration*>(user);
  // Ctrl-C is honoured inside an output interval too (a stalled run may take no sample for minutes): an
  // unrecoverable right-hand-side failure ends the integrator's call at once, with the state of its last step.
  if (in->cancel && in->cancel->load(std::memory_order_relaxed)) {
    in->cancelled = true;
    return -1;
  }
  try {
    in->model->Rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), *in->ws);
  } catch (const std::exception& e) {
    // A force element cannot be evaluated here (e.g. a film closes): recoverable, the integrator retries with a
    // smaller step; the message explains the failure if it persists.
    in->last_error = e.what();
    return 1;
  }
  for (sunindextype i = 0, n = N_VGetLength(ydot); i < n; ++i)
    if (!std::isfinite(NV_Ith_S(ydot, i))) return 1;  // recoverable: the integrator retries with a smaller step
  return 0;
}

void error_handler(int code, const char* module, const char* function, char* msg, void* user) {
  (void)code;
  auto* in = static_cast<Integration*>(user);
  in->last_error = std::string(module) + "/" + function + ": " + msg;
}

SUNLinearSolver_Type ls_type(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }

int ls_setup(SUNLinearSolver S, SUNMatrix) {
  auto* in = static_cast<Integration*>(S->content);
  sunrealtype tcur, gamma, rl1;
  N_Vector ypred, yn, fn, zn1;
  void* user = nullptr;
  if (CVodeGetNonlinearSystemData(in->cvode, &tcur, &ypred, &yn, &fn, &gamma, &rl1, &zn1, &user) != CV_SUCCESS)
    return -1;
  try {
    in->model->Jacobian(tcur, N_VGetArrayPointer(ypred), *in->ws);
    in->have_jacobian = true;
  } catch (const std::exception& e) {
    in->last_error = e.what();
    return 1;
  }
  in->gamma_factored = gamma;
  return in->model->FactorNewton(gamma, *in->ws) ? 0 : 1;
}

int ls_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
  auto* in = static_cast<Integration*>(S->content);
  const RunupModel& model = *in->model;
  RunupWorkspace& ws = *in->ws;
  // CVODE does not call the setup of a matrix-embedded solver on its own schedule, so the solve keeps the Newton
  // matrix current: a new Jacobian when the nonlinear solver failed since the last one (the Jacobian is stale:
  // nonlinear films), every kJacobianMaxSteps steps (CVODE's own default for matrix-based solvers is 51), and at the
  // start of an attempt after a Newton iteration converged slowly (a correction larger than kSlowConvergence times
  // the one before) with a Jacobian at least kSlowAge steps old: such a Jacobian is going stale, and refreshing it
  // before the iteration fails saves the failure's step cut (by 4). A slow iteration with a younger Jacobian is the
  // problem's nonlinearity (contacts, the damper's impacts), which a new Jacobian does not cure. When only the spin
  // speed has moved by more than 2 % since the last Jacobian, the rotor's gyroscopic terms are moved to it exactly
  // and the elements' blocks kept (RespinJacobian: in the run-ups' low-speed windows a tenth of the Jacobians, each
  // as dear as a few right-hand sides). A new factorisation when gamma (the step size) changed. bench/README.md has
  // the measurements.
  constexpr double kJacobianSpeedChange = 0.02;
  constexpr long kJacobianMaxSteps = 50;
  constexpr double kSlowConvergence = 0.3;
  constexpr long kSlowAge = 6;
  sunrealtype tcur, gamma, rl1;
  N_Vector ypred, yn, fn, zn1;
  void* user = nullptr;
  if (CVodeGetNonlinearSystemData(in->cvode, &tcur, &ypred, &yn, &fn, &gamma, &rl1, &zn1, &user) != CV_SUCCESS)
    return -1;
  const double w = model.speed().speed(tcur), w_jac = ws.jac_spin.speed;
  long steps = 0, failures = 0;
  CVodeGetNumSteps(in->cvode, &steps);
  CVodeGetNumNonlinSolvConvFails(in->cvode, &failures);
  if (steps != in->attempt_steps || tcur != in->attempt_t) {
    in->attempt_steps = steps;
    in->attempt_t = tcur;
    in->iteration = 0;
  }
  const bool stale = !in->have_jacobian || failures > in->jacobian_failures ||
                     steps - in->jacobian_step >= kJacobianMaxSteps ||
                     (in->slow && in->iteration == 0 && steps - in->jacobian_step >= kSlowAge);
  if (!stale && std::abs(w - w_jac) > kJacobianSpeedChange * std::max(std::abs(w_jac), 1.0)) {
    model.RespinJacobian(tcur, ws);
    in->gamma_factored = -1.0;
  } else if (stale) {
    in->slow = false;
    in->jacobian_step = steps;
    in->jacobian_failures = failures;
    try {
      model.Jacobian(tcur, N_VGetArrayPointer(ypred), ws);
    } catch (const std::exception& e) {
      in->last_error = e.what();
      return 1;
    }
    in->have_jacobian = true;
    in->gamma_factored = -1.0;
  }
  if (gamma != in->gamma_factored) {
    in->gamma_factored = gamma;
    if (!model.FactorNewton(gamma, ws)) return 1;  // recoverable: CVODE retries with a smaller step
  }
  model.SolveNewton(gamma, N_VGetArrayPointer(b), N_VGetArrayPointer(x), ws);
  CVodeGetErrWeights(in->cvode, in->weights);
  const double norm = N_VWrmsNorm(x, in->weights);
  if (in->iteration > 0 && norm > kSlowConvergence * in->last_correction) in->slow = true;
  in->last_correction = norm;
  ++in->iteration;
  return 0;
}

int ls_free(SUNLinearSolver S) {
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return 0;
}

std::string describe_stop(double t, double speed, const std::string& cause) {
  std::ostringstream os;
  os << "stopped at t = " << t << " s (" << std::llround(speed * 60.0 / (2.0 * M_PI)) << " rpm): " << cause;
  return os.str();
}

}  // namespace

RunupOptions runup_options(const MachineSpec& spec) {
  RunupOptions ro;
  ro.solver = spec.solver;
  ro.sample_rate = spec.output.sample_rate;
  return ro;
}

Integrator resolve_integrator(const RunupModel& model, Integrator requested) {
  if (requested != Integrator::Auto) return requested;
  // Measured (bench/README.md): with linear bearings BDF with the structured Newton solver beats the explicit
  // method 1.5x on the reduced rotor and by far more on the unreduced one. New bearing types refine this rule
  // with their own measurements.
  (void)model;
  return Integrator::CvodeBdf;
}

RunupResult simulate_runup(const RunupModel& model, const RunupOptions& options) {
  if (std::string why; !options.solver.IsValid(&why)) throw std::invalid_argument(why);
  const auto wall0 = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(); };
  RunupResult result;
  result.channels = model.channels();
  result.columns.assign(result.channels.size(), {});

  auto ws = model.make_workspace(options.threads);
  const int ny = model.n_states();
  const double t0 = options.t_start;
  const double t_end = options.t_end > 0.0 ? options.t_end : model.speed().duration();
  const double dt_out = 1.0 / options.sample_rate;

  SUNContext ctx = nullptr;
  SUNContext_Create(nullptr, &ctx);
  N_Vector y = N_VNew_Serial(ny, ctx);
  UseCompiledVectorOps(y);  // the integrators' vectors are clones of y
  std::vector<double> values(result.channels.size());
  auto record = [&](double t) {
    try {
      model.Probes(t, N_VGetArrayPointer(y), *ws, values.data());
    } catch (const std::exception&) {
      std::fill(values.begin(), values.end(), std::nan(""));
    }
    result.time.push_back(t);
    for (std::size_t c = 0; c < values.size(); ++c) result.columns[c].push_back(values[c]);
    if (options.sink) options.sink(t, values.data());
  };

  try {
    if (options.initial_state.empty()) {
      model.InitialState(t0, options.solver.static_start, N_VGetArrayPointer(y), *ws);
    } else {
      if (static_cast<int>(options.initial_state.size()) != ny)
        throw std::invalid_argument("the initial state has " + std::to_string(options.initial_state.size()) +
                                    " values, the model " + std::to_string(ny) + " states");
      std::copy(options.initial_state.begin(), options.initial_state.end(), N_VGetArrayPointer(y));
    }
  } catch (const std::exception& e) {
    result.message = describe_stop(t0, model.spin(t0).speed, e.what());
    N_VDestroy(y);
    SUNContext_Free(&ctx);
    return result;
  }
  result.energy_initial = model.MechanicalEnergy(t0, N_VGetArrayPointer(y));
  record(t0);

  N_Vector atol = N_VClone(y);
  {
    const Eigen::VectorXd a =
        model.AbsoluteTolerances(options.solver.atol, options.solver.atol_scaling == AtolScaling::Typical);
    for (int i = 0; i < ny; ++i) NV_Ith_S(atol, i) = a(i);
  }
  Integration in;
  in.model = &model;
  in.ws = ws.get();
  in.cancel = options.cancel;
  in.weights = N_VClone(y);
  void* mem = nullptr;
  SUNLinearSolver LS = nullptr;
  // Elements whose absolute tolerances depend on the state (scaled tolerances only): the integrator's error weights
  // come from error_weights() at every step.
  const bool state_dependent =
      options.solver.atol_scaling == AtolScaling::Typical && model.HasStateDependentTolerances();
  if (state_dependent) {
    in.rtol = options.solver.rtol;
    in.atol.assign(N_VGetArrayPointer(atol), N_VGetArrayPointer(atol) + ny);
    in.atol_factors.assign(ny, 1.0);
  }
  const Integrator integrator = resolve_integrator(model, options.solver.integrator);
  const bool bdf = integrator == Integrator::CvodeBdf;
  // The settings both integrators take, through their own functions (CVODE's and ERKStep's are alike).
  auto configure = [&](auto set_user_data, auto set_error_handler, auto set_tolerances, auto set_max_steps,
                       auto set_max_step, auto set_stop_time) {
    set_user_data(mem, &in);
    set_error_handler(mem, error_handler, &in);
    set_tolerances(mem, options.solver.rtol, atol);
    set_max_steps(mem, options.solver.max_steps);
    if (options.solver.max_step > 0) set_max_step(mem, options.solver.max_step);
    set_stop_time(mem, t_end);
  };
  if (bdf) {
    mem = CVodeCreate(CV_BDF, ctx);
    in.cvode = mem;
    CVodeInit(mem, rhs_callback, t0, y);
    configure(CVodeSetUserData, CVodeSetErrHandlerFn, CVodeSVtolerances, CVodeSetMaxNumSteps, CVodeSetMaxStep,
              CVodeSetStopTime);
    if (state_dependent) CVodeWFtolerances(mem, error_weights);
    CVodeSetMaxOrd(mem, options.solver.max_order);
    CVodeSetNonlinConvCoef(mem, options.solver.newton_tolerance);
    CVodeSetStabLimDet(mem, options.stability_limit_detection ? SUNTRUE : SUNFALSE);
    LS = SUNLinSolNewEmpty(ctx);
    LS->content = &in;
    LS->ops->gettype = ls_type;
    LS->ops->setup = ls_setup;
    LS->ops->solve = ls_solve;
    LS->ops->free = ls_free;
    CVodeSetLinearSolver(mem, LS, nullptr);
  } else if (integrator == Integrator::ArkodeErk) {
    mem = ERKStepCreate(rhs_callback, t0, y, ctx);
    configure(ERKStepSetUserData, ERKStepSetErrHandlerFn, ERKStepSVtolerances, ERKStepSetMaxNumSteps,
              ERKStepSetMaxStep, ERKStepSetStopTime);
    if (state_dependent) ERKStepWFtolerances(mem, error_weights);
  } else {
    N_VDestroy(atol);
    N_VDestroy(in.weights);
    N_VDestroy(y);
    SUNContext_Free(&ctx);
    throw std::invalid_argument("unknown integrator (cvode-bdf or arkode-erk)");
  }
  N_VDestroy(atol);  // the integrators keep copies

  double last_progress = 0.0;
  double t = t0;
  const long n_out = static_cast<long>(std::floor((t_end - t0) * options.sample_rate + 1e-9));
  result.complete = true;
  for (long k = 1; k <= n_out; ++k) {
    const double tout = std::min(t0 + k * dt_out, t_end);
    const int flag = bdf ? CVode(mem, tout, y, &t, CV_NORMAL) : ERKStepEvolve(mem, tout, y, &t, ARK_NORMAL);
    if (flag < 0 && in.cancelled) {
      result.complete = false;
      result.message = describe_stop(t, model.spin(t).speed, "interrupted");
      break;
    }
    if (flag < 0) {
      const char* name = bdf ? CVodeGetReturnFlagName(flag) : ERKStepGetReturnFlagName(flag);
      std::string cause = std::string(name ? name : "integrator failure");
      if (name) free(const_cast<char*>(name));
      if (!in.last_error.empty()) cause += " (" + in.last_error + ")";
      result.complete = false;
      result.message = describe_stop(t, model.spin(t).speed, cause);
      break;
    }
    record(t);
    if (options.cancel && options.cancel->load()) {
      result.complete = false;
      result.message = describe_stop(t, model.spin(t).speed, "interrupted");
      break;
    }
    if (options.progress && wall() - last_progress > 0.5) {
      last_progress = wall();
      options.progress(t, model.spin(t).speed, last_progress);
    }
  }
  result.t_reached = t;
  const double* yy = N_VGetArrayPointer(y);
  result.energy_final = model.MechanicalEnergy(t, yy);
  result.work_in = yy[ny - 2];
  result.dissipated = yy[ny - 1];

  long steps = 0, etf = 0, ncf = 0, nfe = 0;
  if (bdf) {
    CVodeGetNumSteps(mem, &steps);
    CVodeGetNumErrTestFails(mem, &etf);
    CVodeGetNumNonlinSolvConvFails(mem, &ncf);
    CVodeFree(&mem);
    SUNLinSolFree(LS);
  } else {
    ERKStepGetNumSteps(mem, &steps);
    ERKStepGetNumErrTestFails(mem, &etf);
    long expl = 0;
    ERKStepGetNumRhsEvals(mem, &expl);
    nfe = expl;
    ERKStepFree(&mem);
  }
  (void)nfe;
  result.stats.steps = steps;
  result.stats.error_test_failures = etf;
  result.stats.nonlinear_failures = ncf;
  result.stats.rhs_calls = ws->rhs_calls;
  result.stats.element_calls = ws->element_calls;
  result.stats.jacobian_evaluations = ws->jacobian_evaluations;
  result.stats.linear_setups = ws->factorisations;
  result.stats.wall_time = wall();
  N_VDestroy(in.weights);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  return result;
}

}  // namespace turbodyn

// Integration of a run-up model (runup.h) in time with SUNDIALS: CVODE's BDF with the model's structured Newton
// solver, or ARKODE's explicit Runge-Kutta; output sampling, progress, cancellation and the run's statistics.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "model/engine/runup.h"
#include "model/spec/model_spec.h"

namespace turbodyn {

/// What one run-up asks for: the integration settings of the model file's [solver] table and what belongs to the
/// run alone.
struct RunupOptions {
  SolverSpec solver;           ///< its reduction_cutoff is the model's (make_runup_model) and unused here
  double sample_rate = 20000;  ///< 1/s
  double t_start = 0.0;        ///< s
  double t_end = 0.0;          ///< s, 0 = end of the speed profile
  /// The state at t_start (RunupModel::n_states() values, e.g. a steady state of model/engine/stability.h);
  /// empty: the model's InitialState (static equilibrium or rest, as solver.static_start says).
  std::vector<double> initial_state;
  bool stability_limit_detection = true;  ///< BDF: lower the order when higher orders turn unstable
  /// Threads for the force elements of one right-hand side (RunupModel::make_workspace); the results do not
  /// depend on it. 1 in parameter studies, which already run one simulation per core.
  int threads = 1;
  /// Called about twice a second of wall time.
  std::function<void(double t, double speed, double wall_seconds)> progress;
  /// Called with every output sample (time, channel values); e.g. to stream into a file.
  std::function<void(double t, const double* values)> sink;
  const std::atomic<bool>* cancel = nullptr;  ///< set to stop the run early (Ctrl-C)
};

/// The options a model file's [solver] and [output] tables ask for.
RunupOptions runup_options(const MachineSpec& spec);

/// The integrator Auto stands for with this model (any other request is returned as it is).
Integrator resolve_integrator(const RunupModel& model, Integrator requested);

struct RunupStats {
  long steps = 0;
  long rhs_calls = 0;             ///< right-hand-side evaluations (including those for Jacobians)
  long element_calls = 0;         ///< force-element evaluations
  long jacobian_evaluations = 0;
  long linear_setups = 0;         ///< Newton matrix factorisations
  long error_test_failures = 0;
  long nonlinear_failures = 0;
  double wall_time = 0.0;         ///< s
};

struct RunupResult {
  bool complete = false;
  std::string message;            ///< why it stopped early (empty when complete)
  double t_reached = 0.0;
  std::vector<ProbeChannel> channels;
  std::vector<double> time;
  std::vector<std::vector<double>> columns;  ///< columns[c][sample]
  RunupStats stats;
  // Energy balance: E(t_end) - E(t0) against the work put in minus the energy dissipated.
  double energy_initial = 0.0, energy_final = 0.0, work_in = 0.0, dissipated = 0.0;
};

/// Integrates the run-up. Never throws for integrator failures or cancellation: the result then has
/// complete == false, a message naming the time, speed and cause, and all samples up to that point.
RunupResult simulate_runup(const RunupModel& model, const RunupOptions& options);

}  // namespace turbodyn

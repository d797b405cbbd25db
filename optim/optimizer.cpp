#include "optim/optimizer.h"
#include "studies/parallel.h"
#include "studies/table.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <set>

#include <nlopt.hpp>

#include "optim/evaluation_log.h"

namespace turbodyn::optim {
namespace {

constexpr double kFirstFailureObjective = 1e6;  // objective of a failed evaluation before any succeeded
constexpr double kFailureFactor = 10.0;         // later: this times the largest |objective| seen so far
constexpr double kDefaultLocalFtol = 1e-4;      // MLSL / AUGLAG subsidiary searches when no tolerance is given

nlopt::algorithm nlopt_algorithm(const std::string& name) {
  if (name == "cobyla") return nlopt::LN_COBYLA;
  if (name == "bobyqa") return nlopt::LN_BOBYQA;
  if (name == "sbplx") return nlopt::LN_SBPLX;
  if (name == "direct-l") return nlopt::GN_DIRECT_L;
  if (name == "crs2") return nlopt::GN_CRS2_LM;
  if (name == "isres") return nlopt::GN_ISRES;
  if (name == "mlsl") return nlopt::G_MLSL_LDS;
  if (name == "mma") return nlopt::LD_MMA;
  if (name == "slsqp") return nlopt::LD_SLSQP;
  throw ModelError("unknown algorithm '" + name + "'");
}

std::string nlopt_name(nlopt::algorithm a) {
  // NLopt's own identifiers, as in its documentation.
  switch (a) {
    case nlopt::LN_COBYLA: return "NLOPT_LN_COBYLA";
    case nlopt::LN_BOBYQA: return "NLOPT_LN_BOBYQA";
    case nlopt::LN_SBPLX: return "NLOPT_LN_SBPLX";
    case nlopt::GN_DIRECT_L: return "NLOPT_GN_DIRECT_L";
    case nlopt::GN_CRS2_LM: return "NLOPT_GN_CRS2_LM";
    case nlopt::GN_ISRES: return "NLOPT_GN_ISRES";
    case nlopt::G_MLSL_LDS: return "NLOPT_G_MLSL_LDS";
    case nlopt::LD_MMA: return "NLOPT_LD_MMA";
    case nlopt::LD_SLSQP: return "NLOPT_LD_SLSQP";
    case nlopt::AUGLAG: return "NLOPT_AUGLAG";
    default: return "NLOPT_" + std::to_string(static_cast<int>(a));
  }
}

void set_tolerances(nlopt::opt& o, const AlgorithmOptions& a, unsigned n, bool subsidiary) {
  if (a.xtol_rel > 0) o.set_xtol_rel(a.xtol_rel);
  if (a.xtol_abs > 0) o.set_xtol_abs(std::vector<double>(n, a.xtol_abs));
  if (a.ftol_rel > 0) o.set_ftol_rel(a.ftol_rel);
  if (a.ftol_abs > 0) o.set_ftol_abs(a.ftol_abs);
  if (subsidiary && a.xtol_rel <= 0 && a.xtol_abs <= 0 && a.ftol_rel <= 0 && a.ftol_abs <= 0)
    o.set_ftol_rel(kDefaultLocalFtol);
  if (a.initial_step > 0 && !is_global(a.name)) o.set_initial_step(std::vector<double>(n, a.initial_step));
}

// The state shared by NLopt's callbacks.
class Driver {
 public:
  Driver(const OptimizationSpec& spec, const Evaluator& evaluate, const OptimizerOptions& options)
      : spec_(spec), evaluate_(evaluate), options_(options),
        log_(fingerprint(spec), options.log_file), threads_(studies::run_threads(options.threads, spec.threads)),
        t0_(std::chrono::steady_clock::now()) {}

  double objective(const std::vector<double>& x, std::vector<double>& grad) {
    const std::vector<Point> pts = evaluate_stencil(x, !grad.empty());
    const Assessment& centre = pts[0].assessment;
    if (!grad.empty()) gradient(pts, [](const Assessment& a) { return a.objective; }, grad.data(), 1);
    return centre.objective;
  }

  void constraints(unsigned m, double* result, unsigned n, const double* xp, double* grad) {
    const std::vector<double> x(xp, xp + n);
    const std::vector<Point> pts = evaluate_stencil(x, grad != nullptr, /*from_constraints=*/true);
    for (unsigned i = 0; i < m; ++i) {
      result[i] = pts[0].assessment.g[i];
      if (grad) gradient(pts, [i](const Assessment& a) { return a.g[i]; }, grad + i * n, 1);
    }
  }

  OptimizationResult& result() { return result_; }
  const std::exception_ptr& error() const { return error_; }
  void set_error(std::exception_ptr e) {
    if (!error_) error_ = e;
  }
  bool cancelled() const { return cancelled_; }

 private:
  struct Point {
    std::vector<double> x;    // scaled
    int axis = -1;            // finite-difference direction (-1: the centre)
    double step = 0.0;        // signed scaled step along axis
    Assessment assessment;
  };

  std::vector<double> design_of(const std::vector<double>& x) const {
    std::vector<double> d(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) d[i] = spec_.variables[i].value(x[i]);
    return d;
  }

  // The centre and, for a gradient, the finite-difference points (one-sided at the bounds); evaluated together, the
  // new ones in parallel.
  std::vector<Point> evaluate_stencil(const std::vector<double>& x, bool with_gradient, bool from_constraints = false) {
    std::vector<Point> pts{{x, -1, 0.0, {}}};
    if (with_gradient) {
      const double h = spec_.algorithm.gradient_step;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const bool up = x[i] + h <= 1.0, down = x[i] - h >= 0.0;
        std::vector<double> xp = x;
        if (spec_.algorithm.central_differences && up && down) {
          xp[i] = x[i] + h;
          pts.push_back({xp, static_cast<int>(i), h, {}});
          xp[i] = x[i] - h;
          pts.push_back({xp, static_cast<int>(i), -h, {}});
        } else {
          xp[i] = up ? x[i] + h : x[i] - h;
          pts.push_back({xp, static_cast<int>(i), xp[i] - x[i], {}});
        }
      }
    }
    std::vector<std::vector<double>> designs;
    for (const Point& p : pts) designs.push_back(design_of(p.x));
    const std::vector<std::pair<const Evaluation*, bool>> evals = evaluate_designs(designs);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      pts[k].assessment = assess(spec_, *evals[k].first, failure_objective());
      // Constraint callbacks come with the objective's point: record only what the objective has not.
      if (from_constraints && seen_.count(designs[k])) continue;
      add_history(*evals[k].first, pts[k].assessment, evals[k].second, k > 0);
      seen_.insert(designs[k]);
    }
    return pts;
  }

  // Cached or new evaluations of `designs` (new ones run in parallel, each recorded as it finishes); second = cached.
  std::vector<std::pair<const Evaluation*, bool>> evaluate_designs(const std::vector<std::vector<double>>& designs) {
    if (options_.cancel && options_.cancel->load()) stop();
    std::vector<std::pair<const Evaluation*, bool>> out(designs.size(), {nullptr, true});
    std::vector<std::size_t> todo;
    for (std::size_t k = 0; k < designs.size(); ++k) {
      out[k].first = log_.find(designs[k]);
      const bool duplicate = std::any_of(todo.begin(), todo.end(), [&](std::size_t j) { return designs[j] == designs[k]; });
      if (!out[k].first && !duplicate) todo.push_back(k);
    }
    if (!todo.empty()) {
      const std::size_t first_id = log_.reserve_ids(todo.size());
      std::mutex mutex;
      bool cancelled = false;
      std::exception_ptr error;
      studies::parallel_runs(todo.size(), threads_, [&](std::size_t t) {
        const auto t0 = std::chrono::steady_clock::now();
        Evaluation e;
        e.id = first_id + t;
        e.design = designs[todo[t]];
        try {
          e.cases = evaluate_(e.design, options_.cancel);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(mutex);
          if (!error) error = std::current_exception();
          return;
        }
        e.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        {
          const std::lock_guard<std::mutex> lock(mutex);
          ++result_.new_evaluations;
          if (std::any_of(e.cases.begin(), e.cases.end(), [](const CaseResult& c) { return c.status == "cancelled"; })) {
            cancelled = true;  // not logged: a restart runs it again
            return;
          }
        }
        // For the reader of the log: objective (null if the evaluation failed) and constraint values.
        const Assessment a = assess(spec_, e, NAN);
        const nlohmann::json info = {{"objective", studies::json_number(a.objective)},
                                     {"constraint_values", studies::json_numbers(a.constraint_values)},
                                     {"feasible", a.feasible}};
        log_.record(std::move(e), info);
      });
      if (error) {
        error_ = error;
        throw nlopt::forced_stop();
      }
      if (cancelled || (options_.cancel && options_.cancel->load())) stop();
      for (std::size_t k : todo) out[k] = {log_.find(designs[k]), false};
    }
    for (std::size_t k = 0; k < designs.size(); ++k)
      if (!out[k].first) out[k] = {log_.find(designs[k]), true};
    return out;
  }

  [[noreturn]] void stop() {
    cancelled_ = true;
    throw nlopt::forced_stop();
  }

  // Objective given to failed evaluations: worse than anything seen, so the optimiser moves away (deterministic: it
  // depends only on the requests before this one).
  double failure_objective() const {
    return largest_objective_ > 0.0 ? kFailureFactor * largest_objective_ : kFirstFailureObjective;
  }

  void add_history(const Evaluation& e, const Assessment& a, bool cached, bool gradient_point) {
    HistoryEntry h;
    h.request = result_.history.size();
    h.evaluation = e;
    h.assessment = a;
    h.cached = cached;
    h.gradient_point = gradient_point;
    if (cached) ++result_.cached_evaluations;
    if (!a.failed) largest_objective_ = std::max(largest_objective_, std::abs(a.objective));
    if (a.feasible && (std::isnan(progress_.best_objective) || a.objective < progress_.best_objective))
      progress_.best_objective = a.objective;
    result_.history.push_back(std::move(h));
    progress_.requests = result_.history.size();
    progress_.new_evaluations = result_.new_evaluations;
    progress_.cached_evaluations = result_.cached_evaluations;
    progress_.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    if (options_.progress) options_.progress(result_.history.back(), progress_);
  }

  template <class F>
  void gradient(const std::vector<Point>& pts, F value, double* grad, std::size_t stride) const {
    const std::size_t n = pts[0].x.size();
    std::vector<double> plus(n, NAN), minus(n, NAN), hp(n, 0.0), hm(n, 0.0);
    for (std::size_t k = 1; k < pts.size(); ++k) {
      const std::size_t i = static_cast<std::size_t>(pts[k].axis);
      if (pts[k].step > 0) {
        plus[i] = value(pts[k].assessment);
        hp[i] = pts[k].step;
      } else {
        minus[i] = value(pts[k].assessment);
        hm[i] = pts[k].step;
      }
    }
    const double f0 = value(pts[0].assessment);
    for (std::size_t i = 0; i < n; ++i) {
      double g;
      if (!std::isnan(plus[i]) && !std::isnan(minus[i])) g = (plus[i] - minus[i]) / (hp[i] - hm[i]);
      else if (!std::isnan(plus[i])) g = (plus[i] - f0) / hp[i];
      else g = (minus[i] - f0) / hm[i];
      grad[i * stride] = g;
    }
  }

  const OptimizationSpec& spec_;
  const Evaluator& evaluate_;
  const OptimizerOptions& options_;
  EvaluationLog log_;
  int threads_;
  std::chrono::steady_clock::time_point t0_;
  OptimizationResult result_;
  OptimizationProgress progress_;
  std::set<std::vector<double>> seen_;
  double largest_objective_ = 0.0;
  std::exception_ptr error_;
  bool cancelled_ = false;
};

// NLopt's C++ wrapper turns any exception into a generic failure: keep ours and stop instead.
double objective_callback(const std::vector<double>& x, std::vector<double>& grad, void* data) {
  Driver* d = static_cast<Driver*>(data);
  try {
    return d->objective(x, grad);
  } catch (const nlopt::forced_stop&) {
    throw;
  } catch (...) {
    d->set_error(std::current_exception());
    throw nlopt::forced_stop();
  }
}

void constraint_callback(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
  Driver* d = static_cast<Driver*>(data);
  try {
    d->constraints(m, result, n, x, grad);
  } catch (const nlopt::forced_stop&) {
    throw;
  } catch (...) {
    d->set_error(std::current_exception());
    throw nlopt::forced_stop();
  }
}

}  // namespace

std::string result_name(int code) {
  switch (code) {
    case NLOPT_SUCCESS: return "SUCCESS";
    case NLOPT_STOPVAL_REACHED: return "STOPVAL_REACHED";
    case NLOPT_FTOL_REACHED: return "FTOL_REACHED";
    case NLOPT_XTOL_REACHED: return "XTOL_REACHED";
    case NLOPT_MAXEVAL_REACHED: return "MAXEVAL_REACHED";
    case NLOPT_MAXTIME_REACHED: return "MAXTIME_REACHED";
    case NLOPT_FAILURE: return "FAILURE";
    case NLOPT_INVALID_ARGS: return "INVALID_ARGS";
    case NLOPT_OUT_OF_MEMORY: return "OUT_OF_MEMORY";
    case NLOPT_ROUNDOFF_LIMITED: return "ROUNDOFF_LIMITED";
    case NLOPT_FORCED_STOP: return "FORCED_STOP";
    default: return "UNKNOWN";
  }
}

std::string result_reason(int code) {
  switch (code) {
    case NLOPT_SUCCESS: return "converged";
    case NLOPT_STOPVAL_REACHED: return "the objective reached stopval";
    case NLOPT_FTOL_REACHED: return "the objective changed by less than ftol_rel/ftol_abs";
    case NLOPT_XTOL_REACHED: return "the design changed by less than xtol_rel/xtol_abs";
    case NLOPT_MAXEVAL_REACHED: return "maxeval reached";
    case NLOPT_MAXTIME_REACHED: return "maxtime reached";
    case NLOPT_FAILURE: return "NLopt failed (generic failure)";
    case NLOPT_INVALID_ARGS: return "NLopt rejected the arguments";
    case NLOPT_OUT_OF_MEMORY: return "out of memory";
    case NLOPT_ROUNDOFF_LIMITED: return "roundoff errors limited progress (the best design found is still valid)";
    case NLOPT_FORCED_STOP: return "interrupted";
    default: return "unknown NLopt result";
  }
}

OptimizationResult optimize(const OptimizationSpec& spec, const Evaluator& evaluate, const OptimizerOptions& options) {
  const AlgorithmOptions& a = spec.algorithm;
  std::string why;
  if (!a.IsValid(&why)) throw ModelError(spec.source.string() + ": [algorithm]: " + why);
  if (spec.variables.empty()) throw ModelError(spec.source.string() + ": no design variables");
  const unsigned n = static_cast<unsigned>(spec.variables.size());

  Driver driver(spec, evaluate, options);
  OptimizationResult& result = driver.result();
  const nlopt::algorithm main = nlopt_algorithm(a.name);
  const bool constrained = !spec.constraints.empty();
  const bool auglag = constrained && !supports_constraints(a.name);
  if (constrained && auglag && is_global(a.name))
    throw ModelError(spec.source.string() + ": [algorithm]: " + a.name + " handles bound constraints only");
  nlopt::opt opt(auglag ? nlopt::AUGLAG : main, n);
  result.algorithm = nlopt_name(auglag ? nlopt::AUGLAG : main);
  if (auglag) {
    nlopt::opt sub(main, n);
    set_tolerances(sub, a, n, true);
    opt.set_local_optimizer(sub);
    result.algorithm += " + " + nlopt_name(main);
    result.note = a.name + " handles bound constraints only: the constraints are handled by NLopt's augmented "
                           "Lagrangian (AUGLAG) around it";
  } else if (a.name == "mlsl") {
    AlgorithmOptions la = a;
    la.name = a.local;
    nlopt::opt local(nlopt_algorithm(a.local), n);
    set_tolerances(local, la, n, true);
    opt.set_local_optimizer(local);
    result.algorithm += " + " + nlopt_name(nlopt_algorithm(a.local));
  }
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  set_tolerances(opt, a, n, false);
  if (a.maxeval > 0) opt.set_maxeval(a.maxeval);
  if (a.maxtime > 0) opt.set_maxtime(a.maxtime);
  if (a.has_stopval) opt.set_stopval(a.stopval);
  opt.set_min_objective(objective_callback, &driver);
  if (constrained) {
    const std::size_t m = spec.n_constraint_values();
    opt.add_inequality_mconstraint(constraint_callback, &driver, std::vector<double>(m, a.constraint_tolerance));
  }
  nlopt::srand(a.seed);  // CRS2, ISRES, MLSL: the same sequence on every run (and on a restart)

  std::vector<double> x(n);
  for (unsigned i = 0; i < n; ++i) x[i] = spec.variables[i].scaled(spec.variables[i].start);
  double f = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    opt.optimize(x, f);
  } catch (const nlopt::forced_stop&) {
    if (driver.error()) std::rethrow_exception(driver.error());
  } catch (const nlopt::roundoff_limited&) {
  } catch (const std::invalid_argument& e) {
    if (driver.error()) std::rethrow_exception(driver.error());
    throw ModelError(spec.source.string() + ": NLopt rejected the problem (" + result.algorithm + "): " + e.what());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::runtime_error&) {
    if (driver.error()) std::rethrow_exception(driver.error());
  }
  result.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  result.nlopt_code = static_cast<int>(opt.last_optimize_result());
  result.interrupted = driver.cancelled();
  result.nlopt_result = result_name(result.nlopt_code);
  result.reason = result_reason(result.nlopt_code);

  // The best design: feasible with the lowest objective, else the least infeasible that ran.
  for (std::size_t k = 0; k < result.history.size(); ++k) {
    const Assessment& h = result.history[k].assessment;
    if (!h.feasible) continue;
    if (!result.best || h.objective < result.history[*result.best].assessment.objective) result.best = k;
  }
  result.best_feasible = result.best.has_value();
  if (!result.best)
    for (std::size_t k = 0; k < result.history.size(); ++k) {
      const Assessment& h = result.history[k].assessment;
      if (h.failed) continue;
      if (!result.best || h.max_violation < result.history[*result.best].assessment.max_violation) result.best = k;
    }
  return result;
}

}  // namespace turbodyn::optim

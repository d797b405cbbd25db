// The optimiser: analytic problems with known optima through the same NLopt driver (evaluator injected), the
// optimum support damping of a Jeffcott rotor against its closed form, study-file errors, restart from the log,
// failed evaluations, thread-count invariance and the best-design model file.
#include "optim/optimizer.h"

#include <cmath>
#include <fstream>
#include <mutex>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/io/model_file.h"
#include "model/io/overrides.h"
#include "optim/evaluation_log.h"
#include "optim/report.h"
#include "tests/support/test_support.h"
#include "tests/support/temp_dir.h"

namespace turbodyn::optim {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::filesystem::path temp_dir(const std::string& name) { return turbodyn::testing::fresh_temp_dir("optim_test_" + name); }

// ------------------------------------------------------------------------------------------ analytic problems

// Two variables in [-3, 3], metrics computed directly from the design: no model involved.
OptimizationSpec analytic_spec(const std::string& algorithm, bool constrained) {
  OptimizationSpec s;
  s.name = "analytic";
  s.cases = {{"only", 1.0, {}}};
  for (const char* p : {"x", "y"}) {
    Variable v;
    v.path = p;
    v.paths = {p};
    v.low = -3.0;
    v.high = 3.0;
    v.start = -1.0;
    s.variables.push_back(v);
  }
  Metric f, c;
  f.spec.name = "f";
  c.spec.name = "x_plus_y";
  s.metrics = {f, c};
  s.objective.terms = {{0, 1.0}};
  if (constrained) s.constraints.push_back({"x_plus_y", 1, true, 2.0});
  s.algorithm.name = algorithm;
  s.algorithm.xtol_rel = 1e-8;
  // No ftol: NLopt's COBYLA stops on ftol when it evaluates one point twice in a row.
  s.algorithm.maxeval = 4000;
  return s;
}

// Rosenbrock: f = (1 - x)^2 + 100 (y - x^2)^2, minimum 0 at (1, 1).
std::vector<CaseResult> rosenbrock(const std::vector<double>& d, const std::atomic<bool>*) {
  CaseResult r;
  r.metrics = {std::pow(1 - d[0], 2) + 100 * std::pow(d[1] - d[0] * d[0], 2), d[0] + d[1]};
  return {r};
}

// Constrained quadratic: f = (x - 2)^2 + (y - 1)^2 with x + y <= 2: the projection of (2, 1) on the line,
// (1.5, 0.5), f = 0.5.
std::vector<CaseResult> quadratic(const std::vector<double>& d, const std::atomic<bool>*) {
  CaseResult r;
  r.metrics = {std::pow(d[0] - 2, 2) + std::pow(d[1] - 1, 2), d[0] + d[1]};
  return {r};
}

TEST(Optimizer, RosenbrockMinimumWithLocalGlobalAndGradientAlgorithms) {
  struct Case {
    const char* algorithm;
    double tolerance;  // on |x - x*|: local methods converge tightly, the global ones to their sampling resolution
  };
  for (const Case& c : {Case{"bobyqa", 1e-4}, Case{"sbplx", 1e-3}, Case{"cobyla", 3e-2}, Case{"mma", 1e-3},
                        Case{"slsqp", 1e-3}, Case{"direct-l", 5e-2}, Case{"crs2", 5e-2}, Case{"mlsl", 1e-3}}) {
    SCOPED_TRACE(c.algorithm);
    OptimizationSpec s = analytic_spec(c.algorithm, false);
    if (s.algorithm.name == "mma" || s.algorithm.name == "slsqp") s.algorithm.gradient_step = 1e-7;
    // MMA's conservative approximations crawl along the curved valley, and how fast depends on the round-off of the
    // finite-difference gradient: within 4,000 evaluations on a baseline x86-64 build, 14,430 to reach xtol_rel
    // with fused multiply-adds (x86-64-v3).
    if (s.algorithm.name == "mma") s.algorithm.maxeval = 20000;
    if (is_global(c.algorithm)) {
      s.algorithm.maxeval = 3000;
      s.algorithm.xtol_rel = 0.0;
      s.algorithm.ftol_rel = 0.0;
    }
    if (s.algorithm.name == "mlsl") {
      s.algorithm.maxeval = 1500;
      s.algorithm.local = "bobyqa";
      s.algorithm.xtol_rel = 1e-8;
    }
    const OptimizationResult r = optimize(s, rosenbrock, {});
    ASSERT_TRUE(r.best.has_value());
    const std::vector<double>& x = r.history[*r.best].evaluation.design;
    EXPECT_NEAR(x[0], 1.0, c.tolerance) << r.nlopt_result;
    EXPECT_NEAR(x[1], 1.0, 2 * c.tolerance) << r.nlopt_result;
    EXPECT_GE(r.nlopt_code, 0) << r.reason;
  }
}

TEST(Optimizer, ConstrainedQuadraticRespectsTheConstraint) {
  for (const char* a : {"cobyla", "slsqp", "mma", "isres", "bobyqa", "sbplx"}) {
    SCOPED_TRACE(a);
    OptimizationSpec s = analytic_spec(a, true);
    s.algorithm.gradient_step = 1e-7;
    const double tolerance = std::string(a) == "isres" ? 3e-2 : 2e-3;
    if (std::string(a) == "isres") {
      s.algorithm.maxeval = 20000;
      s.algorithm.xtol_rel = 0.0;
      s.algorithm.ftol_rel = 0.0;
    }
    const OptimizationResult r = optimize(s, quadratic, {});
    ASSERT_TRUE(r.best.has_value());
    ASSERT_TRUE(r.best_feasible);
    const std::vector<double>& x = r.history[*r.best].evaluation.design;
    EXPECT_LE(x[0] + x[1], 2.0 * (1 + s.algorithm.constraint_tolerance));  // the returned design is feasible
    EXPECT_NEAR(x[0], 1.5, tolerance);
    EXPECT_NEAR(x[1], 0.5, tolerance);
    EXPECT_NEAR(r.history[*r.best].assessment.objective, 0.5, 2 * tolerance);
    if (std::string(a) == "bobyqa" || std::string(a) == "sbplx") {
      EXPECT_THAT(r.algorithm, HasSubstr("AUGLAG"));
      EXPECT_THAT(r.note, HasSubstr("augmented Lagrangian"));
    }
  }
}

TEST(Optimizer, MinMaxOverCasesAndWeightedSums) {
  // Two cases shift the quadratic's centre to +1 and -1: min over x of max((x-1)^2, (x+1)^2) is at x = 0 (value 1);
  // the weighted mean with weights 3 and 1 is 3 (x-1)^2/4 + (x+1)^2/4, minimal at x = 0.5 (value 0.75).
  OptimizationSpec s = analytic_spec("cobyla", false);
  s.variables.resize(1);
  s.cases = {{"plus", 3.0, {}}, {"minus", 1.0, {}}};
  const Evaluator shifted = [](const std::vector<double>& d, const std::atomic<bool>*) {
    std::vector<CaseResult> r(2);
    r[0].metrics = {std::pow(d[0] - 1, 2), 0.0};
    r[1].metrics = {std::pow(d[0] + 1, 2), 0.0};
    return r;
  };
  OptimizationResult r = optimize(s, shifted, {});
  EXPECT_NEAR(r.history[*r.best].evaluation.design[0], 0.0, 1e-4);
  EXPECT_NEAR(r.history[*r.best].assessment.objective, 1.0, 1e-4);
  s.objective.cases = CaseAggregate::Weighted;
  r = optimize(s, shifted, {});
  EXPECT_NEAR(r.history[*r.best].evaluation.design[0], 0.5, 1e-4);
  EXPECT_NEAR(r.history[*r.best].assessment.objective, 0.75, 1e-6);
}

TEST(Optimizer, OneVariableWithEveryLocalAlgorithm) {
  // (x - 2)^2 on [-3, 3]: also the algorithms built for several variables (BOBYQA) work on one.
  for (const char* a : {"cobyla", "bobyqa", "sbplx", "mma", "slsqp"}) {
    SCOPED_TRACE(a);
    OptimizationSpec s = analytic_spec(a, false);
    s.variables.resize(1);
    s.algorithm.gradient_step = 1e-7;
    const Evaluator one = [](const std::vector<double>& d, const std::atomic<bool>*) {
      CaseResult r;
      r.metrics = {std::pow(d[0] - 2, 2), 0.0};
      return std::vector<CaseResult>{r};
    };
    const OptimizationResult r = optimize(s, one, {});
    ASSERT_TRUE(r.best.has_value()) << r.reason;
    EXPECT_NEAR(r.history[*r.best].evaluation.design[0], 2.0, 1e-4) << r.nlopt_result;
  }
}

TEST(Optimizer, FailedEvaluationsAreInfeasibleAndTheSearchGoesOn) {
  // The "integrator" gives up for x > 2.3: those designs are logged as failed with their error, get a large
  // objective, and the optimiser moves away and still finds the constrained optimum (1.5, 0.5).
  const Evaluator failing = [](const std::vector<double>& d, const std::atomic<bool>* c) {
    if (d[0] > 2.3) {
      CaseResult r;
      r.metrics = {NAN, NAN};
      r.status = "incomplete";
      r.error = "stopped at t = 0.1 s: TOO_MUCH_WORK";
      return std::vector<CaseResult>{r};
    }
    return quadratic(d, c);
  };
  OptimizationSpec s = analytic_spec("cobyla", true);
  s.variables[0].start = 2.2;
  s.variables[1].start = -2.0;
  const auto dir = temp_dir("failing");
  OptimizerOptions o;
  o.log_file = dir / "evaluations.jsonl";
  const OptimizationResult r = optimize(s, failing, o);
  ASSERT_TRUE(r.best_feasible);
  std::size_t failed = 0;
  for (const HistoryEntry& h : r.history)
    if (h.assessment.failed) {
      ++failed;
      EXPECT_THAT(h.assessment.note, HasSubstr("TOO_MUCH_WORK"));
      EXPECT_FALSE(h.assessment.feasible);
    }
  EXPECT_GT(failed, 0u);
  EXPECT_NEAR(r.history[*r.best].evaluation.design[0], 1.5, 2e-3);
  std::ifstream log(o.log_file);
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("TOO_MUCH_WORK"));
}

TEST(Optimizer, GradientRunsInParallelGiveTheSameResultOnAnyThreadCount) {
  OptimizationSpec s = analytic_spec("slsqp", true);
  s.algorithm.gradient_step = 1e-6;
  s.algorithm.central_differences = true;
  std::vector<std::vector<double>> designs[2];
  for (int t : {1, 2}) {
    OptimizerOptions o;
    o.threads = t;
    const OptimizationResult r = optimize(s, quadratic, o);
    for (const HistoryEntry& h : r.history) designs[t - 1].push_back(h.evaluation.design);
  }
  EXPECT_EQ(designs[0], designs[1]);  // bit for bit
  EXPECT_GT(designs[0].size(), 10u);
}

// ------------------------------------------------------------------------------------------ Jeffcott rotor

// Closed form (docs/optimization.md §"The closed-form test"): disk mass m on a massless shaft of stiffness k_s,
// supports of total stiffness K and damping C. All response curves |Z(w)|/e pass through one fixed point
// w_f^2 = k_s (k_s + 2K) / (2 m (k_s + K)), where |Z|/e = 1 + 2K/k_s; the damping that puts the maximum of the
// curve there, C = (k_s + K) sqrt(2 m K / (k_s (k_s + 2K))), minimises the peak (no curve can pass below the
// fixed point). Fixed-point argument after den Hartog (Mechanical Vibrations, 1956, §3.3); the rotor on damped
// flexible supports: Kirk & Gunter (1972), Vance, Zeidan & Murphy (2010); the formula is derived in
// docs/optimization.md.
struct JeffcottClosedForm {
  double m = 10.0, k_b = 1e5;
  double k_s() const {
    const double E = 210e9, d = 0.02, L = 0.6;
    return 48.0 * E * M_PI * std::pow(d, 4) / 64.0 / std::pow(L, 3);
  }
  double K() const { return 2 * k_b; }
  double c_b_opt() const { return 0.5 * (k_s() + K()) * std::sqrt(2 * m * K() / (k_s() * (k_s() + 2 * K()))); }
  double peak_ratio() const { return 1.0 + 2.0 * K() / k_s(); }
  double fixed_point_rpm() const {
    return std::sqrt(k_s() * (k_s() + 2 * K()) / (2 * m * (k_s() + K()))) * 60.0 / (2 * M_PI);
  }
};

const std::string kJeffcottStudy = testing::source_dir() + "/tests/data/optim/jeffcott_study.toml";

TEST(Optimizer, JeffcottOptimumSupportDampingAgainstTheClosedForm) {
  // The optimiser sees only the peak of the FE model's steady-state response; the peak is flat at the optimum
  // (quadratic in c), so c is found to about the square root of the objective's resolution.
  constexpr double kDampingTolerance = 0.01;   // relative, optimum c_b
  constexpr double kPeakTolerance = 1e-4;      // relative, peak amplitude (shaft mass 1.9e-4 kg against 10 kg)
  constexpr double kSpeedTolerance = 2e-3;     // relative, speed of the peak = the fixed point
  const JeffcottClosedForm cf;
  const double e = 1e-6 / cf.m;  // unbalance 1 g mm on 10 kg
  for (const char* algorithm : {"cobyla", "sbplx", "slsqp"}) {
    SCOPED_TRACE(algorithm);
    OptimizationSpec s = load_optimization(kJeffcottStudy);
    s.algorithm.name = algorithm;
    s.algorithm.gradient_step = 1e-5;
    const OptimizationResult r = optimize(s, model_evaluator(s), {});
    ASSERT_TRUE(r.best_feasible) << r.reason;
    const HistoryEntry& best = r.history[*r.best];
    EXPECT_NEAR(best.evaluation.design[0] / cf.c_b_opt(), 1.0, kDampingTolerance)
        << "c_b = " << best.evaluation.design[0] << " N s/m, closed form " << cf.c_b_opt();
    EXPECT_NEAR(best.evaluation.cases[0].metrics[0] / (cf.peak_ratio() * e), 1.0, kPeakTolerance);
    EXPECT_NEAR(best.evaluation.cases[0].metrics[1] / cf.fixed_point_rpm(), 1.0, kSpeedTolerance);
    std::cout << "[ jeffcott ] " << algorithm << ": c_b = " << best.evaluation.design[0] << " N s/m (closed form "
              << cf.c_b_opt() << "), peak/e = " << best.evaluation.cases[0].metrics[0] / e << " (closed form "
              << cf.peak_ratio() << ") at " << best.evaluation.cases[0].metrics[1] << " rpm (fixed point "
              << cf.fixed_point_rpm() << "), " << r.history.size() << " evaluations\n";
  }
}

TEST(Optimizer, ConstraintOnTheJeffcottSupportForceIsRespected) {
  // With a bound on the peak support force below its value at the unconstrained optimum, the optimum moves to
  // the bound; the returned design satisfies it.
  OptimizationSpec s = load_optimization(kJeffcottStudy);
  Metric force;
  force.spec.name = "peak_force_left";
  force.spec.kind = "response_peak";
  force.spec.probe = "bearing.left";
  force.spec.speed_max = s.metrics[0].spec.speed_max;
  force.points = 120;
  force.unit = "N";
  s.metrics.push_back(force);
  OptimizationSpec free_spec = s;
  const OptimizationResult free = optimize(free_spec, model_evaluator(free_spec), {});
  const double f_free = free.history[*free.best].evaluation.cases[0].metrics[2];
  s.constraints.push_back({"peak_force_left", 2, true, 0.9 * f_free});
  const OptimizationResult r = optimize(s, model_evaluator(s), {});
  ASSERT_TRUE(r.best_feasible);
  const HistoryEntry& b = r.history[*r.best];
  EXPECT_LE(b.evaluation.cases[0].metrics[2], 0.9 * f_free * (1 + s.algorithm.constraint_tolerance));
  EXPECT_NEAR(b.evaluation.cases[0].metrics[2] / (0.9 * f_free), 1.0, 1e-3);  // active constraint
  EXPECT_GT(b.assessment.objective, free.history[*free.best].assessment.objective);
}

TEST(Optimizer, LeastDampingForStabilityAgainstTheClosedForm) {
  // Stability metrics (docs/studies.md) as objective and constraint: the least bearing damping c that keeps the rigid
  // rotor on cross-coupled bearings (q = q1 W) stable to W = 110,000 rpm. Its cylindrical forward whirl,
  // M s^2 + 2c s + 2(k - i q) = 0, is marginal where c = q / w_n = q1 W sqrt(M / 2k) (the Jeffcott rotor's
  // destabilising cross-coupled stiffness, q < c w_n: Vance, Rotordynamics of Turbomachinery, 1988). The shaft's
  // bending (1e14 Pa, 30 mm) lowers w_n by about 1e-4.
  const OptimizationSpec s =
      load_optimization(testing::source_dir() + "/tests/data/stability/rigid_cross_coupled_study.toml");
  EXPECT_EQ(s.metrics[0].unit, "1");
  EXPECT_EQ(s.metrics[1].unit, "1/s");
  constexpr double kMass = 2 * 0.119 + 7850 * M_PI / 4 * 0.03 * 0.03 * 0.14, kK = 3e7, kQ1 = 100.0;
  const double W = 110000 * M_PI / 30, c_closed = kQ1 * W * std::sqrt(kMass / (2 * kK));
  const OptimizationResult r = optimize(s, model_evaluator(s), {});
  ASSERT_TRUE(r.best_feasible) << r.reason;
  const HistoryEntry& best = r.history[*r.best];
  std::cout << "[ least damping ] c = " << best.evaluation.design[0] << " N s/m (closed form " << c_closed
            << "), largest growth " << best.evaluation.cases[0].metrics[1] << " 1/s, " << r.history.size()
            << " evaluations\n";
  EXPECT_NEAR(best.evaluation.design[0] / c_closed, 1.0, 1e-3);
  EXPECT_LE(best.evaluation.cases[0].metrics[1], 0.0);
  EXPECT_NEAR(best.evaluation.cases[0].metrics[0], 0.0, 1e-5);  // marginal: the least damping ratio is 0
  // result.json says at which speeds the designs were judged (stable there only).
  const nlohmann::json j = result_json(s, r);
  for (std::size_t m = 0; m < 2; ++m) {
    EXPECT_EQ(j.at("metrics").at(m).at("name"), s.metrics[m].spec.name);
    const std::vector<double> rpm = j.at("metrics").at(m).at("speeds_rpm").get<std::vector<double>>();
    ASSERT_EQ(rpm.size(), 2u);
    EXPECT_NEAR(rpm[0], 10000, 1e-6);
    EXPECT_NEAR(rpm[1], 110000, 1e-6);
  }
}

TEST(Optimizer, RestartReusesTheLoggedEvaluations) {
  const OptimizationSpec s = load_optimization(kJeffcottStudy);
  std::atomic<int> runs{0};
  const Evaluator base = model_evaluator(s);
  const Evaluator counting = [&](const std::vector<double>& d, const std::atomic<bool>* c) {
    ++runs;
    return base(d, c);
  };
  const auto dir = temp_dir("restart");
  OptimizerOptions o;
  o.log_file = dir / "evaluations.jsonl";
  // An optimisation stopped early (as by Ctrl-C or maxeval), then continued with a larger budget: the first
  // part is replayed from the log, not run again.
  OptimizationSpec first = s;
  first.algorithm.maxeval = 6;
  const OptimizationResult r1 = optimize(first, counting, o);
  EXPECT_EQ(runs.load(), 6);
  EXPECT_EQ(r1.nlopt_result, "MAXEVAL_REACHED");
  runs = 0;
  const OptimizationResult r2 = optimize(s, counting, o);
  EXPECT_EQ(r2.cached_evaluations, 6u);
  EXPECT_EQ(runs.load(), static_cast<int>(r2.history.size()) - 6);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(r2.history[k].evaluation.design, r1.history[k].evaluation.design);
  // The same optimisation again: nothing runs, the result is the same.
  runs = 0;
  const OptimizationResult r3 = optimize(s, counting, o);
  EXPECT_EQ(runs.load(), 0);
  EXPECT_EQ(r3.history.size(), r2.history.size());
  EXPECT_EQ(r3.history[*r3.best].evaluation.design, r2.history[*r2.best].evaluation.design);
  // A log cut short by a kill: the broken last line is skipped and that design runs again.
  {
    std::ifstream in(o.log_file);
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    all.resize(all.size() - 20);
    std::ofstream(o.log_file, std::ios::trunc) << all;
  }
  runs = 0;
  (void)optimize(s, counting, o);
  EXPECT_EQ(runs.load(), 1);
}

TEST(Optimizer, LogOfAnotherProblemIsRefused) {
  const OptimizationSpec s = load_optimization(kJeffcottStudy);
  const auto dir = temp_dir("other_log");
  OptimizerOptions o;
  o.log_file = dir / "evaluations.jsonl";
  OptimizationSpec small = s;
  small.algorithm.maxeval = 2;
  (void)optimize(small, model_evaluator(small), o);
  OptimizationSpec other = s;
  other.metrics[0].points = 50;
  try {
    (void)optimize(other, model_evaluator(other), o);
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("different problem"));
  }
}

TEST(Optimizer, LogOfAnEarlierVersionOfTheModelIsRefused) {
  // The cache was keyed by the model's file name only, so an edited model (a tolerance, a clearance) resumed the
  // evaluations of the old one. A copy of the model, evaluated, then changed by one character in a comment
  // (anything in the file counts: the log cannot know which change matters).
  const auto dir = temp_dir("edited_model");
  std::filesystem::copy_file(testing::source_dir() + "/tests/data/optim/jeffcott.toml", dir / "jeffcott.toml");
  OptimizationSpec s = load_optimization(kJeffcottStudy);
  studies::set_base_model(s, dir / "jeffcott.toml");
  s.algorithm.maxeval = 2;
  OptimizerOptions o;
  o.log_file = dir / "evaluations.jsonl";
  (void)optimize(s, model_evaluator(s), o);
  EXPECT_EQ(optimize(s, model_evaluator(s), o).cached_evaluations, 2u);  // unchanged: resumed
  std::ofstream(s.model, std::ios::app) << "# edited\n";
  studies::set_base_model(s, s.model);  // read again, as a new `turbodyn optimize` reads it
  try {
    (void)optimize(s, model_evaluator(s), o);
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the model file has changed"));
  }
}

// ------------------------------------------------------------------------------------------ study-file errors

// A study file next to a copy of the Jeffcott model: the valid study with `edits` (from, to) substituted.
std::string load_error(const std::string& name, const std::vector<std::pair<std::string, std::string>>& edits) {
  const auto dir = temp_dir("errors_" + name);
  std::filesystem::copy_file(testing::source_dir() + "/tests/data/optim/jeffcott.toml", dir / "jeffcott.toml");
  std::ifstream in(kJeffcottStudy);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : edits) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  std::ofstream(dir / "study.toml") << text;
  try {
    (void)load_optimization(dir / "study.toml");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string load_error(const std::string& name, const std::string& from, const std::string& to) {
  return load_error(name, {{from, to}});
}

TEST(StudyFile, ErrorsNameFileLineKeyAndCause) {
  EXPECT_THAT(load_error("bad_bounds", "low = \"100 N*s/m\"", "low = \"20000 N*s/m\""),
              HasSubstr("study.toml:22:7: variables[0].low: the lower bound 20000 N*s/m must be below the upper bound "
                        "10000 N*s/m"));
  EXPECT_THAT(load_error("start_outside", "start = \"300 N*s/m\"", "start = \"30 N*s/m\""),
              HasSubstr("variables[0].start: the start 30 N*s/m lies outside the bounds [100 N*s/m, 10000 N*s/m]"));
  EXPECT_THAT(load_error("units", "high = \"10000 N*s/m\"", "high = \"10 kN*s/m\""),
              HasSubstr("variables[0].high: is written in 'kN*s/m' but the variable's other values in 'N*s/m'"));
  const std::string unknown = load_error("algorithm", "name = \"cobyla\"", "name = \"cobila\"");
  EXPECT_THAT(unknown, HasSubstr("study.toml:15:8: algorithm.name: unknown value 'cobila'"));
  EXPECT_THAT(unknown, HasSubstr("did you mean 'cobyla'?"));
  EXPECT_THAT(unknown, HasSubstr("'direct-l', 'crs2', 'isres', 'mlsl', 'mma', 'slsqp'"));
  EXPECT_THAT(load_error("metric", "metric = \"peak_disk\"", "metric = \"peak_disc\""),
              HasSubstr("objective.metric: unknown metric 'peak_disc'; did you mean 'peak_disk'?"));
  EXPECT_THAT(load_error("no_bound", "[objective]", "[[constraints]]\nmetric = \"peak_speed\"\n[objective]"),
              HasSubstr("constraints[0]: a constraint needs a bound: upper = "));
  const std::string constraint = "[[constraints]]\nmetric = \"peak_speed\"\nupper = \"2000 rpm\"\n[objective]";
  EXPECT_THAT(load_error("global_constrained", {{"name = \"cobyla\"", "name = \"direct-l\""}, {"[objective]", constraint}}),
              HasSubstr("study.toml:15:8: algorithm.name: direct-l handles bound constraints only"));
  EXPECT_THAT(load_error("global_maxeval", "name = \"cobyla\"\nxtol_rel = 1e-6\nmaxeval = 60", "name = \"crs2\""),
              HasSubstr("study.toml:14:1: algorithm: the global algorithm crs2 stops only on maxeval or maxtime"));
  EXPECT_THAT(load_error("no_stop", "xtol_rel = 1e-6\nmaxeval = 60", ""),
              HasSubstr("algorithm: no stopping criterion"));
  EXPECT_THAT(load_error("probe", "probe = \"disk.disk\"", "probe = \"disk.disc\""),
              HasSubstr("metrics[0].probe: the steady-state response has no probe 'disk.disc'; did you mean 'disk.disk'?"));
  EXPECT_THAT(load_error("log_scale", "low = \"100 N*s/m\"", "low = \"0 N*s/m\""),
              HasSubstr("variables[0].scale: a logarithmic scale needs a positive lower bound"));
}

TEST(StudyFile, ConstraintBoundsAreReadInTheMetricsUnit) {
  const auto dir = temp_dir("bound_units");
  std::filesystem::copy_file(testing::source_dir() + "/tests/data/optim/jeffcott.toml", dir / "jeffcott.toml");
  std::ifstream in(kJeffcottStudy);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text += "\n[[constraints]]\nmetric = \"peak_disk\"\nupper = \"0.5 um\"\n"
          "[[constraints]]\nmetric = \"peak_speed\"\nlower = \"25 Hz\"\n";
  std::ofstream(dir / "study.toml") << text;
  const OptimizationSpec s = load_optimization(dir / "study.toml");
  ASSERT_EQ(s.constraints.size(), 2u);
  EXPECT_DOUBLE_EQ(s.constraints[0].bound, 0.5e-6);  // m
  EXPECT_TRUE(s.constraints[0].upper);
  EXPECT_DOUBLE_EQ(s.constraints[1].bound, 1500.0);  // rpm
  EXPECT_FALSE(s.constraints[1].upper);
}

// ------------------------------------------------------------------------------------------ best design file

TEST(ModelPatch, BestDesignIsPatchedInPlaceAndLoads) {
  const std::string base = testing::source_dir() + "/examples/reference_damper.toml";
  const std::vector<Override> o = {{"bearings.compressor.damper.clearance", "73.5 um"},
                                   {"bearings.turbine.damper.length", "4.25 mm"}};
  const std::string text = patched_model(base, o, "optimised by a test\nsecond line");
  EXPECT_THAT(text, HasSubstr("# optimised by a test\n# second line\n"));
  EXPECT_THAT(text, HasSubstr("clearance = \"73.5 um\"                # radial clearance"));  // comment kept
  EXPECT_THAT(text, HasSubstr("length = \"4.25 mm\""));
  const MachineSpec patched = load_model_from_string(text, "best.toml");
  const MachineSpec direct = load_model(base, o);
  EXPECT_DOUBLE_EQ(patched.bearings[0].damper.clearance, direct.bearings[0].damper.clearance);
  EXPECT_DOUBLE_EQ(patched.bearings[0].damper.clearance, 73.5e-6);
  EXPECT_DOUBLE_EQ(patched.bearings[1].damper.length, 4.25e-3);
  // A key the file lacks goes into its table, the comments stay.
  const std::string added = patched_model(base, {{"bearings.compressor.damper.n_circ", "48"}}, "");
  EXPECT_THAT(added, HasSubstr("oil_temperature = \"90 degC\"\nn_circ = 48\n\n[bearings.turbine]"));
  EXPECT_THAT(added, HasSubstr("# radial clearance"));
  EXPECT_EQ(load_model_from_string(added, "best.toml").bearings[0].damper.n_circ, 48);
  // A table the file lacks: the whole model is written out instead, with the same values.
  const std::string table = patched_model(base, {{"damping.beta", "1e-6"}}, "");
  EXPECT_THAT(table, Not(HasSubstr("# radial clearance")));
  EXPECT_DOUBLE_EQ(load_model_from_string(table, "best.toml").damping.beta, 1e-6);
}

}  // namespace
}  // namespace turbodyn::optim

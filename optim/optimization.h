// Design optimisation on the rotor model: the optimisation study file and what it asks for (docs/optimization.md).
//
// A study names a base model file, design variables (model-file key paths with bounds), operating cases (extra
// overrides such as unbalance levels), metrics of each run (the run-up metrics of `turbodyn sweep`, plus
// steady-state response peaks of the linear rotor), an objective assembled from the metrics (weighted sum of
// metrics per case; min-max or weighted mean over the cases), inequality constraints on metrics, and the NLopt
// algorithm with its stopping criteria.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "model/io/model_file.h"
#include "studies/study.h"

namespace turbodyn::optim {

/// One design variable. The optimiser works on x in [0, 1] (x = 0 at low, 1 at high, linear or logarithmic in
/// between); the run gets `--set path=<value> <unit>`, so the model loader converts and checks the unit.
struct Variable {
  std::string path;          ///< name in the results: the model-file key path, or `name` for tied paths
  std::vector<std::string> paths;  ///< model-file key paths (as for --set) all set to the value, e.g. the clearance
                                   ///< of both dampers

  std::string unit;          ///< unit low, high and start are written in ("" = SI)
  double low = 0.0, high = 0.0, start = 0.0;  ///< in `unit`; low < high, start in [low, high]
  bool log_scale = false;    ///< x maps logarithmically (low > 0)

  double value(double x) const;  ///< design value (in `unit`) of the scaled coordinate x in [0, 1]
  double scaled(double v) const; ///< inverse of value()
};

/// An operating case: overrides applied on top of the design (e.g. an unbalance level).
struct OperatingCase {
  std::string name;
  double weight = 1.0;                ///< for cases = "weighted"
  std::vector<Override> overrides;
};

/// A metric of every run of every case. Run-up metrics are those of docs/studies.md; `response_peak` and
/// `response_peak_speed` are the largest steady-state 1x amplitude of the linear rotor (model/rotor/response.h) over the
/// speed window and the speed where it occurs.
struct Metric {
  studies::MetricSpec spec;
  int points = 200;       ///< response metrics: speeds of the grid before the peak is refined
  std::string unit;       ///< "m", "N", "rpm", ... ("" when unknown, e.g. kind = summary)
  bool response() const { return spec.kind == "response_peak" || spec.kind == "response_peak_speed"; }
};

/// How the per-case objectives J_c combine: the largest (min-max design) or the weighted mean sum w_c J_c / sum w_c.
enum class CaseAggregate { Max, Weighted };

struct ObjectiveTerm {
  std::size_t metric = 0;  ///< index into OptimizationSpec::metrics
  double weight = 1.0;     ///< multiplies the metric in its unit (metric_unit)
};

/// J_c = sum_t weight_t * metric_t(case c); objective = aggregate over the cases; minimised.
struct Objective {
  std::vector<ObjectiveTerm> terms;
  CaseAggregate cases = CaseAggregate::Max;
};

/// metric <= bound (upper) or metric >= bound (lower), required in every case. The optimiser sees the normalised
/// g = (metric - bound) / |bound| (upper) or (bound - metric) / |bound| (lower); feasible when g <= tolerance.
struct Constraint {
  std::string name;
  std::size_t metric = 0;
  bool upper = true;
  double bound = 0.0;      ///< in the metric's unit
};

/// NLopt algorithm names accepted in the study file.
const std::vector<std::string>& algorithm_names();
/// Algorithms that handle nonlinear inequality constraints themselves (the others are wrapped in AUGLAG or refused).
bool supports_constraints(const std::string& algorithm);
bool is_global(const std::string& algorithm);
bool needs_gradient(const std::string& algorithm);

struct AlgorithmOptions {
  std::string name = "cobyla";        ///< one of algorithm_names()
  std::string local = "bobyqa";       ///< mlsl: its local optimiser; bobyqa/sbplx with constraints: AUGLAG's
  double xtol_rel = 0.0, xtol_abs = 0.0;  ///< on the scaled variables (xtol_abs: fraction of each range)
  double ftol_rel = 0.0, ftol_abs = 0.0;
  double stopval = 0.0;
  bool has_stopval = false;
  int maxeval = 0;                    ///< optimiser calls of the objective (0 = no limit)
  double maxtime = 0.0;               ///< s (0 = no limit)
  double initial_step = 0.0;          ///< fraction of each range (0 = NLopt's default)
  bool central_differences = false;   ///< finite-difference gradients: central (2n runs) or forward (n runs)
  double gradient_step = 1e-3;        ///< fraction of each range
  std::uint64_t seed = 1;             ///< for the stochastic algorithms (crs2, isres, mlsl)
  /// On the normalised constraints: a design whose constraint exceeds its bound by at most this fraction of the
  /// bound counts as feasible (local methods such as COBYLA approach the boundary from either side).
  double constraint_tolerance = 1e-6;
  /// false (with the reason) for inconsistent options, e.g. a global algorithm without maxeval or maxtime.
  bool IsValid(std::string* error) const;
};

/// The fixed overrides come before the design's (run_overrides).
struct OptimizationSpec : studies::StudyCommon {
  std::vector<Variable> variables;
  std::vector<OperatingCase> cases;        ///< at least one
  std::vector<Metric> metrics;
  Objective objective;
  std::vector<Constraint> constraints;
  AlgorithmOptions algorithm;
  std::vector<std::string> spectrogram_probes;  ///< channels drawn for the initial and the best design
  std::string final_runs = "full";              ///< "full" ramp, the study's "window", or "none"

  std::size_t n_constraint_values() const { return constraints.size() * cases.size(); }
};

/// Reads and checks a study file (including its metrics and constraint units against the base model); errors
/// (ModelError) name file, line, key and cause.
OptimizationSpec load_optimization(const std::filesystem::path& file);

/// The overrides of one run: fixed, then the design values (with their units), then the case's.
std::vector<Override> run_overrides(const OptimizationSpec& spec, const std::vector<double>& design,
                                    const OperatingCase* operating_case);

/// Design values (in the variables' units) of the start point.
std::vector<double> start_design(const OptimizationSpec& spec);

/// "51 um" style text of a design value.
std::string value_text(const Variable& v, double value);

}  // namespace turbodyn::optim

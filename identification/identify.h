// Identification of model parameters from a measured run-up: a nonlinear least-squares problem solved with Ceres
// (Agarwal, Mierle et al., "Ceres Solver", http://ceres-solver.org; Levenberg-Marquardt with bounds).
//
//   min_x  sum_i rho(r_i(x)^2) / 2,   lower <= v(x) <= upper,
//   r(x) = weighted, normalised feature differences (residuals.h) of the model at parameter values v(x)
//
// x are scaled parameters (x = (v - lower) / (upper - lower), or v / start), so that one finite-difference step and
// one trust region suit all of them. The Jacobian is computed by finite differences that we form ourselves: the
// n perturbed model runs (2n for central differences) of one Jacobian are independent, so they execute in parallel
// with TBB (Ceres' NumericDiffCostFunction would run them one after another). Every model run is cached by its
// exact parameter vector, so the runs Ceres asks for twice (the accepted trial point, the covariance) cost nothing.
// Results do not depend on the thread count: each run is deterministic and results are placed by index.
//
// Uncertainty: ceres::Covariance gives (J^T J)^-1 at the solution in scaled parameters; it is multiplied by the
// residual variance s^2 = 2 F / (m - n) (F the final cost, m residuals, n parameters), i.e. the usual estimate
// when the noise level is not known beforehand (e.g. Seber & Wild, "Nonlinear Regression", 1989, §2.1), then
// transformed to the parameters' units.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "identification/evaluation.h"
#include "identification/features.h"
#include "identification/identify_study.h"
#include "identification/measurement.h"
#include "identification/residuals.h"

namespace turbodyn::identification {

struct IdentifyOptions {
  int threads = 0;                                    ///< parallel model runs; 0: the study's setting, else all cores
  const std::atomic<bool>* cancel = nullptr;          ///< stop after the current iteration when set
  std::function<void(const std::string&)> progress;   ///< one line per iteration (serialised)
};

struct IdentifyResult {
  std::vector<double> start, estimate, std_dev;  ///< parameter units; std_dev NaN without a covariance
  Eigen::MatrixXd covariance, correlation;       ///< parameter units; empty without a covariance
  bool covariance_ok = false;
  std::string covariance_message;                ///< why there is none (rank-deficient Jacobian, ...)
  double residual_variance = 0.0;                ///< s^2 = 2 F / (m - n)
  std::size_t n_residuals = 0;
  double initial_cost = 0.0, final_cost = 0.0;   ///< Ceres costs (half the sum of squared residuals)
  int iterations = 0;
  bool converged = false;                        ///< Ceres terminated by convergence
  bool cancelled = false;
  std::string termination;                       ///< Ceres' message
  std::string brief_report, full_report;
  std::size_t model_runs = 0;                    ///< distinct model evaluations
  double wall_time = 0.0;                        ///< s
  int threads = 1;                               ///< parallel model runs used
  MeasuredData measured;
  std::vector<FeatureTrack> measured_features, initial_features, fitted_features;
  Record initial_record, fitted_record;          ///< run-up method: the model's sensor signals
  std::vector<ResidualRow> rows;
  std::vector<double> fitted_residuals;          ///< at the estimate
  std::vector<double> amplitude_scales;          ///< per feature (see Residuals)
  std::vector<std::string> warnings;
  /// Overrides identify() added to the study's fixed ones for every model run (identify.speed = "measured": the
  /// measured speed as a [speed] table); fitted.toml carries them too.
  std::vector<Override> added_fixed;
};

/// The measured speed as a model-file override: the [speed] table replaced by profile = "table" with at most
/// `max_points` points (block means of the measured speed, times from the record's first sample), SI values.
std::vector<Override> measured_speed_table(const Record& record, std::size_t max_points = 400);

/// Reads the measurement, extracts its features, and fits the parameters. Throws ModelError for a bad study or
/// measured file, or when the model cannot be evaluated at the start values.
IdentifyResult identify(const IdentifyStudy& study, const IdentifyOptions& options = {});

}  // namespace turbodyn::identification

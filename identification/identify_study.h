// The identification study file (`turbodyn identify STUDY`, docs/identification.md): base model, measured data
// with its columns, units and sensor positions, features with weights, parameters with bounds and start values
// (model-file key paths, as for --set), and the settings of the least-squares solver.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "identification/features.h"
#include "identification/measurement.h"
#include "model/io/model_file.h"
#include "studies/study.h"

namespace turbodyn::identification {

/// How the model's features are computed: nonlinear run-up (time integration, then the same signal processing as
/// the measurement), or the steady-state unbalance response of the linear rotor (linear bearings only; 1x only).
enum class Method { Runup, Response };

/// One parameter to fit. Values are in `unit` (the unit the study file writes them in; "" = SI); the model loader
/// converts and checks the unit when the value is applied as an override.
struct ParameterSpec {
  std::string name;                  ///< label; default: the first path
  std::vector<std::string> paths;    ///< model-file key paths that all take this value ("bearings.left.k")
  std::string unit;
  double start = 0.0, lower = 0.0, upper = 0.0;
  double truth = std::numeric_limits<double>::quiet_NaN();  ///< known true value (synthetic data), for reports
};

enum class Loss { None, Huber, Cauchy, SoftLOne };
enum class Scaling { Bounds, Start };

/// Settings of the Ceres problem.
struct SolverSpec {
  Loss loss = Loss::None;
  double loss_scale = 1.0;           ///< a of the robust loss, in units of the normalised residual
  int max_iterations = 30;
  double step = 1e-3;                ///< finite-difference step in scaled parameters (see Scaling)
  bool central = false;              ///< central instead of forward differences (2n instead of n runs)
  Scaling scaling = Scaling::Bounds; ///< Bounds: x = (v - lower) / (upper - lower); Start: x = v / start
  /// Relative cost change at which Ceres stops. Near the minimum (cost ~ (m - n) s^2 / 2) a change of ftol means
  /// a parameter offset of about sqrt(ftol (m - n)) standard deviations. Run-ups carry integration noise (the cost
  /// jitters by ~1e-4 relative at rtol 1e-6), so their default is 1e-3 (~0.2 sigma for 50 residuals); the
  /// smooth steady-state response gets 1e-8. NaN = the default of the method.
  double function_tolerance = std::numeric_limits<double>::quiet_NaN();
  double parameter_tolerance = std::numeric_limits<double>::quiet_NaN();  ///< step in scaled parameters; NaN = 1e-4
                                                                          ///< (run-up), 1e-8 (response)
  double gradient_tolerance = 1e-10;
};

/// The fixed overrides come before the parameters'.
struct IdentifyStudy : studies::StudyCommon {
  Method method = Method::Runup;
  bool speed_from_measurement = false;  ///< run-ups follow the measured speed (a table), not the model's [speed]
  MeasurementSpec measurement;
  ProcessingSpec processing;
  std::vector<FeatureSpec> features;
  std::vector<ParameterSpec> parameters;
  SolverSpec solver;
};

/// Reads and checks a study file; errors (ModelError) name file:line:column, the key and the cause. The measured
/// file itself is read later (read_measurement).
IdentifyStudy load_identify_study(const std::filesystem::path& file);

/// "none", "huber", "cauchy", "soft-l1".
std::string to_string(Loss l);

}  // namespace turbodyn::identification

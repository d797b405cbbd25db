// One model evaluation of an identification: the base model with the fixed overrides and the parameter values
// applied, run (nonlinear run-up or steady-state response) and turned into the study's features with the same
// signal processing as the measurement.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "identification/features.h"
#include "identification/identify_study.h"

namespace turbodyn::identification {

struct Evaluation {
  bool ok = false;
  std::string error;                     ///< why not ok (model error, integrator gave up, cancelled)
  std::vector<FeatureTrack> features;
  Record record;                         ///< run-up method with keep_record: the sensors' model signals
  double wall_time = 0.0;                ///< s
};

/// Thread-safe: every call builds its own model and workspace.
class Evaluator {
 public:
  /// Checks the study against the model once (the start values apply, the sensors' probes exist, the method suits
  /// the bearings); throws ModelError naming the study file otherwise.
  explicit Evaluator(const IdentifyStudy& study);

  /// The overrides of one evaluation: the study's fixed ones, then every path of every parameter with its value
  /// (`values` in the parameters' units).
  std::vector<Override> overrides(const std::vector<double>& values) const;

  /// Runs the model at `values`; never throws for a failing run (ok = false and the error).
  Evaluation evaluate(const std::vector<double>& values, bool keep_record,
                      const std::atomic<bool>* cancel = nullptr) const;

  /// The measurement has a phase reference and the 1x phases are compared.
  bool with_phase() const { return with_phase_; }

 private:
  const IdentifyStudy& study_;
  bool with_phase_ = false;
};

/// The value as an override string: shortest round-trip decimal, then " <unit>" if any.
std::string format_value(double value, const std::string& unit);

}  // namespace turbodyn::identification

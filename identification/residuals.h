// Residuals of an identification: the weighted, normalised differences between the model's and the measured
// features (docs/identification.md, "Residuals"). The layout (which rows exist) is fixed by the measurement, so
// every model evaluation gives a vector of the same length.
//
//   order1x with phase   w (Re, Im)(Z_model - Z_meas) / s_A,   Z = A e^{i phase}   (2 rows per speed)
//   order1x without      w (A_model - A_meas) / s_A                                 (1 row per speed)
//   subsync              w (A_model - A_meas) / s_A, and where A_meas > threshold also w (f_model - f_meas) / s_f
//   resonance            w (speed_model - speed_meas) / s_n
//
// With s the measurement noise of each feature the rows are standard normal at the true parameters; the
// automatic scales (RMS of the measured amplitudes, spectral resolution, 1 % of the resonance speed) only fix the
// relative weight of the feature kinds: the covariance is scaled by the residual variance afterwards.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "identification/features.h"

namespace turbodyn::identification {

struct ResidualRow {
  std::size_t feature = 0;   ///< index into the study's features
  std::size_t point = 0;     ///< speed index (order1x, subsync)
  std::string quantity;      ///< "re", "im", "amplitude", "frequency", "resonance_speed"
  double scale = 1.0;        ///< s above, SI (Hz for frequencies and speeds)
  double weight = 1.0;
};

class Residuals {
 public:
  /// `resolution_hz`: the spectral resolution of the measurement (default frequency scale).
  Residuals(const std::vector<FeatureSpec>& features, const std::vector<FeatureTrack>& measured, double resolution_hz);

  std::size_t size() const { return rows_.size(); }
  const std::vector<ResidualRow>& rows() const { return rows_; }
  /// Fills r (dim size()); false if the model lacks a value a row needs (NaN).
  bool evaluate(const std::vector<FeatureTrack>& model, double* r) const;
  /// Amplitude scale and subsync threshold used per feature (after the automatic defaults).
  const std::vector<double>& amplitude_scales() const { return amplitude_scale_; }
  const std::vector<double>& thresholds() const { return threshold_; }

 private:
  std::vector<FeatureSpec> features_;
  std::vector<FeatureTrack> measured_;
  std::vector<ResidualRow> rows_;
  std::vector<double> amplitude_scale_, threshold_;
};

}  // namespace turbodyn::identification

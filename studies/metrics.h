// Metrics of one run-up, computed from its probes and its summary (docs/studies.md).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/engine/integrator.h"
#include "studies/study.h"

namespace turbodyn::studies {

/// Unit of a metric's value in the results ("m", "N", "rpm", "Hz", "1", or the probe's unit).
std::string metric_unit(const MetricSpec& m, const std::vector<ProbeChannel>& channels);

/// Throws ModelError (naming the study file and the metric) if a metric refers to a probe the model does not have.
void check_metrics(const StudySpec& study, const std::vector<ProbeChannel>& channels);

/// Value of the metric for one run; NaN when it is undefined for that run (e.g. no sub-synchronous amplitude above
/// the threshold, or an empty speed window).
double evaluate_metric(const MetricSpec& m, const RunupResult& r, const nlohmann::json& summary, double sample_rate);

}  // namespace turbodyn::studies

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

/// The value at `path` in a run summary: a dotted path ("stats.steps") or a JSON pointer
/// ("/probes/disk.compressor.x/max_abs"); nullptr if there is none.
const nlohmann::json* summary_node(const nlohmann::json& summary, const std::string& path);

/// The summary a run of `model` writes, with every key present (values of an empty run): what summary metrics are
/// checked against before any run.
nlohmann::json summary_template(const MachineSpec& spec, const RunupModel& model);

/// Throws ModelError (naming the study file and the metric) if a metric refers to a probe the model does not have,
/// or to a value the run summary (`summary`, from summary_template) does not hold.
void check_metrics(const StudySpec& study, const std::vector<ProbeChannel>& channels, const nlohmann::json& summary);

/// Value of the metric for one run; NaN when it is undefined for that run (e.g. no sub-synchronous amplitude above
/// the threshold, or an empty speed window).
double evaluate_metric(const MetricSpec& m, const RunupResult& r, const nlohmann::json& summary, double sample_rate);

}  // namespace turbodyn::studies

// Metrics of a design that the linearised stability analysis gives (model/engine/stability.h; `turbodyn
// stability`), without a run-up: how fast the fastest mode grows over a speed range, at what speed a growing mode
// first appears, its whirl frequency, the least damping ratio. docs/studies.md, "Stability metrics".
#pragma once

#include <atomic>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/spec/model_spec.h"
#include "studies/study.h"

namespace turbodyn::studies {

/// stability_growth, stability_growth_speed, stability_frequency, stability_damping, stability_onset_speed.
bool is_stability_metric(const std::string& kind);

/// Throws ModelError ("STUDY: metrics[I].kind: ...") if `metrics` hold a stability metric and the base model `spec`
/// has an element the analysis does not cover (floating rings, journal bearings, ...): checked before any run.
void check_stability_metrics(const StudyCommon& study, const std::vector<MetricSpec>& metrics,
                             const MachineSpec& spec);

/// The note a study's run carries where its stability analyses found the steady state anew from rest at `speeds`
/// (rad/s; StabilityPoint::restarted): they name the speeds; "" if none.
std::string stability_restart_note(const std::set<double>& speeds);

/// The speeds a stability metric analyses: speed_count speeds evenly over [speed_min, speed_max] (rad/s).
std::vector<double> stability_speeds(const MetricSpec& m);

/// What a result file says of a stability metric's grid: {"speeds_rpm": [...]} and, for stability_onset_speed on
/// more than one speed, "onset_resolution_rpm" (the grid's step halved kStabilityOnsetBisections times); an empty
/// object for any other metric. A design is judged at those speeds only (docs/studies.md).
nlohmann::json stability_grid_json(const MetricSpec& m);

/// The stability metrics among `metrics` for the machine `spec` (NaN in every other place, and where a metric is
/// undefined: no growing mode for stability_onset_speed). Metrics with the same rotor share and continuation_steps
/// share the analyses at their common speeds; the onset's halvings are analysed each time. An analysis that fails
/// (no steady state found at a speed) ends that metric's speeds there: the metric is taken over the speeds analysed,
/// and *error says at which speed and why ("" if none failed). A set `cancel` stops before the next grid speed's
/// analysis (*error "cancelled"). Throws nothing for a failing analysis; throws std::invalid_argument if the model has
/// an element the analysis does not cover (check_stability_supported). *note, if given, names the speeds (grid speeds
/// and the onset's halvings) whose steady state was found anew from rest because the branch from the speed below
/// ended (StabilityPoint::restarted), "" if none: the metrics there are those of another branch.
std::vector<double> evaluate_stability_metrics(const MachineSpec& spec, const std::vector<MetricSpec>& metrics,
                                               std::string* error, const std::atomic<bool>* cancel = nullptr,
                                               std::string* note = nullptr);

}  // namespace turbodyn::studies

#include "studies/stability_metrics.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "model/engine/speed_text.h"
#include "model/engine/stability.h"
#include "model/spec/constants.h"
#include "model/spec/errors.h"

namespace turbodyn::studies {
namespace {

// What one analysed speed says, reduced to the modes that count (the metric's rotor share and frequency limit).
struct SpeedSummary {
  double speed = 0.0;            // rad/s
  double growth = kNaN;          // largest growth rate (1/s) of a counted mode
  double frequency = kNaN;       // Hz of that mode (signed: > 0 forward)
  double damping = kNaN;         // least damping ratio of a counted mode
  bool grows = false;            // a counted mode grows beyond round-off (StabilityMode::grows)
};

// Analyses at speeds, with the results kept, for one rotor share (which the analysis filters by) and one fraction of
// the continuation's steps. Each continues its steady state up from the highest speed below it analysed so far. A
// failure is remembered and every speed from the failed one up is refused (one that cannot reach a speed does not
// reach a higher one); speeds below it are still analysed (the onset's halvings).
class Analyses {
 public:
  Analyses(const MachineSpec& spec, double min_rotor_share, double continuation_steps,
           const std::atomic<bool>* cancel)
      : spec_(spec), cancel_(cancel) {
    options_.min_rotor_share = min_rotor_share;
    options_.continuation_step_factor = continuation_steps;
  }
  // The summary at `speed` of the modes `filter` counts, or false (and error() says why) if the analysis failed or
  // was cancelled.
  bool at(double speed, const StabilityModeFilter& filter, SpeedSummary* out) {
    auto it = done_.find(speed);
    if (it == done_.end()) {
      if (speed >= failed_at_) return false;
      if (cancel_ && cancel_->load()) return error_ = "cancelled", failed_at_ = 0.0, false;
      try {
        auto below = done_.lower_bound(speed);  // the first at or above: the one before it is below
        const StabilityPoint* from = below == done_.begin() ? nullptr : &std::prev(below)->second;
        it = done_.emplace(speed, analyse_stability(spec_, speed, options_, from)).first;
        if (it->second.restarted) restarted_.insert(speed);
      } catch (const std::invalid_argument&) {
        throw;
      } catch (const std::exception& e) {
        error_ = "stability analysis at " + rpm_text(speed) + ": " + e.what();
        failed_at_ = speed;
        return false;
      }
    }
    const StabilityPoint& p = it->second;
    SpeedSummary s;
    s.speed = speed;
    for (const StabilityMode& m : p.modes) {
      if (!filter.counts(m)) continue;  // the analysis keeps growing modes of any share
      if (std::isnan(s.growth) || m.growth_rate > s.growth) s.growth = m.growth_rate, s.frequency = m.frequency;
      if (std::isnan(s.damping) || m.damping_ratio < s.damping) s.damping = m.damping_ratio;
    }
    s.grows = grows_counted(p, filter);
    *out = s;
    return true;
  }
  // The onset over the grid (find_stability_onset); a failing analysis is remembered as in at().
  StabilityOnset onset(const std::vector<SpeedSummary>& grid, const StabilityModeFilter& filter) {
    std::vector<const StabilityPoint*> points;
    for (const SpeedSummary& s : grid) points.push_back(&done_.at(s.speed));
    StabilityOnset o = find_stability_onset(spec_, points, filter, options_);
    if (!o.error.empty() && error_.empty()) error_ = o.error;
    restarted_.insert(o.restarted.begin(), o.restarted.end());
    return o;
  }
  const std::string& error() const { return error_; }
  // Speeds (rad/s) whose steady state was found anew from rest: grid speeds and the onset's halvings.
  const std::set<double>& restarted() const { return restarted_; }

 private:
  const MachineSpec& spec_;
  const std::atomic<bool>* cancel_;
  StabilityOptions options_;
  std::map<double, StabilityPoint> done_;
  std::set<double> restarted_;
  std::string error_;
  double failed_at_ = std::numeric_limits<double>::infinity();
};

double metric_value(const MetricSpec& m, Analyses& a) {
  const std::vector<double> speeds = stability_speeds(m);
  const StabilityModeFilter filter{m.min_rotor_share, m.frequency_max};
  std::vector<SpeedSummary> grid;
  for (double s : speeds) {
    SpeedSummary sum;
    if (!a.at(s, filter, &sum)) break;
    grid.push_back(sum);
  }
  if (m.kind == "stability_onset_speed") {
    const StabilityOnset o = a.onset(grid, filter);
    return o.found ? o.speed * kRadPerSToRpm : kNaN;  // at the window's start if it grows there already
  }
  const SpeedSummary* top = nullptr;
  double damping = kNaN;
  for (const SpeedSummary& s : grid) {
    if (!std::isnan(s.growth) && (!top || s.growth > top->growth)) top = &s;
    if (!std::isnan(s.damping) && (std::isnan(damping) || s.damping < damping)) damping = s.damping;
  }
  if (m.kind == "stability_damping") return damping;
  if (!top) return kNaN;
  if (m.kind == "stability_growth") return top->growth;
  if (m.kind == "stability_growth_speed") return top->speed * kRadPerSToRpm;
  return top->frequency;  // stability_frequency
}

}  // namespace

std::string stability_restart_note(const std::set<double>& speeds) {
  if (speeds.empty()) return "";
  std::string text;
  for (double w : speeds) text += (text.empty() ? "" : ", ") + rpm_text(w);
  return "stability: steady state found anew from rest at " + text +
         " (the branch from the speed below ended: a fold; docs/ball-bearing.md, \"A sweep over speeds\")";
}

bool is_stability_metric(const std::string& kind) {
  return kind == "stability_growth" || kind == "stability_growth_speed" || kind == "stability_frequency" ||
         kind == "stability_damping" || kind == "stability_onset_speed";
}

void check_stability_metrics(const StudyCommon& study, const std::vector<MetricSpec>& metrics,
                             const MachineSpec& spec) {
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    if (!is_stability_metric(metrics[i].kind)) continue;
    try {
      check_stability_supported(spec);
    } catch (const std::invalid_argument& e) {
      throw ModelError(study.source.string() + ": metrics[" + std::to_string(i) + "].kind: " + metrics[i].kind +
                       ": the linearised stability analysis cannot take this model: " + e.what());
    }
    return;
  }
}

std::vector<double> stability_speeds(const MetricSpec& m) {
  std::vector<double> s;
  const int n = std::max(m.speed_count, 1);
  for (int i = 0; i < n; ++i)
    s.push_back(n == 1 ? m.speed_max : m.speed_min + (m.speed_max - m.speed_min) * i / (n - 1));
  return s;
}

nlohmann::json stability_grid_json(const MetricSpec& m) {
  nlohmann::json e = nlohmann::json::object();
  if (!is_stability_metric(m.kind)) return e;
  const std::vector<double> speeds = stability_speeds(m);
  nlohmann::json rpm = nlohmann::json::array();
  for (double w : speeds) rpm.push_back(w * kRadPerSToRpm);
  e["speeds_rpm"] = rpm;
  if (m.kind == "stability_onset_speed" && speeds.size() > 1)
    e["onset_resolution_rpm"] = stability_onset_resolution((speeds[1] - speeds[0]) * kRadPerSToRpm);
  return e;
}

std::vector<double> evaluate_stability_metrics(const MachineSpec& spec, const std::vector<MetricSpec>& metrics,
                                               std::string* error, const std::atomic<bool>* cancel,
                                               std::string* note) {
  std::vector<double> out(metrics.size(), kNaN);
  // The analyses of one rotor share and one fraction of the steps serve every metric that uses them.
  std::map<std::pair<double, double>, Analyses> by_options;
  error->clear();
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    const MetricSpec& m = metrics[i];
    if (!is_stability_metric(m.kind)) continue;
    const std::pair<double, double> key{m.min_rotor_share, m.continuation_steps};
    auto it = by_options.find(key);
    if (it == by_options.end())
      it = by_options.emplace(std::piecewise_construct, std::forward_as_tuple(key),
                              std::forward_as_tuple(spec, m.min_rotor_share, m.continuation_steps, cancel)).first;
    out[i] = metric_value(m, it->second);
    if (error->empty()) *error = it->second.error();
  }
  if (note) {
    std::set<double> restarted;
    for (const auto& [options, a] : by_options) restarted.insert(a.restarted().begin(), a.restarted().end());
    *note = stability_restart_note(restarted);
  }
  return out;
}

}  // namespace turbodyn::studies

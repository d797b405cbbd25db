#include "studies/study_keys.h"

#include <limits>

#include <cmath>
#include <string>

#include "studies/stability_metrics.h"

namespace turbodyn::studies {

using input::Bound;
using input::Reader;

UnitValue node_value(const toml::node& n, const std::string& context, const std::string& example) {
  if (n.is_integer()) return {static_cast<double>(*n.value<int64_t>()), ""};
  if (n.is_floating_point()) {
    const double v = *n.value<double>();
    if (!std::isfinite(v)) throw ModelError(context + ": value is not finite (" + std::to_string(v) + ")");
    return {v, ""};
  }
  if (n.is_string()) return split_value(*n.value<std::string>(), context);
  throw ModelError(context + ": expected a number or a string such as \"" + example + "\"");
}

double OneUnitValues::take(const toml::node& n, const std::string& key) {
  const UnitValue v = node_value(n, key_location(r_, key), example_);
  if (unit_set_ && v.unit != unit_)
    r_.fail(key, "is written in '" + v.unit + "' but the " + whose_ + " other values in '" + unit_ + "'; " + advice_);
  unit_ = v.unit;
  unit_set_ = true;
  return v.value;
}

double OneUnitValues::take(const std::string& key) {
  const toml::node* n = r_.get(key);
  return n ? take(*n, key) : std::numeric_limits<double>::quiet_NaN();
}

std::string key_location(const Reader& r, const std::string& key) { return r.location(key) + ": " + r.key_path(key); }

void read_metric_window(Reader& r, MetricSpec& m, const std::string& example) {
  const std::vector<double> window = r.quantity_list("speed_window", dim::angular_speed, Bound::NonNegative);
  if (!window.empty()) {
    if (window.size() != 2 || !(window[1] > window[0])) r.fail("speed_window", "expected [low, high] with low < high");
    m.speed_min = window[0];
    m.speed_max = window[1];
  }
  if (const toml::node* n = r.get("threshold")) {
    // The unit follows the probe (m or N): read either.
    const UnitValue v = node_value(*n, key_location(r, "threshold"), example);
    m.threshold = v.value;
    if (!v.unit.empty()) {
      const std::string text = n->value<std::string>().value_or("");
      try {
        m.threshold = parse_quantity(text, dim::length);
      } catch (const UnitError&) {
        try {
          m.threshold = parse_quantity(text, dim::force);
        } catch (const UnitError& e) {
          r.fail("threshold", std::string("expected a length or a force: ") + e.what());
        }
      }
    }
  }
  if (r.has("order_band")) {
    if (m.kind.rfind("subsync_", 0) != 0)
      r.fail("order_band", "applies to the subsync_* metrics only, not to kind = \"" + m.kind + "\"");
    const std::vector<double> band = r.quantity_list("order_band", dim::dimensionless, Bound::Positive);
    if (band.size() != 2 || !(band[0] < band[1]) || !(band[1] < 1.0))
      r.fail("order_band", "expected [low, high] as fractions of the rotor speed with 0 < low < high < 1");
    m.order_min = band[0];
    m.order_max = band[1];
  }
  if ((m.kind == "subsync_onset_speed" || m.kind == "subsync_jump_speed") && !(m.threshold > 0.0))
    r.fail("threshold", m.kind + " needs a positive threshold (amplitude in the probe's unit)");
}

void read_metric_subject(Reader& r, MetricSpec& m, double window_min, double window_max) {
  if (!is_stability_metric(m.kind)) {
    m.probe = r.text_or("probe", "");
    if (m.probe.empty()) r.fail_missing("probe", "a probe name such as \"disk.compressor.x\" or \"bearing.turbine\"");
    m.name = r.text_or("name", m.kind + "(" + m.probe + ")");
    return;
  }
  if (r.has("probe"))
    r.fail("probe", "kind = \"" + m.kind + "\" reads no probe: it analyses the model's linearised stability over "
                    "the metric's speed_window (docs/studies.md, \"Stability metrics\")");
  if (r.has("threshold")) r.fail("threshold", "applies to amplitudes of a run, not to kind = \"" + m.kind + "\"");
  m.name = r.text_or("name", m.kind);
  m.speed_count = static_cast<int>(r.integer_or("speed_count", m.speed_count, 2, 1000));
  m.min_rotor_share = r.quantity_or("min_rotor_share", dim::dimensionless, m.min_rotor_share, Bound::NonNegative);
  if (!(m.min_rotor_share <= 1.0))
    r.fail("min_rotor_share", "must lie in [0, 1]: the fraction of a mode's motion in the rotor");
  m.frequency_max = r.quantity_or("frequency_max", dim::frequency, 0.0, Bound::Positive);
  m.continuation_steps =
      r.quantity_or("continuation_steps", dim::dimensionless, m.continuation_steps, Bound::Positive);
  if (!(m.continuation_steps <= 1.0))
    r.fail("continuation_steps", "must lie in (0, 1]: the fraction of the continuation's regular steps");
  if (m.speed_max <= 0.0) {
    if (window_max <= 0.0)
      r.fail_missing("speed_window",
                     "the speeds a stability metric analyses, [low, high] (here or in the study's table)");
    m.speed_min = window_min;
    m.speed_max = window_max;
  }
}

}  // namespace turbodyn::studies

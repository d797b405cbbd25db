// The reading of keys that every study type writes alike inside its own tables: values with units, and a metric's
// speed window and threshold.
#pragma once

#include <string>

#include <toml++/toml.h>

#include "model/io/model_file.h"  // before toml_reader.h, which uses its closest_match without including it
#include "model/io/toml_reader.h"
#include "studies/study.h"

namespace turbodyn::studies {

/// A number or "<number> <unit>" (the unit is checked where the value is applied); otherwise ModelError naming
/// `context`, with `example` (such as "580 mg*mm") as the form to write.
UnitValue node_value(const toml::node& n, const std::string& context, const std::string& example);

/// Values of one study entry that must all be written in one unit (a parameter's levels, low, high, ...): the first
/// value read sets unit(), a later one in another unit is a ModelError naming its key.
class OneUnitValues {
 public:
  /// `whose` and `advice` complete the message "... but the WHOSE other values in 'mm'; ADVICE"; `example` as for
  /// node_value.
  OneUnitValues(input::Reader& r, std::string whose, std::string advice, std::string example)
      : r_(r), whose_(std::move(whose)), advice_(std::move(advice)), example_(std::move(example)) {}
  /// The value of node `n`, read for `key` (the key a message names).
  double take(const toml::node& n, const std::string& key);
  /// The value of `key`, NaN when absent.
  double take(const std::string& key);
  const std::string& unit() const { return unit_; }

 private:
  input::Reader& r_;
  std::string whose_, advice_, example_, unit_;
  bool unit_set_ = false;
};

/// "FILE:LINE:COLUMN: table.key" of a key, to start a message with.
std::string key_location(const input::Reader& r, const std::string& key);

/// A metric's speed_window = [low, high] and threshold (a length or a force; subsync_onset_speed needs a positive
/// one). `example` as for node_value.
void read_metric_window(input::Reader& r, MetricSpec& m, const std::string& example);

/// The keys of a metric that follow its kind: for the stability_* kinds no probe, speed_count (2 to 1000, default
/// 15), min_rotor_share (0 to 1, default 0.01), frequency_max (Hz, > 0; default any), continuation_steps ((0, 1],
/// default 1) and a speed window, here or the study's [window_min, window_max] (rad/s; 0 = none); for every other
/// kind a probe. Sets m.name to "KIND(PROBE)" or "KIND" unless a name is given.
void read_metric_subject(input::Reader& r, MetricSpec& m, double window_min, double window_max);

}  // namespace turbodyn::studies

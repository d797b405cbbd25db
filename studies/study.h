// Parameter studies (design of experiments) on the run-up model: the study file and what it asks for.
//
// A study names a base model file, the parameters to vary (model-file key paths, as for --set), a design that
// turns their ranges into runs, and the metrics to extract from every run. See docs/studies.md.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "model/io/model_file.h"
#include "studies/design.h"

namespace turbodyn::input {
class Reader;
}

namespace turbodyn::studies {

/// A value as written in the study file: a number and the unit it was written in ("580 mg*mm" -> 580, "mg*mm").
/// Sampling happens in that unit; the model loader converts and checks the unit when the run's override is applied.
struct UnitValue {
  double value = 0.0;
  std::string unit;  ///< "" for plain (SI) numbers
};

/// One metric computed from every run (docs/studies.md lists the kinds).
struct MetricSpec {
  std::string name;   ///< column name in the results
  std::string kind;   ///< max, min, max_radius, rms, mean, peak_1x, peak_1x_speed, subsync_max, subsync_ratio,
                      ///< subsync_onset_speed, subsync_jump_speed, subsync_frequency, summary, stability_growth,
                      ///< stability_growth_speed, stability_frequency, stability_damping, stability_onset_speed
  std::string probe;  ///< channel name ("disk.compressor.x"), a pair stem for max_radius ("disk.compressor"), or
                      ///< for kind = summary a dotted path into summary-like values ("stats.steps"); "" for the
                      ///< stability_* kinds, which analyse the model rather than read a run
  double speed_min = 0.0, speed_max = 0.0;  ///< rad/s window; speed_max = 0 means no upper limit
  double threshold = 0.0;                   ///< subsync_onset/jump_speed: amplitude in the probe's SI unit
  /// subsync_* metrics: the band searched for the sub-synchronous line, as fractions of the rotor speed f_d
  /// (order_band = [low, high]; never below 5 Hz). Narrowing it picks one whirl, e.g. a floating ring's outer-film
  /// whirl near half the ring speed ([0.05, 0.3]) apart from the inner-film whirl near 0.5-0.6 f_d.
  double order_min = 0.05, order_max = 0.9;
  /// stability_* metrics (studies/stability_metrics.h): speed_count speeds evenly over the speed window are analysed,
  /// and a mode counts if at least min_rotor_share of its motion is in the rotor (StabilityMode::rotor_share) and
  /// its frequency is at most frequency_max.
  int speed_count = 15;
  double min_rotor_share = 0.01;
  double frequency_max = 0.0;  ///< Hz: only modes whose |housing-frame frequency| is at most this count; 0 = any
  /// stability_* metrics: the fraction (0, 1] of the continuation's regular steps between speeds and from rest
  /// (StabilityOptions::continuation_step_factor; `turbodyn stability --continuation-steps`), to check that a
  /// design's steady states do not depend on the steps.
  double continuation_steps = 1.0;
};

/// What every kind of study ([study], [optimize], [identify]) says about its runs: the keys name, model (relative to
/// the study file, must exist), threads, speed_window = [low, high] and fixed = ["PATH=VALUE", ...]. The study types
/// derive from it, so that one reader fills it and one run evaluation (run_evaluation.h) reads it.
struct StudyCommon {
  std::filesystem::path source;  ///< the study file ("" when built in code)
  std::string name;
  std::filesystem::path model;   ///< base model file
  int threads = 0;               ///< parallel runs, 0 = all cores
  double speed_window_min = 0.0; ///< rad/s: a run starts where the ramp reaches this speed (0 = start)
  double speed_window_max = 0.0; ///< rad/s: a run stops where the ramp reaches this speed (0 = end)
  std::vector<Override> fixed;   ///< applied to every run before the run's own overrides
  /// The model file's bytes and their digest (run_log.h: text_digest), read once with the study file: every run of
  /// the batch loads this text, so a model file edited while a batch runs changes none of its runs, and the
  /// results name the model the runs used. Empty for a study built in code, whose runs read the file.
  std::string model_text;
  std::string model_digest;
};
StudyCommon read_study_common(input::Reader& r, const std::filesystem::path& file);
/// Sets the study's base model to `model` and reads its text and digest (model_text, model_digest); throws
/// ModelError if the file cannot be read. Set `model` only through this, or model_text holds another file.
void set_base_model(StudyCommon& study, const std::filesystem::path& model);
/// The head table of a study file, `table` ("study", "optimize", "identify"), which must be there: reads the keys
/// every study has into `common` and returns the table's Reader for the study's own keys (the caller finishes it).
input::Reader read_study_head(input::Reader& top, const std::string& table, const std::filesystem::path& file,
                              StudyCommon& common);

/// The study's base model with `overrides` (the study's fixed values, a case's and a design's): a fault in them is
/// a ModelError that names the study file first, then the override ("STUDY: --set PATH=VALUE: ...").
MachineSpec load_study_model(const StudyCommon& study, const std::vector<Override>& overrides);
/// The same without the study file's name in the messages (load_model's errors): what each run loads.
MachineSpec load_base_model(const StudyCommon& study, const std::vector<Override>& overrides);
/// The digest of the model the runs load: model_digest, or the file's for a study built in code.
std::string base_model_digest(const StudyCommon& study);
/// Writes the base model with `overrides` patched in (model/io/overrides.h: patched_model_text) to `file`, from the
/// text the runs used; throws ModelError if it cannot be written.
void write_patched_base_model(const StudyCommon& study, const std::vector<Override>& overrides,
                              const std::string& header, const std::filesystem::path& file);

/// Checks the paths a study varies against its base model (loaded with `overrides`): each must be a number the
/// model file reads (model_file.h: numeric_model_keys), not a name or a choice. Each path comes with the key that
/// gave it ("parameters[0].path"); throws ModelError "STUDY: KEY: ..." with a suggestion.
void check_varied_paths(const StudyCommon& study, const std::vector<Override>& overrides,
                        const std::vector<std::pair<std::string, std::string>>& key_and_path);

/// Checks that the study's speed_window overlaps the speeds the base model's run passes through (else every run
/// would end at once, without a sample).
void check_speed_window(const StudyCommon& study, const SpeedProfile& speed);

struct StudySpec : StudyCommon {
  std::vector<std::string> parameter_units;///< unit each parameter is written and sampled in ("" = SI)
  /// Further model paths each parameter sets to its value (`also = [...]`, e.g. the same clearance in both bearings).
  std::vector<std::vector<std::string>> parameter_also;
  DesignSpec design;
  std::vector<MetricSpec> metrics;
};

/// Reads and checks a study file; errors (ModelError) name file, line, key and cause.
StudySpec load_study(const std::filesystem::path& file);

/// "580 mg*mm" -> {580, "mg*mm"}; a bare number -> {value, ""}. Throws ModelError naming `context` otherwise.
UnitValue split_value(const std::string& text, const std::string& context);

/// The --set overrides of run `i` of `design` (parameter values written with their units).
std::vector<Override> run_overrides(const StudySpec& study, const Design& design, std::size_t i);

}  // namespace turbodyn::studies

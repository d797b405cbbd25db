#include "studies/study.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "model/io/overrides.h"
#include "model/io/toml_reader.h"
#include "studies/run_log.h"
#include "studies/study_keys.h"
#include "studies/table.h"
#include "model/spec/constants.h"
#include "model/spec/text.h"

namespace turbodyn::studies {
namespace {

using input::Bound;
using input::Reader;
using input::Sources;


// Reads one [[parameters]] entry into a Parameter and the unit it is written in.
Parameter read_parameter(Reader& r, DesignKind kind, std::string& unit, std::vector<std::string>& also) {
  Parameter p;
  p.path = r.text_or("path", "");
  if (p.path.empty()) r.fail("path", "missing required key (the model-file path of the parameter, e.g. \"disks.turbine.unbalance\")");
  if (const toml::array* more = r.array("also")) {
    for (const toml::node& n : *more) {
      if (!n.is_string()) r.fail("also", "expected model-file paths (strings) that take the parameter's value too");
      const std::string path = *n.value<std::string>();
      if (path == p.path || std::find(also.begin(), also.end(), path) != also.end())
        r.fail("also", "'" + path + "' is given twice");
      also.push_back(path);
    }
  }
  Distribution& d = p.distribution;
  OneUnitValues values(r, "parameter's", "write all values of a parameter in one unit", "580 mg*mm");
  if (const toml::array* levels = r.array("levels")) {
    if (levels->empty()) r.fail("levels", "the list is empty");
    d.kind = Distribution::Kind::Levels;
    for (const toml::node& n : *levels) d.levels.push_back(values.take(n, "levels"));
  }
  const std::string dist = r.choice("distribution", {"uniform", "normal", "log-uniform"}, "uniform");
  if (const toml::node* n = r.get("low")) d.low = values.take(*n, "low");
  if (const toml::node* n = r.get("high")) d.high = values.take(*n, "high");
  if (const toml::node* n = r.get("mean")) d.mean = values.take(*n, "mean");
  if (const toml::node* n = r.get("std")) d.std = values.take(*n, "std");
  unit = values.unit();
  d.n_levels = static_cast<int>(r.integer_or("n_levels", 0, 2, 1000000));
  if (d.kind != Distribution::Kind::Levels) {
    if (dist == "normal") {
      d.kind = Distribution::Kind::Normal;
      if (!r.has("mean") || !r.has("std")) r.fail_table("a normal distribution needs mean and std");
    } else {
      d.kind = dist == "log-uniform" ? Distribution::Kind::LogUniform : Distribution::Kind::Uniform;
      if (!r.has("low") || !r.has("high")) r.fail_table("give levels = [...], or low and high (and n_levels for a full factorial)");
    }
    if (kind == DesignKind::FullFactorial && d.kind != Distribution::Kind::Levels && d.n_levels < 2)
      r.fail_table("a full-factorial design of a range needs n_levels >= 2 (or give levels = [...])");
  }
  r.finish();
  return p;
}

MetricSpec read_metric(Reader& r, const StudySpec& s) {
  MetricSpec m;
  m.kind = r.choice("kind",
                    {"max", "min", "max_radius", "rms", "mean", "peak_1x", "peak_1x_speed", "subsync_max",
                     "subsync_ratio",
                     "subsync_onset_speed", "subsync_jump_speed", "subsync_frequency", "summary", "stability_growth",
                     "stability_growth_speed", "stability_frequency", "stability_damping", "stability_onset_speed"},
                    "");
  if (m.kind.empty()) r.fail("kind", "missing required key (max, max_radius, rms, mean, peak_1x, ...)");
  read_metric_window(r, m, "580 mg*mm");
  read_metric_subject(r, m, s.speed_window_min, s.speed_window_max);
  r.finish();
  return m;
}

}  // namespace

UnitValue split_value(const std::string& text, const std::string& context) {
  const std::string s = trim_blanks(text);
  double v = 0.0;
  const char* begin = s.data() + (s.size() > 0 && s[0] == '+' ? 1 : 0);
  const auto res = std::from_chars(begin, s.data() + s.size(), v);
  if (res.ec != std::errc() || !std::isfinite(v))
    throw ModelError(context + ": '" + text + "' does not start with a number");
  return {v, trim_blanks(std::string_view(res.ptr, s.data() + s.size() - res.ptr))};
}

StudyCommon read_study_common(input::Reader& r, const std::filesystem::path& file) {
  StudyCommon s;
  s.source = file;
  s.name = r.text_or("name", file.stem().string());
  const std::string model = r.text_or("model", "");
  if (model.empty()) r.fail_missing("model", "the base model file");
  s.model = std::filesystem::path(model).is_absolute() ? std::filesystem::path(model) : file.parent_path() / model;
  if (!std::filesystem::exists(s.model)) r.fail("model", "no such file: " + s.model.string());
  set_base_model(s, s.model);
  s.threads = static_cast<int>(r.integer_or("threads", 0, 0, 4096));
  const std::vector<double> window = r.quantity_list("speed_window", dim::angular_speed, Bound::NonNegative);
  if (!window.empty()) {
    if (window.size() != 2 || !(window[1] > window[0])) r.fail("speed_window", "expected [low, high] with low < high");
    s.speed_window_min = window[0];
    s.speed_window_max = window[1];
  }
  if (const toml::array* fixed = r.array("fixed"))
    for (const toml::node& n : *fixed) {
      if (!n.is_string()) r.fail("fixed", "expected strings \"PATH=VALUE\"");
      s.fixed.push_back(r.parsed("fixed", *n.value<std::string>(), parse_override));
    }
  return s;
}

namespace {

// Runs `read` (which loads the study's base model) so that a ModelError names the study file first.
template <class F>
auto in_study_context(const StudyCommon& study, F&& read) {
  try {
    return read();
  } catch (const ModelError& e) {
    const std::string source = study.source.string();
    if (source.empty() || std::string(e.what()).rfind(source, 0) == 0) throw;
    throw ModelError(source + ": " + e.what());
  }
}

// The text the runs load: the one read with the study, or the file's for a study built in code (as load_model
// reads it).
std::string base_model_text(const StudyCommon& study) {
  return study.model_text.empty() ? input::read_text_file(study.model, "model file") : study.model_text;
}

}  // namespace

void set_base_model(StudyCommon& study, const std::filesystem::path& model) {
  study.model = model;
  study.model_text = input::read_text_file(model, "model file");
  study.model_digest = text_digest(study.model_text);
}

MachineSpec load_study_model(const StudyCommon& study, const std::vector<Override>& overrides) {
  return in_study_context(study, [&] { return load_base_model(study, overrides); });
}

MachineSpec load_base_model(const StudyCommon& study, const std::vector<Override>& overrides) {
  return load_model_from_string(base_model_text(study), study.model.string(), overrides);
}

std::string base_model_digest(const StudyCommon& study) {
  return study.model_text.empty() ? file_digest(study.model) : study.model_digest;
}

void write_patched_base_model(const StudyCommon& study, const std::vector<Override>& overrides,
                              const std::string& header, const std::filesystem::path& file) {
  write_patched_model_text(base_model_text(study), study.model.string(), overrides, header, file);
}

void check_varied_paths(const StudyCommon& study, const std::vector<Override>& overrides,
                        const std::vector<std::pair<std::string, std::string>>& key_and_path) {
  const std::vector<std::string> numeric =
      in_study_context(study, [&] {
        return numeric_model_keys_from_string(base_model_text(study), study.model.string(), overrides);
      });
  for (const auto& [key, path] : key_and_path) {
    if (std::binary_search(numeric.begin(), numeric.end(), path)) continue;
    const std::string hint = closest_match(path, numeric);
    throw ModelError(study.source.string() + ": " + key + ": '" + path +
                     "' is not a number the model " + study.model.filename().string() +
                     " reads (a study varies numeric values such as lengths, masses, stiffnesses)" +
                     (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
  }
}

void check_speed_window(const StudyCommon& study, const SpeedProfile& speed) {
  if (study.speed_window_min <= 0.0 && study.speed_window_max <= 0.0) return;
  double lo = std::min(speed.start, speed.end), hi = std::max(speed.start, speed.end);
  for (double v : speed.speeds) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (study.speed_window_min < hi && (study.speed_window_max <= 0.0 || study.speed_window_max > lo)) return;
  std::ostringstream os;
  constexpr double kRpm = kRadPerSToRpm;
  os << study.source.string() << ": speed_window: [" << study.speed_window_min * kRpm << ", "
     << study.speed_window_max * kRpm << "] rpm lies outside the speeds of the run of "
     << study.model.filename().string() << " (" << lo * kRpm << " to " << hi * kRpm
     << " rpm): every run would stop before its first sample";
  throw ModelError(os.str());
}

input::Reader read_study_head(input::Reader& top, const std::string& table, const std::filesystem::path& file,
                              StudyCommon& common) {
  const bool vowel = std::string("aeiou").find(table.front()) != std::string::npos;
  input::Reader r =
      top.required_table(table, std::string(vowel ? "an [" : "a [") + table + "] table with at least model = \"...\"");
  common = read_study_common(r, file);
  return r;
}

StudySpec load_study(const std::filesystem::path& file) {
  input::TomlFile in(file, "study file");
  StudySpec s;
  Reader& top = in.top();
  {
    read_study_head(top, "study", file, s).finish();
  }
  {
    Reader r = top.required_table("design", "a [design] table with kind = \"...\"");
    static constexpr EnumName<DesignKind> kKinds[] = {
        {DesignKind::FullFactorial, "full-factorial"}, {DesignKind::LatinHypercube, "latin-hypercube"},
        {DesignKind::Sobol, "sobol"},                   {DesignKind::Halton, "halton"},
        {DesignKind::MonteCarlo, "monte-carlo"},        {DesignKind::Table, "table"}};
    s.design.kind = r.enumeration("kind", kKinds, DesignKind::FullFactorial);
    const long runs = r.integer_or("runs", 0, 0, 10000000);
    s.design.runs = static_cast<std::size_t>(runs);
    s.design.seed = static_cast<std::uint64_t>(r.integer_or("seed", 1, 0, std::numeric_limits<long>::max()));
    s.design.scramble = r.flag_or("scramble", false);
    if (const toml::array* table = r.array("table")) {
      for (const toml::node& row : *table) {
        if (!row.is_array()) r.fail("table", "expected rows [[v1, v2, ...], ...]");
        std::vector<double> values;
        for (const toml::node& v : *row.as_array()) values.push_back(node_value(v, key_location(r, "table"), "580 mg*mm").value);
        s.design.table.push_back(values);
      }
    }
    const bool sampled = s.design.kind != DesignKind::FullFactorial && s.design.kind != DesignKind::Table;
    if (sampled && runs < 1) r.fail("runs", "missing: this design needs the number of runs (runs = 16)");
    if (s.design.kind == DesignKind::Table && s.design.table.empty()) r.fail("table", "missing: the rows of the table");
    r.finish();
  }
  top.required_tables("parameters", "at least one [[parameters]] entry (path = ...)", [&](Reader& r, std::size_t) {
    std::string unit;
    std::vector<std::string> also;
    Parameter p = read_parameter(r, s.design.kind, unit, also);
    s.design.parameters.push_back(p);
    s.parameter_units.push_back(unit);
    s.parameter_also.push_back(also);
  });
  top.required_tables("metrics", "at least one [[metrics]] entry (kind, probe)", [&](Reader& r, std::size_t i) {
    s.metrics.push_back(read_metric(r, s));
    for (std::size_t k = 0; k < i; ++k)
      if (s.metrics[k].name == s.metrics[i].name)
        r.fail("name", "metrics[" + std::to_string(k) + "] has the name '" + s.metrics[i].name +
                           "' already (each metric is one column of the results: give it a name = \"...\" of its own)");
  });
  top.finish();
  try {
    (void)make_design(s.design);
  } catch (const std::invalid_argument& e) {
    throw ModelError(file.string() + ": [design]: " + e.what());
  }
  return s;
}

std::vector<Override> run_overrides(const StudySpec& study, const Design& design, std::size_t i) {
  std::vector<Override> o = study.fixed;
  for (std::size_t p = 0; p < design.paths.size(); ++p) {
    const std::string value = value_text(design.values[i][p], study.parameter_units[p]);
    o.push_back({design.paths[p], value});
    if (p < study.parameter_also.size())
      for (const std::string& path : study.parameter_also[p]) o.push_back({path, value});
  }
  return o;
}

}  // namespace turbodyn::studies

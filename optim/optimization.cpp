#include "optim/optimization.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "model/rotor/rotor.h"
#include "model/engine/runup.h"
#include "model/io/toml_reader.h"
#include "studies/channels.h"
#include "studies/metrics.h"
#include "studies/stability_metrics.h"
#include "studies/study_keys.h"
#include "studies/table.h"
#include "model/spec/constants.h"

namespace turbodyn::optim {
namespace {

using input::Bound;
using input::Reader;
using input::Sources;


struct AlgorithmInfo {
  const char* name;
  bool constraints, global, gradient;
};

// NLopt's algorithms by the names of the study file (docs/optimization.md).
constexpr AlgorithmInfo kAlgorithms[] = {
    {"cobyla", true, false, false}, {"bobyqa", false, false, false}, {"sbplx", false, false, false},
    {"direct-l", false, true, false}, {"crs2", false, true, false}, {"isres", true, true, false},
    {"mlsl", false, true, false},     {"mma", true, false, true},     {"slsqp", true, false, true},
};

const AlgorithmInfo* info(const std::string& name) {
  for (const AlgorithmInfo& a : kAlgorithms)
    if (name == a.name) return &a;
  return nullptr;
}

// A number or "<number> <unit>" (unit checked later by the model loader, as in the sweep's study file).
studies::UnitValue node_value(const toml::node& n, const std::string& context) {
  return studies::node_value(n, context, "51 um");
}

std::string location(const Reader& r, const std::string& key) { return studies::key_location(r, key); }

std::string shown(double v, const std::string& unit) { return studies::value_text(v, unit); }

Variable read_variable(Reader& r) {
  Variable v;
  const std::string path = r.text_or("path", "");
  if (!path.empty()) v.paths.push_back(path);
  if (const toml::array* paths = r.array("paths")) {
    if (!path.empty()) r.fail("paths", "give either path or paths");
    for (const toml::node& n : *paths) {
      if (!n.is_string()) r.fail("paths", "expected model-file paths (strings)");
      v.paths.push_back(*n.value<std::string>());
    }
  }
  if (v.paths.empty())
    r.fail_missing("path", "the model-file path of the variable, e.g. \"bearings.compressor.damper.clearance\", or "
                           "paths = [...] for several keys set to one value");
  v.path = r.text_or("name", v.paths.size() == 1 ? v.paths[0] : v.paths[0] + " (+" + std::to_string(v.paths.size() - 1) + ")");
  studies::OneUnitValues values(r, "variable's", "write low, high and start in one unit", "51 um");
  v.low = values.take("low");
  v.high = values.take("high");
  v.unit = values.unit();
  if (std::isnan(v.low)) r.fail_missing("low", "the lower bound, e.g. \"30 um\"");
  if (std::isnan(v.high)) r.fail_missing("high", "the upper bound, e.g. \"120 um\"");
  if (!(v.low < v.high))
    r.fail("low", "the lower bound " + shown(v.low, v.unit) + " must be below the upper bound " + shown(v.high, v.unit));
  const std::string scale = r.choice("scale", {"linear", "log"}, "linear");
  v.log_scale = scale == "log";
  if (v.log_scale && !(v.low > 0.0)) r.fail("scale", "a logarithmic scale needs a positive lower bound");
  v.start = values.take("start");
  v.unit = values.unit();
  if (std::isnan(v.start)) {
    v.start = v.value(0.5);
  } else if (v.start < v.low || v.start > v.high) {
    r.fail("start", "the start " + shown(v.start, v.unit) + " lies outside the bounds [" + shown(v.low, v.unit) +
                        ", " + shown(v.high, v.unit) + "]");
  }
  r.finish();
  return v;
}

Metric read_metric(Reader& r, double window_min, double window_max) {
  Metric m;
  studies::MetricSpec& s = m.spec;
  const std::vector<std::string> kinds = {"max", "min", "max_radius", "rms", "mean", "peak_1x", "peak_1x_speed",
                                          "subsync_max", "subsync_ratio", "subsync_onset_speed", "subsync_jump_speed",
                                          "subsync_frequency", "summary", "response_peak", "response_peak_speed",
                                          "stability_growth", "stability_growth_speed", "stability_frequency",
                                          "stability_damping", "stability_onset_speed"};
  s.kind = r.choice("kind", kinds, "");
  if (s.kind.empty()) r.fail_missing("kind", "max, max_radius, peak_1x, ..., response_peak, stability_growth, ...");
  studies::read_metric_window(r, s, "51 um");
  studies::read_metric_subject(r, s, window_min, window_max);
  m.points = static_cast<int>(r.integer_or("points", 200, 3, 1000000));
  if (m.response() && s.speed_max <= 0.0) {
    if (window_max <= 0.0)
      r.fail("speed_window", "a steady-state response metric needs a speed window (here or in [optimize])");
    s.speed_min = window_min;
    s.speed_max = window_max;
  }
  r.finish();
  return m;
}

std::size_t metric_index(Reader& r, const std::string& key, const std::vector<Metric>& metrics) {
  const std::string name = r.text_or(key, "");
  if (name.empty()) r.fail_missing(key, "the name of one of the [[metrics]]");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    if (metrics[i].spec.name == name) return i;
    names.push_back(metrics[i].spec.name);
  }
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  r.fail(key, "unknown metric '" + name + "'" + studies::did_you_mean(name, names, " (metrics: " + known + ")"));
}

// A constraint bound in the unit the metric's values have (metric_unit): lengths in m, forces in N, speeds in rpm.
double bound_value(Reader& r, const std::string& key, const std::string& unit) {
  const toml::node* n = r.get(key);
  const studies::UnitValue v = node_value(*n, location(r, key));
  if (v.unit.empty()) return v.value;
  const std::string text = *n->value<std::string>();
  try {
    if (unit == "m") return parse_quantity(text, dim::length);
    if (unit == "N") return parse_quantity(text, dim::force);
    if (unit == "rpm") return parse_quantity(text, dim::angular_speed) * kRadPerSToRpm;
    if (unit == "Hz") return parse_quantity(text, dim::frequency);
    if (unit == "1") return parse_quantity(text, dim::dimensionless);
  } catch (const UnitError& e) {
    r.fail(key, std::string("the metric is in ") + unit + ": " + e.what());
  }
  if (v.unit == unit) return v.value;
  r.fail(key, "the metric's values are in '" + (unit.empty() ? std::string("(unknown)") : unit) +
                  "'; write the bound as a plain number in that unit");
}

// x/y (or fx/fy) channels of a pair stem, as the run-up metrics read them.
// Checks the metrics against the base model (probes exist, response metrics have a linear model) and sets their
// units.
void resolve_metrics(OptimizationSpec& s) {
  const std::vector<Override> overrides = run_overrides(s, start_design(s), &s.cases.front());
  const MachineSpec machine = studies::load_study_model(s, overrides);
  std::vector<std::pair<std::string, std::string>> paths;
  for (std::size_t i = 0; i < s.variables.size(); ++i)
    for (const std::string& p : s.variables[i].paths)
      paths.emplace_back("variables[" + std::to_string(i) + "].path", p);
  studies::check_varied_paths(s, overrides, paths);
  const std::unique_ptr<RunupModel> model = make_runup_model(machine);
  const std::vector<ProbeChannel>& channels = model->channels();
  const std::vector<std::string> names = studies::channel_names(channels);
  const nlohmann::json summary = studies::summary_template(machine, *model);
  if (std::any_of(s.metrics.begin(), s.metrics.end(), [](const Metric& m) { return !m.response(); }))
    studies::check_speed_window(s, machine.speed);
  std::vector<studies::MetricSpec> specs;
  for (const Metric& m : s.metrics) specs.push_back(m.spec);
  studies::check_stability_metrics(s, specs, machine);
  for (std::size_t i = 0; i < s.metrics.size(); ++i) {
    Metric& m = s.metrics[i];
    const std::string where = s.source.string() + ": metrics[" + std::to_string(i) + "].probe: ";
    if (studies::is_stability_metric(m.spec.kind)) {
      m.unit = studies::metric_unit(m.spec, channels);
      continue;
    }
    if (m.response()) {
      for (const BearingSpec& b : machine.bearings)
        if (b.type != BearingType::Linear || b.damper.enabled || b.pedestal_mass > 0.0)
          throw ModelError(s.source.string() + ": metrics[" + std::to_string(i) + "].kind: " + m.spec.kind +
                           " needs the linear rotor (linear bearings without dampers or pedestals); bearing '" +
                           b.name + "' is not; use a run-up metric");
      std::vector<std::string> stems;
      for (const DiskSpec& d : machine.disks)
        for (const char* sfx : {"", ".x", ".y"}) stems.push_back("disk." + d.name + sfx);
      for (const BearingSpec& b : machine.bearings)
        for (const char* sfx : {"", ".fx", ".fy"}) stems.push_back("bearing." + b.name + sfx);
      if (std::find(stems.begin(), stems.end(), m.spec.probe) == stems.end())
        throw ModelError(where + "the steady-state response has no probe '" + m.spec.probe + "'" +
                         studies::did_you_mean(m.spec.probe, stems, " (use disk.NAME or bearing.NAME)"));
      m.unit = m.spec.kind == "response_peak_speed" ? "rpm" : m.spec.probe.rfind("disk.", 0) == 0 ? "m" : "N";
      continue;
    }
    if (m.spec.kind != "summary") {
      const bool ok = m.spec.kind == "max_radius" ? studies::pair_channels(channels, m.spec.probe).first >= 0
                                                  : studies::find_channel(channels, m.spec.probe) >= 0;
      if (!ok) throw ModelError(where + studies::unknown_probe(m.spec.probe, names));
    } else if (const nlohmann::json* v = studies::summary_node(summary, m.spec.probe);
               !v || !(v->is_number() || v->is_boolean())) {
      throw ModelError(where + "the run summary has no number '" + m.spec.probe +
                       "' (e.g. stats.steps, energy.balance_error_j, t_reached_s; docs/output-format.md)");
    }
    m.unit = studies::metric_unit(m.spec, channels);
  }
  // Spectrogram probes: the channels of the objective's metrics unless given.
  if (s.spectrogram_probes.empty()) {
    for (const ObjectiveTerm& t : s.objective.terms) {
      const std::string& p = s.metrics[t.metric].spec.probe;
      for (const std::string& c : {p, p + ".x", p + ".fx"})
        if (std::find(names.begin(), names.end(), c) != names.end() &&
            std::find(s.spectrogram_probes.begin(), s.spectrogram_probes.end(), c) == s.spectrogram_probes.end()) {
          s.spectrogram_probes.push_back(c);
          break;
        }
    }
  }
  for (const std::string& p : s.spectrogram_probes)
    if (studies::find_channel(channels, p) < 0)
      throw ModelError(s.source.string() + ": optimize.spectrograms: the model has no probe '" + p + "'" +
                       studies::did_you_mean(p, names));
}

}  // namespace

double Variable::value(double x) const {
  x = std::clamp(x, 0.0, 1.0);
  if (x == 0.0) return low;
  if (x == 1.0) return high;
  return log_scale ? low * std::pow(high / low, x) : low + x * (high - low);
}

double Variable::scaled(double v) const {
  const double x = log_scale ? std::log(v / low) / std::log(high / low) : (v - low) / (high - low);
  return std::clamp(x, 0.0, 1.0);
}

const std::vector<std::string>& algorithm_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const AlgorithmInfo& a : kAlgorithms) n.push_back(a.name);
    return n;
  }();
  return names;
}

bool supports_constraints(const std::string& a) { return info(a) && info(a)->constraints; }
bool is_global(const std::string& a) { return info(a) && info(a)->global; }
bool needs_gradient(const std::string& a) { return info(a) && info(a)->gradient; }

bool AlgorithmOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!info(name)) return fail("unknown algorithm '" + name + "'");
  if (name == "mlsl" && (!info(local) || is_global(local)))
    return fail("mlsl needs a local optimiser (local = cobyla, bobyqa, sbplx, mma or slsqp), got '" + local + "'");
  if (is_global(name) && maxeval <= 0 && maxtime <= 0.0)
    return fail("the global algorithm " + name + " stops only on maxeval or maxtime: give one of them");
  if (maxeval <= 0 && maxtime <= 0.0 && xtol_rel <= 0.0 && xtol_abs <= 0.0 && ftol_rel <= 0.0 && ftol_abs <= 0.0 &&
      !has_stopval)
    return fail("no stopping criterion: give at least one of xtol_rel, xtol_abs, ftol_rel, ftol_abs, maxeval, maxtime");
  if (!(gradient_step > 0.0 && gradient_step < 0.5)) return fail("gradient_step must lie in (0, 0.5)");
  if (initial_step < 0.0 || initial_step > 1.0) return fail("initial_step must lie in [0, 1]");
  if (constraint_tolerance < 0.0) return fail("constraint_tolerance must not be negative");
  return true;
}

std::vector<double> start_design(const OptimizationSpec& spec) {
  std::vector<double> d;
  for (const Variable& v : spec.variables) d.push_back(v.start);
  return d;
}

std::string value_text(const Variable& v, double value) { return shown(value, v.unit); }

std::vector<Override> run_overrides(const OptimizationSpec& spec, const std::vector<double>& design,
                                    const OperatingCase* operating_case) {
  std::vector<Override> o = spec.fixed;
  for (std::size_t i = 0; i < spec.variables.size(); ++i)
    for (const std::string& p : spec.variables[i].paths) o.push_back({p, value_text(spec.variables[i], design[i])});
  if (operating_case) o.insert(o.end(), operating_case->overrides.begin(), operating_case->overrides.end());
  return o;
}

OptimizationSpec load_optimization(const std::filesystem::path& file) {
  input::TomlFile in(file, "study file");
  OptimizationSpec s;
  Reader& top = in.top();
  {
    Reader r = studies::read_study_head(top, "optimize", file, s);
    if (const toml::array* probes = r.array("spectrograms"))
      for (const toml::node& n : *probes) {
        if (!n.is_string()) r.fail("spectrograms", "expected probe names such as \"disk.turbine.x\"");
        s.spectrogram_probes.push_back(*n.value<std::string>());
      }
    s.final_runs = r.choice("final_runs", {"full", "window", "none"}, "full");
    r.finish();
  }
  {
    Reader r = top.required_table("algorithm", "an [algorithm] table with name = \"cobyla\" (or another) and stopping criteria");
    AlgorithmOptions& a = s.algorithm;
    a.name = r.choice("name", algorithm_names(), "");
    if (a.name.empty()) r.fail_missing("name", "one of cobyla, bobyqa, sbplx, direct-l, crs2, isres, mlsl, mma, slsqp");
    std::vector<std::string> locals;
    for (const std::string& n : algorithm_names())
      if (!is_global(n)) locals.push_back(n);
    a.local = r.choice("local", locals, a.local);
    a.xtol_rel = r.quantity_or("xtol_rel", dim::dimensionless, 0.0, Bound::NonNegative);
    a.xtol_abs = r.quantity_or("xtol_abs", dim::dimensionless, 0.0, Bound::NonNegative);
    a.ftol_rel = r.quantity_or("ftol_rel", dim::dimensionless, 0.0, Bound::NonNegative);
    a.ftol_abs = r.quantity_or("ftol_abs", dim::dimensionless, 0.0, Bound::NonNegative);
    if (r.has("stopval")) {
      a.has_stopval = true;
      a.stopval = r.quantity("stopval", dim::dimensionless);
    }
    a.maxeval = static_cast<int>(r.integer_or("maxeval", 0, 1, 10000000));
    a.maxtime = r.quantity_or("maxtime", dim::time, 0.0, Bound::Positive);
    a.initial_step = r.quantity_or("initial_step", dim::dimensionless, 0.0, Bound::Positive);
    a.central_differences = r.choice("gradient", {"forward", "central"}, "forward") == "central";
    a.gradient_step = r.quantity_or("gradient_step", dim::dimensionless, a.gradient_step, Bound::Positive);
    a.seed = static_cast<std::uint64_t>(r.integer_or("seed", 1, 0, std::numeric_limits<long>::max()));
    a.constraint_tolerance =
        r.quantity_or("constraint_tolerance", dim::dimensionless, a.constraint_tolerance, Bound::NonNegative);
    std::string why;
    if (!a.IsValid(&why)) r.fail_table(why);
    r.finish();
  }
  top.required_tables("variables", "at least one [[variables]] entry (path, low, high)", [&](Reader& r, std::size_t) {
    s.variables.push_back(read_variable(r));
    for (std::size_t j = 0; j + 1 < s.variables.size(); ++j)
      for (const std::string& p : s.variables.back().paths)
        if (std::find(s.variables[j].paths.begin(), s.variables[j].paths.end(), p) != s.variables[j].paths.end())
          r.fail(r.has("paths") ? "paths" : "path", "'" + p + "' is already set by variables[" + std::to_string(j) + "]");
  });
  top.each_table("cases", [&](Reader& r, std::size_t i) {
    OperatingCase c;
    c.name = r.text_or("name", "case " + std::to_string(i));
    c.weight = r.quantity_or("weight", dim::dimensionless, 1.0, Bound::Positive);
    if (const toml::array* set = r.array("set"))
      for (const toml::node& o : *set) {
        if (!o.is_string()) r.fail("set", "expected strings \"PATH=VALUE\"");
        c.overrides.push_back(r.parsed("set", *o.value<std::string>(), parse_override));
      }
    r.finish();
    s.cases.push_back(c);
  });
  if (s.cases.empty()) s.cases.push_back({"nominal", 1.0, {}});
  top.required_tables("metrics", "at least one [[metrics]] entry (kind, probe)", [&](Reader& r, std::size_t) {
    s.metrics.push_back(read_metric(r, s.speed_window_min, s.speed_window_max));
    for (std::size_t j = 0; j + 1 < s.metrics.size(); ++j)
      if (s.metrics[j].spec.name == s.metrics.back().spec.name)
        r.fail("name", "the name '" + s.metrics[j].spec.name + "' is already used by metrics[" + std::to_string(j) + "]");
  });
  {
    Reader r = top.required_table("objective", "an [objective] table with metric = \"...\" (minimised)");
    s.objective.cases = r.choice("cases", {"max", "weighted"}, "max") == "max" ? CaseAggregate::Max
                                                                                : CaseAggregate::Weighted;
    if (r.has("metric")) s.objective.terms.push_back({metric_index(r, "metric", s.metrics), 1.0});
    if (const toml::array* terms = r.array("terms")) {
      for (std::size_t i = 0; i < terms->size(); ++i) {
        const toml::node& n = (*terms)[i];
        if (!n.is_table()) r.fail("terms", "expected tables {metric = \"...\", weight = 1.0}");
        Reader t(*n.as_table(), r.key_path("terms") + "[" + std::to_string(i) + "]", in.sources());
        ObjectiveTerm term;
        term.metric = metric_index(t, "metric", s.metrics);
        term.weight = t.quantity_or("weight", dim::dimensionless, 1.0);
        t.finish();
        s.objective.terms.push_back(term);
      }
    }
    if (s.objective.terms.empty())
      r.fail_missing("metric", "the metric to minimise, or terms = [{metric = \"...\", weight = 1.0}, ...]");
    r.finish();
  }
  std::vector<std::string> pending_bound_keys;  // "upper" or "lower" per constraint, read once the units are known
  top.each_table("constraints", [&](Reader& r, std::size_t) {
    Constraint c;
    c.metric = metric_index(r, "metric", s.metrics);
    c.name = r.text_or("name", s.metrics[c.metric].spec.name);
    const bool upper = r.has("upper"), lower = r.has("lower");
    if (!upper && !lower)
      r.fail_table("a constraint needs a bound: upper = \"...\" (metric <= upper) or lower = \"...\" (metric >= lower)");
    if (upper && lower) r.fail("lower", "give either upper or lower (write two constraints for a band)");
    c.upper = upper;
    r.finish();
    s.constraints.push_back(c);
    pending_bound_keys.push_back(upper ? "upper" : "lower");
  });
  if (!s.constraints.empty() && !supports_constraints(s.algorithm.name) && is_global(s.algorithm.name)) {
    Reader r = top.required_table("algorithm", "");
    r.fail("name", s.algorithm.name + " handles bound constraints only, not the study's [[constraints]]; use isres "
                   "(global) or cobyla, mma, slsqp (local), or bobyqa/sbplx (wrapped in NLopt's augmented Lagrangian, "
                   "AUGLAG)");
  }
  top.finish();
  resolve_metrics(s);
  Reader again(in.root(), "", in.sources());
  again.each_table("constraints", [&](Reader& r, std::size_t i) {
    s.constraints[i].bound = bound_value(r, pending_bound_keys[i], s.metrics[s.constraints[i].metric].unit);
  });
  return s;
}

}  // namespace turbodyn::optim

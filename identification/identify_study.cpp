#include "identification/identify_study.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "model/io/toml_reader.h"
#include "studies/channels.h"
#include "studies/study.h"
#include "studies/study_keys.h"
#include "model/spec/constants.h"

namespace turbodyn::identification {
namespace {

using input::Bound;
using input::Reader;
using input::Sources;

// A quantity in the unit dimension of a sensor, or absent (0).
double sensor_quantity(Reader& r, const std::string& key, const Dimension& d) {
  return r.quantity_or(key, d, 0.0, Bound::NonNegative);
}

std::string unit_key(Reader& r, const std::string& key, const Dimension& d) {
  const std::string u = r.text_or(key, "");
  if (u.empty()) return u;
  try {
    (void)unit_factor(u, d);
  } catch (const UnitError& e) {
    r.fail(key, std::string("unit '") + u + "': " + e.what());
  }
  return u;
}

void read_measurement_table(Reader& r, const std::filesystem::path& study_file, MeasurementSpec& m) {
  const std::string file = r.text_or("file", "");
  if (file.empty()) r.fail_missing("file", "the measured file, CSV or HDF5");
  m.file = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : study_file.parent_path() / file;
  const std::string format = r.choice("format", {"timeseries", "spectra"}, "timeseries");
  m.format = format == "spectra" ? MeasurementFormat::Spectra : MeasurementFormat::TimeSeries;
  m.time = {r.text_or("time", "time"), unit_key(r, "time_unit", dim::time)};
  m.speed = {r.text_or("speed", ""), unit_key(r, "speed_unit", dim::angular_speed)};
  m.angle = {r.text_or("angle", ""), unit_key(r, "angle_unit", dim::angle)};
  m.tacho = r.text_or("tacho", "");
  if (const toml::node* n = r.get("pulses_per_rev")) {
    m.pulses_per_rev = n->value<double>().value_or(0.0);
    if (!(m.pulses_per_rev >= 1.0)) r.fail("pulses_per_rev", "expected a number >= 1");
  }
  if (const toml::node* n = r.get("tacho_threshold")) {
    if (!n->value<double>()) r.fail("tacho_threshold", "expected a number (in the tacho column's values)");
    m.tacho_threshold = *n->value<double>();
  }
  m.frequency = {r.text_or("frequency", "frequency"), unit_key(r, "frequency_unit", dim::frequency)};
  if (m.format == MeasurementFormat::Spectra && m.speed.column.empty())
    r.fail_missing("speed", "the rotor-speed column of the spectra");
  if (m.format == MeasurementFormat::TimeSeries && m.speed.column.empty() && m.tacho.empty() && m.angle.column.empty())
    r.fail_table("give the rotor speed: speed = \"<column>\", tacho = \"<column>\" or angle = \"<column>\"");
  const toml::array* sensors = r.array("sensors");
  if (!sensors || sensors->empty()) r.fail_missing("sensors", "[[measurement.sensors]] entries");
  for (std::size_t i = 0; i < sensors->size(); ++i) {
    const toml::node& n = (*sensors)[i];
    const std::string path = "measurement.sensors[" + std::to_string(i) + "]";
    if (!n.is_table()) r.fail("sensors", "expected tables ([[measurement.sensors]])");
    Reader s(*n.as_table(), path, r.sources());
    SensorSpec sp;
    sp.column.column = s.text_or("column", "");
    if (sp.column.column.empty()) s.fail_missing("column", "the column of the measured file");
    sp.name = s.text_or("name", sp.column.column);
    sp.probe = s.text_or("probe", "");
    if (sp.probe.empty()) s.fail_missing("probe", "the model probe at the sensor's position, e.g. \"disk.compressor.x\"");
    sp.quantity = s.enumeration("quantity", kQuantities, Quantity::Displacement);
    sp.column.unit = unit_key(s, "unit", dimension_of(sp.quantity));
    for (const SensorSpec& other : m.sensors)
      if (other.name == sp.name) s.fail("name", "a sensor named '" + sp.name + "' exists already");
    s.finish();
    m.sensors.push_back(sp);
  }
  r.finish();
}

std::vector<double> speeds_hz(Reader& r, const std::string& key) {
  std::vector<double> v = r.quantity_list(key, dim::angular_speed, Bound::NonNegative);
  for (double& x : v) x /= kTwoPi;
  return v;
}

FeatureSpec read_feature(Reader& r, const MeasurementSpec& m, Method method) {
  FeatureSpec f;
  if (!r.has("kind")) r.fail_missing("kind", "order1x, subsync or resonance");
  f.kind = r.enumeration("kind", kFeatureKinds, FeatureKind::Order1x);
  const std::string sensor = r.text_or("sensor", m.sensors.size() == 1 ? m.sensors[0].name : "");
  if (sensor.empty()) r.fail_missing("sensor", "the name of a [[measurement.sensors]] entry");
  std::vector<std::string> names;
  bool found = false;
  for (std::size_t i = 0; i < m.sensors.size(); ++i) {
    names.push_back(m.sensors[i].name);
    if (m.sensors[i].name == sensor) {
      f.sensor = i;
      found = true;
    }
  }
  if (!found) r.fail("sensor", "no sensor named '" + sensor + "'" + studies::did_you_mean(sensor, names));
  f.name = r.text_or("name", to_string(f.kind) + "_" + sensor);
  const Dimension d = dimension_of(m.sensors[f.sensor].quantity);
  f.weight = r.quantity_or("weight", dim::dimensionless, 1.0, Bound::Positive);
  f.amplitude_scale = sensor_quantity(r, "scale", d);
  if (f.kind == FeatureKind::Resonance) {
    const std::vector<double> range = speeds_hz(r, "speed_range");
    if (range.size() != 2 || !(range[1] > range[0]))
      r.fail("speed_range", "a resonance needs speed_range = [low, high] with low < high");
    f.range_min_hz = range[0];
    f.range_max_hz = range[1];
    f.speed_scale = r.quantity_or("speed_scale", dim::angular_speed, 0.0, Bound::NonNegative) / kTwoPi;
  } else {
    f.speeds_hz = speeds_hz(r, "speeds");
    const std::vector<double> range = speeds_hz(r, "speed_range");
    const long n = r.integer_or("n_speeds", 0, 2, limits::kMaxModalSpeeds);
    if (f.speeds_hz.empty()) {
      if (range.empty()) r.fail_missing("speeds", "speeds = [...], or speed_range = [low, high] with n_speeds");
      if (range.size() != 2 || !(range[1] > range[0])) r.fail("speed_range", "expected [low, high] with low < high");
      if (n < 2) r.fail_missing("n_speeds", "the number of speeds (>= 2) spread evenly over speed_range");
      for (long i = 0; i < n; ++i) f.speeds_hz.push_back(range[0] + (range[1] - range[0]) * double(i) / double(n - 1));
    } else if (!range.empty() || n) {
      r.fail("speeds", "give either speeds = [...] or speed_range with n_speeds, not both");
    }
  }
  if (f.kind == FeatureKind::Order1x) {
    const bool can = m.format == MeasurementFormat::TimeSeries && m.has_phase_reference();
    f.phase = r.flag_or("phase", can);
    if (f.phase && !can)
      r.fail("phase", m.format == MeasurementFormat::Spectra
                          ? std::string("spectra carry no phase; set phase = false")
                          : std::string("the measurement has no phase reference (give a tacho or angle column)"));
  } else {
    f.phase = false;
  }
  if (f.kind == FeatureKind::Subsync) {
    if (method == Method::Response) r.fail("kind", "the steady-state response (method = \"response\") has no sub-synchronous content");
    f.frequency_scale = r.quantity_or("frequency_scale", dim::frequency, 0.0, Bound::NonNegative);
    f.threshold = sensor_quantity(r, "threshold", d);
    if (const toml::array* band = r.array("band")) {
      if (band->size() != 2 || !(*band)[0].value<double>() || !(*band)[1].value<double>())
        r.fail("band", "expected [low, high] as fractions of the rotor speed, e.g. [0.05, 0.9]");
      f.band_low = *(*band)[0].value<double>();
      f.band_high = *(*band)[1].value<double>();
      if (!(f.band_low >= 0.0 && f.band_high > f.band_low && f.band_high < 1.0))
        r.fail("band", "expected 0 <= low < high < 1");
    }
  }
  r.finish();
  return f;
}

ParameterSpec read_parameter(Reader& r) {
  ParameterSpec p;
  const toml::node* path = r.get("path");
  if (!path) r.fail_missing("path", "a model-file key path such as \"bearings.compressor.clearance\", or a list");
  if (path->is_string()) {
    p.paths.push_back(*path->value<std::string>());
  } else if (const toml::array* a = path->as_array()) {
    for (const toml::node& n : *a) {
      if (!n.is_string()) r.fail("path", "expected strings");
      p.paths.push_back(*n.value<std::string>());
    }
  }
  if (p.paths.empty()) r.fail("path", "expected a key path or a non-empty list of key paths");
  p.name = r.text_or("name", p.paths.front());
  studies::OneUnitValues values(r, "parameter's", "write all values of a parameter in one unit", "15 um");
  for (const char* key : {"start", "lower", "upper"})
    if (!r.has(key)) r.fail_missing(key, "a value such as \"15 um\"");
  p.start = values.take("start");
  p.lower = values.take("lower");
  p.upper = values.take("upper");
  p.truth = values.take("true");
  p.unit = values.unit();
  if (!(p.lower < p.upper)) r.fail("upper", "must be above lower");
  if (!(p.start >= p.lower && p.start <= p.upper)) r.fail("start", "must lie within [lower, upper]");
  r.finish();
  return p;
}

constexpr EnumName<Loss> kLosses[] = {
    {Loss::None, "none"}, {Loss::Huber, "huber"}, {Loss::Cauchy, "cauchy"}, {Loss::SoftLOne, "soft-l1"}};

}  // namespace

std::string to_string(Loss l) { return name_of(kLosses, l); }

IdentifyStudy load_identify_study(const std::filesystem::path& file) {
  input::TomlFile in(file, "study file");
  const Sources& src = in.sources();
  Reader& top = in.top();
  IdentifyStudy s;
  {
    Reader r = studies::read_study_head(top, "identify", file, s);
    s.method = r.choice("method", {"runup", "response"}, "runup") == "response" ? Method::Response : Method::Runup;
    s.speed_from_measurement = r.choice("speed", {"model", "measured"}, "model") == "measured";
    if (s.speed_from_measurement && s.method != Method::Runup)
      r.fail("speed", "\"measured\" drives run-ups; the steady-state response (method = \"response\") has none");
    r.finish();
  }
  {
    Reader r = top.required_table("measurement", "a [measurement] table (file, columns, [[measurement.sensors]])");
    read_measurement_table(r, file, s.measurement);
  }
  if (s.speed_from_measurement && s.measurement.format != MeasurementFormat::TimeSeries)
    top.fail_table("identify.speed = \"measured\" needs a measured time series (format = \"timeseries\"): processed "
                   "spectra carry no speed history");
  if (s.method == Method::Response && s.measurement.format == MeasurementFormat::TimeSeries)
    top.fail_table("method = \"response\" (steady state) compares with processed spectra only; use format = "
                   "\"spectra\" or method = \"runup\"");
  if (const toml::table* proc = top.table("processing")) {
    Reader r(*proc, "processing", src);
    s.processing.revolutions = r.quantity_or("revolutions", dim::dimensionless, 8.0, Bound::Positive);
    s.processing.track_points = static_cast<std::size_t>(r.integer_or("track_points", 400, 10, 1000000));
    s.processing.segment = static_cast<std::size_t>(r.integer_or("segment", 1024, 8, limits::kMaxSpectrogramSegment));
    s.processing.overlap = r.quantity_or("overlap", dim::dimensionless, 0.75, Bound::NonNegative);
    if (s.processing.overlap >= 1.0) r.fail("overlap", "must be below 1");
    const std::string w = r.choice("window", {"hann", "hamming", "blackman", "flattop", "rectangular"}, "hann");
    s.processing.window = signal::window_from_string(w);
    r.finish();
  }
  top.required_tables("features", "at least one [[features]] entry (kind, sensor)", [&](Reader& r, std::size_t) {
    s.features.push_back(read_feature(r, s.measurement, s.method));
  });
  top.required_tables("parameters", "at least one [[parameters]] entry (path, start, lower, upper)",
                      [&](Reader& r, std::size_t) { s.parameters.push_back(read_parameter(r)); });
  if (const toml::table* solver = top.table("solver")) {
    Reader r(*solver, "solver", src);
    SolverSpec& o = s.solver;
    o.loss = r.enumeration("loss", kLosses, Loss::None);
    o.loss_scale = r.quantity_or("loss_scale", dim::dimensionless, 1.0, Bound::Positive);
    o.max_iterations = static_cast<int>(r.integer_or("max_iterations", 30, 0, 1000000));
    o.step = r.quantity_or("step", dim::dimensionless, 1e-3, Bound::Positive);
    o.central = r.choice("differences", {"forward", "central"}, "forward") == "central";
    o.scaling = r.choice("scaling", {"bounds", "start"}, "bounds") == "start" ? Scaling::Start : Scaling::Bounds;
    o.function_tolerance = r.quantity_or("function_tolerance", dim::dimensionless, o.function_tolerance, Bound::Positive);
    o.parameter_tolerance = r.quantity_or("parameter_tolerance", dim::dimensionless, o.parameter_tolerance, Bound::Positive);
    o.gradient_tolerance = r.quantity_or("gradient_tolerance", dim::dimensionless, 1e-10, Bound::Positive);
    r.finish();
    if (o.scaling == Scaling::Start)
      for (const ParameterSpec& p : s.parameters)
        if (!(p.start > 0.0)) r.fail("scaling", "scaling = \"start\" needs positive start values ('" + p.name + "')");
  }
  top.finish();
  const bool runup = s.method == Method::Runup;
  if (std::isnan(s.solver.function_tolerance)) s.solver.function_tolerance = runup ? 1e-3 : 1e-8;
  if (std::isnan(s.solver.parameter_tolerance)) s.solver.parameter_tolerance = runup ? 1e-4 : 1e-8;
  return s;
}

}  // namespace turbodyn::identification

#include "identification/measurement.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "model/io/model_file.h"
#include "model/io/timeseries_file.h"
#include "studies/channels.h"
#include "model/spec/constants.h"
#include "model/spec/text.h"

namespace turbodyn::identification {
namespace {

// Time steps that differ by more than this fraction of the mean step count as uneven sampling (then resampled).
constexpr double kUnevenSampling = 1e-3;

// A table read from a file: named columns with the unit in the header (if any) and where every value came from.
struct Table {
  std::string file;
  std::vector<std::string> names, units;
  std::vector<std::vector<double>> columns;     // only the columns asked for are filled
  std::vector<std::size_t> lines;               // file line of every row (CSV), 0 for HDF5
  std::vector<std::vector<std::size_t>> fields; // CSV: 1-based character column of the field, per column and row

  int find(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    return -1;
  }
  std::size_t require(const std::string& name, const std::string& role) const {
    const int c = find(name);
    if (c >= 0) return static_cast<std::size_t>(c);
    std::string msg = file + ": no column '" + name + "' (" + role + "); the file has:";
    for (const std::string& n : names) msg += " '" + n + "'";
    throw ModelError(msg + studies::did_you_mean(name, names));
  }
};

// Splits one CSV line at commas (quotes around a field are allowed and removed); `starts` gets the 1-based
// character column of every field.
std::vector<std::string> split_csv(const std::string& line, std::vector<std::size_t>& starts) {
  std::vector<std::string> out;
  starts.clear();
  std::string cur;
  bool quoted = false;
  std::size_t start = 1;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (ch == '"') {
      quoted = !quoted;
    } else if (ch == ',' && !quoted) {
      out.push_back(cur);
      starts.push_back(start);
      cur.clear();
      start = i + 2;
    } else {
      cur += ch;
    }
  }
  out.push_back(cur);
  starts.push_back(start);
  return out;
}

// "x_comp [um]" -> ("x_comp", "um"); "x_comp" -> ("x_comp", "").
std::pair<std::string, std::string> split_header(const std::string& field) {
  const std::string f = trim_blanks(field);
  const std::size_t open = f.find('[');
  if (open != std::string::npos && f.back() == ']')
    return {trim_blanks(f.substr(0, open)), trim_blanks(f.substr(open + 1, f.size() - open - 2))};
  return {f, ""};
}

// Reads the header and the columns `wanted` of a CSV file; other columns are not parsed.
Table read_csv(const std::filesystem::path& path, const std::vector<std::string>& wanted) {
  std::ifstream in(path);
  Table t;
  t.file = path.string();
  if (std::error_code ec; std::filesystem::is_directory(path, ec))
    throw ModelError(t.file + ": is a directory, not a measured file");
  if (!in) throw ModelError(t.file + ": cannot open the measured file");
  std::string line;
  std::size_t line_no = 0;
  bool header = true;
  std::vector<std::size_t> use;  // column indices to parse
  std::vector<std::size_t> starts;
  while (std::getline(in, line)) {
    ++line_no;
    // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first column's name.
    if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    const std::string s = trim_blanks(line);
    if (s.empty() || s[0] == '#') continue;
    const std::vector<std::string> f = split_csv(line, starts);
    if (header) {
      for (const std::string& h : f) {
        auto [name, unit] = split_header(h);
        t.names.push_back(name);
        t.units.push_back(unit);
      }
      t.columns.resize(t.names.size());
      t.fields.resize(t.names.size());
      for (const std::string& w : wanted) {
        const int c = t.find(w);
        if (c >= 0 && std::find(use.begin(), use.end(), c) == use.end()) use.push_back(static_cast<std::size_t>(c));
      }
      header = false;
      continue;
    }
    if (f.size() != t.names.size()) {
      std::ostringstream os;
      os << t.file << ':' << line_no << ": " << f.size() << " fields, but the header names " << t.names.size()
         << " columns";
      throw ModelError(os.str());
    }
    for (std::size_t c : use) {
      const std::string v = trim_blanks(f[c]);
      double x = 0.0;
      const char* b = v.data() + (!v.empty() && v[0] == '+' ? 1 : 0);
      const auto res = std::from_chars(b, v.data() + v.size(), x);
      if (v.empty() || res.ec != std::errc() || res.ptr != v.data() + v.size() || !std::isfinite(x)) {
        std::ostringstream os;
        os << t.file << ':' << line_no << ':' << starts[c] << ": column '" << t.names[c] << "': "
           << (v.empty() ? std::string("empty field") : "'" + v + "'") << " is not a finite number";
        throw ModelError(os.str());
      }
      t.columns[c].push_back(x);
      t.fields[c].push_back(starts[c]);
    }
    t.lines.push_back(line_no);
  }
  if (header) throw ModelError(t.file + ": empty file (expected a header line naming the columns)");
  if (t.lines.empty()) throw ModelError(t.file + ": no data rows after the header");
  return t;
}

Table read_h5(const std::filesystem::path& path) {
  TimeSeriesData d;
  try {
    d = read_hdf5_timeseries(path);
  } catch (const TimeSeriesError& e) {
    throw ModelError(e.what());
  }
  Table t;
  t.file = path.string();
  t.names.push_back("time");
  t.units.push_back("s");
  t.columns.push_back(d.time);
  for (std::size_t c = 0; c < d.channels.size(); ++c) {
    t.names.push_back(d.channels[c].name);
    t.units.push_back(d.channels[c].unit);
    t.columns.push_back(d.columns[c]);
  }
  t.lines.assign(d.time.size(), 0);
  // NaNs: HDF5 has no lines; name the row.
  for (std::size_t c = 0; c < t.columns.size(); ++c)
    for (std::size_t i = 0; i < t.columns[c].size(); ++i)
      if (!std::isfinite(t.columns[c][i])) {
        (void)i;  // checked per used column in value_error below
        break;
      }
  return t;
}

std::string where(const Table& t, std::size_t column, std::size_t row) {
  std::ostringstream os;
  os << t.file;
  if (!t.lines.empty() && t.lines[row] > 0) {
    os << ':' << t.lines[row];
    if (column < t.fields.size() && row < t.fields[column].size()) os << ':' << t.fields[column][row];
  } else {
    os << ": row " << row;
  }
  return os.str();
}

// Values of one column in SI; the unit comes from the study (ref.unit) or the header, and both must agree.
std::vector<double> column_si(const Table& t, const ColumnRef& ref, const Dimension& d, const std::string& role) {
  const std::size_t c = t.require(ref.column, role);
  const std::string& header_unit = t.units[c];
  double factor = 1.0;
  auto factor_of = [&](const std::string& unit, const std::string& from) {
    try {
      return unit_factor(unit, d);
    } catch (const UnitError& e) {
      throw ModelError(t.file + ": column '" + ref.column + "' (" + role + "): unit '" + unit + "' " + from + ": " +
                       e.what());
    }
  };
  if (!header_unit.empty()) factor = factor_of(header_unit, "in the file's header");
  if (!ref.unit.empty()) {
    const double f = factor_of(ref.unit, "from the study file");
    if (!header_unit.empty() && std::abs(f - factor) > 1e-12 * std::abs(f))
      throw ModelError(t.file + ": column '" + ref.column + "': the header says '" + header_unit +
                       "' but the study file '" + ref.unit + "'");
    factor = f;
  }
  std::vector<double> v = t.columns[c];
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      throw ModelError(where(t, c, i) + ": column '" + ref.column + "': value is not a finite number (NaN)");
    v[i] *= factor;
  }
  return v;
}

std::vector<double> raw_column(const Table& t, const std::string& name, const std::string& role) {
  const std::size_t c = t.require(name, role);
  for (std::size_t i = 0; i < t.columns[c].size(); ++i)
    if (!std::isfinite(t.columns[c][i]))
      throw ModelError(where(t, c, i) + ": column '" + name + "': value is not a finite number (NaN)");
  return t.columns[c];
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xi, std::size_t& k) {
  while (k + 2 < x.size() && x[k + 1] < xi) ++k;
  const double a = (xi - x[k]) / (x[k + 1] - x[k]);
  return y[k] + a * (y[k + 1] - y[k]);
}

// Rotor angle and speed from tacho pulses: rising edges through the threshold (time by linear interpolation
// between the two samples around the crossing), pulse k at angle 2 pi k / pulses_per_rev (0 at the first pulse).
// Between pulses the angle is the mean of the two quadratics through the neighbouring pulse triples (one near the
// ends), so a constant angular acceleration, as in a linear run-up, is reproduced exactly; a linear
// interpolation would be off by 2 pi a T^2 / 8 (a the acceleration in rev/s^2, T the pulse interval), e.g.
// 0.16 rad at 50 Hz in a 500 Hz/s ramp, which biases the 1x phase. Beyond the first and last pulses the end
// quadratics are extrapolated. The speed is the derivative of the same curve.
void from_tacho(const Table& t, const MeasurementSpec& spec, const std::vector<double>& time, std::vector<double>& angle,
                std::vector<double>& speed_hz) {
  const std::vector<double> v = raw_column(t, spec.tacho, "tacho pulses");
  double level = spec.tacho_threshold;
  if (std::isnan(level)) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    level = 0.5 * (*lo + *hi);
  }
  std::vector<double> pulses;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i - 1] < level && v[i] >= level)
      pulses.push_back(time[i - 1] + (level - v[i - 1]) / (v[i] - v[i - 1]) * (time[i] - time[i - 1]));
  if (pulses.size() < 3)
    throw ModelError(t.file + ": column '" + spec.tacho + "': " + std::to_string(pulses.size()) +
                     " tacho pulses (rising edges through " + std::to_string(level) + "); at least 3 are needed");
  const double step = kTwoPi / spec.pulses_per_rev;
  const std::size_t np = pulses.size();
  // Quadratic through pulses j, j+1, j+2 (angles step*j ...): value and derivative at time x.
  auto quad = [&](std::size_t j, double x, double& a, double& da) {
    const double t0 = pulses[j], t1 = pulses[j + 1], t2 = pulses[j + 2];
    const double y0 = step * double(j), y1 = y0 + step, y2 = y1 + step;
    const double l0 = (x - t1) * (x - t2) / ((t0 - t1) * (t0 - t2));
    const double l1 = (x - t0) * (x - t2) / ((t1 - t0) * (t1 - t2));
    const double l2 = (x - t0) * (x - t1) / ((t2 - t0) * (t2 - t1));
    const double d0 = ((x - t1) + (x - t2)) / ((t0 - t1) * (t0 - t2));
    const double d1 = ((x - t0) + (x - t2)) / ((t1 - t0) * (t1 - t2));
    const double d2 = ((x - t0) + (x - t1)) / ((t2 - t0) * (t2 - t1));
    a = y0 * l0 + y1 * l1 + y2 * l2;
    da = y0 * d0 + y1 * d1 + y2 * d2;
  };
  angle.resize(time.size());
  speed_hz.resize(time.size());
  std::size_t k = 0;  // interval [pulses[k], pulses[k+1]]
  for (std::size_t i = 0; i < time.size(); ++i) {
    const double x = time[i];
    while (k + 2 < np && x > pulses[k + 1]) ++k;
    double a = 0.0, da = 0.0;
    // Triples that contain the interval k: starting at k-1 and at k (where they exist).
    const bool left = k >= 1 && k + 1 < np, right = k + 2 < np;
    if (left && right && x >= pulses[0] && x <= pulses[np - 1]) {
      double a1, d1, a2, d2;
      quad(k - 1, x, a1, d1);
      quad(k, x, a2, d2);
      a = 0.5 * (a1 + a2);
      da = 0.5 * (d1 + d2);
    } else {
      // Before the second pulse (k = 0, also at a sample exactly on it) the first triple, from the second-to-last
      // pulse on the last one.
      quad(k == 0 ? 0 : np - 3, x, a, da);
    }
    angle[i] = a;
    speed_hz[i] = da / kTwoPi;
  }
}

}  // namespace

const EnumName<Quantity> kQuantities[3] = {
    {Quantity::Displacement, "displacement"}, {Quantity::Acceleration, "acceleration"}, {Quantity::Force, "force"}};

std::string to_string(Quantity q) { return name_of(kQuantities, q); }

Dimension dimension_of(Quantity q) {
  switch (q) {
    case Quantity::Displacement: return dim::length;
    case Quantity::Acceleration: return dim::acceleration;
    case Quantity::Force: return dim::force;
  }
  return dim::length;
}

double unit_factor(const std::string& unit, const Dimension& d) { return parse_quantity("1 " + unit, d); }

MeasuredData read_measurement(const MeasurementSpec& spec) {
  MeasuredData out;
  out.format = spec.format;
  std::string ext = spec.file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool h5 = ext == ".h5" || ext == ".hdf5";
  if (!std::filesystem::exists(spec.file)) throw ModelError(spec.file.string() + ": no such measured file");
  if (h5 && spec.format == MeasurementFormat::Spectra)
    throw ModelError(spec.file.string() + ": spectra are read from CSV files only");
  std::vector<std::string> wanted{spec.time.column, spec.speed.column, spec.angle.column, spec.tacho,
                                  spec.frequency.column};
  for (const SensorSpec& s : spec.sensors) wanted.push_back(s.column.column);
  const Table t = h5 ? read_h5(spec.file) : read_csv(spec.file, wanted);

  if (spec.format == MeasurementFormat::Spectra) {
    const std::vector<double> speed = column_si(t, spec.speed, dim::angular_speed, "rotor speed");
    const std::vector<double> freq = column_si(t, spec.frequency, dim::frequency, "frequency");
    std::vector<std::vector<double>> amp;
    for (const SensorSpec& s : spec.sensors)
      amp.push_back(column_si(t, s.column, dimension_of(s.quantity), "sensor " + s.name));
    SpectraSet& sp = out.spectra;
    sp.amplitude.resize(spec.sensors.size());
    // Rows with the same speed form one spectrum; spectra must come in ascending speed, bins in ascending frequency.
    const std::size_t cs = t.require(spec.speed.column, "rotor speed"), cf = t.require(spec.frequency.column, "");
    for (std::size_t i = 0; i < speed.size(); ++i) {
      const double fd = speed[i] / kTwoPi;
      const bool same = !sp.speed_hz.empty() && std::abs(fd - sp.speed_hz.back()) <= 1e-9 * std::abs(fd);
      if (!same) {
        if (!sp.speed_hz.empty() && fd < sp.speed_hz.back())
          throw ModelError(where(t, cs, i) + ": column '" + spec.speed.column +
                           "': the spectra must come in ascending rotor speed (this row's speed is below the "
                           "previous spectrum's)");
        sp.speed_hz.push_back(fd);
        sp.frequency_hz.emplace_back();
        for (auto& a : sp.amplitude) a.emplace_back();
      } else if (freq[i] <= sp.frequency_hz.back().back()) {
        throw ModelError(where(t, cf, i) + ": column '" + spec.frequency.column +
                         "': frequency does not increase within the spectrum at this speed");
      }
      sp.frequency_hz.back().push_back(freq[i]);
      for (std::size_t s = 0; s < amp.size(); ++s) sp.amplitude[s].back().push_back(amp[s][i]);
    }
    return out;
  }

  // Time series.
  std::vector<double> time = column_si(t, spec.time, dim::time, "time");
  const std::size_t ct = t.require(spec.time.column, "time");
  if (time.size() < 16) throw ModelError(t.file + ": only " + std::to_string(time.size()) + " rows; a run-up needs more");
  for (std::size_t i = 1; i < time.size(); ++i)
    if (!(time[i] > time[i - 1])) {
      std::ostringstream os;
      os << where(t, ct, i) << ": column '" << spec.time.column << "': time does not increase (" << time[i]
         << " s after " << time[i - 1] << " s" << (t.lines[i - 1] ? " on line " + std::to_string(t.lines[i - 1]) : "")
         << ")";
      throw ModelError(os.str());
    }
  std::vector<double> speed_hz, angle;
  if (!spec.tacho.empty()) {
    from_tacho(t, spec, time, angle, speed_hz);
  } else {
    if (spec.speed.column.empty() && spec.angle.column.empty())
      throw ModelError(t.file + ": the study names neither a speed, an angle nor a tacho column");
    if (!spec.angle.column.empty()) angle = column_si(t, spec.angle, dim::angle, "rotor angle");
    if (!spec.speed.column.empty()) {
      speed_hz = column_si(t, spec.speed, dim::angular_speed, "rotor speed");
      for (double& v : speed_hz) v /= kTwoPi;
    } else {  // speed from the angle by differences
      speed_hz.resize(time.size());
      for (std::size_t i = 0; i < time.size(); ++i) {
        const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, time.size() - 1);
        speed_hz[i] = (angle[b] - angle[a]) / (time[b] - time[a]) / kTwoPi;
      }
    }
    if (angle.empty()) {  // integrate the speed (no phase reference)
      angle.assign(time.size(), 0.0);
      for (std::size_t i = 1; i < time.size(); ++i)
        angle[i] = angle[i - 1] + M_PI * (speed_hz[i] + speed_hz[i - 1]) * (time[i] - time[i - 1]);
    }
  }
  std::vector<std::vector<double>> channels;
  for (const SensorSpec& s : spec.sensors)
    channels.push_back(column_si(t, s.column, dimension_of(s.quantity), "sensor " + s.name));

  // Uniform sampling: resample linearly if the steps are uneven.
  const std::size_t n = time.size();
  const double dt = (time.back() - time.front()) / static_cast<double>(n - 1);
  bool uneven = false;
  for (std::size_t i = 1; i < n && !uneven; ++i) uneven = std::abs(time[i] - time[i - 1] - dt) > kUnevenSampling * dt;
  Record& r = out.record;
  r.sample_rate = 1.0 / dt;
  if (!uneven) {
    r.time = std::move(time);
    r.speed_hz = std::move(speed_hz);
    r.angle = std::move(angle);
    r.channels = std::move(channels);
  } else {
    out.resampled = true;
    r.time.resize(n);
    for (std::size_t i = 0; i < n; ++i) r.time[i] = time.front() + dt * static_cast<double>(i);
    r.time.back() = time.back();
    auto resample = [&](const std::vector<double>& y) {
      std::vector<double> o(n);
      std::size_t k = 0;
      for (std::size_t i = 0; i < n; ++i) o[i] = interpolate(time, y, r.time[i], k);
      return o;
    };
    r.speed_hz = resample(speed_hz);
    r.angle = resample(angle);
    for (const auto& c : channels) r.channels.push_back(resample(c));
  }
  return out;
}

}  // namespace turbodyn::identification

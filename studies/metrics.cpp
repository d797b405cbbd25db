#include "studies/metrics.h"

#include <cmath>
#include <limits>

#include "model/io/run_summary.h"
#include "post/signal.h"
#include "studies/channels.h"
#include "studies/stability_metrics.h"
#include "model/spec/constants.h"

namespace turbodyn::studies {
namespace {

constexpr double kHzToRpm = 60.0;

bool in_window(const MetricSpec& m, double speed_hz) {
  const double w = 2.0 * M_PI * speed_hz;
  return w >= m.speed_min && (m.speed_max <= 0.0 || w <= m.speed_max);
}

// Sub-synchronous content per STFT segment: band [max(5 Hz, order_min f_d), order_max f_d] (by default 0.05 and
// 0.9); synchronous: +-2 bins at f_d.
struct SubsyncTrack {
  std::vector<double> speed_hz, sync, sub, sub_frequency;
};

SubsyncTrack subsync_track(const std::vector<double>& signal, const std::vector<double>& speed, double fs,
                           double order_min, double order_max) {
  SubsyncTrack t;
  signal::StftOptions so;
  so.segment_length = std::min<std::size_t>(2048, signal.size());
  if (so.segment_length < 8) return t;
  const signal::Spectrogram sg = signal::stft(signal, fs, so);
  const std::vector<double> fd = signal::values_at_segment_centres(sg, speed, fs);
  const double df = sg.frequencies.size() > 1 ? sg.frequencies[1] - sg.frequencies[0] : 1.0;
  for (std::size_t s = 0; s < sg.n_segments(); ++s) {
    double sync = 0.0, sub = 0.0, fsub = kNaN;
    for (std::size_t k = 0; k < sg.n_bins(); ++k) {
      const double f = sg.frequencies[k], a = sg.at(s, k);
      if (std::abs(f - fd[s]) <= 2.0 * df) sync = std::max(sync, a);
      if (f >= std::max(5.0, order_min * fd[s]) && f <= order_max * fd[s] && a > sub) {
        sub = a;
        fsub = f;
      }
    }
    t.speed_hz.push_back(fd[s]);
    t.sync.push_back(sync);
    t.sub.push_back(sub);
    t.sub_frequency.push_back(fsub);
  }
  return t;
}

}  // namespace

std::string metric_unit(const MetricSpec& m, const std::vector<ProbeChannel>& channels) {
  if (m.kind == "peak_1x_speed" || m.kind == "subsync_onset_speed" || m.kind == "subsync_jump_speed" ||
      m.kind == "stability_growth_speed" || m.kind == "stability_onset_speed")
    return "rpm";
  if (m.kind == "subsync_frequency" || m.kind == "stability_frequency") return "Hz";
  if (m.kind == "subsync_ratio" || m.kind == "stability_damping") return "1";
  if (m.kind == "stability_growth") return "1/s";
  if (m.kind == "summary") return "";
  if (m.kind == "max_radius") {
    const auto [a, b] = pair_channels(channels, m.probe);
    (void)b;
    return a >= 0 ? channels[a].unit : "";
  }
  const int c = find_channel(channels, m.probe);
  return c >= 0 ? channels[c].unit : "";
}

const nlohmann::json* summary_node(const nlohmann::json& summary, const std::string& path) {
  if (!path.empty() && path[0] == '/') {
    try {
      const nlohmann::json::json_pointer ptr(path);
      return summary.contains(ptr) ? &summary.at(ptr) : nullptr;
    } catch (const nlohmann::json::exception&) {
      return nullptr;  // not a valid JSON pointer ("/a~2"): no such value
    }
  }
  const nlohmann::json* node = &summary;
  std::size_t pos = 0;
  while (pos <= path.size()) {
    const std::size_t dot = path.find('.', pos);
    const std::string key = path.substr(pos, dot == std::string::npos ? std::string::npos : dot - pos);
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    pos = dot + 1;
  }
  return node;
}

namespace {

// The dotted paths of the numbers and booleans in `j` (keys with dots in JSON-pointer form), for suggestions.
void summary_paths(const nlohmann::json& j, const std::string& dotted, const std::string& pointer,
                   std::vector<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items())
      summary_paths(v, dotted.empty() ? k : dotted + "." + k, pointer + "/" + k, out);
    return;
  }
  if (j.is_number() || j.is_boolean()) out.push_back(pointer.find('.') != std::string::npos ? pointer : dotted);
}

}  // namespace

nlohmann::json summary_template(const MachineSpec& spec, const RunupModel& model) {
  RunupResult empty;
  empty.channels = model.channels();
  empty.columns.assign(empty.channels.size(), {});
  return run_summary(spec, model, runup_options(spec), empty, {});
}

void check_metrics(const StudySpec& study, const std::vector<ProbeChannel>& channels, const nlohmann::json& summary) {
  for (std::size_t i = 0; i < study.metrics.size(); ++i) {
    const MetricSpec& m = study.metrics[i];
    const std::string where = study.source.string() + ": metrics[" + std::to_string(i) + "]";
    if (is_stability_metric(m.kind)) continue;  // no probe (checked by check_stability_supported)
    if (m.kind == "summary") {
      const nlohmann::json* node = summary_node(summary, m.probe);
      if (node && (node->is_number() || node->is_boolean())) continue;
      std::vector<std::string> paths;
      summary_paths(summary, "", "", paths);
      throw ModelError(where + ".probe: " +
                       (node ? "'" + m.probe + "' in the run summary is not a number"
                             : "the run summary has no value '" + m.probe + "'") +
                       did_you_mean(m.probe, paths, " (e.g. stats.steps, energy.balance_error_j, t_reached_s)"));
    }
    const bool ok = m.kind == "max_radius" ? pair_channels(channels, m.probe).first >= 0
                                            : find_channel(channels, m.probe) >= 0;
    if (!ok) throw ModelError(where + ".probe: " + unknown_probe(m.probe, channel_names(channels)));
  }
}

double evaluate_metric(const MetricSpec& m, const RunupResult& r, const nlohmann::json& summary, double fs) {
  if (m.kind == "summary") {
    const nlohmann::json* node = summary_node(summary, m.probe);
    if (!node) return kNaN;
    if (node->is_boolean()) return node->get<bool>() ? 1.0 : 0.0;
    return node->is_number() ? node->get<double>() : kNaN;
  }
  const int sc = kind_channel(r.channels, ProbeChannel::Kind::Speed);
  const int ac = kind_channel(r.channels, ProbeChannel::Kind::Angle);
  const std::vector<double>& speed = r.columns[sc];
  if (m.kind == "max_radius") {
    const auto [a, b] = pair_channels(r.channels, m.probe);
    double best = kNaN;
    for (std::size_t i = 0; i < r.time.size(); ++i)
      if (in_window(m, speed[i])) {
        const double v = std::hypot(r.columns[a][i], r.columns[b][i]);
        best = std::isnan(best) ? v : std::max(best, v);
      }
    return best;
  }
  const int c = find_channel(r.channels, m.probe);
  const std::vector<double>& x = r.columns[c];
  if (m.kind == "max" || m.kind == "min" || m.kind == "rms" || m.kind == "mean") {
    double acc = 0.0, best = 0.0, least = std::numeric_limits<double>::infinity();
    std::size_t n = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!in_window(m, speed[i])) continue;
      best = std::max(best, std::abs(x[i]));
      least = std::min(least, x[i]);
      acc += m.kind == "rms" ? x[i] * x[i] : x[i];
      ++n;
    }
    if (n == 0) return kNaN;
    if (m.kind == "max") return best;
    if (m.kind == "min") return least;  // signed: e.g. a film's thinnest point
    return m.kind == "rms" ? std::sqrt(acc / n) : acc / n;
  }
  if (m.kind == "peak_1x" || m.kind == "peak_1x_speed") {
    signal::OrderTrackOptions oo;
    oo.points = 300;
    signal::OrderTrack t;
    try {
      t = signal::track_order(x, r.columns[ac], speed, fs, oo);
    } catch (const std::invalid_argument&) {
      return kNaN;
    }
    double best = kNaN, at = kNaN;
    for (std::size_t i = 0; i < t.amplitude.size(); ++i)
      if (in_window(m, t.speeds[i]) && (std::isnan(best) || t.amplitude[i] > best)) {
        best = t.amplitude[i];
        at = t.speeds[i] * kHzToRpm;
      }
    return m.kind == "peak_1x" ? best : at;
  }
  // Sub-synchronous metrics.
  const SubsyncTrack t = subsync_track(x, speed, fs, m.order_min, m.order_max);
  double best = kNaN, ratio = kNaN, freq = kNaN, onset = kNaN, jump = kNaN, largest_jump = 0.0;
  std::size_t previous = t.speed_hz.size();  // last segment in the window whose line exceeds the threshold
  for (std::size_t s = 0; s < t.speed_hz.size(); ++s) {
    if (!in_window(m, t.speed_hz[s])) continue;
    if (t.sub[s] > m.threshold) {
      // Jump: the largest change of the dominant line's frequency between two consecutive segments in which a
      // sub-synchronous line above the threshold is present (e.g. a floating ring's inner-film whirl jumping to
      // the next rotor mode). Reported at the later segment's speed.
      if (previous < t.speed_hz.size()) {
        const double change = std::abs(t.sub_frequency[s] - t.sub_frequency[previous]);
        if (change > largest_jump) largest_jump = change, jump = t.speed_hz[s] * kHzToRpm;
      }
      previous = s;
    }
    if (std::isnan(best) || t.sub[s] > best) {
      best = t.sub[s];
      freq = t.sub_frequency[s];
    }
    if (t.sync[s] > 0.0) ratio = std::isnan(ratio) ? t.sub[s] / t.sync[s] : std::max(ratio, t.sub[s] / t.sync[s]);
    if (std::isnan(onset) && t.sub[s] > m.threshold) onset = t.speed_hz[s] * kHzToRpm;
  }
  if (m.kind == "subsync_max") return best;
  if (m.kind == "subsync_ratio") return ratio;
  if (m.kind == "subsync_frequency") return freq;
  if (m.kind == "subsync_jump_speed") return jump;
  return onset;  // subsync_onset_speed
}

}  // namespace turbodyn::studies

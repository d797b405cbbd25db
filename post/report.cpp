#include "post/report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "model/elements/force_element.h"
#include "model/engine/stability.h"
#include "post/html_page.h"
#include "post/run_pictures.h"

namespace turbodyn::post {
namespace {

constexpr double kHzToRpm = 60.0;
// A study's table on the page stops here; results.csv holds every run.
constexpr std::size_t kMaxStudyRows = 400;

using Row = std::vector<std::string>;

std::string text(const nlohmann::json& j, const std::string& key, const std::string& fallback = "") {
  return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : fallback;
}

std::string join(const nlohmann::json& list, const std::string& sep) {
  std::string s;
  if (!list.is_array()) return s;
  for (const auto& v : list) s += (s.empty() ? "" : sep) + (v.is_string() ? v.get<std::string>() : v.dump());
  return s;
}

// Model, overrides and command: the first section of every page.
void origin(HtmlPage& page, const std::string& model_source, const nlohmann::json& overrides,
            const std::string& command) {
  page.heading("Model and command");
  std::vector<std::pair<std::string, std::string>> rows{
      {"model file", "<code>" + html_escape(model_source) + "</code>"}};
  if (overrides.is_array() && !overrides.empty()) {
    std::string o;
    for (const auto& v : overrides) o += "<code>--set " + html_escape(v.get<std::string>()) + "</code> ";
    rows.emplace_back("overrides", o);
  }
  page.key_values("origin", rows);
  if (!command.empty()) page.command(command);
}

// A page on one model's result, titled "WHAT: <model name>" and opened by the model, its overrides and `command`.
HtmlPage model_page(const std::string& what, const std::string& kind, const nlohmann::json& j,
                    const std::string& command) {
  const nlohmann::json& model = j.at("model");
  HtmlPage page(what + ": " + text(model, "name"), kind);
  origin(page, text(model, "source"), j.value("overrides", nlohmann::json::array()), command);
  return page;
}

void pictures_and_files(HtmlPage& page, const ReportInputs& in) {
  page.heading("Pictures");
  page.pictures(in.pictures);
  page.heading("Files");
  page.files(in.files);
}

// The index of the largest finite value of an array of numbers (or -1).
long argmax(const nlohmann::json& a) {
  long best = -1;
  double v = -INFINITY;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].is_number() && a[i].get<double>() > v) {
      v = a[i].get<double>();
      best = static_cast<long>(i);
    }
  return best;
}

// A section on the speeds at which each stability metric of a study or an optimisation judged its designs (the
// result file's "metrics": speeds_rpm, onset_resolution_rpm), if it has any.
void stability_grids(HtmlPage& page, const std::string& F, const nlohmann::json& j) {
  const auto list = j.find("metrics");
  if (list == j.end() || !list->is_array()) return;
  const nlohmann::json& metrics = *list;
  bool stability_heading = false;
  for (std::size_t m = 0; m < metrics.size(); ++m) {
    const auto s = metrics[m].find("speeds_rpm");
    if (s == metrics[m].end() || !s->is_array() || s->empty()) continue;
    if (!stability_heading) page.heading("Stability metrics"), stability_heading = true;
    const std::string at = json_pointer(json_pointer("/metrics", m), "speeds_rpm");
    const std::size_t n = s->size();
    std::string html = html_escape(text(metrics[m], "name")) + ": the linearised model analysed at " +
                       std::to_string(n) + (n == 1 ? " speed, " : " speeds from ") +
                       HtmlPage::number(F, j, json_pointer(at, 0), 1.0, "rpm", 5);
    if (n > 1) {
      html += " to " + HtmlPage::number(F, j, json_pointer(at, n - 1), 1.0, "rpm", 5);
      if ((*s)[0].is_number() && (*s)[1].is_number())
        html += ", " + display_number((*s)[1].get<double>() - (*s)[0].get<double>(), 4) + " rpm apart";
      if (metrics[m].contains("onset_resolution_rpm"))
        html += " (an onset found within " +
                HtmlPage::number(F, j, json_pointer(json_pointer("/metrics", m), "onset_resolution_rpm"), 1.0, "rpm",
                                 3) +
                " below it)";
      html += ". A design is judged at these speeds only: an unstable window narrower than their spacing can lie "
              "between two of them unseen, so a design called stable here needs a finer grid before it is taken as "
              "stable.";
    } else {
      html += ".";
    }
    page.paragraph_html(html);
  }
}

}  // namespace

std::pair<std::vector<std::string>, std::vector<std::string>> split_pictures(const std::vector<std::string>& files) {
  std::pair<std::vector<std::string>, std::vector<std::string>> out;
  for (const std::string& f : files)
    (f.size() > 4 && f.compare(f.size() - 4, 4, ".png") == 0 ? out.first : out.second).push_back(f);
  return out;
}

void write_run_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "summary.json";
  const nlohmann::json& model = j.at("model");
  HtmlPage page("Run-up: " + text(model, "name"), "run");
  const bool complete = j.value("complete", false);
  if (!complete)
    page.alert("INCOMPLETE: the run-up " + text(j, "message") +
               "; everything up to that point is written and shown here.");
  origin(page, text(model, "source"), j.value("overrides", nlohmann::json::array()), text(j, "command"));
  if (!in.command.empty()) {
    page.paragraph("Pictures redrawn by:");
    page.command(in.command);
    if (j.contains("plot_overrides") && !j["plot_overrides"].empty())
      page.paragraph("with the output settings " + join(j["plot_overrides"], ", "));
  }

  page.heading("Run");
  page.key_values(
      "run", {{"status", complete ? "<span class=\"ok\">complete</span>" : "<span class=\"bad\">incomplete</span>"},
              {"time reached", HtmlPage::number(F, j, "/t_reached_s", 1.0, "s") + " of " +
                                   HtmlPage::number(F, j, "/options/t_end_s", 1.0, "s")},
              {"integrator", html_escape(text(j.at("options"), "integrator"))},
              {"steps", HtmlPage::number(F, j, "/stats/steps", 1.0, "", 7)},
              {"right-hand sides", HtmlPage::number(F, j, "/stats/rhs_calls", 1.0, "", 8)},
              {"wall time", HtmlPage::number(F, j, "/stats/wall_time_s", 1.0, "s", 3)},
              {"energy balance error", HtmlPage::number(F, j, "/energy/balance_error_j", 1.0, "J", 3)}});

  page.heading("Maxima of the probes");
  std::vector<Row> rows;
  for (const auto& [name, p] : j.at("probes").items()) {
    const Display d = display_of(text(p, "unit"));
    const std::string at = json_pointer("/probes", name);
    rows.push_back({"<code>" + html_escape(name) + "</code>", html_escape(text(p, "description")),
                    HtmlPage::number(F, j, at + "/max_abs", d.factor, d.unit),
                    HtmlPage::number(F, j, at + "/speed_at_max_rpm", 1.0, "rpm", 5),
                    HtmlPage::number(F, j, at + "/time_at_max_s", 1.0, "s"),
                    // A probe's limit (a ball bearing's contact pressure: ISO 76's; a film's permissible minimum
                    // thickness), marked where the run passes it; a film's thinnest point with its smallest value.
                    (name.ends_with(kMinFilmProbeSuffix)
                         ? (p.contains("limit") ? "at least " + HtmlPage::number(F, j, at + "/limit", d.factor, d.unit)
                                                : std::string("none")) +
                               "; smallest " + HtmlPage::number(F, j, at + "/min", d.factor, d.unit) + " at " +
                               HtmlPage::number(F, j, at + "/speed_at_min_rpm", 1.0, "rpm", 5)
                         : HtmlPage::number(F, j, at + "/limit", d.factor, d.unit)) +
                        (p.contains("over_limit") && !p["over_limit"].is_null()
                             ? " <span class=\"bad\">passed from " +
                                   HtmlPage::number(F, j, at + "/over_limit/speed_rpm", 1.0, "rpm", 5) + "</span>"
                             : "")});
  }
  page.table("probes", {"probe", "what", "largest |value|", "at rotor speed", "at time", "limit"}, rows);

  if (j.contains("spectrogram_maxima") && !j["spectrogram_maxima"].empty()) {
    page.heading("Largest spectral lines");
    page.paragraph("The largest amplitude of each spectrogram (the way the paper quotes its maxima).");
    rows.clear();
    std::vector<Row> subsynchronous;
    for (const auto& [name, m] : j["spectrogram_maxima"].items()) {
      const Display d = display_of(text(m, "unit"));
      const std::string at = json_pointer("/spectrogram_maxima", name);
      const std::string probe = "<code>" + html_escape(name) + "</code>";
      rows.push_back({probe, HtmlPage::number(F, j, at + "/amplitude", d.factor, d.unit),
                      HtmlPage::number(F, j, at + "/frequency_hz", 1.0, "Hz"),
                      m.contains("speed_hz") ? HtmlPage::number(F, j, at + "/speed_hz", kHzToRpm, "rpm", 5)
                                             : HtmlPage::number(F, j, at + "/time_s", 1.0, "s")});
      if (m.contains("subsynchronous"))
        subsynchronous.push_back({probe, HtmlPage::number(F, j, at + "/subsynchronous/amplitude", d.factor, d.unit),
                                  HtmlPage::number(F, j, at + "/subsynchronous/frequency_hz", 1.0, "Hz"),
                                  HtmlPage::number(F, j, at + "/subsynchronous/order", 1.0, "x", 2),
                                  HtmlPage::number(F, j, at + "/subsynchronous/speed_hz", kHzToRpm, "rpm", 5),
                                  HtmlPage::number(F, j, at + "/subsynchronous_at_end/amplitude", d.factor, d.unit),
                                  HtmlPage::number(F, j, at + "/subsynchronous_at_end/frequency_hz", 1.0, "Hz"),
                                  HtmlPage::number(F, j, at + "/subsynchronous_at_end/order", 1.0, "x", 2)});
    }
    page.table("spectral", {"probe", "amplitude", "frequency", "at rotor speed (or time)"}, rows);
    if (!subsynchronous.empty()) {
      page.heading("Largest sub-synchronous lines");
      page.paragraph("Lines below the rotor speed (oil whirl, a cage's or ball set's whirl, a rub's 0.5x), clear of "
                     "the 1x line's sweep within a segment and of its window's leakage (below 1e-3 of it), over the "
                     "run and in its last segment.");
      page.table("subsynchronous",
                 {"probe", "amplitude", "frequency", "order", "at rotor speed", "at the end", "frequency", "order"},
                 subsynchronous);
    }
  }
  std::vector<std::string> warnings = in.warnings;
  if (j.contains("warnings"))
    for (const auto& w : j["warnings"]) warnings.push_back(w.get<std::string>());
  if (!warnings.empty()) page.heading("Warnings");
  page.warnings(warnings);
  ReportInputs with_pictures = in;
  if (with_pictures.pictures.empty() && j.contains("pictures"))
    for (const auto& p : j["pictures"]) with_pictures.pictures.push_back(p.get<std::string>());
  pictures_and_files(page, with_pictures);
  page.write(dir);
}

void write_modal_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "modal.json";
  HtmlPage page = model_page("Modal analysis", "modal", j, in.command);
  page.heading("Rotor");
  page.key_values("rotor", {{"frame", html_escape(text(j, "frame"))},
                            {"nodes", HtmlPage::number(F, j, "/model/n_nodes", 1.0, "", 6)},
                            {"degrees of freedom", HtmlPage::number(F, j, "/model/n_dof", 1.0, "", 6)},
                            {"rotor mass", HtmlPage::number(F, j, "/model/total_mass_kg", 1.0, "kg")}});
  page.heading("Critical speeds");
  page.paragraph("Crossings of the natural frequencies with the order lines. The branch slope s = df_n/df_d at the "
                 "crossing and the damping ratio ζ give the amplification factor a steady response to that order "
                 "would show, |n − s|/(2nζ) to first order (API RP 684's half-power AF; below 2.5 API 617 calls a "
                 "resonance critically damped, and a first-order reading no longer holds; – for an unstable mode).");
  std::vector<Row> rows;
  const nlohmann::json& crit = j.at("critical_speeds");
  for (std::size_t i = 0; i < crit.size(); ++i) {
    const std::string at = json_pointer("/critical_speeds", i);
    rows.push_back({HtmlPage::number(F, j, at + "/order", 1.0, "x", 3), html_escape(text(crit[i], "whirl")),
                    HtmlPage::number(F, j, at + "/speed_rpm", 1.0, "rpm", 5),
                    HtmlPage::number(F, j, at + "/frequency_hz", 1.0, "Hz"),
                    HtmlPage::number(F, j, at + "/damping_ratio", 1.0, "", 3),
                    HtmlPage::number(F, j, at + "/branch_slope", 1.0, "", 3),
                    crit[i].value("critically_damped", false)
                        ? std::string("< 2.5 (critically damped)")
                        : HtmlPage::number(F, j, at + "/amplification_factor", 1.0, "", 3)});
  }
  if (rows.empty()) page.paragraph("No order line crosses a natural frequency in the speed range.");
  else page.table("critical_speeds", {"order", "whirl", "rotor speed", "natural frequency", "damping ratio",
                                      "branch slope s", "AF (first order)"},
                  rows);
  if (!j.at("campbell").empty()) {
    const nlohmann::json& first = j["campbell"][0];
    page.heading("Natural frequencies at " + display_number(first.at("speed_rpm").get<double>(), 5) + " rpm");
    rows.clear();
    for (std::size_t i = 0; i < first.at("modes").size(); ++i) {
      const std::string at = json_pointer("/campbell/0/modes", i);
      rows.push_back({std::to_string(i + 1), HtmlPage::number(F, j, at + "/frequency_hz", 1.0, "Hz"),
                      HtmlPage::number(F, j, at + "/damping_ratio", 1.0, "", 3),
                      html_escape(text(first["modes"][i], "whirl"))});
    }
    page.table("modes", {"mode", "damped natural frequency", "damping ratio", "whirl"}, rows);
  }
  if (j.contains("backbones")) {
    page.heading("Forward 1x critical speeds at a whirl amplitude");
    page.paragraph("The rotor's synchronous whirl on the ball bearings' nonlinear quasi-static reaction (turbodyn "
                   "modal --amplitudes): where a passage of each size peaks.");
    const nlohmann::json& branches = j["backbones"].at("branches");
    for (std::size_t b = 0; b < branches.size(); ++b) {
      const std::string at = json_pointer("/backbones/branches", b);
      const nlohmann::json& br = branches[b];
      rows.clear();
      for (std::size_t i = 0; i < br.at("points").size(); ++i) {
        const std::string pt = json_pointer(at + "/points", i);
        rows.push_back({HtmlPage::number(F, j, pt + "/amplitude_m", 1e6, "µm", 4),
                        HtmlPage::number(F, j, pt + "/speed_rpm", 1.0, "rpm", 5),
                        HtmlPage::number(F, j, pt + "/frequency_hz", 1.0, "Hz")});
      }
      page.paragraph_html("Branch " + std::to_string(br.at("branch").get<int>() + 1) + ", amplitude at " +
                     html_escape(text(br, "amplitude_at")) + "; linearised " +
                     HtmlPage::number(F, j, at + "/linear_speed_rpm", 1.0, "rpm", 5) + "." +
                     (br.value("complete", true) ? std::string()
                                                 : " INCOMPLETE: " + html_escape(text(br, "stopped"))));
      if (!rows.empty())
        page.table("backbone_" + std::to_string(b), {"whirl amplitude", "critical speed", "frequency"}, rows);
    }
  }
  if (!in.warnings.empty()) page.heading("Warnings");
  page.warnings(in.warnings);
  pictures_and_files(page, in);
  page.write(dir);
}

void write_stability_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "stability.json";
  HtmlPage page = model_page("Linearised stability", "stability", j, in.command);
  if (!j.value("complete", true))
    page.alert("INCOMPLETE: no steady state, the analysis ends there and the speeds before it are shown: " +
               j.value("stopped", std::string("?")));
  if (const auto o = j.find("onset"); o != j.end() && o->is_object()) {
    std::ostringstream os;
    os.precision(6);
    os << "Onset of instability (a mode with at least " << j.value("min_rotor_share", 0.0)
       << " of its motion in the rotor grows): ";
    if (o->value("at_first_speed", false))
      os << "at or below the first speed, " << o->at("speed_rpm").get<double>() << " rpm.";
    else
      os << o->at("speed_rpm").get<double>() << " rpm, within " << o->at("resolution_rpm").get<double>()
         << " rpm below (the interval from the speed before halved " << o->at("halvings").get<int>() << " times)"
         << (o->contains("halving_stopped") ? "; halving stopped: " + o->at("halving_stopped").get<std::string>()
                                            : std::string())
         << ".";
    if (const auto r = o->find("halving_restarted_rpm"); r != o->end())
      for (const nlohmann::json& rpm : *r)
        os << " The halving at " << rpm.get<double>() << " rpm " << kHalvingRestartedText;
    page.paragraph(os.str());
  } else if (o != j.end()) {
    page.paragraph("No mode with rotor motion grows at the speeds analysed.");
  }
  page.heading("Assumptions");
  for (const nlohmann::json& a : j.at("assumptions")) page.paragraph(a.get<std::string>());
  // Per speed the fastest-growing (least damped) mode among those that move the rotor (modes are stored by
  // decreasing growth rate), how many of those grow, and how many growing modes stay in the elements' own states
  // (e.g. a ball set's density wave on a nearly still rotor): both mean the steady state does not persist.
  const double min_share = j.value("min_rotor_share", 0.0);
  page.heading("Fastest-growing (least damped) mode with rotor motion at each speed");
  std::vector<Row> rows;
  int speeds_rotor = 0, speeds_elements = 0;
  const nlohmann::json& res = j.at("results");
  for (std::size_t i = 0; i < res.size(); ++i) {
    const nlohmann::json& modes = res[i].at("modes");
    const std::string at = json_pointer("/results", i);
    int growing = 0, growing_elements = 0;
    std::size_t first = modes.size();
    for (std::size_t k = 0; k < modes.size(); ++k) {
      const bool rotor = modes[k].at("rotor_share").get<double>() >= min_share;
      if (rotor && first == modes.size()) first = k;
      const bool grows = modes[k].value("grows", false);
      growing += grows && rotor;
      growing_elements += grows && !rotor;
    }
    speeds_rotor += growing > 0;
    speeds_elements += growing_elements > 0;
    Row row = {HtmlPage::number(F, j, at + "/speed_rpm", 1.0, "rpm", 5),
               HtmlPage::number(F, j, at + "/cage_speed_rad_s", 1.0, "rad/s")};
    if (first == modes.size()) {
      row.insert(row.end(), {"–", "–", "–", "–", "–", "–"});
    } else {
      const std::string m0 = json_pointer(at + "/modes", first);
      row.insert(row.end(), {HtmlPage::number(F, j, m0 + "/frequency_hz", 1.0, "Hz"),
                             HtmlPage::number(F, j, m0 + "/growth_rate_per_s", 1.0, "1/s"),
                             HtmlPage::number(F, j, m0 + "/damping_ratio", 1.0, "", 3),
                             HtmlPage::number(F, j, m0 + "/rotor_share", 1.0, "", 3),
                             HtmlPage::number(F, j, m0 + "/ball_set_share", 1.0, "", 3),
                             modes[first].value("ball_set_lobes", -1) >= 0
                                 ? std::to_string(modes[first].value("ball_set_lobes", -1))
                                 : std::string("–")});
    }
    row.insert(row.end(), {std::to_string(growing), std::to_string(growing_elements)});
    rows.push_back(row);
  }
  const std::string share = display_number(100.0 * min_share, 3) + " %";
  if (speeds_rotor > 0)
    page.alert("UNSTABLE: at " + std::to_string(speeds_rotor) + " of the speeds analysed a mode with at least " +
               share + " of its motion in the rotor grows (column \"growing, with rotor\"); the steady turning "
               "state does not persist there.");
  if (speeds_elements > 0)
    page.alert("At " + std::to_string(speeds_elements) + " of the speeds analysed a mode of the elements' own "
               "states grows with less than " + share + " of its motion in the rotor (column \"growing, "
               "elements only\"): the elements' steady state (e.g. a ball set's spacing) does not persist there, "
               "though the rotor hardly takes part.");
  page.table("least_damped", {"rotor speed", "cage speed", "frequency", "growth rate", "damping ratio",
                              "rotor share", "ball-set share", "ball-set lobes", "growing, with rotor",
                              "growing, elements only"}, rows);
  page.paragraph("Modes with at least " + share + " of their motion in the rotor's degrees of freedom (states "
                 "scaled by their typical sizes; --min-rotor-share) count as rotor modes, as in the pictures and "
                 "the terminal listing. Frequency in the housing frame, positive for forward whirl. The ball-set "
                 "share is the part of the mode in the balls' orbital angles and rates, the lobes the "
                 "circumferential order of that motion (1: a one-lobed density wave, the balls closing up on one "
                 "side). Every mode is in stability.json and stability.csv.");
  pictures_and_files(page, in);
  page.write(dir);
}

void write_response_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "response.json";
  HtmlPage page = model_page("Unbalance response", "response", j, in.command);
  page.heading("Peaks");
  page.paragraph("The largest steady-state 1x response over the speeds computed, and the speed where it occurs.");
  std::vector<Row> rows;
  const nlohmann::json& cols = j.at("columns");
  for (const auto& [name, values] : cols.items()) {
    std::string what, unit;
    double scale = 1.0;
    auto ends = [&](const std::string& s) {
      return name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    if (ends(".major_semi_axis_m")) what = "orbit major semi-axis", unit = "µm", scale = 1e6;
    else if (ends(".fx_amplitude_n")) what = "force amplitude x", unit = "N";
    else if (ends(".fy_amplitude_n")) what = "force amplitude y", unit = "N";
    else continue;
    const long k = argmax(values);
    if (k < 0) continue;
    rows.push_back({"<code>" + html_escape(name) + "</code>", html_escape(what),
                    HtmlPage::number(F, j, json_pointer(json_pointer("/columns", name), k), scale, unit),
                    HtmlPage::number(F, j, json_pointer("/columns/speed_hz", k), kHzToRpm, "rpm", 5)});
  }
  page.table("peaks", {"column", "what", "peak", "at rotor speed"}, rows);
  if (j.contains("resonances")) {
    page.heading("Resonances");
    page.paragraph("Each peak of a wheel's orbit against speed with its half-power points, where the response has "
                   "fallen to 1/√2 of the peak, and the amplification factor AF = peak speed / (upper − lower "
                   "half-power speed) of API RP 684 (about 1/(2ζ) for a lightly damped mode; API 617 calls AF < 2.5 "
                   "critically damped). Found on the response itself, not on the sampled speeds alone; – where the "
                   "response does not fall to the half-power level on that side within the speeds.");
    std::vector<Row> res;
    for (std::size_t k = 0; k < j.at("resonances").size(); ++k) {
      const std::string at = json_pointer("/resonances", k);
      res.push_back({"<code>" + html_escape(text(j.at("resonances")[k], "column")) + "</code>",
                     HtmlPage::number(F, j, at + "/speed_rpm", 1.0, "rpm", 5),
                     HtmlPage::number(F, j, at + "/speed_hz", 1.0, "Hz", 5),
                     HtmlPage::number(F, j, at + "/peak", 1e6, "µm"),
                     HtmlPage::number(F, j, at + "/lower_speed_hz", 1.0, "Hz", 5),
                     HtmlPage::number(F, j, at + "/upper_speed_hz", 1.0, "Hz", 5),
                     HtmlPage::number(F, j, at + "/amplification_factor", 1.0, "", 3)});
    }
    page.table("resonances", {"column", "rotor speed", "frequency", "peak", "lower half-power", "upper half-power",
                              "AF"},
               res);
  }
  if (j.contains("nonlinear")) {
    const nlohmann::json& nl = j.at("nonlinear");
    page.heading("Nonlinear steady state");
    page.paragraph("The forward synchronous whirl under the wheels' unbalance on the ball bearings' quasi-static "
                   "reaction, traced by arclength continuation through its folds. Where the speed turns back a slow "
                   "run-up on that branch jumps to another one; where it turns forward again a slow run-down on it does.");
    if (!nl.value("covers_range", false))
      page.alert("Part of the speed range has no steady state within the model (the pieces end early, below).");
    std::vector<Row> pieces, folds;
    for (std::size_t k = 0; k < nl.at("pieces").size(); ++k) {
      const nlohmann::json& p = nl.at("pieces")[k];
      const std::string base = "/nonlinear/pieces/" + std::to_string(k);
      const std::string status = p.contains("joins_piece")
                                     ? "joins piece " + std::to_string(p.at("joins_piece").get<int>())
                                 : p.value("complete", false) ? "reaches the end of the range"
                                                              : "ends early: " + text(p, "stopped");
      pieces.push_back({std::to_string(k + 1),
                        html_escape(text(p, "direction")) + " from " +
                            HtmlPage::number(F, j, base + "/from_speed_rpm", 1.0, "rpm", 5),
                        std::to_string(p.at("columns").at("speed_hz").size()), html_escape(status)});
      for (std::size_t f = 0; f < p.at("folds").size(); ++f) {
        const std::string fp = base + "/folds/" + std::to_string(f);
        folds.push_back({std::to_string(k + 1), html_escape(text(p.at("folds")[f], "kind")),
                         HtmlPage::number(F, j, fp + "/speed_rpm", 1.0, "rpm", 5),
                         HtmlPage::number(F, j, fp + "/speed_hz", 1.0, "Hz"),
                         HtmlPage::number(F, j, fp + "/largest_radius_m", 1e6, "µm")});
      }
    }
    page.table("nonlinear_pieces", {"piece", "continued", "points", "status"}, pieces);
    if (!folds.empty())
      page.table("nonlinear_folds", {"piece", "the speed", "at rotor speed", "frequency", "largest wheel whirl"},
                 folds);
  }
  if (!in.warnings.empty()) page.heading("Warnings");
  page.warnings(in.warnings);
  pictures_and_files(page, in);
  page.write(dir);
}

// The steady operating points of a floating-ring bearing (turbodyn bearing on a type = "floating-ring" bearing).
void write_floating_ring_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "bearing.json";
  const nlohmann::json& b = j.at("bearing");
  HtmlPage page = model_page("Floating-ring bearing " + text(b, "name") + " (" + text(b, "thermal") + " films)",
                             "bearing", j, in.command);
  page.heading("Load");
  page.key_values("load", {{"Fx", HtmlPage::number(F, j, "/load_n/0", 1.0, "N")},
                           {"Fy", HtmlPage::number(F, j, "/load_n/1", 1.0, "N")}});
  page.heading("Steady operating points against rotor speed");
  std::vector<Row> rows;
  const nlohmann::json& res = j.at("results");
  for (std::size_t i = 0; i < res.size(); ++i) {
    const std::string at = json_pointer("/results", i);
    rows.push_back({HtmlPage::number(F, j, at + "/speed_rpm", 1.0, "rpm", 5),
                    HtmlPage::number(F, j, at + "/ring_speed_ratio", 1.0, "", 4),
                    HtmlPage::number(F, j, at + "/inner_eccentricity", 1.0, "", 3),
                    HtmlPage::number(F, j, at + "/outer_eccentricity", 1.0, "", 3),
                    HtmlPage::number(F, j, at + "/inner_temperature_k", 1.0, "K", 5),
                    HtmlPage::number(F, j, at + "/outer_temperature_k", 1.0, "K", 5),
                    HtmlPage::number(F, j, at + "/inner_power_w", 1.0, "W"),
                    HtmlPage::number(F, j, at + "/outer_power_w", 1.0, "W"),
                    HtmlPage::number(F, j, at + "/inner_side_flow_m3_s", 6e7, "L/min", 3),
                    HtmlPage::number(F, j, at + "/outer_side_flow_m3_s", 6e7, "L/min", 3),
                    HtmlPage::number(F, j, at + "/drill_hole_pressure_pa", 1e-5, "bar", 3)});
  }
  page.table("bearing", {"rotor speed", "ring / shaft speed", "e/c inner", "e/c outer", "T inner", "T outer",
                         "power loss inner", "power loss outer", "side flow inner", "side flow outer",
                         "drill holes (inner film's feed)"},
             rows);
  pictures_and_files(page, in);
  page.write(dir);
}

void write_bearing_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  if (text(j.at("bearing"), "type") == "floating-ring") return write_floating_ring_report(dir, j, in);
  const std::string F = "bearing.json";
  HtmlPage page = model_page("Ball bearing " + text(j.at("bearing"), "name"), "bearing", j, in.command);
  page.heading("Load");
  page.key_values("load", {{"Fx", HtmlPage::number(F, j, "/load_n/0", 1.0, "N")},
                           {"Fy", HtmlPage::number(F, j, "/load_n/1", 1.0, "N")},
                           {"Fz (on top of the preload)", HtmlPage::number(F, j, "/load_n/2", 1.0, "N")}});
  page.heading("Stiffness and cage speed against rotor speed");
  std::vector<Row> rows;
  const nlohmann::json& res = j.at("results");
  const Display k = display_of("N/m");
  for (std::size_t i = 0; i < res.size(); ++i) {
    const std::string at = json_pointer("/results", i);
    rows.push_back({HtmlPage::number(F, j, at + "/speed_rpm", 1.0, "rpm", 5),
                    HtmlPage::number(F, j, at + "/cage_speed_ratio", 1.0, "", 4),
                    HtmlPage::number(F, j, at + "/stiffness/0/0", k.factor, k.unit),
                    HtmlPage::number(F, j, at + "/stiffness/1/1", k.factor, k.unit),
                    HtmlPage::number(F, j, at + "/stiffness/2/2", k.factor, k.unit),
                    HtmlPage::number(F, j, at + "/stiffness/3/3", 1.0, "N m/rad"),
                    HtmlPage::number(F, j, at + "/max_contact_pressure_pa", 1e-6, "MPa", 4)});
  }
  page.table("bearing",
             {"rotor speed", "cage / shaft speed", "k_xx", "k_yy", "k_zz", "k_θxθx", "largest contact pressure"},
             rows);
  if (!in.warnings.empty()) page.heading("Warnings");
  page.warnings(in.warnings);
  pictures_and_files(page, in);
  page.write(dir);
}

void write_study_report(const std::filesystem::path& dir, const nlohmann::json& j, const std::string& kind,
                        const ReportInputs& in) {
  const std::string F = "results.json";
  HtmlPage page("Study: " + text(j, "study"), kind);
  origin(page, text(j, "model"), nlohmann::json::array(), in.command);
  const nlohmann::json& runs = j.at("runs");
  std::size_t incomplete = 0, failed = 0;
  for (const auto& r : runs) {
    incomplete += text(r, "status") == "incomplete";
    failed += text(r, "status") == "failed";
  }
  const std::size_t total = j.at("runs_total").get<std::size_t>(), recorded = j.at("runs_recorded").get<std::size_t>();
  if (recorded < total)
    page.alert("INCOMPLETE STUDY: " + std::to_string(recorded) + " of " + std::to_string(total) +
               " runs recorded (interrupted, or shards not merged yet).");
  if (incomplete + failed > 0)
    page.alert(std::to_string(incomplete) + " run(s) incomplete (the integrator gave up, or a stability analysis "
               "found no steady state at a speed: the error column says which; metrics of the part that ran) and " +
               std::to_string(failed) + " failed (no metrics); marked in the table and the pictures.");
  page.heading("Runs");
  page.key_values("counts", {{"runs in the design", HtmlPage::number(F, j, "/runs_total", 1.0, "", 7)},
                             {"runs recorded", HtmlPage::number(F, j, "/runs_recorded", 1.0, "", 7)},
                             {"failed", HtmlPage::number(F, j, "/runs_failed", 1.0, "", 7)}});

  const nlohmann::json& params = j.at("parameters");
  const nlohmann::json& metrics = j.at("metrics");
  std::vector<Display> disp;
  for (const auto& m : metrics) disp.push_back(display_of(text(m, "unit")));
  stability_grids(page, F, j);
  if (j.contains("sensitivity") && !j["sensitivity"].empty()) {
    page.heading("Sensitivity");
    page.paragraph("Standardised regression coefficients: the change of the metric, in standard deviations, per "
                   "standard deviation of the parameter; R² tells how much of the metric's variation the linear "
                   "model explains.");
    std::vector<std::string> header{"metric", "R²"};
    for (const auto& p : params) header.push_back(text(p, "path"));
    std::vector<Row> rows;
    for (const auto& m : metrics) {
      const std::string name = text(m, "name");
      if (!j["sensitivity"].contains(name)) continue;
      const std::string at = json_pointer("/sensitivity", name);
      Row row{html_escape(name), HtmlPage::number(F, j, at + "/r_squared", 1.0, "", 3)};
      for (std::size_t p = 0; p < params.size(); ++p)
        row.push_back(HtmlPage::number(F, j, json_pointer(at + "/src", p), 1.0, "", 3));
      rows.push_back(row);
    }
    page.table("sensitivity", header, rows);
  }

  page.heading("Study table");
  std::vector<std::string> header{"run"};
  for (const auto& p : params)
    header.push_back(text(p, "path") + (text(p, "unit").empty() ? "" : " [" + text(p, "unit") + "]"));
  for (std::size_t m = 0; m < metrics.size(); ++m)
    header.push_back(text(metrics[m], "name") + (disp[m].unit.empty() ? "" : " [" + disp[m].unit + "]"));
  header.push_back("status");
  std::vector<Row> rows;
  for (std::size_t i = 0; i < runs.size() && i < kMaxStudyRows; ++i) {
    const std::string at = json_pointer("/runs", i);
    Row row{HtmlPage::number(F, j, at + "/index", 1.0, "", 7)};
    for (std::size_t p = 0; p < params.size(); ++p)
      row.push_back(HtmlPage::number(F, j, json_pointer(at + "/parameters", p)));
    for (std::size_t m = 0; m < metrics.size(); ++m)
      row.push_back(HtmlPage::number(F, j, json_pointer(at + "/metrics", m), disp[m].factor));
    const std::string status = text(runs[i], "status");
    const std::string note = text(runs[i], "note");
    row.push_back((status == "ok" ? "ok"
                                  : "<span class=\"bad\">" + html_escape(status) + "</span> " +
                                        html_escape(text(runs[i], "error"))) +
                  (note.empty() ? "" : " (" + html_escape(note) + ")"));
    rows.push_back(row);
  }
  page.table("runs", header, rows);
  if (runs.size() > kMaxStudyRows)
    page.paragraph("The first " + std::to_string(kMaxStudyRows) + " of " + std::to_string(runs.size()) +
                   " runs; results.csv holds them all.");
  page.warnings(in.warnings);
  pictures_and_files(page, in);
  page.write(dir);
}

void write_optimize_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "result.json";
  HtmlPage page("Optimisation: " + text(j, "study"), "optimize");
  if (j.value("interrupted", false))
    page.alert("INTERRUPTED: the results are those of the evaluations finished so far; run the same command again "
               "to continue.");
  if (!j.value("best_feasible", false))
    page.alert(j.at("best").is_null() ? "NO RESULT: every evaluation failed."
                                      : "NO FEASIBLE DESIGN: the best design shown violates constraints.");
  origin(page, text(j, "model"), nlohmann::json::array(), in.command);
  page.heading("Convergence");
  page.key_values("convergence",
                  {{"algorithm", html_escape(text(j.at("algorithm"), "as_run"))},
                   {"result", html_escape(text(j, "nlopt_result") + ": " + text(j, "reason"))},
                   {"requests", HtmlPage::number(F, j, "/evaluations/requests", 1.0, "", 6)},
                   {"new evaluations", HtmlPage::number(F, j, "/evaluations/new", 1.0, "", 6)},
                   {"from the cache", HtmlPage::number(F, j, "/evaluations/cached", 1.0, "", 6)},
                   {"wall time", HtmlPage::number(F, j, "/wall_time_s", 1.0, "s", 3)},
                   {"initial objective", HtmlPage::number(F, j, "/initial/objective")},
                   {"best objective", HtmlPage::number(F, j, "/best/objective")}});
  stability_grids(page, F, j);
  if (!j.at("best").is_null()) {
    page.heading("Optimum");
    std::vector<Row> rows;
    const nlohmann::json& vars = j.at("variables");
    for (std::size_t i = 0; i < vars.size(); ++i)
      rows.push_back({"<code>" + html_escape(text(vars[i], "path")) + "</code>",
                      HtmlPage::number(F, j, json_pointer("/initial/design_values", i), 1.0, text(vars[i], "unit"), 5),
                      HtmlPage::number(F, j, json_pointer("/best/design_values", i), 1.0, text(vars[i], "unit"), 5),
                      HtmlPage::number(F, j, json_pointer(json_pointer("/variables", i), "low"), 1.0, "", 5) + " … " +
                          HtmlPage::number(F, j, json_pointer(json_pointer("/variables", i), "high"), 1.0,
                                           text(vars[i], "unit"), 5)});
    page.table("design", {"variable", "initial", "optimum", "bounds"}, rows);
    const nlohmann::json& cons = j["best"].at("constraints");
    if (!cons.empty()) {
      rows.clear();
      for (std::size_t k = 0; k < cons.size(); ++k) {
        const std::string at = json_pointer("/best/constraints", k);
        const bool upper = cons[k].contains("upper");
        rows.push_back({html_escape(text(cons[k], "name")), html_escape(text(cons[k], "case")),
                        HtmlPage::number(F, j, at + "/value", 1.0, text(cons[k], "unit")),
                        std::string(upper ? "≤ " : "≥ ") +
                            HtmlPage::number(F, j, at + (upper ? "/upper" : "/lower"), 1.0, text(cons[k], "unit")),
                        cons[k].value("satisfied", false) ? "<span class=\"ok\">yes</span>"
                                                          : "<span class=\"bad\">no</span>"});
      }
      page.table("constraints", {"constraint", "case", "value at the optimum", "bound", "satisfied"}, rows);
    }
  }
  std::vector<std::string> warnings = in.warnings;
  if (j.contains("warnings"))
    for (const auto& w : j["warnings"]) warnings.push_back(w.get<std::string>());
  page.warnings(warnings);
  pictures_and_files(page, in);
  page.write(dir);
}

void write_identify_report(const std::filesystem::path& dir, const nlohmann::json& j, const ReportInputs& in) {
  const std::string F = "estimates.json";
  HtmlPage page("Identification: " + text(j, "study"), "identify");
  if (j.value("cancelled", false))
    page.alert("INTERRUPTED: the estimates are those of the last finished iteration.");
  if (!j.value("converged", false)) page.alert("NOT CONVERGED: " + text(j, "termination"));
  if (!j.value("covariance_ok", false))
    page.alert("No covariance (the σ are missing): " + text(j, "covariance_message"));
  origin(page, text(j, "model"), nlohmann::json::array(), in.command);
  page.paragraph("Measurement: " + text(j, "measurement") + " (method " + text(j, "method") + ")");
  page.heading("Estimates");
  std::vector<Row> rows;
  const nlohmann::json& ps = j.at("parameters");
  bool truth = false;
  for (const auto& p : ps) truth = truth || p.contains("true");
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const std::string at = json_pointer("/parameters", i), unit = text(ps[i], "unit");
    Row row{html_escape(text(ps[i], "name")),
            HtmlPage::number(F, j, at + "/estimate", 1.0, unit, 5) + " ± " +
                HtmlPage::number(F, j, at + "/std_dev", 1.0, unit, 2),
            HtmlPage::number(F, j, at + "/start", 1.0, unit, 5)};
    if (truth) {
      row.push_back(HtmlPage::number(F, j, at + "/true", 1.0, unit, 5));
      row.push_back(HtmlPage::number(F, j, at + "/error_in_std_devs", 1.0, "σ", 2));
    }
    if (ps[i].value("at_bound", false)) row[0] += " <span class=\"bad\">at a bound</span>";
    rows.push_back(row);
  }
  std::vector<std::string> header{"parameter", "estimate ± σ", "start"};
  if (truth) header.insert(header.end(), {"true value", "error"});
  page.table("estimates", header, rows);
  page.heading("Convergence");
  page.key_values("convergence", {{"termination", html_escape(text(j, "termination"))},
                                  {"iterations", HtmlPage::number(F, j, "/iterations", 1.0, "", 6)},
                                  {"initial cost", HtmlPage::number(F, j, "/cost/initial")},
                                  {"final cost", HtmlPage::number(F, j, "/cost/final")},
                                  {"residuals", HtmlPage::number(F, j, "/residuals/count", 1.0, "", 7)},
                                  {"model runs", HtmlPage::number(F, j, "/model_runs", 1.0, "", 6)},
                                  {"wall time", HtmlPage::number(F, j, "/wall_time_s", 1.0, "s", 3)}});
  page.warnings(in.warnings);
  pictures_and_files(page, in);
  page.write(dir);
}

}  // namespace turbodyn::post

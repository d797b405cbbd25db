#include "optim/report.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "post/plot.h"
#include "post/plot_style.h"
#include "post/run_pictures.h"
#include "model/io/result_header.h"
#include "studies/stability_metrics.h"
#include "studies/study.h"
#include "studies/table.h"

namespace turbodyn::optim {
namespace {

using studies::json_number;

std::string with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " [" + unit + "]";
}

// Column prefix of a case: none when there is only one.
std::string case_prefix(const OptimizationSpec& s, std::size_t c) {
  return s.cases.size() == 1 ? "" : s.cases[c].name + ": ";
}

nlohmann::json entry_json(const OptimizationSpec& s, const HistoryEntry& h) {
  nlohmann::json design = nlohmann::json::object(), values = nlohmann::json::array();
  for (std::size_t i = 0; i < s.variables.size(); ++i) {
    design[s.variables[i].path] = value_text(s.variables[i], h.evaluation.design[i]);
    values.push_back(h.evaluation.design[i]);
  }
  nlohmann::json cons = nlohmann::json::array();
  for (std::size_t k = 0; k < s.constraints.size(); ++k)
    for (std::size_t c = 0; c < s.cases.size(); ++c) {
      const std::size_t i = k * s.cases.size() + c;
      const Constraint& con = s.constraints[k];
      cons.push_back({{"name", con.name}, {"case", s.cases[c].name}, {"value", json_number(h.assessment.constraint_values[i])},
                      {con.upper ? "upper" : "lower", con.bound}, {"unit", s.metrics[con.metric].unit},
                      {"g", h.assessment.g[i]}, {"satisfied", h.assessment.g[i] <= s.algorithm.constraint_tolerance}});
    }
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t c = 0; c < s.cases.size() && c < h.evaluation.cases.size(); ++c) {
    nlohmann::json m = nlohmann::json::object();
    for (std::size_t k = 0; k < s.metrics.size(); ++k) m[s.metrics[k].spec.name] = json_number(h.evaluation.cases[c].metrics[k]);
    cases.push_back({{"case", s.cases[c].name}, {"objective", json_number(h.assessment.case_objectives[c])},
                     {"metrics", m}, {"status", h.evaluation.cases[c].status}, {"error", h.evaluation.cases[c].error}});
  }
  return {{"request", h.request}, {"evaluation", h.evaluation.id}, {"design", design}, {"design_values", values},
          {"objective", h.assessment.objective}, {"feasible", h.assessment.feasible}, {"failed", h.assessment.failed},
          {"note", h.assessment.note}, {"constraints", cons}, {"cases", cases}};
}

}  // namespace

void write_history_csv(const OptimizationSpec& s, const OptimizationResult& r, const std::filesystem::path& file) {
  studies::CsvWriter csv(file);
  csv.texts({"request", "evaluation", "source", "kind"});
  for (const Variable& v : s.variables) csv.text(with_unit(v.path, v.unit));
  for (std::size_t c = 0; c < s.cases.size(); ++c)
    for (const Metric& m : s.metrics) csv.text(case_prefix(s, c) + with_unit(m.spec.name, m.unit));
  csv.text("objective");
  for (const Constraint& k : s.constraints)
    for (std::size_t c = 0; c < s.cases.size(); ++c)
      csv.text(case_prefix(s, c) + with_unit(k.name, s.metrics[k.metric].unit) + (k.upper ? " <= " : " >= ") +
               studies::table_number(k.bound))
          .text(case_prefix(s, c) + "g(" + k.name + ")");
  csv.texts({"feasible", "status", "wall_time_s"}).end_row();
  for (const HistoryEntry& h : r.history) {
    csv.integer(h.request).integer(h.evaluation.id).text(h.cached ? "cached" : "new");
    csv.text(h.gradient_point ? "gradient" : "design").numbers(h.evaluation.design);
    for (std::size_t c = 0; c < s.cases.size(); ++c)
      for (std::size_t m = 0; m < s.metrics.size(); ++m)
        csv.number(c < h.evaluation.cases.size() ? h.evaluation.cases[c].metrics[m] : NAN);
    csv.number(h.assessment.objective);
    for (std::size_t i = 0; i < h.assessment.g.size(); ++i)
      csv.number(h.assessment.constraint_values[i]).number(h.assessment.g[i]);
    csv.text(h.assessment.feasible ? "yes" : "no").text(h.assessment.failed ? "failed: " + h.assessment.note : "ok");
    csv.number(h.evaluation.wall_time).end_row();
  }
}

nlohmann::json result_json(const OptimizationSpec& s, const OptimizationResult& r) {
  nlohmann::json j;
  j["turbodyn_version"] = turbodyn_version();
  j["study"] = s.name;
  j["study_file"] = s.source.string();
  j["model"] = s.model.string();
  j["model_digest"] = studies::base_model_digest(s);
  const AlgorithmOptions& a = s.algorithm;
  j["algorithm"] = {{"name", a.name}, {"as_run", r.algorithm}, {"note", r.note}, {"local", a.local},
                    {"xtol_rel", a.xtol_rel}, {"xtol_abs", a.xtol_abs}, {"ftol_rel", a.ftol_rel},
                    {"ftol_abs", a.ftol_abs}, {"stopval", a.has_stopval ? nlohmann::json(a.stopval) : nlohmann::json()},
                    {"maxeval", a.maxeval}, {"maxtime_s", a.maxtime}, {"initial_step", a.initial_step},
                    {"gradient", a.central_differences ? "central" : "forward"}, {"gradient_step", a.gradient_step},
                    {"seed", a.seed}, {"constraint_tolerance", a.constraint_tolerance}};
  j["nlopt_result"] = r.nlopt_result;
  j["nlopt_code"] = r.nlopt_code;
  j["reason"] = r.reason;
  j["interrupted"] = r.interrupted;
  std::size_t designs = 0;
  for (const HistoryEntry& h : r.history) designs += !h.gradient_point;
  j["evaluations"] = {{"requests", r.history.size()}, {"designs_proposed", designs}, {"new", r.new_evaluations},
                      {"cached", r.cached_evaluations}};
  j["wall_time_s"] = r.wall_time;
  j["variables"] = nlohmann::json::array();
  for (const Variable& v : s.variables)
    j["variables"].push_back({{"path", v.path}, {"paths", v.paths}, {"unit", v.unit}, {"low", v.low}, {"high", v.high}, {"start", v.start},
                              {"scale", v.log_scale ? "log" : "linear"}});
  j["metrics"] = nlohmann::json::array();
  for (const Metric& m : s.metrics) {
    nlohmann::json e = {{"name", m.spec.name}, {"kind", m.spec.kind}, {"unit", m.unit}};
    e.update(studies::stability_grid_json(m.spec));  // the speeds a stability metric analysed
    j["metrics"].push_back(e);
  }
  if (!r.history.empty()) j["initial"] = entry_json(s, r.history.front());
  j["best_feasible"] = r.best_feasible;
  j["best"] = r.best ? entry_json(s, r.history[*r.best]) : nlohmann::json(nullptr);
  return j;
}

void write_convergence_plot(const OptimizationSpec& s, const OptimizationResult& r, const std::filesystem::path& png) {
  plot::Series feasible{"feasible design", {}, {}, plot::Series::Style::Points, plot::style::kFeasible, 1.5};
  plot::Series infeasible{"infeasible design", {}, {}, plot::Series::Style::Points, plot::style::kInfeasible, 1.5};
  // A step line: the best holds until an evaluation improves on it.
  plot::Series best{"best feasible so far", {}, {}, plot::Series::Style::Steps, plot::style::kBestSoFar, 2.0};
  double b = NAN;
  for (const HistoryEntry& h : r.history) {
    const Assessment& a = h.assessment;
    if (a.feasible && (std::isnan(b) || a.objective < b)) b = a.objective;
    if (!std::isnan(b)) {
      best.x.push_back(static_cast<double>(h.request));
      best.y.push_back(b);
    }
    if (h.gradient_point || a.failed) continue;
    plot::Series& p = a.feasible ? feasible : infeasible;
    p.x.push_back(static_cast<double>(h.request));
    p.y.push_back(a.objective);
  }
  plot::LineChart chart;
  chart.title = "Convergence: " + s.name + " (" + s.algorithm.name + ")";
  chart.xlabel = "evaluation (request to the model, incl. finite-difference points)";
  std::string unit;
  // A unit when the objective is a plain sum of metrics of one unit, shown as the pictures show that quantity
  // (a displacement in µm).
  unit = s.metrics[s.objective.terms[0].metric].unit;
  for (const ObjectiveTerm& t : s.objective.terms)
    if (t.weight != 1.0 || s.metrics[t.metric].unit != unit) unit.clear();
  const post::Display d = post::display_of(unit);
  chart.ylabel = with_unit("objective", d.unit);
  for (plot::Series* p : {&feasible, &infeasible, &best}) {
    for (double& v : p->y) v *= d.factor;
    if (!p->x.empty()) chart.series.push_back(*p);
  }
  if (chart.series.empty()) return;
  plot::render_png(chart, png, plot::Size{900, 600});
}

}  // namespace turbodyn::optim

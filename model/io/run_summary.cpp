#include "model/io/run_summary.h"

#include "model/io/result_header.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

namespace turbodyn {

nlohmann::json run_summary(const MachineSpec& spec, const RunupModel& model, const RunupOptions& ro,
                           const RunupResult& r, const std::vector<Override>& overrides) {
  nlohmann::json j = result_header(spec, overrides);
  j["complete"] = r.complete;
  j["message"] = r.message;
  j["model"].update({{"n_dof", model.n_dof()}, {"n_states", model.n_states()},
                     {"n_force_elements", model.elements().size()}});
  const double t_end = ro.t_end > 0.0 ? ro.t_end : model.speed().duration();
  j["options"] = {{"integrator", to_string(resolve_integrator(model, ro.solver.integrator))}, {"rtol", ro.solver.rtol},
                  {"atol", ro.solver.atol}, {"atol_scaling", to_string(ro.solver.atol_scaling)},
                  {"max_step_s", ro.solver.max_step}, {"max_steps", ro.solver.max_steps},
                  {"max_order", ro.solver.max_order}, {"newton_tolerance", ro.solver.newton_tolerance},
                  {"sample_rate_hz", ro.sample_rate}, {"static_start", ro.solver.static_start},
                  {"t_start_s", ro.t_start}, {"t_end_s", t_end}, {"rotor_coordinates", model.n_dof()},
                  {"rotor_fe_dof", model.n_physical_dof()},
                  {"reduction_lowest_dropped_mode_hz", model.reduction_cutoff()}};
  j["t_reached_s"] = r.t_reached;
  j["stats"] = {{"wall_time_s", r.stats.wall_time}, {"steps", r.stats.steps}, {"rhs_calls", r.stats.rhs_calls},
                {"force_element_calls", r.stats.element_calls},
                {"jacobian_evaluations", r.stats.jacobian_evaluations},
                {"newton_matrix_factorisations", r.stats.linear_setups},
                {"error_test_failures", r.stats.error_test_failures},
                {"nonlinear_solver_failures", r.stats.nonlinear_failures}};
  j["energy"] = {{"initial_j", r.energy_initial}, {"final_j", r.energy_final}, {"work_in_j", r.work_in},
                 {"dissipated_j", r.dissipated},
                 {"balance_error_j", r.energy_final - r.energy_initial - r.work_in + r.dissipated}};
  int speed_col = 0;
  for (std::size_t c = 0; c < r.channels.size(); ++c)
    if (r.channels[c].kind == ProbeChannel::Kind::Speed) speed_col = static_cast<int>(c);
  nlohmann::json probes = nlohmann::json::object();
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const ProbeChannel& ch = r.channels[c];
    if (ch.kind == ProbeChannel::Kind::Speed || ch.kind == ProbeChannel::Kind::Angle) continue;
    const std::vector<double>& col = r.columns[c];
    std::size_t at_max = 0, at_min = 0;
    for (std::size_t i = 1; i < col.size(); ++i) {
      if (std::abs(col[i]) > std::abs(col[at_max])) at_max = i;
      if (col[i] < col[at_min]) at_min = i;
    }
    const bool empty = col.empty();
    const double speed_hz = empty ? 0.0 : r.columns[speed_col][at_max];
    probes[ch.name] = {{"unit", ch.unit}, {"description", ch.description},
                       {"max_abs", empty ? 0.0 : std::abs(col[at_max])},
                       {"time_at_max_s", empty ? 0.0 : r.time[at_max]},
                       {"speed_at_max_hz", speed_hz}, {"speed_at_max_rpm", speed_hz * 60.0},
                       {"min", empty ? 0.0 : col[at_min]}, {"time_at_min_s", empty ? 0.0 : r.time[at_min]},
                       {"speed_at_min_rpm", empty ? 0.0 : r.columns[speed_col][at_min] * 60.0}};
    if (std::isfinite(ch.limit)) {
      nlohmann::json& p = probes[ch.name];
      p["limit"] = ch.limit;
      p["limit_below"] = ch.limit_below;
      p["limit_note"] = ch.limit_note;
      p["over_limit"] = nullptr;  // where the value first passes the limit (|value| above it, or below it), if it does
      for (std::size_t i = 0; i < col.size(); ++i)
        if (ch.limit_below ? col[i] < ch.limit : std::abs(col[i]) > ch.limit) {
          p["over_limit"] = {{"time_s", r.time[i]}, {"speed_rpm", r.columns[speed_col][i] * 60.0}};
          break;
        }
    }
  }
  j["probes"] = probes;
  return j;
}

namespace {

// Each probe of the summary that passes its limit, with the statement of where (`with_time`: and when) and how far.
std::vector<std::pair<std::string, const nlohmann::json*>> limits_passed(const nlohmann::json& summary,
                                                                        bool with_time) {
  std::vector<std::pair<std::string, const nlohmann::json*>> out;
  if (!summary.contains("probes")) return out;
  for (const auto& [name, p] : summary["probes"].items()) {
    if (!p.contains("over_limit") || p["over_limit"].is_null()) continue;
    // Pressures in MPa, lengths (film thicknesses) in µm to a tenth, everything else in its SI unit.
    const std::string unit = p.value("unit", "");
    const double scale = unit == "Pa" ? 1e-6 : unit == "m" ? 1e6 : 1.0;
    const std::string shown = unit == "Pa" ? "MPa" : unit == "m" ? "µm" : unit;
    const int digits = unit == "m" ? 1 : 0;
    const bool below = p.value("limit_below", false);
    std::ostringstream os;
    os << std::fixed << std::setprecision(digits) << name << " is first " << (below ? "below" : "above")
       << " its limit of " << p["limit"].get<double>() * scale << " " << shown << " at " << std::setprecision(0)
       << p["over_limit"]["speed_rpm"].get<double>() << " rpm";
    if (with_time) os << " (t = " << std::setprecision(4) << p["over_limit"]["time_s"].get<double>() << " s)";
    const char* extreme = below ? "min" : "max_abs";
    const char* at = below ? "speed_at_min_rpm" : "speed_at_max_rpm";
    os << ", " << (below ? "smallest " : "largest ") << std::setprecision(digits) << p[extreme].get<double>() * scale
       << " " << shown << " at " << std::setprecision(0) << p[at].get<double>() << " rpm";
    out.emplace_back(os.str(), &p);
  }
  return out;
}

}  // namespace

std::vector<std::string> probe_limit_warnings(const nlohmann::json& summary) {
  std::vector<std::string> out;
  for (const auto& [text, p] : limits_passed(summary, true))
    out.push_back(text + ". The limit: " + p->value("limit_note", std::string()) +
                  ". The run goes on as the model describes it");
  return out;
}

std::string probe_limit_note(const nlohmann::json& summary) {
  std::string out;
  for (const auto& [text, p] : limits_passed(summary, false)) out += (out.empty() ? "" : "; ") + text;
  return out;
}

}  // namespace turbodyn

#include "app/response_command.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/modal_command.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "post/plot.h"
#include "post/report.h"
#include "app/command_line.h"
#include "model/rotor/response.h"
#include "model/io/output_file.h"
#include "model/io/result_header.h"
#include "model/rotor/rotor.h"

namespace turbodyn::app {

int run_response_command(const ResponseCommandOptions& options) {
  const MachineSpec spec = load_model(options.model_file, options.overrides);
  require_linear_supports(spec, true);
  for (const BearingSpec& b : spec.bearings)
    if (b.type == BearingType::FloatingRing)
      throw ModelError(spec.source.string() + ": bearings." + b.name + ": floating-ring bearings are in the linear "
                       "analyses of `turbodyn modal` only; the unbalance response takes linear and ball bearings");
  Rotor rotor = build_rotor(spec);
  // Ball bearings: their quasi-static linearisation at every speed, as in `turbodyn modal` (docs/ball-bearing.md).
  add_ball_bearing_linearisations(spec, rotor);
  const std::vector<double> speeds = analysis_speeds(spec, options.speeds, std::max(spec.modal.n_speeds, 201));
  std::filesystem::create_directories(options.output_dir);

  // Columns: speed, then per disk |x|, |y|, major semi-axis, phase of x; per bearing |Fx|, |Fy|.
  std::vector<std::string> names{"speed_rad_s", "speed_hz"};
  for (const RigidDisk& d : rotor.disks)
    for (const char* s : {".x_amplitude_m", ".y_amplitude_m", ".major_semi_axis_m", ".x_phase_rad"})
      names.push_back("disk." + d.name + s);
  for (const LinearBearing& b : rotor.bearings)
    for (const char* s : {".fx_amplitude_n", ".fy_amplitude_n"}) names.push_back("bearing." + b.name + s);
  std::vector<std::vector<double>> cols(names.size());
  for (double w : speeds) {
    SteadyResponse r;
    try {
      r = unbalance_response(rotor, w);
    } catch (const QuasiStaticError& e) {
      throw ModelError(spec.source.string() + ": a ball bearing's linearisation failed: " + e.what());
    }
    std::size_t c = 0;
    cols[c++].push_back(w);
    cols[c++].push_back(w / (2 * M_PI));
    for (const RigidDisk& d : rotor.disks) {
      const std::complex<double> x = r.q(rotor.dof(d.node, kX)), y = r.q(rotor.dof(d.node, kY));
      cols[c++].push_back(std::abs(x));
      cols[c++].push_back(std::abs(y));
      cols[c++].push_back(major_semi_axis(x, y));
      cols[c++].push_back(std::arg(x));
    }
    for (std::size_t b = 0; b < rotor.bearings.size(); ++b) {
      cols[c++].push_back(std::abs(r.bearing_fx[b]));
      cols[c++].push_back(std::abs(r.bearing_fy[b]));
    }
  }
  {
    OutputFile file(options.output_dir / "response.csv");
    std::ostream& csv = file.stream();
    csv << std::setprecision(12);
    for (std::size_t c = 0; c < names.size(); ++c) csv << (c ? "," : "") << names[c];
    csv << "\n";
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      for (std::size_t c = 0; c < names.size(); ++c) csv << (c ? "," : "") << cols[c][i];
      csv << "\n";
    }
    file.commit();
  }
  nlohmann::json j = result_header(spec, options.overrides);
  for (std::size_t c = 0; c < names.size(); ++c) j["columns"][names[c]] = cols[c];
  write_output_file(options.output_dir / "response.json", j.dump(1) + "\n");
  if (options.plots) {
    plot::LineChart chart;
    chart.title = "Steady-state unbalance response: " + spec.name;
    chart.xlabel = "rotor speed f_d [Hz]";
    chart.ylabel = "1x orbit major semi-axis [µm]";
    chart.logy = true;
    std::size_t c = 2;
    for (const RigidDisk& d : rotor.disks) {
      std::vector<double> um = cols[c + 2];
      for (double& v : um) v *= 1e6;
      chart.series.push_back({"disk " + d.name, cols[1], um, plot::Series::Style::Lines, "", 1.5});
      c += 4;
    }
    plot::render_png(chart, options.output_dir / "response.png");
  }
  post::write_response_report(options.output_dir, j,
                              {command_line(), options.plots ? std::vector<std::string>{"response.png"}
                                                             : std::vector<std::string>{},
                               {"response.json", "response.csv"}, {}});
  std::cout << "Wrote " << (options.output_dir / "response.csv").string() << ", response.json, report.html"
            << (options.plots ? ", response.png" : "") << " (" << speeds.size() << " speeds)\n";
  return 0;
}

}  // namespace turbodyn::app

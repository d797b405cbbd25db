#include "app/identify_command.h"
#include "app/interrupt.h"

#include <atomic>
#include <cmath>
#include <csignal>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "identification/identify.h"
#include "identification/identify_study.h"
#include "identification/report.h"
#include "app/command_line.h"
#include "post/report.h"
#include <fstream>
#include <nlohmann/json.hpp>

namespace turbodyn::app {
int run_identify_command(const IdentifyCommandOptions& options) {
  using namespace identification;
  const IdentifyStudy study = load_identify_study(options.study_file);
  IdentifyOptions io;
  io.threads = options.threads;
  io.cancel = InterruptGuard::flag();
  io.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const IdentifyResult r = [&] {
    const InterruptGuard guard;
    return identify(study, io);
  }();
  std::vector<std::string> warnings = r.warnings;
  const std::vector<std::string> files = write_identify_results(study, r, options.output_dir, options.plots, warnings);
  {
    std::ifstream in(options.output_dir / "estimates.json");
    auto [pictures, others] = post::split_pictures(files);
    post::write_identify_report(options.output_dir, nlohmann::json::parse(in),
                                {command_line(), pictures, others, warnings});
  }

  std::cout << study.name << ": " << r.brief_report << "\n";
  std::cout << std::setprecision(6);
  for (std::size_t i = 0; i < study.parameters.size(); ++i) {
    const ParameterSpec& p = study.parameters[i];
    std::cout << "  " << std::left << std::setw(24) << p.name << std::right << " = " << r.estimate[i];
    if (std::isfinite(r.std_dev[i])) std::cout << " +- " << r.std_dev[i];
    if (!p.unit.empty()) std::cout << " " << p.unit;
    if (std::isfinite(p.truth)) std::cout << "   (true " << p.truth << ")";
    std::cout << "\n";
  }
  std::cout << r.model_runs << " model runs on " << r.threads << " threads, " << std::fixed << std::setprecision(1)
            << r.wall_time << " s\n"
            << "Wrote " << (options.output_dir / "estimates.json").string() << " and " << files.size() - 1
            << " more files\n";
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  if (r.cancelled) {
    std::cerr << "interrupted: the results are those of the last finished iteration\n";
    return kExitInterrupted;
  }
  return 0;
}

}  // namespace turbodyn::app

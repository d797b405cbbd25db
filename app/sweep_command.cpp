#include "app/sweep_command.h"
#include "app/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "model/io/model_file.h"
#include "studies/sweep.h"
#include "app/command_line.h"
#include "model/io/output_file.h"
#include "post/report.h"
#include <fstream>
#include <nlohmann/json.hpp>

namespace turbodyn::app {
namespace {


void parse_shard(const std::string& text, std::size_t& k, std::size_t& n) {
  const std::size_t slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    std::size_t pk = 0, pn = 0;
    k = std::stoul(text.substr(0, slash), &pk);
    n = std::stoul(text.substr(slash + 1), &pn);
    if (pk != slash || pn != text.size() - slash - 1 || n == 0 || k >= n) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw ModelError("--shard '" + text + "': expected K/N with 0 <= K < N, e.g. --shard 3/16");
  }
}

// report.html of a study's output directory, from the results.json just written.
void write_report(const std::filesystem::path& dir, const std::vector<std::string>& files, const std::string& kind) {
  std::ifstream in(dir / "results.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  auto [pictures, others] = post::split_pictures(files);
  others.push_back("runs.jsonl");
  post::write_study_report(dir, j, kind, {command_line(), pictures, others, {}});
}

}  // namespace

int run_sweep_command(const SweepCommandOptions& options) {
  const studies::StudySpec study = studies::load_study(options.study_file);
  studies::SweepOptions so;
  so.output_dir = options.output_dir;
  so.threads = options.threads;
  if (!options.shard.empty()) parse_shard(options.shard, so.shard_k, so.shard_n);
  so.cancel = InterruptGuard::flag();
  const bool tty = isatty(STDERR_FILENO);
  so.progress = [&](const studies::SweepProgress& p) {
    std::ostringstream os;
    os << "runs " << p.done << "/" << p.total << " done (" << p.failed << " failed"
       << (p.resumed ? ", " + std::to_string(p.resumed) + " resumed" : "") << "), wall " << format_duration(p.wall_time)
       << ", left ~" << format_duration(p.eta);
    if (tty) std::cerr << "\r" << os.str() << "   " << std::flush;
    else std::cerr << os.str() << "\n";
  };
  const studies::SweepResult r = [&] {
    const InterruptGuard guard;
    return studies::run_sweep(study, so);
  }();
  if (tty) std::cerr << "\n";
  const std::vector<std::string> files =
      studies::write_results(study, r.design, r.runs, options.output_dir, options.plots);
  write_report(options.output_dir, files, "sweep");
  std::size_t failed = 0;
  for (const auto& run : r.runs) failed += run.status != "ok";
  std::cout << study.name << ": " << r.runs.size() << " of " << r.design.values.size() << " runs recorded"
            << (so.shard_n > 1 ? " in shard " + options.shard : "") << " (" << r.resumed
            << " resumed from an earlier invocation, " << failed << " failed or incomplete)\n"
            << "Wrote " << (options.output_dir / "results.csv").string() << " and " << files.size() - 1
            << " more files\n";
  if (InterruptGuard::interrupted() && !r.complete) {
    std::cerr << "interrupted: the finished runs are recorded in " << (options.output_dir / "runs.jsonl").string()
              << "; run the same command again to resume\n";
    return kExitInterrupted;
  }
  return 0;
}

int run_merge_command(const std::filesystem::path& study_file, const std::vector<std::filesystem::path>& dirs,
                      const std::filesystem::path& output_dir, bool plots) {
  const studies::StudySpec study = studies::load_study(study_file);
  const studies::Design design = studies::make_design(study.design);
  std::map<std::size_t, studies::RunRecord> runs;
  for (const auto& d : dirs) {
    if (!std::filesystem::exists(d / "runs.jsonl")) throw ModelError(d.string() + ": no runs.jsonl in this directory");
    for (auto& r : studies::read_runs(study, d)) runs[r.index] = r;
  }
  std::vector<studies::RunRecord> all;
  for (auto& [i, r] : runs) all.push_back(r);
  const std::vector<std::string> files = studies::write_results(study, design, all, output_dir, plots);
  auto [pictures, others] = post::split_pictures(files);
  std::ifstream in(output_dir / "results.json");
  post::write_study_report(output_dir, nlohmann::json::parse(in), "merge", {command_line(), pictures, others, {}});
  std::cout << study.name << ": merged " << all.size() << " of " << design.values.size() << " runs from "
            << dirs.size() << " directories into " << output_dir.string() << "\n";
  if (all.size() < design.values.size())
    std::cerr << "warning: " << design.values.size() - all.size() << " runs are missing (shards not run yet?)\n";
  return 0;
}

}  // namespace turbodyn::app

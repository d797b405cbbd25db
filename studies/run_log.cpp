#include "studies/run_log.h"

#include "model/spec/errors.h"

namespace turbodyn::studies {

RunLogContents read_run_log(const std::filesystem::path& file, const nlohmann::json& header,
                            const std::string& mismatch) {
  RunLogContents c;
  std::ifstream in(file);
  if (!in) return c;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      continue;  // cut short by a kill: that run is done again
    }
    if (!c.has_header) {
      if (j != header) throw ModelError(file.string() + ": " + mismatch);
      c.has_header = true;
      continue;
    }
    c.records.push_back(std::move(j));
  }
  return c;
}

RunLog::RunLog(const std::filesystem::path& file, const nlohmann::json& header, const std::string& mismatch) {
  RunLogContents c = read_run_log(file, header, mismatch);
  records_ = std::move(c.records);
  std::filesystem::create_directories(file.parent_path().empty() ? "." : file.parent_path());
  out_.open(file, c.has_header ? std::ios::app : std::ios::trunc);
  if (!out_) throw ModelError(file.string() + ": cannot write");
  if (!c.has_header) out_ << header.dump() << "\n" << std::flush;
}

void RunLog::append(const nlohmann::json& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  out_ << line.dump() << "\n" << std::flush;
}

}  // namespace turbodyn::studies

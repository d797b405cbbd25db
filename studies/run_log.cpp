#include "studies/run_log.h"

#include <cstdint>
#include <sstream>

#include "model/spec/errors.h"

namespace turbodyn::studies {

namespace {

struct Fnv1a {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bit
  void add(const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(data[i]);
      h *= 1099511628211ull;
    }
  }
  std::string hex() const {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string digest(16, '0');
    std::uint64_t v = h;
    for (int i = 15; i >= 0; --i, v >>= 4) digest[i] = kHex[v & 0xf];
    return digest;
  }
};

}  // namespace

std::string file_digest(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "unreadable";
  Fnv1a f;
  char buffer[4096];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) f.add(buffer, static_cast<std::size_t>(in.gcount()));
  return f.hex();
}

std::string text_digest(const std::string& bytes) {
  Fnv1a f;
  f.add(bytes.data(), bytes.size());
  return f.hex();
}

RunLogContents read_run_log(const std::filesystem::path& file, const nlohmann::json& header,
                            const std::string& mismatch) {
  RunLogContents c;
  std::ifstream in(file, std::ios::binary);
  if (!in) return c;
  std::ostringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  std::size_t begin = 0;
  for (int line_no = 1; begin < all.size(); ++line_no) {
    const std::size_t newline = all.find('\n', begin);
    if (newline == std::string::npos) break;  // cut short by a kill: that run is done again
    const std::string line = all.substr(begin, newline - begin);
    begin = newline + 1;
    c.complete_bytes = begin;
    if (line.empty()) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      throw ModelError(file.string() + ":" + std::to_string(line_no) +
                       ": a damaged line (not JSON) inside the log; a kill cuts only the last line short. Move the "
                       "file away to start the batch afresh");
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
  // A last line cut short by a kill goes, so that the next line does not continue it.
  if (c.has_header) std::filesystem::resize_file(file, c.complete_bytes);
  out_.open(file, c.has_header ? std::ios::app : std::ios::trunc);
  if (!out_) throw ModelError(file.string() + ": cannot write");
  if (!c.has_header) out_ << header.dump() << "\n" << std::flush;
}

void RunLog::append(const nlohmann::json& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  out_ << line.dump() << "\n" << std::flush;
}

}  // namespace turbodyn::studies

// The resume log of a batch of runs (a sweep's runs.jsonl, an optimisation's evaluations.jsonl): JSON lines, a header
// that identifies the batch, then one line per finished run, each written and flushed as the run finishes and read
// back when the batch starts again, so that an interrupted or killed batch does not redo finished runs.
#pragma once

#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace turbodyn::studies {

struct RunLogContents {
  bool has_header = false;              ///< the file has a complete first line
  std::vector<nlohmann::json> records;  ///< the complete lines after it
  std::size_t complete_bytes = 0;       ///< the length of the file up to the end of its last complete line
};

/// A digest of the bytes of `file` (64-bit FNV-1a, 16 hex digits; "unreadable" if it cannot be read). A batch's
/// header carries its model file's digest, so that a log written for an earlier version of the model is not resumed.
std::string file_digest(const std::filesystem::path& file);
/// The same digest of bytes already read.
std::string text_digest(const std::string& bytes);

/// The lines of `file` (none if it does not exist); a last line cut short by a kill (no newline) is skipped. Throws
/// ModelError "FILE: `mismatch`" when the first complete line is not `header`, i.e. the file belongs to another
/// batch, and "FILE:LINE: a damaged line" for a complete line that is not JSON.
RunLogContents read_run_log(const std::filesystem::path& file, const nlohmann::json& header,
                            const std::string& mismatch);

class RunLog {
 public:
  /// Reads `file` as read_run_log does and opens it for appending, after cutting off a last line cut short by a
  /// kill. A file without a complete header line (new, empty, or killed while the header was written) starts over
  /// with `header`.
  RunLog(const std::filesystem::path& file, const nlohmann::json& header, const std::string& mismatch);

  /// The records read when the log was opened.
  const std::vector<nlohmann::json>& records() const { return records_; }

  /// Writes one line; on disk when it returns, before anything else can fail. Thread-safe.
  void append(const nlohmann::json& line);

 private:
  std::vector<nlohmann::json> records_;
  std::mutex mutex_;
  std::ofstream out_;
};

}  // namespace turbodyn::studies

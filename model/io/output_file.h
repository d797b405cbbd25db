// Writing a result file safely: into a temporary file beside it, checked, then renamed over the target. A reader
// never sees half a file, a symbolic link at the target is replaced instead of followed (its target stays as it
// is), and a failed write (full disk, a directory in the way, no permission) is an error naming the file and the
// cause instead of a silent short file.
#pragma once

#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>

namespace turbodyn {

class OutputFile {
 public:
  /// Opens `<file>.tmp` for writing; throws std::runtime_error naming the file if it cannot.
  explicit OutputFile(std::filesystem::path file);
  /// Without commit() the temporary file is removed and the target left as it was.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return out_; }
  /// Flushes and closes the temporary file, checks that every write succeeded and renames it to the target;
  /// throws std::runtime_error "cannot write FILE: cause" otherwise.
  void commit();

 private:
  std::filesystem::path file_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// OutputFile in one call: the whole text, checked and renamed into place.
void write_output_file(const std::filesystem::path& file, const std::string& text);

/// For a file written as a run goes (the time series, a study's tables: streamed, so that a killed run keeps what
/// it wrote, hence not renamed into place): a symbolic link at `file` is removed before the file is created, so the
/// file takes the link's place and the link's target stays as it is. Anything else at `file` is left alone.
void remove_symlink(const std::filesystem::path& file);

}  // namespace turbodyn

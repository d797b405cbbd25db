#include "model/io/output_file.h"

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace turbodyn {

namespace {

std::string cause() { return errno != 0 ? std::strerror(errno) : "the write failed"; }

}  // namespace

OutputFile::OutputFile(std::filesystem::path file) : file_(std::move(file)) {
  temporary_ = file_;
  temporary_ += ".tmp";
  std::error_code ec;
  if (std::filesystem::is_directory(std::filesystem::symlink_status(file_, ec)))
    throw std::runtime_error("cannot write " + file_.string() + ": a directory is in the way");
  errno = 0;
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write " + file_.string() + ": " + cause());
}

OutputFile::~OutputFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void OutputFile::commit() {
  errno = 0;
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written || out_.fail()) {
    const std::string why = cause();
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
    throw std::runtime_error("cannot write " + file_.string() + ": " + why);
  }
  // rename() replaces the target entry itself: a symbolic link there is replaced, not followed.
  std::error_code ec;
  std::filesystem::rename(temporary_, file_, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw std::runtime_error("cannot write " + file_.string() + ": " + ec.message());
  }
  committed_ = true;
}

void remove_symlink(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(file, ec))) std::filesystem::remove(file, ec);
}

void write_output_file(const std::filesystem::path& file, const std::string& text) {
  OutputFile out(file);
  out.stream() << text;
  out.commit();
}

}  // namespace turbodyn

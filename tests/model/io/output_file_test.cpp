// Result files are written beside the target and renamed into place: complete or not at all, a symbolic link
// replaced instead of followed, a failed write an error that names the file.
#include "model/io/output_file.h"
#include "tests/support/temp_dir.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace turbodyn {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  return turbodyn::testing::fresh_temp_dir("output_file_test_" + name + "_" +
                                           std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
}

TEST(OutputFile, WritesAndReplacesASymlinkInsteadOfFollowingIt) {
  const fs::path dir = fresh_dir("symlink");
  write_output_file(dir / "a.json", "{}\n");
  EXPECT_EQ(testing::read_file(dir / "a.json"), "{}\n");
  EXPECT_FALSE(fs::exists(dir / "a.json.tmp"));
  // A link at the target: the file it points to keeps its content, the link becomes the result file.
  { std::ofstream(dir / "precious.txt") << "keep me"; }
  fs::create_symlink(dir / "precious.txt", dir / "summary.json");
  write_output_file(dir / "summary.json", "result");
  EXPECT_EQ(testing::read_file(dir / "precious.txt"), "keep me");
  EXPECT_FALSE(fs::is_symlink(dir / "summary.json"));
  EXPECT_EQ(testing::read_file(dir / "summary.json"), "result");
  fs::remove_all(dir);
}

TEST(OutputFile, StreamedFilesReplaceASymlinkInsteadOfWritingThroughIt) {
  const fs::path dir = fresh_dir("remove_symlink");
  { std::ofstream(dir / "precious.txt") << "keep me"; }
  fs::create_symlink(dir / "precious.txt", dir / "timeseries.csv");
  remove_symlink(dir / "timeseries.csv");
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "timeseries.csv")));
  EXPECT_EQ(testing::read_file(dir / "precious.txt"), "keep me");
  remove_symlink(dir / "precious.txt");  // a regular file is left alone, a missing one is no error
  remove_symlink(dir / "missing.txt");
  EXPECT_EQ(testing::read_file(dir / "precious.txt"), "keep me");
  fs::remove_all(dir);
}

TEST(OutputFile, AFailedWriteIsAnErrorNamingTheFileAndLeavesTheOldOne) {
  const fs::path dir = fresh_dir("fail");
  // A directory in the way of the result file.
  fs::create_directories(dir / "modal.json");
  try {
    write_output_file(dir / "modal.json", "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("modal.json"), std::string::npos) << e.what();
  }
  // The directory does not exist.
  EXPECT_THROW(write_output_file(dir / "missing" / "a.csv", "x"), std::runtime_error);
  // Without commit() nothing replaces the old file.
  write_output_file(dir / "b.csv", "old");
  {
    OutputFile out(dir / "b.csv");
    out.stream() << "half a fi";
  }
  EXPECT_EQ(testing::read_file(dir / "b.csv"), "old");
  EXPECT_FALSE(fs::exists(dir / "b.csv.tmp"));
  // A full device: every write fails.
  if (fs::exists("/dev/full")) {
    fs::create_symlink("/dev/full", dir / "full.csv.tmp");
    try {
      OutputFile out(dir / "full.csv");
      out.stream() << std::string(1 << 16, 'x');
      out.commit();
      FAIL() << "a write to /dev/full succeeded";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("full.csv"), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace turbodyn

#include "studies/run_log.h"

#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/spec/errors.h"

namespace turbodyn::studies {
namespace {

using ::testing::HasSubstr;

const nlohmann::json kHeader = {{"study", "a"}, {"runs", 3}};

std::filesystem::path fresh_file(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("turbodyn_run_log_test_" + name);
  std::filesystem::remove_all(d);
  return d / "log.jsonl";
}

std::string content(const std::filesystem::path& f) {
  std::ifstream in(f);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RunLog, WritesTheHeaderThenAppendsAndReadsBack) {
  const auto f = fresh_file("append");
  {
    RunLog log(f, kHeader, "another study");
    EXPECT_TRUE(log.records().empty());
    log.append({{"index", 0}});
    log.append({{"index", 2}});
  }
  EXPECT_EQ(content(f), kHeader.dump() + "\n{\"index\":0}\n{\"index\":2}\n");
  RunLog again(f, kHeader, "another study");
  ASSERT_EQ(again.records().size(), 2u);
  EXPECT_EQ(again.records()[1].at("index"), 2);
  again.append({{"index", 1}});
  EXPECT_EQ(read_run_log(f, kHeader, "").records.size(), 3u);
}

TEST(RunLog, SkipsALineCutShortByAKill) {
  const auto f = fresh_file("cut");
  std::filesystem::create_directories(f.parent_path());
  std::ofstream(f) << kHeader.dump() << "\n{\"index\":0}\n{\"ind";
  const RunLogContents c = read_run_log(f, kHeader, "");
  EXPECT_TRUE(c.has_header);
  EXPECT_EQ(c.records.size(), 1u);
}

TEST(RunLog, AppendingAfterALineCutShortStartsANewLine) {
  // Issue 20: the next record continued the cut line ("{\"ind{\"index\":1}"), so it was lost on the next resume.
  const auto f = fresh_file("cut_append");
  std::filesystem::create_directories(f.parent_path());
  std::ofstream(f) << kHeader.dump() << "\n{\"index\":0}\n{\"ind";
  {
    RunLog log(f, kHeader, "");
    log.append({{"index", 1}});
  }
  EXPECT_EQ(content(f), kHeader.dump() + "\n{\"index\":0}\n{\"index\":1}\n");
  EXPECT_EQ(read_run_log(f, kHeader, "").records.size(), 2u);
}

TEST(RunLog, ADamagedLineInsideTheLogIsRefusedWithItsLineNumber) {
  const auto f = fresh_file("damaged");
  std::filesystem::create_directories(f.parent_path());
  std::ofstream(f) << kHeader.dump() << "\n{\"index\":0}\nnot json\n{\"index\":2}\n";
  try {
    RunLog log(f, kHeader, "");
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("log.jsonl:3: a damaged line"));
  }
}

TEST(RunLog, AHeaderCutShortStartsOver) {
  const auto f = fresh_file("cut_header");
  std::filesystem::create_directories(f.parent_path());
  std::ofstream(f) << "{\"stu";
  { RunLog log(f, kHeader, ""); }
  EXPECT_EQ(content(f), kHeader.dump() + "\n");
}

TEST(RunLog, AnotherBatchsLogIsRefused) {
  const auto f = fresh_file("other");
  { RunLog log(f, kHeader, ""); }
  try {
    RunLog log(f, {{"study", "b"}}, "holds another study's runs");
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("log.jsonl: holds another study's runs"));
  }
  EXPECT_EQ(content(f), kHeader.dump() + "\n");
  EXPECT_FALSE(read_run_log(fresh_file("none"), kHeader, "").has_header);
}

}  // namespace
}  // namespace turbodyn::studies

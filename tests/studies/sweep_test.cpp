// Parameter studies: analytic trends, thread-count invariance, failing runs, resume and shards.
#include "studies/sweep.h"

#include <cmath>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "model/io/result_header.h"
#include "studies/run_log.h"
#include "tests/support/test_support.h"
#include "tests/support/temp_dir.h"

namespace turbodyn::studies {
namespace {

using ::testing::HasSubstr;

std::filesystem::path temp_dir(const std::string& name) { return turbodyn::testing::fresh_temp_dir("sweep_test_" + name); }

// A study file next to the examples (so that model = "..." resolves), written for the test.
std::filesystem::path write_study(const std::string& name, const std::string& body) {
  const auto dir = temp_dir("files_" + name);
  std::filesystem::copy_file(testing::source_dir() + "/examples/reference_linear.toml", dir / "reference_linear.toml");
  const auto f = dir / (name + ".toml");
  std::ofstream(f) << body;
  return f;
}

// Cheap runs: up to 40,000 rpm (past the first forward critical), output at 5 kHz.
const char* kCheap = R"(
[study]
model = "reference_linear.toml"
speed_window = ["0 rpm", "40000 rpm"]
fixed = ["output.sample_rate=5 kHz", "disks.compressor.unbalance=0"]
)";

// A study of the cheap runs with one parameter and one metric, the maximum of `probe`: `design` and `parameter`
// are the keys of its [design] table and of its [[parameters]] entry.
std::string one_parameter_study(const std::string& design, const std::string& parameter, const std::string& probe) {
  return std::string(kCheap) + "[design]\n" + design + "\n[[parameters]]\n" + parameter +
         "\n[[metrics]]\nkind = \"max\"\nprobe = \"" + probe + "\"\n";
}

// The ModelError of a sweep of the study `body` (file NAME.toml) that the study file loads but the sweep refuses
// before its first run; "" (and a failure) if it runs.
std::string sweep_error(const std::string& name, const std::string& body) {
  const StudySpec s = load_study(write_study(name, body));
  SweepOptions o;
  o.output_dir = temp_dir(name + "_out");
  try {
    run_sweep(s, o);
  } catch (const ModelError& e) {
    return e.what();
  }
  ADD_FAILURE() << name << ": no error";
  return "";
}

TEST(Sweep, ResponseIsLinearInTheUnbalance) {
  // A linear rotor: every response scales exactly with the single unbalance (superposition), so max |x| / U is
  // the same for every level, to the integration error. That is not the tolerance's 1e-6: through the lightly damped
  // first critical the smallest level (25 um at atol 1 nm) can be 4e-4 off a run at rtol 1e-9, atol 1e-13, for a
  // step sequence that differs from a 2e-6-accurate one by round-off only (rtol 1.0000001e-6 instead of 1e-6 puts
  // the 300 mg mm level 4.3e-4 off); a wrong level would be off by 1e-1 or more.
  const auto f = write_study("linear", one_parameter_study("kind = \"full-factorial\"",
                                                           "path = \"disks.turbine.unbalance\"\n"
                                                           "levels = [\"100 mg*mm\", \"300 mg*mm\", \"900 mg*mm\"]",
                                                           "disk.turbine.x"));
  const StudySpec s = load_study(f);
  SweepOptions o;
  o.output_dir = temp_dir("linear_out");
  const SweepResult r = run_sweep(s, o);
  ASSERT_TRUE(r.complete);
  ASSERT_EQ(r.runs.size(), 3u);
  const double per_unit = r.runs[0].metrics[0] / r.runs[0].parameters[0];
  for (const RunRecord& run : r.runs) {
    EXPECT_EQ(run.status, "ok") << run.error;
    EXPECT_NEAR(run.metrics[0] / run.parameters[0] / per_unit, 1.0, 2e-3);
  }
}

const char* kSmallLhs = R"(
[design]
kind = "latin-hypercube"
runs = 4
seed = 7
[[parameters]]
path = "bearings.compressor.k"
low = "2e7 N/m"
high = "4e7 N/m"
[[parameters]]
path = "disks.turbine.unbalance"
low = "300 mg*mm"
high = "900 mg*mm"
[[metrics]]
kind = "max_radius"
probe = "disk.compressor"
[[metrics]]
kind = "peak_1x"
probe = "disk.turbine.x"
)";

TEST(Sweep, ResultsDoNotDependOnTheThreadCount) {
  const StudySpec s = load_study(write_study("threads", std::string(kCheap) + kSmallLhs));
  SweepOptions one, two;
  one.output_dir = temp_dir("threads_1");
  one.threads = 1;
  two.output_dir = temp_dir("threads_2");
  two.threads = 2;
  const SweepResult a = run_sweep(s, one), b = run_sweep(s, two);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_EQ(a.runs[i].index, b.runs[i].index);
    EXPECT_EQ(a.runs[i].parameters, b.runs[i].parameters);
    for (std::size_t m = 0; m < a.runs[i].metrics.size(); ++m) EXPECT_EQ(a.runs[i].metrics[m], b.runs[i].metrics[m]);
  }
}

TEST(Sweep, AFailingRunIsRecordedAndTheStudyGoesOn) {
  const StudySpec s = load_study(write_study(
      "failing", one_parameter_study("kind = \"full-factorial\"",
                                     "path = \"bearings.compressor.k\"\nlevels = [\"3e7 N/m\", \"-1e7 N/m\", \"2e7 N/m\"]",
                                     "disk.compressor.x")));
  SweepOptions o;
  o.output_dir = temp_dir("failing_out");
  const SweepResult r = run_sweep(s, o);
  ASSERT_EQ(r.runs.size(), 3u);
  EXPECT_EQ(r.runs[0].status, "ok");
  EXPECT_EQ(r.runs[1].status, "failed");
  EXPECT_THAT(r.runs[1].error, HasSubstr("must not be negative"));
  EXPECT_TRUE(std::isnan(r.runs[1].metrics[0]));
  EXPECT_EQ(r.runs[2].status, "ok");
}

TEST(Sweep, ResumesWithoutRedoingFinishedRuns) {
  const StudySpec s = load_study(write_study("resume", std::string(kCheap) + kSmallLhs));
  SweepOptions o;
  o.output_dir = temp_dir("resume_out");
  const SweepResult full = run_sweep(s, o);
  ASSERT_TRUE(full.complete);
  // A killed study: the last two runs never got recorded and the last line was cut in half.
  const auto log = o.output_dir / "runs.jsonl";
  std::vector<std::string> lines;
  {
    std::ifstream in(log);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  ASSERT_EQ(lines.size(), 5u);  // header + 4 runs
  {
    std::ofstream out(log, std::ios::trunc);
    for (int i = 0; i < 3; ++i) out << lines[i] << "\n";
    out << lines[3].substr(0, lines[3].size() / 2);  // no newline: cut by the kill
  }
  const SweepResult again = run_sweep(s, o);
  EXPECT_EQ(again.resumed, 2u);
  ASSERT_TRUE(again.complete);
  ASSERT_EQ(again.runs.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(again.runs[i].metrics, full.runs[i].metrics);
}

TEST(Sweep, DoesNotResumeTheRunsOfAnEarlierVersionOfTheModel) {
  // The log was keyed by the model's file name only: an edited model resumed the old model's runs. Any change of
  // the file's bytes (here a comment) makes it another study's log.
  const auto f = write_study("edited_model", std::string(kCheap) + kSmallLhs);
  const StudySpec s = load_study(f);
  SweepOptions o;
  o.output_dir = temp_dir("edited_model_out");
  ASSERT_TRUE(run_sweep(s, o).complete);
  EXPECT_EQ(run_sweep(s, o).resumed, 4u);  // unchanged: resumed
  std::ofstream(f.parent_path() / "reference_linear.toml", std::ios::app) << "# edited\n";
  // The study is read again, as a new `turbodyn sweep` reads it (a study read before the edit runs the model it
  // read: next test).
  try {
    (void)run_sweep(load_study(f), o);
    FAIL() << "resumed the runs of the earlier model";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the model file has changed"));
  }
}

TEST(Sweep, AModelFileEditedWhileTheBatchRunsChangesNoneOfItsRuns) {
  // Each run read the model file when it started, and results.json took the file's digest when it was written: a
  // model edited during a long batch gave runs of two models under one digest. The study now reads the model once.
  const auto f = write_study("edited_during", std::string(kCheap) + kSmallLhs);
  const StudySpec s = load_study(f);
  EXPECT_EQ(s.model_digest, file_digest(s.model));
  SweepOptions before;
  before.output_dir = temp_dir("edited_during_before");
  const SweepResult a = run_sweep(s, before);
  ASSERT_TRUE(a.complete);
  std::ofstream(f.parent_path() / "reference_linear.toml", std::ios::trunc) << "not a model\n";
  SweepOptions after;
  after.output_dir = temp_dir("edited_during_after");
  const SweepResult b = run_sweep(s, after);
  ASSERT_TRUE(b.complete);
  ASSERT_EQ(b.runs.size(), a.runs.size());
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_EQ(b.runs[i].status, "ok");
    EXPECT_EQ(b.runs[i].metrics, a.runs[i].metrics);
  }
  const auto dir = temp_dir("edited_during_results");
  write_results(s, b.design, b.runs, dir, false);
  std::ifstream in(dir / "results.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("model_digest"), s.model_digest);
  EXPECT_NE(j.at("model_digest"), file_digest(s.model));
}

TEST(Sweep, ShardsCoverTheDesignAndMergeToTheSameTable) {
  const StudySpec s = load_study(write_study("shards", std::string(kCheap) + kSmallLhs));
  SweepOptions a, b;
  a.output_dir = temp_dir("shard0");
  a.shard_k = 0;
  a.shard_n = 2;
  b.output_dir = temp_dir("shard1");
  b.shard_k = 1;
  b.shard_n = 2;
  const SweepResult ra = run_sweep(s, a), rb = run_sweep(s, b);
  EXPECT_EQ(ra.runs.size() + rb.runs.size(), 4u);
  for (const RunRecord& r : ra.runs) EXPECT_EQ(r.index % 2, 0u);
  std::vector<RunRecord> merged = read_runs(s, a.output_dir);
  for (RunRecord& r : read_runs(s, b.output_dir)) merged.push_back(r);
  EXPECT_EQ(merged.size(), 4u);
  const auto dir = temp_dir("merged");
  merged[1].note = "stability: a note";
  const auto files = write_results(s, ra.design, merged, dir, false);
  EXPECT_THAT(files, ::testing::Contains("results.csv"));
  {
    std::ifstream csv(dir / "results.csv");
    std::string header, row;
    std::getline(csv, header);
    EXPECT_THAT(header, ::testing::EndsWith(",status,error,note,wall_time_s"));
    std::vector<std::string> rows;
    while (std::getline(csv, row)) rows.push_back(row);
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(std::count_if(rows.begin(), rows.end(),
                            [](const std::string& r) { return r.find(",stability: a note,") != std::string::npos; }),
              1);
  }
  // results.json says which program and which model file (by its content) made it.
  std::ifstream in(dir / "results.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("turbodyn_version"), turbodyn_version());
  EXPECT_EQ(j.at("model_digest"), file_digest(s.model));
  EXPECT_EQ(j.at("model_digest").get<std::string>().size(), 16u);
  const nlohmann::json& runs = j.at("runs");
  EXPECT_EQ(std::count_if(runs.begin(), runs.end(), [](const nlohmann::json& r) { return r.at("note") != ""; }), 1);
  EXPECT_EQ(runs.at(merged[1].index).at("note"), "stability: a note");  // the runs in index order
}

TEST(Sweep, AnotherStudysDirectoryIsRefused) {
  const StudySpec s1 = load_study(write_study("first", std::string(kCheap) + kSmallLhs));
  std::string other = std::string(kCheap) + kSmallLhs;
  other.replace(other.find("seed = 7"), 8, "seed = 8");
  const StudySpec s2 = load_study(write_study("second", other));
  SweepOptions o;
  o.output_dir = temp_dir("refuse");
  o.shard_k = 0;
  o.shard_n = 4;  // one run only
  run_sweep(s1, o);
  EXPECT_THROW(run_sweep(s2, o), ModelError);
  // A metric read over another speed window is another study too: its finished runs hold other numbers.
  std::string windowed = std::string(kCheap) + kSmallLhs;
  windowed.replace(windowed.find("probe = "), 0, "speed_window = [\"0 rpm\", \"20000 rpm\"]\n");
  const StudySpec s3 = load_study(write_study("third", windowed));
  EXPECT_THROW(run_sweep(s3, o), ModelError);
}

TEST(StudyFile, ClearErrors) {
  auto error_of = [](const std::string& body) {
    try {
      load_study(write_study("errors", body));
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error_of(std::string(kCheap) + R"(
[design]
kind = "latin-hypercub"
runs = 4
)"), HasSubstr("did you mean 'latin-hypercube'"));
  const std::string unbalance = "path = \"disks.turbine.unbalance\"\n";
  EXPECT_THAT(error_of(one_parameter_study("kind = \"latin-hypercube\"", unbalance + "low = \"1 mg*mm\"\nhigh = \"2 mg*mm\"",
                                           "disk.turbine.x")),
              HasSubstr("design.runs"));
  EXPECT_THAT(error_of(one_parameter_study("kind = \"full-factorial\"",
                                           unbalance + "low = \"1 mg*mm\"\nhigh = \"2 g*mm\"\nn_levels = 2",
                                           "disk.turbine.x")),
              HasSubstr("one unit"));
  // A probe the model does not have is found before any run starts.
  EXPECT_THAT(sweep_error("probe", one_parameter_study("kind = \"full-factorial\"",
                                                       unbalance + "levels = [\"1 mg*mm\"]", "disk.turbine.z")),
              HasSubstr("did you mean 'disk.turbine.x'"));
  // order_band: sub-synchronous metrics only, as fractions of the rotor speed below 1.
  const std::string levels = unbalance + "levels = [\"1 mg*mm\"]";
  const std::string factorial = "kind = \"full-factorial\"";
  EXPECT_THAT(error_of(one_parameter_study(factorial, levels, "disk.turbine.x") + "order_band = [0.05, 0.3]\n"),
              HasSubstr("order_band: applies to the subsync_* metrics only"));
  std::string subsync = one_parameter_study(factorial, levels, "disk.turbine.x");
  subsync.replace(subsync.find("kind = \"max\""), 12, "kind = \"subsync_max\"");
  EXPECT_THAT(error_of(subsync + "order_band = [0.3, 1.2]\n"), HasSubstr("0 < low < high < 1"));
  EXPECT_THAT(error_of(subsync + "order_band = [0.3]\n"), HasSubstr("0 < low < high < 1"));
  EXPECT_EQ(error_of(subsync + "order_band = [0.05, 0.3]\n"), "");
}

TEST(StudyFile, AlsoSetsFurtherPathsToTheParametersValue) {
  // One stiffness for both bearings: the run gets the value at the parameter's path and at each path of `also`.
  const std::string both = "path = \"bearings.compressor.k\"\nalso = [\"bearings.turbine.k\"]\n"
                           "levels = [\"2e7 N/m\", \"4e7 N/m\"]";
  const StudySpec s = load_study(write_study("also", one_parameter_study("kind = \"full-factorial\"", both, "disk.turbine.x")));
  const Design d = make_design(s.design);
  const std::vector<Override> o = run_overrides(s, d, 1);
  auto value_of = [&](const std::string& path) {
    for (const Override& v : o)
      if (v.path == path) return v.value;
    return std::string("(none)");
  };
  EXPECT_EQ(value_of("bearings.compressor.k"), value_of("bearings.turbine.k"));
  EXPECT_THAT(value_of("bearings.turbine.k"), HasSubstr("4e+07"));
  // A path the model does not read is refused before any run, naming the study file and the path.
  const std::string wrong = "path = \"bearings.compressor.k\"\nalso = [\"bearings.turbin.k\"]\nlevels = [\"2e7 N/m\"]";
  EXPECT_THAT(sweep_error("also_wrong", one_parameter_study("kind = \"full-factorial\"", wrong, "disk.turbine.x")),
              HasSubstr("also_wrong.toml: --set bearings.turbin.k="));
  // The same path twice is an error of the study file.
  const std::string twice = "path = \"bearings.compressor.k\"\nalso = [\"bearings.compressor.k\"]\nlevels = [\"2e7 N/m\"]";
  try {
    load_study(write_study("also_twice", one_parameter_study("kind = \"full-factorial\"", twice, "disk.turbine.x")));
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("also"));
    EXPECT_THAT(e.what(), HasSubstr("given twice"));
  }
}

TEST(Sweep, FixedOverridesNeedNotMakeAModelWithoutTheParameters) {
  // The fixed overrides add a disk whose position only the design gives (as an end seal's fixed length needs the
  // varied gap): the runs and the results table are made with the parameters applied.
  const std::string body = R"(
[study]
model = "reference_linear.toml"
speed_window = ["0 rpm", "20000 rpm"]
fixed = ["output.sample_rate=5 kHz", "disks.extra.mass=0.05 kg"]
[design]
kind = "full-factorial"
[[parameters]]
path = "disks.extra.z"
levels = ["60 mm", "70 mm"]
[[metrics]]
kind = "max"
probe = "disk.turbine.x"
)";
  const StudySpec s = load_study(write_study("fixed_needs_design", body));
  SweepOptions o;
  o.output_dir = temp_dir("fixed_needs_design_out");
  const SweepResult r = run_sweep(s, o);
  ASSERT_EQ(r.runs.size(), 2u);
  for (const RunRecord& run : r.runs) EXPECT_EQ(run.status, "ok") << run.error;
  EXPECT_NO_THROW(write_results(s, r.design, r.runs, o.output_dir, false));
  EXPECT_TRUE(std::filesystem::exists(o.output_dir / "results.csv"));
}

TEST(StudyFile, AFaultInTheStudysOverridesNamesTheStudyFileAndTheOverride) {
  // Issue 20 (found by the input fuzzer): the message named the override only, not the study file that holds it.
  std::string body = one_parameter_study("kind = \"full-factorial\"",
                                         "path = \"disks.turbine.unbalance\"\nlevels = [\"1 mg*mm\"]", "disk.turbine.x");
  body.replace(body.find("\"disks.compressor.unbalance=0\""), 30, "\"disks.compresor.unbalance=0\"");
  // An override that is no PATH=VALUE is located at the study's key (found by the long input fuzzer).
  std::string empty = body;
  const std::string misspelt = "\"disks.compresor.unbalance=0\"";
  empty.replace(empty.find(misspelt), misspelt.size(), "\"solver.rtol=\"");
  try {
    load_study(write_study("empty_fixed", empty));
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("empty_fixed.toml:5:"));
    EXPECT_THAT(e.what(), HasSubstr("study.fixed: --set solver.rtol=: the value after '=' is empty"));
  }
  const std::string e = sweep_error("bad_fixed", body);
  EXPECT_THAT(e, HasSubstr("bad_fixed.toml: --set disks.compresor.unbalance=0:"));
  EXPECT_THAT(e, HasSubstr("disks.compresor.z: missing required key"));  // a new disk, not a misspelt one
}

}  // namespace
}  // namespace turbodyn::studies

// The pages of the commands, built from their result JSON: a run's page (incomplete marker, escaped model name,
// maxima in µm, command, warnings, pictures) and a study's (incomplete and failed runs marked, numbers tied to
// results.json).
#include "post/report.h"
#include "model/engine/stability.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_checks.h"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace turbodyn::post {
namespace {

using ::testing::HasSubstr;

std::filesystem::path report_dir(const std::string& name) { return testing::fresh_temp_dir("report_test_" + name); }

TEST(Report, RunReportFromASummary) {
  const auto dir = report_dir("run");
  nlohmann::json j;
  j["complete"] = false;
  j["message"] = "gave up at t = 0.2 s";
  j["model"] = {{"name", "Rotor & <co>"}, {"source", "m.toml"}};
  j["overrides"] = {"speed.end=40000 rpm"};
  j["command"] = "turbodyn run m.toml -o out";
  j["options"] = {{"integrator", "cvode-bdf"}, {"t_end_s", 0.5}};
  j["t_reached_s"] = 0.2;
  j["stats"] = {{"wall_time_s", 0.1}, {"steps", 10}, {"rhs_calls", 20}};
  j["energy"] = {{"balance_error_j", 1e-9}};
  j["probes"] = {{"disk.c.x", {{"unit", "m"}, {"description", "x"}, {"max_abs", 3e-5}, {"speed_at_max_rpm", 39000.0},
                               {"time_at_max_s", 0.19}}},
                  {"bearing.b.max_contact_pressure",
                   {{"unit", "Pa"}, {"description", "p"}, {"max_abs", 4.659e9}, {"speed_at_max_rpm", 46513.0},
                    {"time_at_max_s", 1.24}, {"limit", 4.2e9}, {"limit_note", "ISO 76"},
                    {"over_limit", {{"time_s", 1.203}, {"speed_rpm", 45113.0}}}}},
                  // Films' thinnest points: one with a permissible minimum it passes, one without a limit.
                  {"bearing.t.min_film_thickness",
                   {{"unit", "m"}, {"description", "h"}, {"max_abs", 1.2e-5}, {"speed_at_max_rpm", 1000.0},
                    {"time_at_max_s", 0.01}, {"min", 0.6e-6}, {"speed_at_min_rpm", 12645.0}, {"time_at_min_s", 0.3},
                    {"limit", 2e-6}, {"limit_below", true}, {"limit_note", "permissible"},
                    {"over_limit", {{"time_s", 0.28}, {"speed_rpm", 10532.0}}}}},
                  {"bearing.c.min_film_thickness",
                   {{"unit", "m"}, {"description", "h"}, {"max_abs", 1.2e-5}, {"speed_at_max_rpm", 1000.0},
                    {"time_at_max_s", 0.01}, {"min", 4.5e-6}, {"speed_at_min_rpm", 2869.0}, {"time_at_min_s", 0.07}}}};
  j["pictures"] = {"spectrogram_disk.c.x.png"};
  j["warnings"] = {"no spectrogram of y"};
  write_run_report(dir, j, {});
  const std::string html = testing::read_file(dir / "report.html");
  turbodyn::testing::expect_contains(html, {
      "Rotor &amp; &lt;co&gt;",
      "INCOMPLETE",
      ">30.00 µm</span>",
      ">4659 MPa</span>",
      ">4200 MPa</span> <span class=\"bad\">passed from <span",
      ">45113 rpm</span>",
      "at least <span",
      ">2.000 µm</span>; smallest <span",
      ">0.6000 µm</span> at <span",
      ">12645 rpm</span> <span class=\"bad\">passed from <span",
      ">10532 rpm</span>",
      "none; smallest <span",
      ">4.500 µm</span> at <span",
      "turbodyn run m.toml -o out",
      "no spectrogram of y",
      "<img src=\"spectrogram_disk.c.x.png\"",
  });
  EXPECT_FALSE(std::filesystem::exists(dir / "report.html.tmp"));
  std::filesystem::remove_all(dir);
}

TEST(Report, RunReportListsTheLargestSubsynchronousLines) {
  const auto dir = report_dir("run_subsynchronous");
  nlohmann::json j;
  j["complete"] = true;
  j["model"] = {{"name", "m"}, {"source", "m.toml"}};
  j["options"] = {{"integrator", "cvode-bdf"}, {"t_end_s", 4.0}};
  j["t_reached_s"] = 4.0;
  j["probes"] = nlohmann::json::object();
  const nlohmann::json line = {{"amplitude", 3.43e-5}, {"frequency_hz", 698.2}, {"order", 0.4283},
                               {"speed_hz", 1630.0}, {"time_s", 2.6}};
  const nlohmann::json at_end = {{"amplitude", 2.1e-6}, {"frequency_hz", 1001.0}, {"order", 0.4004},
                                 {"speed_hz", 2500.0}, {"time_s", 3.95}};
  j["spectrogram_maxima"] = {
      {"disk.c.x", {{"amplitude", 5.18e-4}, {"unit", "m"}, {"frequency_hz", 775.5}, {"speed_hz", 775.5},
                    {"subsynchronous", line}, {"subsynchronous_at_end", at_end}}},
      {"bearing.c.fx", {{"amplitude", 2880.0}, {"unit", "N"}, {"frequency_hz", 775.5}, {"speed_hz", 775.5}}}};
  write_run_report(dir, j, {});
  const std::string html = testing::read_file(dir / "report.html");
  turbodyn::testing::expect_contains(html, {"Largest sub-synchronous lines", ">34.30 µm</span>", ">698.2 Hz</span>",
                                            ">0.43 x</span>", ">97800 rpm</span>", ">2.100 µm</span>",
                                            ">0.40 x</span>"});
  // A spectrogram without such a line (bearing.c.fx) gets no row.
  EXPECT_EQ(html.find("<code>bearing.c.fx</code>", html.find("Largest sub-synchronous lines")), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Report, StudyReportMarksIncompleteAndFailedRuns) {
  const auto dir = report_dir("study");
  nlohmann::json j;
  j["study"] = "s";
  j["model"] = "m.toml";
  j["parameters"] = {{{"path", "bearings.a.k"}, {"unit", "N/m"}}};
  j["metrics"] = {{{"name", "max_x"}, {"unit", "m"}}};
  j["runs"] = {{{"index", 0}, {"parameters", {2e7}}, {"metrics", {2.5e-5}}, {"status", "ok"}, {"error", ""}},
               {{"index", 1}, {"parameters", {3e7}}, {"metrics", {nullptr}}, {"status", "failed"},
                {"error", "boom <x>"}}};
  j["runs_total"] = 3;
  j["runs_recorded"] = 2;
  j["runs_failed"] = 1;
  j["sensitivity"] = nlohmann::json::object();
  write_study_report(dir, j, "sweep", {"turbodyn sweep s.toml", {}, {"results.csv"}, {}});
  const std::string html = testing::read_file(dir / "report.html");
  turbodyn::testing::expect_contains(html, {
      "INCOMPLETE STUDY: 2 of 3 runs",
      "0 run(s) incomplete",
      "data-pointer=\"/runs/0/metrics/0\"",
      ">25.00</span>",  // in µm, as the column header says
      "max_x [µm]",
      "boom &lt;x&gt;",
  });
  std::filesystem::remove_all(dir);
}

TEST(Report, StabilityReportNamesTheOnsetsHalvingsFoundAnewFromRest) {
  // stability.json's onset with a halving whose steady state was found anew from rest (a fold below it).
  const auto dir = report_dir("stability_restart");
  nlohmann::json j;
  j["model"] = {{"name", "m"}, {"source", "m.toml"}};
  j["min_rotor_share"] = 0.5;
  j["onset"] = {{"speed_rpm", 61000.0}, {"resolution_rpm", 312.5}, {"halvings", 6}, {"at_first_speed", false},
                {"halving_restarted_rpm", {60500.0}}};
  j["assumptions"] = nlohmann::json::array();
  j["results"] = nlohmann::json::array();
  write_stability_report(dir, j, {"turbodyn stability m.toml", {}, {}, {}});
  turbodyn::testing::expect_contains(
      testing::read_file(dir / "report.html"),
      {"61000 rpm, within 312.5 rpm below", std::string("The halving at 60500 rpm ") + kHalvingRestartedText});
  std::filesystem::remove_all(dir);
}

TEST(Report, StudyReportNamesTheSpeedsItsStabilityMetricsAnalysed) {
  // A stability metric's grid (results.json's speeds_rpm, onset_resolution_rpm) and the caveat that goes with it.
  const auto dir = report_dir("study_stability");
  nlohmann::json j;
  j["study"] = "s";
  j["model"] = "m.toml";
  j["parameters"] = {{{"path", "bearings.a.preload"}, {"unit", "N"}}};
  j["metrics"] = {{{"name", "onset"}, {"unit", "rpm"}, {"speeds_rpm", {10000.0, 30000.0, 50000.0}},
                   {"onset_resolution_rpm", 312.5}},
                  {{"name", "growth"}, {"unit", "1/s"}, {"speeds_rpm", {50000.0}}},
                  {{"name", "max_x"}, {"unit", "m"}}};
  j["runs"] = {{{"index", 0}, {"parameters", {40.0}}, {"metrics", {45000.0, 12.0, 1e-5}}, {"status", "ok"}}};
  j["runs_total"] = 1;
  j["runs_recorded"] = 1;
  j["runs_failed"] = 0;
  write_study_report(dir, j, "sweep", {"turbodyn sweep s.toml", {}, {"results.csv"}, {}});
  const std::string html = testing::read_file(dir / "report.html");
  turbodyn::testing::expect_contains(html, {
      "Stability metrics",
      "onset: the linearised model analysed at 3 speeds from",
      "data-pointer=\"/metrics/0/speeds_rpm/2\"",
      "20000 rpm apart",
      "data-pointer=\"/metrics/0/onset_resolution_rpm\"",
      "an unstable window narrower than their spacing",
      "growth: the linearised model analysed at 1 speed, ",
  });
  EXPECT_THAT(html, ::testing::Not(HasSubstr("max_x: the linearised")));
  // A hand-edited file with something else in the list: shown as missing, not a crash.
  j["metrics"][0]["speeds_rpm"] = {"fast", nullptr};
  EXPECT_NO_THROW(write_study_report(dir, j, "sweep", {"turbodyn sweep s.toml", {}, {"results.csv"}, {}}));
  EXPECT_THAT(testing::read_file(dir / "report.html"),
              HasSubstr("onset: the linearised model analysed at 2 speeds from"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace turbodyn::post

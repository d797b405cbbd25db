#include "studies/run_evaluation.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/engine/speed_profile.h"
#include "tests/support/test_support.h"
#include "model/spec/constants.h"

namespace turbodyn::studies {
namespace {

using ::testing::HasSubstr;


// The reference rotor up to 30,000 rpm, output at 5 kHz: a run of a few seconds of wall time at most.
StudyCommon cheap_study() {
  StudyCommon s;
  s.model = testing::source_dir() + "/examples/reference_linear.toml";
  s.speed_window_max = 30000 * kRpmToRadPerS;
  s.fixed = {{"output.sample_rate", "5 kHz"}};
  return s;
}

MetricSpec probe_metric(const std::string& kind, const std::string& probe) {
  MetricSpec m;
  m.name = kind;
  m.kind = kind;
  m.probe = probe;
  return m;
}

TEST(RunEvaluation, TheRunStopsAtTheWindowAndGivesItsMetrics) {
  const StudyCommon s = cheap_study();
  const RunupRun run = run_runup(s, s.fixed);
  ASSERT_TRUE(run.result.complete) << run.result.message;
  EXPECT_NEAR(run.options.t_end, time_at_speed(run.spec.speed, s.speed_window_max), 1e-12);
  EXPECT_LT(run.options.t_end, SpeedFunction(run.spec.speed).duration());

  const RunRecord r =
      evaluate_run(s, {probe_metric("max", "disk.turbine.x"), probe_metric("summary", "no.such.key")}, s.fixed);
  EXPECT_EQ(r.status, "ok") << r.error;
  ASSERT_EQ(r.metrics.size(), 2u);
  EXPECT_GT(r.metrics[0], 0.0);
  EXPECT_TRUE(std::isnan(r.metrics[1]));
  EXPECT_GT(r.wall_time, 0.0);
}

TEST(RunEvaluation, AFailingRunIsReportedNotThrown) {
  StudyCommon s = cheap_study();
  std::vector<Override> o = s.fixed;
  o.push_back({"bearings.compressor.k", "12 furlongs"});
  const RunRecord r = evaluate_run(s, {probe_metric("max", "disk.turbine.x")}, o);
  EXPECT_EQ(r.status, "failed");
  EXPECT_THAT(r.error, HasSubstr("furlongs"));
  ASSERT_EQ(r.metrics.size(), 1u);
  EXPECT_TRUE(std::isnan(r.metrics[0]));
  EXPECT_THROW(run_runup(s, o), ModelError);
}

TEST(RunEvaluation, ARunWhoseBallBearingPassesTheStaticPressureLimitSaysSoInItsNote) {
  // The reference ball bearings with 8,000 N of preload at the compressor: about 1,700 N on each of its balls,
  // above ISO 76's 4,200 MPa from the start (docs/ball-bearing.md, "Contact pressure"); 2 ms of the ramp.
  StudyCommon s;
  s.model = testing::source_dir() + "/examples/reference_ball.toml";
  s.fixed = {{"bearings.compressor.preload", "8000 N"}, {"speed.duration", "2 s"}, {"speed.end", "2000 rpm"}};
  s.speed_window_max = 2 * kRpmToRadPerS;  // 2 ms of the 2-s ramp to 2,000 rpm
  const RunRecord r = evaluate_run(s, {probe_metric("max", "bearing.compressor.max_contact_pressure")}, s.fixed);
  EXPECT_EQ(r.status, "ok") << r.error;
  EXPECT_GT(r.metrics[0], 4.2e9);
  EXPECT_THAT(r.note, HasSubstr("bearing.compressor.max_contact_pressure is first above its limit of 4200 MPa at 0 rpm"));
  EXPECT_THAT(r.note, ::testing::Not(HasSubstr("bearing.turbine")));  // 40 N of preload: about 1,000 MPa
}

TEST(RunEvaluation, TimeAtSpeedOnARamp) {
  SpeedProfile p;
  p.start = 100.0;
  p.end = 1100.0;
  p.duration = 10.0;
  EXPECT_EQ(time_at_speed(p, 50.0), 0.0);
  EXPECT_NEAR(time_at_speed(p, 600.0), 5.0, 1e-9);
  EXPECT_EQ(time_at_speed(p, 2000.0), 10.0);
}

}  // namespace
}  // namespace turbodyn::studies

// The stability metrics of a study (studies/stability_metrics.h) against the closed form of a rigid rotor whose
// bearings' cross-coupled stiffness grows with speed, and what a study with them refuses.
#include "studies/stability_metrics.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "model/engine/stability.h"
#include "model/io/model_file.h"
#include "model/io/overrides.h"
#include "model/spec/constants.h"
#include "model/spec/errors.h"
#include "studies/run_evaluation.h"
#include "studies/sweep.h"
#include "tests/support/test_support.h"

namespace turbodyn::studies {
namespace {

using ::testing::HasSubstr;


// tests/data/stability/rigid_cross_coupled.toml: a rigid rotor symmetric about its middle on two equal bearings of
// stiffness k, damping c and a cross-coupled stiffness q = q1 * speed (kxy = q, kyx = -q, linear in the speed
// between the table's entries at 0 and 20,000 rad/s).
struct RigidRotor {
  MachineSpec spec;
  double mass = 0.0;  // kg, the whole rotor
  double k = 3e7, c = 100.0, q1 = 100.0;
};

RigidRotor rigid_rotor() {
  RigidRotor r;
  r.spec = load_model(testing::source_dir() + "/tests/data/stability/rigid_cross_coupled.toml");
  const ShaftSection& shaft = r.spec.shaft.at(0);
  r.mass = 2 * 0.119 + r.spec.materials.at(shaft.material).density * M_PI / 4 * shaft.outer_diameter *
                           shaft.outer_diameter * shaft.length;
  for (const BearingSpec& b : r.spec.bearings) {  // the constants above are the file's
    EXPECT_EQ(b.linear.k[0].at(0), r.k);
    EXPECT_EQ(b.linear.c[0].at(0), r.c);
    EXPECT_DOUBLE_EQ(b.linear.k[1].at(1) / b.linear.speeds.at(1), r.q1);
  }
  return r;
}

// The cylindrical whirl z = x + i y of the rigid rotor: M z'' + 2c z' + 2(k - i q) z = 0; its forward root.
std::complex<double> forward_root(const RigidRotor& r, double speed) {
  const std::complex<double> b = 2 * r.c, c0 = 2.0 * std::complex<double>(r.k, -r.q1 * speed);
  const std::complex<double> d = std::sqrt(b * b - 4.0 * r.mass * c0);
  const std::complex<double> s1 = (-b + d) / (2 * r.mass), s2 = (-b - d) / (2 * r.mass);
  return s1.imag() > 0 ? s1 : s2;
}

MetricSpec stability_metric(const std::string& kind, double low_rpm, double high_rpm, int count) {
  MetricSpec m;
  m.name = m.kind = kind;
  m.speed_min = low_rpm * kRpmToRadPerS;
  m.speed_max = high_rpm * kRpmToRadPerS;
  m.speed_count = count;
  return m;
}

TEST(StabilityMetrics, ARigidRotorOnCrossCoupledBearingsLosesStabilityWhereTheClosedFormSays) {
  // Marginal stability of the cylindrical forward whirl: s = i w with M w^2 = 2k and 2c w = 2q, so the onset speed is
  // c sqrt(2k/M) / q1, 73,426 rpm here (the Jeffcott rotor's destabilising cross-coupled stiffness, q < c w_n:
  // Vance, Rotordynamics of Turbomachinery, 1988). The window's top (110,000 rpm) stays below the conical modes'
  // onset (their frequency sqrt(2 k a^2 / I_d) is 1.6 times higher). The onset is bracketed by the grid and halved
  // six times: found to 1/64 of the grid's step, the last speed found growing returned, so the marginal speed lies
  // within [value - step/64, value], up to 1e-3: the criterion of growth (a damping ratio below -1e-5,
  // StabilityMode::grows) lies some 60 rpm (8e-4) above it, the bending less. Growth rate, frequency and damping
  // ratio of the fastest mode at the window's top: the forward root.
  const RigidRotor r = rigid_rotor();
  constexpr double kLow = 10000, kHigh = 110000, kTolerance = 1e-3;
  constexpr int kCount = 11;
  const std::vector<MetricSpec> metrics = {stability_metric("stability_onset_speed", kLow, kHigh, kCount),
                                           stability_metric("stability_growth", kLow, kHigh, kCount),
                                           stability_metric("stability_growth_speed", kLow, kHigh, kCount),
                                           stability_metric("stability_frequency", kLow, kHigh, kCount),
                                           stability_metric("stability_damping", kLow, kHigh, kCount)};
  std::string error;
  const std::vector<double> v = evaluate_stability_metrics(r.spec, metrics, &error);
  EXPECT_EQ(error, "");
  const double onset = r.c * std::sqrt(2 * r.k / r.mass) / r.q1 / kRpmToRadPerS;
  const double step = (kHigh - kLow) / (kCount - 1) / 64;
  const std::complex<double> top = forward_root(r, kHigh * kRpmToRadPerS);
  std::printf("[ rigid rotor ] onset %.1f rpm (closed form %.1f, resolution %.1f rpm); at %.0f rpm growth %.3f 1/s "
              "(%.3f), %.2f Hz (%.2f), damping ratio %.5f (%.5f)\n",
              v[0], onset, step, kHigh, v[1], top.real(), v[3], top.imag() / (2 * M_PI), v[4],
              -top.real() / std::abs(top));
  EXPECT_GE(v[0], onset * (1 - kTolerance));
  EXPECT_LE(v[0] - step, onset * (1 + kTolerance));
  EXPECT_NEAR(v[1] / top.real(), 1.0, 1e-2);  // the growth is a small difference of large terms
  EXPECT_DOUBLE_EQ(v[2], kHigh);
  EXPECT_NEAR(v[3] / (top.imag() / (2 * M_PI)), 1.0, kTolerance);
  EXPECT_NEAR(v[4] / (-top.real() / std::abs(top)), 1.0, 1e-2);
}

TEST(StabilityMetrics, WithoutAGrowingModeTheOnsetIsUndefinedAndTheGrowthNegative) {
  // Below the onset every mode decays: no onset speed (NaN, an empty cell in the results), the largest growth rate
  // negative and, on this rotor, the cylindrical forward mode's (the least damped).
  const RigidRotor r = rigid_rotor();
  std::string error;
  const std::vector<double> v = evaluate_stability_metrics(r.spec,
                                                           {stability_metric("stability_onset_speed", 10000, 60000, 3),
                                                            stability_metric("stability_growth", 10000, 60000, 3)},
                                                           &error);
  EXPECT_EQ(error, "");
  EXPECT_TRUE(std::isnan(v[0]));
  EXPECT_NEAR(v[1] / forward_root(r, 60000 * kRpmToRadPerS).real(), 1.0, 1e-2);
}

TEST(StabilityMetrics, AFrequencyLimitCountsOnlyTheModesBelowIt) {
  // The rigid rotor's cylindrical forward whirl (1,224 Hz) is its only growing mode: with frequency_max above it the
  // onset is the one without a limit; below it no mode counts (onset and growth undefined).
  const RigidRotor r = rigid_rotor();
  MetricSpec onset = stability_metric("stability_onset_speed", 10000, 110000, 11);
  MetricSpec growth = stability_metric("stability_growth", 10000, 110000, 11);
  std::string error;
  const double free_onset = evaluate_stability_metrics(r.spec, {onset}, &error).at(0);
  onset.frequency_max = growth.frequency_max = 1500.0;
  std::vector<double> v = evaluate_stability_metrics(r.spec, {onset, growth}, &error);
  EXPECT_EQ(v[0], free_onset);
  EXPECT_GT(v[1], 0.0);
  onset.frequency_max = growth.frequency_max = 1000.0;
  v = evaluate_stability_metrics(r.spec, {onset, growth}, &error);
  EXPECT_TRUE(std::isnan(v[0]));
  EXPECT_TRUE(std::isnan(v[1]));
  EXPECT_EQ(error, "");
}

TEST(StabilityMetrics, AStudysRunOfStabilityMetricsIsTheAnalysisOfItsModel) {
  // A study's run (evaluate_run) with only a stability metric: the value evaluate_stability_metrics gives for the
  // same model file, status ok. On examples/reference_ball.toml the ball set's one-lobed wave grows from about
  // 55,000 rpm (docs/ball-bearing.md, "Linearised stability").
  StudyCommon s;
  s.model = testing::source_dir() + "/examples/reference_ball.toml";
  const MetricSpec m = stability_metric("stability_onset_speed", 50000, 60000, 2);
  const RunRecord rec = evaluate_run(s, {m}, {});
  EXPECT_EQ(rec.status, "ok") << rec.error;
  EXPECT_EQ(rec.note, "");  // every speed continued from the one below
  std::string error;
  const std::vector<double> v = evaluate_stability_metrics(load_model(s.model), {m}, &error);
  EXPECT_EQ(rec.metrics.at(0), v.at(0));
  std::printf("[ reference_ball ] onset %.0f rpm\n", v[0]);
  EXPECT_GT(v[0], 50000);
  EXPECT_LT(v[0], 60000);
}

TEST(StabilityMetrics, AMetricsContinuationStepsAreThoseOfItsAnalyses) {
  // continuation_steps = 0.5: each speed's steady state continued in half the steps, as `turbodyn stability
  // --continuation-steps 0.5` does, so that a study's user checks that the states do not depend on the steps
  // (docs/studies.md, "Stability metrics"). The metric is the analyses' with StabilityOptions::
  // continuation_step_factor 0.5 to the last bit, and not the regular steps' (other Newton paths, another round-off).
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  MetricSpec m = stability_metric("stability_growth", 10000, 12000, 2);
  m.continuation_steps = 0.5;
  std::string error;
  const double half = evaluate_stability_metrics(spec, {m}, &error).at(0);
  EXPECT_EQ(error, "");
  m.continuation_steps = 1.0;
  const double regular = evaluate_stability_metrics(spec, {m}, &error).at(0);
  StabilityOptions o;
  o.min_rotor_share = m.min_rotor_share;
  o.continuation_step_factor = 0.5;
  const StabilityPoint low = analyse_stability(spec, 10000 * kRpmToRadPerS, o),
                       high = analyse_stability(spec, 12000 * kRpmToRadPerS, o, &low);
  const StabilityModeFilter counts{m.min_rotor_share, 0.0};
  double expected = std::numeric_limits<double>::quiet_NaN();
  for (const StabilityPoint* p : {&low, &high})
    for (const StabilityMode& mode : p->modes)
      if (counts.counts(mode) && !(mode.growth_rate <= expected)) expected = mode.growth_rate;
  std::printf("[ reference_ball, 10,000-12,000 rpm ] largest growth rate %.12g 1/s in half the steps, %.12g in the "
              "regular ones\n", half, regular);
  EXPECT_EQ(half, expected);
  EXPECT_NE(half, regular);
  EXPECT_NEAR(half, regular, 1e-3);  // the same state
}

TEST(StabilityMetrics, ARunSaysWhereItsSteadyStateWasFoundAnewFromRest) {
  // The study's runs of bench/validation_studies.sh ball_stability have no such speed; the engine's halvings and
  // sweeps report them (Stability.TheOnsetsHalvingsSayWhich..., Stability.AnAnalysisContinuedFromALowerSpeed...).
  EXPECT_EQ(stability_restart_note({}), "");
  const std::string note = stability_restart_note({61000 * kRpmToRadPerS, 52500 * kRpmToRadPerS});
  EXPECT_THAT(note, HasSubstr("found anew from rest at 52500 rpm, 61000 rpm"));
}

TEST(StabilityMetrics, AnAnalysisThatFailsEndsTheSpeedsThereAndTheOnsetIsStillHalvedBelow) {
  // With 200 N of preload and an outer groove of 0.56 ball diameters, Eq. 23's rolling state folds back at
  // 77,450 rpm (the same speed to 10 rpm from sweeps starting at 10,000 and at 50,000 rpm and in steps of 1,000 rpm):
  // the analysis at 90,000 rpm finds no steady state. The metrics are taken over the speeds below; the onset,
  // bracketed by 50,000 and 70,000 rpm, is still halved there; the error names the speed that failed. (Until the
  // twenty-fifth stop this was 300 N at 20 deg, whose fold at 82,710 rpm was on the branch of the rolling state that
  // a run does not take; docs/ball-bearing.md, "A sweep over speeds".)
  StudyCommon s;
  s.model = testing::source_dir() + "/examples/reference_ball.toml";
  const MachineSpec spec = load_model(s.model, {parse_override("bearings.compressor.preload=200 N"),
                                                parse_override("bearings.turbine.preload=200 N"),
                                                parse_override("bearings.compressor.outer_groove_ratio=0.56"),
                                                parse_override("bearings.turbine.outer_groove_ratio=0.56")});
  std::string error;
  const std::vector<double> v =
      evaluate_stability_metrics(spec,
                                 {stability_metric("stability_onset_speed", 50000, 90000, 3),
                                  stability_metric("stability_growth_speed", 50000, 90000, 3)},
                                 &error);
  std::printf("[ 200 N, f_o 0.56 ] onset %.1f rpm, fastest at %.0f rpm; %s\n", v[0], v[1], error.c_str());
  EXPECT_THAT(error, HasSubstr("stability analysis at 90000 rpm: element 'compressor': no steady state found"));
  EXPECT_GT(v[0], 50000);
  EXPECT_LT(v[0], 70000);  // not the grid's 70,000 rpm: halved
  EXPECT_LE(v[1], 70000);
}

TEST(StabilityMetrics, TheExampleStudiesReadAndTheirModelsAreOnesTheAnalysisTakes) {
  // examples/study_reference_ball_stability*.toml (docs/studies.md): stability metrics only, over the study's window,
  // on models the analysis covers; their designs are run by bench/validation_studies.sh ball_stability.
  for (const auto& [file, count] : {std::pair<std::string, int>{"study_reference_ball_stability.toml", 15},
                                    std::pair<std::string, int>{"study_reference_ball_stability_global.toml", 8},
                                    std::pair<std::string, int>{"study_reference_ball_stability_mount.toml", 8}}) {
    SCOPED_TRACE(file);
    const StudySpec s = load_study(testing::source_dir() + "/examples/" + file);
    ASSERT_GE(s.metrics.size(), 3u);
    for (const MetricSpec& m : s.metrics) {
      EXPECT_TRUE(is_stability_metric(m.kind)) << m.name;
      EXPECT_EQ(m.speed_count, count);
      EXPECT_DOUBLE_EQ(m.speed_min, 10000 * kRpmToRadPerS);
      EXPECT_DOUBLE_EQ(m.speed_max, 150000 * kRpmToRadPerS);
    }
    EXPECT_NO_THROW(
        check_stability_metrics(s, s.metrics, load_study_model(s, run_overrides(s, make_design(s.design), 0))));
  }
}

std::filesystem::path study_file(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "turbodyn_stability_metrics_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

std::string load_error(const std::filesystem::path& file) {
  try {
    (void)load_study(file);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(StabilityMetrics, AStudyOfOtherSpeedsDoesNotResumeTheRunsAndAnyThreadCountGivesTheSameNumbers) {
  // The speeds and the rotor share make the metric's numbers: a study that changes them is another study, and its
  // output directory's finished runs are not taken for its own (one file name: the study's name is its stem). On the
  // rigid rotor (milliseconds per design).
  const std::string body = "[study]\nmodel = \"" + testing::source_dir() +
                           "/tests/data/stability/rigid_cross_coupled.toml\"\n"
                           "speed_window = [\"10000 rpm\", \"110000 rpm\"]\n[design]\nkind = \"full-factorial\"\n"
                           "[[parameters]]\npath = \"bearings.left.c\"\nalso = [\"bearings.right.c\"]\n"
                           "levels = [\"100 N*s/m\", \"200 N*s/m\"]\n[[metrics]]\nkind = \"stability_growth\"\n";
  SweepOptions o;
  o.output_dir = std::filesystem::temp_directory_path() / "turbodyn_stability_metrics_test" / "resume";
  std::filesystem::remove_all(o.output_dir);
  const SweepResult first = run_sweep(load_study(study_file("r.toml", body + "speed_count = 3\n")), o);
  ASSERT_TRUE(first.complete);
  EXPECT_GT(first.runs.at(0).metrics.at(0), 0.0);  // 100 N s/m: unstable at the top (onset 73,426 rpm)
  EXPECT_LT(first.runs.at(1).metrics.at(0), 0.0);  // 200 N s/m: stable to 110,000 rpm (149.8 N s/m suffice)
  EXPECT_EQ(run_sweep(load_study(study_file("r.toml", body + "speed_count = 3\n")), o).resumed, 2u);
  EXPECT_THROW(run_sweep(load_study(study_file("r.toml", body + "speed_count = 4\n")), o), ModelError);
  // One thread or two: the same numbers (each design is its own analysis).
  SweepOptions one = o;
  one.output_dir = o.output_dir.parent_path() / "resume_one_thread";
  one.threads = 1;
  std::filesystem::remove_all(one.output_dir);
  const SweepResult serial = run_sweep(load_study(study_file("r.toml", body + "speed_count = 3\n")), one);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(serial.runs.at(i).metrics.at(0), first.runs.at(i).metrics.at(0));
  EXPECT_THROW(run_sweep(load_study(study_file("r.toml", body + "speed_count = 3\nmin_rotor_share = 0.5\n")), o),
               ModelError);
  EXPECT_THROW(run_sweep(load_study(study_file("r.toml", body + "speed_count = 3\ncontinuation_steps = 0.5\n")), o),
               ModelError);
}

TEST(StabilityMetrics, AStudysResultsNameTheSpeedsItsStabilityMetricsAnalysed) {
  // A design is stable at the speeds analysed only: results.json lists them per stability metric, and the onset's
  // resolution (the grid's step halved kStabilityOnsetBisections times). On the rigid rotor, 3 speeds over
  // 10,000-110,000 rpm: the onset of the closed form (73,426 rpm) lies between the second and third, and the metric
  // finds it from above within that resolution (and the growth criterion's 0.01 1/s, about 60 rpm).
  const std::string body = "[study]\nmodel = \"" + testing::source_dir() +
                           "/tests/data/stability/rigid_cross_coupled.toml\"\n"
                           "speed_window = [\"10000 rpm\", \"110000 rpm\"]\n"
                           "[design]\nkind = \"full-factorial\"\n[[parameters]]\npath = \"bearings.left.c\"\n"
                           "also = [\"bearings.right.c\"]\nlevels = [\"100 N*s/m\"]\n"
                           "[[metrics]]\nkind = \"stability_onset_speed\"\nspeed_count = 3\n"
                           "[[metrics]]\nkind = \"stability_growth\"\nspeed_count = 3\n";
  const StudySpec study = load_study(study_file("speeds.toml", body));
  SweepOptions o;
  o.output_dir = std::filesystem::temp_directory_path() / "turbodyn_stability_metrics_test" / "speeds";
  std::filesystem::remove_all(o.output_dir);
  const SweepResult r = run_sweep(study, o);
  ASSERT_TRUE(r.complete);
  write_results(study, r.design, r.runs, o.output_dir, false);
  std::ifstream in(o.output_dir / "results.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& onset = j.at("metrics").at(0);
  ASSERT_EQ(onset.at("kind"), "stability_onset_speed");
  const std::vector<double> speeds = onset.at("speeds_rpm").get<std::vector<double>>();
  ASSERT_EQ(speeds.size(), 3u);
  EXPECT_NEAR(speeds[0], 10000, 1e-6);
  EXPECT_NEAR(speeds[1], 60000, 1e-6);
  EXPECT_NEAR(speeds[2], 110000, 1e-6);
  const double resolution = onset.at("onset_resolution_rpm").get<double>();
  EXPECT_NEAR(resolution, 50000.0 / 64, 1e-6);
  EXPECT_EQ(j.at("metrics").at(1).at("speeds_rpm"), onset.at("speeds_rpm"));
  EXPECT_FALSE(j.at("metrics").at(1).contains("onset_resolution_rpm"));  // the growth is taken at the grid's speeds
  const double found = r.runs.at(0).metrics.at(0), closed_form = 73426;
  EXPECT_GT(found, closed_form - 60);
  EXPECT_LT(found, closed_form + resolution + 60);
}

TEST(StabilityMetrics, AStudyRefusesWhatTheAnalysisCannotTake) {
  const std::string head = "[study]\nmodel = \"" + testing::source_dir() + "/examples/MODEL\"\n" +
                           "[design]\nkind = \"full-factorial\"\n[[parameters]]\npath = \"disks.turbine.unbalance\"\n"
                           "levels = [\"580 mg*mm\"]\n[[metrics]]\nkind = \"stability_growth\"\n";
  const auto with = [&](const std::string& model, const std::string& keys) {
    std::string t = head;
    t.replace(t.find("MODEL"), 5, model);
    return t + keys;
  };
  // No speeds: neither the metric nor the study has a speed window.
  EXPECT_THAT(load_error(study_file("a.toml", with("reference_ball.toml", ""))),
              HasSubstr("metrics[0].speed_window: missing"));
  // A probe, a threshold, a share outside [0, 1], a single speed.
  const std::string window = "speed_window = [\"10000 rpm\", \"20000 rpm\"]\n";
  EXPECT_THAT(load_error(study_file("b.toml", with("reference_ball.toml", window + "probe = \"disk.turbine.x\"\n"))),
              HasSubstr("metrics[0].probe: kind = \"stability_growth\" reads no probe"));
  EXPECT_THAT(load_error(study_file("c.toml", with("reference_ball.toml", window + "threshold = \"1 um\"\n"))),
              HasSubstr("metrics[0].threshold"));
  EXPECT_THAT(load_error(study_file("d.toml", with("reference_ball.toml", window + "min_rotor_share = 2\n"))),
              HasSubstr("metrics[0].min_rotor_share: must lie in [0, 1]"));
  EXPECT_THAT(load_error(study_file("e.toml", with("reference_ball.toml", window + "speed_count = 1\n"))),
              HasSubstr("metrics[0].speed_count"));
  EXPECT_THAT(load_error(study_file("g.toml", with("reference_ball.toml", window + "frequency_max = \"0 Hz\"\n"))),
              HasSubstr("metrics[0].frequency_max"));
  EXPECT_THAT(load_error(study_file("h.toml", with("reference_ball.toml", window + "continuation_steps = 0\n"))),
              HasSubstr("metrics[0].continuation_steps: must be positive"));
  EXPECT_THAT(load_error(study_file("i.toml", with("reference_ball.toml", window + "continuation_steps = 1.5\n"))),
              HasSubstr("metrics[0].continuation_steps: must lie in (0, 1]"));
  // A model the analysis does not cover: refused before any run, naming the study, the metric and the bearing.
  const std::filesystem::path ring = study_file("f.toml", with("reference_floating_ring.toml", window));
  const StudySpec study = load_study(ring);
  SweepOptions o;
  o.output_dir = ring.parent_path() / "out_f";
  try {
    (void)run_sweep(study, o);
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("f.toml: metrics[0].kind: stability_growth: the linearised stability analysis "
                                    "cannot take this model: bearing 'compressor'"));
  }
  EXPECT_FALSE(std::filesystem::exists(o.output_dir / "runs.jsonl"));
}

}  // namespace
}  // namespace turbodyn::studies

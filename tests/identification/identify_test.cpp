// Identification (`turbodyn identify`): known answers from synthetic measurements, bad measured files, and
// determinism across thread counts (docs/identification.md, "Tests").
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "identification/identify.h"
#include "identification/identify_study.h"
#include "identification/measurement.h"
#include "identification/report.h"
#include "model/io/model_file.h"
#include "model/io/result_header.h"
#include "model/io/toml_reader.h"
#include "model/rotor/response.h"
#include "model/rotor/rotor.h"
#include "model/engine/integrator.h"
#include "model/io/timeseries_file.h"
#include "studies/channels.h"
#include "studies/run_log.h"
#include "tests/support/temp_dir.h"

namespace turbodyn::identification {
namespace {

// Estimates must lie within this many of their reported standard deviations of the truth (a 3-sigma band:
// 99.7 % for a Gaussian estimate; each test draws one fixed noise realisation, so it is deterministic).
constexpr double kSigmas = 3.0;

std::filesystem::path source(const std::string& rel) { return std::filesystem::path(TURBODYN_SOURCE_DIR) / rel; }

std::filesystem::path scratch(const std::string& name) {
  return turbodyn::testing::fresh_temp_dir("identify_test_" + name);
}

void write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
}

// ---------------------------------------------------------------------------------------------- linear Jeffcott

// Noisy 1x spectra of the Jeffcott rotor (k = 2e5 N/m, c = 200 N s/m, both bearings) at 1000 .. 6000 rpm: per
// speed a background bin at 0.5 f_d and the 1x line, additive Gaussian noise of 1 um (about 1 % of the peak).
constexpr double kTrueK = 2e5, kTrueC = 200.0, kJeffcottNoise = 1e-6;

std::filesystem::path jeffcott_study(const std::filesystem::path& dir) {
  const MachineSpec spec = load_model(source("tests/data/identification/jeffcott.toml"));
  const Rotor rotor = build_rotor(spec);
  const int x = rotor.dof(rotor.disks[0].node, kX), y = rotor.dof(rotor.disks[0].node, kY);
  std::mt19937_64 rng(42);
  std::normal_distribution<double> noise(0.0, kJeffcottNoise);
  std::ostringstream csv;
  csv << "speed [rpm],frequency [Hz],x [um],y [um]\n" << std::setprecision(10);
  for (int i = 0; i <= 100; ++i) {
    const double rpm = 1000.0 + 50.0 * i, fd = rpm / 60.0;
    const SteadyResponse r = unbalance_response(rotor, 2.0 * M_PI * fd);
    csv << rpm << ',' << 0.5 * fd << ',' << 1e6 * std::abs(noise(rng)) << ',' << 1e6 * std::abs(noise(rng)) << '\n';
    csv << rpm << ',' << fd << ',' << 1e6 * std::abs(std::abs(r.q(x)) + noise(rng)) << ','
        << 1e6 * std::abs(std::abs(r.q(y)) + noise(rng)) << '\n';
  }
  write(dir / "jeffcott_spectra.csv", csv.str());
  const std::string study = "[identify]\nmodel = \"" + source("tests/data/identification/jeffcott.toml").string() +
                            "\"\n" + input::read_text_file(source("tests/data/identification/jeffcott_study_keys.toml"), "study");
  write(dir / "study.toml", study);
  return dir / "study.toml";
}

TEST(Identify, LinearJeffcottBearingStiffnessAndDampingFromNoisyUnbalanceResponse) {
  const auto dir = scratch("jeffcott");
  const IdentifyStudy study = load_identify_study(jeffcott_study(dir));
  const IdentifyResult r = identify(study);
  ASSERT_TRUE(r.covariance_ok) << r.covariance_message;
  EXPECT_TRUE(r.converged) << r.full_report;
  std::cout << "k = " << r.estimate[0] << " +- " << r.std_dev[0] << " N/m (true " << kTrueK << "), c = "
            << r.estimate[1] << " +- " << r.std_dev[1] << " N s/m (true " << kTrueC << "), correlation "
            << r.correlation(0, 1) << ", residual sigma " << std::sqrt(r.residual_variance) << ", " << r.model_runs
            << " model runs\n";
  EXPECT_LT(std::abs(r.estimate[0] - kTrueK), kSigmas * r.std_dev[0]);
  EXPECT_LT(std::abs(r.estimate[1] - kTrueC), kSigmas * r.std_dev[1]);
  // "Within noise": with 1 um noise on ~100 um peaks, k to 1 % and c to 5 %.
  EXPECT_LT(std::abs(r.estimate[0] / kTrueK - 1.0), 0.01);
  EXPECT_LT(std::abs(r.estimate[1] / kTrueC - 1.0), 0.05);
  // The residuals were scaled by the true noise, so their standard deviation comes out near 1.
  EXPECT_NEAR(std::sqrt(r.residual_variance), 1.0, 0.2);
  // Outputs, and fitted.toml is a valid model file carrying the estimates.
  std::vector<std::string> warnings;
  write_identify_results(study, r, dir / "out", false, warnings);
  const MachineSpec fitted = load_model(dir / "out" / "fitted.toml");
  EXPECT_NEAR(fitted.bearings[0].linear.k[0].front(), r.estimate[0], 1e-6 * r.estimate[0]);
  {
    // estimates.json says which program and which model file (by its content) made it.
    std::ifstream in(dir / "out" / "estimates.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("turbodyn_version"), turbodyn_version());
    EXPECT_EQ(j.at("model_digest"), studies::file_digest(study.model));
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "features.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "ceres_summary.txt"));
}

// A feature whose speed range reaches beyond the measured spectra (1000-6000 rpm): those speeds are left out of
// the fit, and the warning names them.
TEST(Identify, SpeedsBeyondTheMeasurementAreNamedInTheWarning) {
  const auto dir = scratch("jeffcott_beyond");
  const std::filesystem::path file = jeffcott_study(dir);
  std::string text = input::read_text_file(file, "study");
  const std::string range = "speed_range = [\"1000 rpm\", \"6000 rpm\"]\nn_speeds = 101";
  const std::size_t at = text.find(range);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, range.size(), "speed_range = [\"1000 rpm\", \"7000 rpm\"]\nn_speeds = 15");
  write(file, text);
  const IdentifyResult r = identify(load_identify_study(file));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("feature 'order1x_x': 3 of its 15 speeds (6143, 6571, 7000 rpm) have no measured value"),
            std::string::npos)
      << r.warnings[0];
  EXPECT_LT(std::abs(r.estimate[0] / kTrueK - 1.0), 0.01);  // the speeds inside still identify k
}

// ------------------------------------------------------------------------------ nonlinear: journal bearings

// A run-up of tests/data/identification/journal_rotor.toml (clearance 30 um, viscosity 10 mPa s: the file's
// values) written as a bench would: HDF5 with time, speed in rpm, a tacho signal and the two displacements in um
// with Gaussian noise of 0.1 um.
constexpr double kTrueClearanceUm = 30.0, kTrueViscosityMPas = 10.0, kJournalNoiseUm = 0.1;

// One [[parameters]] entry of an identification study: `path` is the TOML value of its path key (a string or a list).
std::string parameter_entry(const std::string& name, const std::string& path, const std::string& start,
                            const std::string& lower, const std::string& upper, const std::string& truth) {
  return "[[parameters]]\nname = \"" + name + "\"\npath = " + path + "\nstart = \"" + start + "\"\nlower = \"" +
         lower + "\"\nupper = \"" + upper + "\"\ntrue = \"" + truth + "\"\n\n";
}

const std::string kJournalParameters =
    parameter_entry("clearance", R"(["bearings.left.clearance", "bearings.right.clearance"])", "34 um", "20 um",
                    "45 um", "30 um") +
    parameter_entry("viscosity", R"("oil.viscosity")", "12 mPa*s", "5 mPa*s", "20 mPa*s", "10 mPa*s");

// truth: overrides of the bench run (e.g. its speed history); identify_keys: extra lines of the [identify] table.
std::filesystem::path runup_study(const std::filesystem::path& dir, const std::string& model_file,
                                  const std::string& parameters, int max_iterations,
                                  const std::vector<Override>& truth = {}, const std::string& identify_keys = "") {
  const MachineSpec spec = load_model(source(model_file), truth);
  const auto model = make_runup_model(spec);
  const RunupResult r = simulate_runup(*model, runup_options(spec));
  EXPECT_TRUE(r.complete) << r.message;
  const int cs = studies::find_channel(r.channels, "speed"), ca = studies::find_channel(r.channels, "spin_angle");
  const int cx = studies::find_channel(r.channels, "disk.mid.x"), cy = studies::find_channel(r.channels, "disk.mid.y");
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, kJournalNoiseUm);
  {
    Hdf5TimeSeriesWriter w(dir / "journal_runup.h5",
                           {{"speed", "rpm", ""}, {"tacho", "V", "key-phasor"}, {"x", "um", ""}, {"y", "um", ""}});
    for (std::size_t i = 0; i < r.time.size(); ++i) {
      // Key-phasor: rising edge through 2.5 V at rotor angle 0, edges 1.5 rad wide (as in
      // scripts/make_synthetic_measurement.sh).
      const double a = r.columns[ca][i], wrapped = a - 2.0 * M_PI * std::floor(a / (2.0 * M_PI) + 0.5);
      const double rise = std::clamp(0.5 + wrapped / 1.5, 0.0, 1.0), fall = std::clamp(0.5 - (wrapped - 2.0) / 1.5, 0.0, 1.0);
      const double row[4] = {60.0 * r.columns[cs][i], 5.0 * std::min(rise, fall),
                             1e6 * r.columns[cx][i] + noise(rng), 1e6 * r.columns[cy][i] + noise(rng)};
      w.append(r.time[i], row);
    }
    w.finish(true);
  }
  const std::string study = R"([identify]
model = ")" + source(model_file).string() + R"("
)" + identify_keys + R"(

[measurement]
file = "journal_runup.h5"
speed = "speed"
tacho = "tacho"

[[measurement.sensors]]
column = "x"
probe = "disk.mid.x"

[[measurement.sensors]]
column = "y"
probe = "disk.mid.y"

[processing]
revolutions = 4

[[features]]
kind = "order1x"
sensor = "x"
speed_range = ["5000 rpm", "11500 rpm"]
n_speeds = 14

[[features]]
kind = "order1x"
sensor = "y"
speed_range = ["5000 rpm", "11500 rpm"]
n_speeds = 14

)" + parameters + R"(
[solver]
max_iterations = )" + std::to_string(max_iterations) + "\n";
  write(dir / "study.toml", study);
  return dir / "study.toml";
}

TEST(Identify, NonlinearJournalBearingClearanceAndViscosityFromNoisyRunup) {
  const auto dir = scratch("journal");
  const IdentifyStudy study = load_identify_study(runup_study(dir, "tests/data/identification/journal_rotor.toml", kJournalParameters, 15));
  IdentifyOptions o;
  o.threads = 2;
  const IdentifyResult r = identify(study, o);
  ASSERT_TRUE(r.covariance_ok) << r.covariance_message;
  std::cout << "clearance = " << r.estimate[0] << " +- " << r.std_dev[0] << " um (true " << kTrueClearanceUm
            << "), viscosity = " << r.estimate[1] << " +- " << r.std_dev[1] << " mPa s (true " << kTrueViscosityMPas
            << "), correlation " << r.correlation(0, 1) << ", " << r.iterations << " iterations, " << r.model_runs
            << " model runs, " << r.wall_time << " s\n";
  EXPECT_LT(std::abs(r.estimate[0] - kTrueClearanceUm), kSigmas * r.std_dev[0]);
  EXPECT_LT(std::abs(r.estimate[1] - kTrueViscosityMPas), kSigmas * r.std_dev[1]);
  // The fit moved well away from the start (34 um, 12 mPa s): the band above is not met by standing still.
  EXPECT_LT(std::abs(r.estimate[0] - kTrueClearanceUm), 0.25 * std::abs(34.0 - kTrueClearanceUm));
  EXPECT_LT(std::abs(r.estimate[1] - kTrueViscosityMPas), 0.25 * std::abs(12.0 - kTrueViscosityMPas));
  EXPECT_LT(r.final_cost, 0.01 * r.initial_cost);
}

// The bench ran up faster than the model file's ramp and not linearly (4000 -> 9000 rpm in 0.08 s, on to 12,000 rpm
// at 0.2 s, against the file's 4000 -> 12000 rpm in 0.25 s). With identify.speed = "measured" every run-up follows
// the measured speed (a table from the tacho-derived record): the estimates come back within 3 sigma, the model
// runs span the measured record, and fitted.toml carries the table.
TEST(Identify, RunupsFollowTheMeasuredSpeedWhenAsked) {
  const auto dir = scratch("measured_speed");
  const std::vector<Override> bench = {
      {"speed", R"({profile = "table", times = ["0 s", "0.08 s", "0.2 s"], speeds = ["4000 rpm", "9000 rpm", "12000 rpm"]})"}};
  const IdentifyStudy study = load_identify_study(runup_study(
      dir, "tests/data/identification/journal_rotor.toml", kJournalParameters, 15, bench, R"(speed = "measured")"));
  ASSERT_TRUE(study.speed_from_measurement);
  IdentifyOptions o;
  o.threads = 2;
  const IdentifyResult r = identify(study, o);
  ASSERT_TRUE(r.covariance_ok) << r.covariance_message;
  std::cout << "clearance = " << r.estimate[0] << " +- " << r.std_dev[0] << " um, viscosity = " << r.estimate[1]
            << " +- " << r.std_dev[1] << " mPa s, " << r.model_runs << " model runs\n";
  EXPECT_LT(std::abs(r.estimate[0] - kTrueClearanceUm), kSigmas * r.std_dev[0]);
  EXPECT_LT(std::abs(r.estimate[1] - kTrueViscosityMPas), kSigmas * r.std_dev[1]);
  EXPECT_LT(std::abs(r.estimate[0] - kTrueClearanceUm), 0.25 * std::abs(34.0 - kTrueClearanceUm));
  ASSERT_FALSE(r.fitted_record.time.empty());
  EXPECT_NEAR(r.fitted_record.time.back(), 0.2, 1e-3);                // the measured duration, not the file's 0.25 s
  EXPECT_NEAR(r.fitted_record.speed_hz.back() * 60.0, 12000.0, 30.0);  // the measured end speed
  std::vector<std::string> warnings;
  write_identify_results(study, r, dir / "out", false, warnings);
  const MachineSpec fitted = load_model(dir / "out" / "fitted.toml");
  EXPECT_EQ(fitted.speed.kind, SpeedProfile::Kind::Table);
  EXPECT_NEAR(fitted.speed.duration, 0.2, 1e-3);
}

TEST(Identify, MeasuredSpeedNeedsATimeSeries) {
  // The Jeffcott study compares processed spectra, which carry no speed history.
  const auto dir = scratch("measured_speed_spectra");
  const std::filesystem::path file = jeffcott_study(dir);
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("method = \"response\""), 19, "method = \"runup\"\nspeed = \"measured\"");
  write(file, text);
  try {
    (void)load_identify_study(dir / "study.toml");
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("needs a measured time series"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("study.toml"), std::string::npos) << e.what();
  }
}

// The floating-ring variant: inner and outer film clearances of both bearings (true 30 and 60 um).
TEST(Identify, NonlinearFloatingRingClearancesFromNoisyRunup) {
  const auto dir = scratch("floating_ring");
  const std::string parameters =
      parameter_entry("inner_clearance", R"(["bearings.left.inner_clearance", "bearings.right.inner_clearance"])",
                      "34 um", "20 um", "45 um", "30 um") +
      parameter_entry("outer_clearance", R"(["bearings.left.outer_clearance", "bearings.right.outer_clearance"])",
                      "68 um", "40 um", "90 um", "60 um");
  const IdentifyStudy study =
      load_identify_study(runup_study(dir, "tests/data/identification/floating_ring_rotor.toml", parameters, 15));
  IdentifyOptions o;
  o.threads = 2;
  const IdentifyResult r = identify(study, o);
  ASSERT_TRUE(r.covariance_ok) << r.covariance_message;
  std::cout << "inner clearance = " << r.estimate[0] << " +- " << r.std_dev[0] << " um (true 30), outer clearance = "
            << r.estimate[1] << " +- " << r.std_dev[1] << " um (true 60), correlation " << r.correlation(0, 1) << ", "
            << r.iterations << " iterations, " << r.model_runs << " model runs, " << r.wall_time << " s\n";
  EXPECT_LT(std::abs(r.estimate[0] - 30.0), kSigmas * r.std_dev[0]);
  EXPECT_LT(std::abs(r.estimate[1] - 60.0), kSigmas * r.std_dev[1]);
  EXPECT_LT(std::abs(r.estimate[0] - 30.0), 0.25 * 4.0);
  EXPECT_LT(std::abs(r.estimate[1] - 60.0), 0.25 * 8.0);
}

// Results do not depend on the number of threads: the same model runs, placed by index, the same Ceres steps.
TEST(Identify, SameEstimatesWithOneAndTwoThreads) {
  const auto dir = scratch("threads");
  const IdentifyStudy study = load_identify_study(runup_study(dir, "tests/data/identification/journal_rotor.toml", kJournalParameters, 2));
  IdentifyOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const IdentifyResult a = identify(study, one), b = identify(study, two);
  ASSERT_EQ(a.estimate.size(), b.estimate.size());
  for (std::size_t i = 0; i < a.estimate.size(); ++i) {
    EXPECT_EQ(a.estimate[i], b.estimate[i]);
    EXPECT_EQ(a.std_dev[i], b.std_dev[i]);
  }
  EXPECT_EQ(a.final_cost, b.final_cost);
  EXPECT_EQ(a.model_runs, b.model_runs);
}

// --------------------------------------------------------------------------------------- bad measured files

MeasurementSpec bench_spec(const std::filesystem::path& file) {
  MeasurementSpec m;
  m.file = file;
  m.time = {"time", ""};
  m.speed = {"speed", "rpm"};
  SensorSpec s;
  s.name = "x";
  s.column = {"x", ""};
  s.probe = "disk.mid.x";
  m.sensors.push_back(s);
  return m;
}

std::string good_rows(int n, int from = 0) {
  std::ostringstream os;
  for (int i = from; i < n; ++i) os << 1e-3 * i << ',' << 3000 + i << ',' << std::sin(0.3 * i) << '\n';
  return os.str();
}

std::string error_of(const MeasurementSpec& m) {
  try {
    (void)read_measurement(m);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "(no error)";
}

// The error of loading the bench study with the measured file `file` written with `text` first.
std::string error_reading(const std::filesystem::path& file, const std::string& text) {
  write(file, text);
  return error_of(bench_spec(file));
}

TEST(Identify, MeasuredFileWithMissingColumnNamesTheColumnAndListsThePresentOnes) {
  const auto dir = scratch("bad_missing");
  const std::string e = error_reading(dir / "m.csv", "time [s],speed [rpm],z [um]\n" + good_rows(40));
  EXPECT_NE(e.find("m.csv: no column 'x' (sensor x); the file has: 'time' 'speed' 'z'"), std::string::npos) << e;
}

TEST(Identify, MeasuredFileWithAByteOrderMarkReads) {
  // Issue 20: a spreadsheet's UTF-8 byte-order mark made the first column "\xEF\xBB\xBFtime": "no column 'time'".
  const auto dir = scratch("bom");
  EXPECT_EQ(error_reading(dir / "m.csv", "\xEF\xBB\xBFtime [s],speed [rpm],x [um]\n" + good_rows(40)), "(no error)");
}

TEST(Identify, MeasuredFileThatIsADirectoryIsNamedSo) {
  const auto dir = scratch("dir");
  std::filesystem::create_directories(dir / "m.csv");
  EXPECT_NE(error_of(bench_spec(dir / "m.csv")).find("m.csv: is a directory, not a measured file"), std::string::npos);
}

TEST(Identify, MeasuredFileWithNonMonotonicTimeNamesLineAndColumn) {
  const auto dir = scratch("bad_time");
  const std::string e = error_reading(
      dir / "m.csv", "time [s],speed [rpm],x [um]\n" + good_rows(20) + "0.0185,3020,0.1\n" + good_rows(40, 21));
  // Line 22 = header + 20 rows + the bad one.
  EXPECT_NE(e.find("m.csv:22:1: column 'time': time does not increase (0.0185 s after 0.019 s on line 21)"),
            std::string::npos)
      << e;
}

TEST(Identify, MeasuredFileWithNaNNamesLineFieldAndColumn) {
  const auto dir = scratch("bad_nan");
  const std::string e = error_reading(
      dir / "m.csv", "time [s],speed [rpm],x [um]\n" + good_rows(10) + "0.010,3010,NaN\n" + good_rows(40, 11));
  EXPECT_NE(e.find("m.csv:12:12: column 'x': 'NaN' is not a finite number"), std::string::npos) << e;
  const std::string e2 = error_reading(
      dir / "m2.csv", "time [s],speed [rpm],x [um]\n" + good_rows(10) + "0.010,,0.5\n" + good_rows(40, 11));
  EXPECT_NE(e2.find("m2.csv:12:7: column 'speed': empty field is not a finite number"), std::string::npos) << e2;
}

TEST(Identify, MeasuredFileWithUnknownUnitNamesColumnAndSuggests) {
  const auto dir = scratch("bad_unit");
  const std::string e = error_reading(dir / "m.csv", "time [s],speed [rpm],x [mum]\n" + good_rows(40));
  EXPECT_NE(e.find("m.csv: column 'x' (sensor x): unit 'mum' in the file's header:"), std::string::npos) << e;
  EXPECT_NE(e.find("mum"), std::string::npos) << e;
  // A unit of the wrong kind (a speed where a displacement is expected) is refused too.
  const std::string e2 = error_reading(dir / "m2.csv", "time [s],speed [rpm],x [rpm]\n" + good_rows(40));
  EXPECT_NE(e2.find("column 'x' (sensor x): unit 'rpm'"), std::string::npos) << e2;
}

TEST(Identify, UnknownUnitInTheStudyFileNamesItsLine) {
  const auto dir = scratch("bad_study_unit");
  write(dir / "m.csv", "time,speed,x\n" + good_rows(40));
  write(dir / "study.toml", R"([identify]
model = ")" + source("tests/data/identification/jeffcott.toml").string() + R"("

[measurement]
file = "m.csv"
speed = "speed"
speed_unit = "rpm"

[[measurement.sensors]]
column = "x"
unit = "furlong"
probe = "disk.mid.x"

[[features]]
kind = "order1x"
speeds = ["3000 rpm"]

[[parameters]]
path = "bearings.left.k"
start = 1e5
lower = 1e4
upper = 1e6
)");
  try {
    (void)load_identify_study(dir / "study.toml");
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("study.toml:11:8: measurement.sensors[0].unit: unit 'furlong'"), std::string::npos)
        << e.what();
  }
}

// A measured record of n samples at fs whose tacho pulses once per revolution of the rotor angle angle(t) [rad]
// (rising edge through 2.5 V at angle 0, 1.5 rad wide), with a zero sensor channel x, read back.
template <class Angle>
MeasuredData tacho_record(const std::string& name, int n, double fs, Angle angle) {
  const auto dir = scratch(name);
  std::ostringstream csv;
  csv << "time,tacho,x\n" << std::setprecision(17);
  for (int i = 0; i < n; ++i) {
    const double t = i / fs, a = angle(t);
    const double w = a - 2.0 * M_PI * std::floor(a / (2.0 * M_PI) + 0.5);
    csv << t << ',' << 5.0 * std::min(std::clamp(0.5 + w / 1.5, 0.0, 1.0), std::clamp(0.5 - (w - 2.0) / 1.5, 0.0, 1.0))
        << ",0\n";
  }
  write(dir / "m.csv", csv.str());
  MeasurementSpec m;
  m.file = dir / "m.csv";
  m.tacho = "tacho";
  SensorSpec s;
  s.name = "x";
  s.column = {"x", "m"};
  m.sensors.push_back(s);
  return read_measurement(m);
}

// The tacho path: the angle from pulses of a constant-acceleration run-up is exact (quadratic interpolation).
TEST(Identify, TachoAngleOfALinearRampIsExact) {
  const double f0 = 50.0, alpha = 500.0, fs = 5000.0;  // Hz, Hz/s, 1/s
  auto angle = [&](double t) { return 2.0 * M_PI * (f0 * t + 0.5 * alpha * t * t); };
  const MeasuredData d = tacho_record("tacho", 2000, fs, angle);
  double worst = 0.0, worst_speed = 0.0;
  for (std::size_t i = 0; i < d.record.time.size(); ++i) {
    const double t = d.record.time[i];
    worst = std::max(worst, std::abs(std::remainder(d.record.angle[i] - angle(t), 2.0 * M_PI)));
    worst_speed = std::max(worst_speed, std::abs(d.record.speed_hz[i] - (f0 + alpha * t)));
  }
  EXPECT_LT(worst, 1e-4);        // rad (the pulse times come from linear interpolation between samples)
  EXPECT_LT(worst_speed, 2e-3);  // Hz, of 50 .. 250 Hz
}

// A run-up from rest whose tacho passes the threshold exactly at a sample on the second pulse (as synthetic records
// written with a few decimals do): the angle there came from the last pulses' quadratic, far off, and the order
// tracking refused the record ("the rotor angle must be monotonic"). Times are multiples of 2^-12 s, so the pulse
// time interpolated between samples is that sample's time exactly.
TEST(Identify, TachoAngleFromRestWithAPulseExactlyOnASample) {
  const double alpha = 64.0, fs = 4096.0;  // Hz/s from rest: revolution 2 at t = 0.25 s, sample 1024
  auto angle = [&](double t) { return M_PI * alpha * t * t; };
  const MeasuredData d = tacho_record("tacho_rest", 4096, fs, angle);
  ASSERT_EQ(d.record.time[1024], 0.25);
  double worst = 0.0, worst_speed = 0.0;
  for (std::size_t i = 0; i < d.record.time.size(); ++i) {
    const double t = d.record.time[i];
    worst = std::max(worst, std::abs(std::remainder(d.record.angle[i] - angle(t), 2.0 * M_PI)));
    worst_speed = std::max(worst_speed, std::abs(d.record.speed_hz[i] - alpha * t));
    if (i > 0) {
      EXPECT_GE(d.record.angle[i], d.record.angle[i - 1]) << "sample " << i;
    }
  }
  EXPECT_LT(worst, 1e-3);        // rad
  EXPECT_LT(worst_speed, 1e-2);  // Hz, of 0 .. 64 Hz
}

}  // namespace
}  // namespace turbodyn::identification

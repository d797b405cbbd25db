// Time-series files: exact HDF5 round trip, what survives when the writer's process dies, CSV export, and errors.
#include "model/io/timeseries_file.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>

namespace turbodyn {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// Each test writes into its own scratch directory, removed afterwards.
class TimeSeriesFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = std::filesystem::temp_directory_path() / ("turbodyn_ts_" + std::to_string(getpid()) + "_" + test);
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::filesystem::path path(const std::string& name) const { return dir_ / name; }

  std::filesystem::path dir_;
};

// Deliberately not in name order, to check that channels come back in creation order.
std::vector<Channel> three_channels() {
  return {{"disk.compressor.x", "m", "horizontal displacement of the compressor wheel"},
          {"bearing_1-force.y", "N", "vertical force of bearing 1 (UTF-8: \xc2\xb1 5 \xc2\xb5m)"},
          {"ring.speed", "rad/s", ""}};
}

double sample_time(std::size_t row) { return static_cast<double>(row) / 20000.0; }

// Values that use every bit of a double: irrational fractions over many decades, signed zero, subnormals,
// infinities and a NaN with a payload.
double sample(std::size_t row, std::size_t channel) {
  switch ((row + channel) % 97) {
    case 0: return -0.0;
    case 1: return std::numeric_limits<double>::denorm_min() * static_cast<double>(row + 1);
    case 2: return std::numeric_limits<double>::infinity();
    case 3: return -std::numeric_limits<double>::max();
    case 4: return std::bit_cast<double>(std::uint64_t{0x7ff8000000000123});
    default:
      return std::sin(0.001 * static_cast<double>(row) * static_cast<double>(channel + 1)) *
             std::pow(10.0, static_cast<double>(static_cast<int>(row % 41) - 20));
  }
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Rows [0, rows) of `data` hold exactly sample_time/sample, bit for bit. Returns the number of differing values.
std::size_t differing_values(const TimeSeriesData& data, std::size_t rows) {
  std::size_t differing = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    differing += !same_bits(data.time[r], sample_time(r));
    for (std::size_t c = 0; c < data.columns.size(); ++c) differing += !same_bits(data.columns[c][r], sample(r, c));
  }
  return differing;
}

// A file marked incomplete that holds exactly the first `rows` samples, bit for bit.
void expect_incomplete_with_rows(const TimeSeriesData& data, std::size_t rows) {
  EXPECT_FALSE(data.complete);
  ASSERT_EQ(data.time.size(), rows);
  EXPECT_EQ(differing_values(data, rows), 0u);
}

void append_samples(Hdf5TimeSeriesWriter& writer, std::size_t from, std::size_t to) {
  std::vector<double> row(writer.channels().size());
  for (std::size_t r = from; r < to; ++r) {
    for (std::size_t c = 0; c < row.size(); ++c) row[c] = sample(r, c);
    writer.append(sample_time(r), row.data());
  }
}

void expect_channels(const TimeSeriesData& data, const std::vector<Channel>& expected) {
  ASSERT_EQ(data.channels.size(), expected.size());
  ASSERT_EQ(data.columns.size(), expected.size());
  for (std::size_t c = 0; c < expected.size(); ++c) {
    EXPECT_EQ(data.channels[c].name, expected[c].name);
    EXPECT_EQ(data.channels[c].unit, expected[c].unit);
    EXPECT_EQ(data.channels[c].description, expected[c].description);
  }
}

std::string timeseries_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const TimeSeriesError& e) {
    return e.what();
  }
  return "";
}

// The time series is streamed, not renamed into place: a symbolic link at its path is replaced, its target kept.
TEST_F(TimeSeriesFile, ALinkAtThePathIsReplacedNotWrittenThrough) {
  { std::ofstream(path("precious.txt")) << "keep me"; }
  std::filesystem::create_symlink(path("precious.txt"), path("run.h5"));
  std::filesystem::create_symlink(path("precious.txt"), path("run.csv"));
  {
    Hdf5TimeSeriesWriter writer(path("run.h5"), three_channels(), 8);
    append_samples(writer, 0, 20);
    writer.finish(true);
  }
  write_csv(path("run.csv"), {{"x", "m", ""}}, {0.0, 1.0}, {{1.0, 2.0}});
  EXPECT_FALSE(std::filesystem::is_symlink(path("run.h5")));
  EXPECT_FALSE(std::filesystem::is_symlink(path("run.csv")));
  EXPECT_EQ(read_hdf5_timeseries(path("run.h5")).time.size(), 20u);
  std::ifstream in(path("precious.txt"));
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "keep me");
}

TEST_F(TimeSeriesFile, RoundTripIsBitwiseExact) {
  constexpr std::size_t kRows = 10000;  // not a multiple of the buffer (512) nor of the chunk (4096)
  const std::filesystem::path file = path("run.h5");
  {
    Hdf5TimeSeriesWriter writer(file, three_channels(), 512);
    writer.set_attribute("machine", "examples/reference_linear.toml");
    writer.set_attribute("output_rate_hz", 20000.0);
    writer.set_attribute("note", "replaced below");
    writer.set_attribute("note", 3.5);  // replacing may change the type
    append_samples(writer, 0, kRows);
    EXPECT_EQ(writer.rows(), kRows);
    EXPECT_TRUE(writer.is_open());
    writer.finish(true);
    EXPECT_FALSE(writer.is_open());
    EXPECT_EQ(writer.rows(), kRows);
  }
  const TimeSeriesData data = read_hdf5_timeseries(file);
  expect_channels(data, three_channels());
  ASSERT_EQ(data.time.size(), kRows);
  for (const std::vector<double>& column : data.columns) ASSERT_EQ(column.size(), kRows);
  EXPECT_EQ(differing_values(data, kRows), 0u);
  EXPECT_TRUE(data.complete);
  EXPECT_EQ(data.string_attributes, (std::map<std::string, std::string>{
                                        {"machine", "examples/reference_linear.toml"}, {"software", "turbodyn"}}));
  EXPECT_EQ(data.number_attributes, (std::map<std::string, double>{{"note", 3.5}, {"output_rate_hz", 20000.0}}));
}

TEST_F(TimeSeriesFile, FinishFalseMarksIncomplete) {
  const std::filesystem::path file = path("failed.h5");
  Hdf5TimeSeriesWriter writer(file, three_channels(), 100);
  append_samples(writer, 0, 250);
  writer.finish(false);
  const TimeSeriesData data = read_hdf5_timeseries(file);
  expect_incomplete_with_rows(data, 250);
}

TEST_F(TimeSeriesFile, TimeOnlyWithoutChannels) {
  const std::filesystem::path file = path("time_only.h5");
  Hdf5TimeSeriesWriter writer(file, {}, 8);
  for (std::size_t r = 0; r < 20; ++r) writer.append(sample_time(r), nullptr);
  writer.finish(true);
  const TimeSeriesData data = read_hdf5_timeseries(file);
  EXPECT_TRUE(data.channels.empty());
  ASSERT_EQ(data.time.size(), 20u);
  EXPECT_EQ(data.time[19], sample_time(19));
}

TEST_F(TimeSeriesFile, DestructorWithoutFinishFlushesAndLeavesIncomplete) {
  const std::filesystem::path file = path("abandoned.h5");
  {
    Hdf5TimeSeriesWriter writer(file, three_channels());  // default buffer: nothing written before the destructor
    append_samples(writer, 0, 1000);
    writer.set_attribute("status", "integrator failed at t = 0.05 s");
  }
  const TimeSeriesData data = read_hdf5_timeseries(file);
  expect_channels(data, three_channels());
  expect_incomplete_with_rows(data, 1000);
  EXPECT_EQ(data.string_attributes.at("status"), "integrator failed at t = 0.05 s");
}

// Runs `body` in a forked child, which must end by calling die(): the child then stops with _exit(1) like a crashed
// run, without destructors, finish() or HDF5's library shutdown (which would close and so flush the file).
// Returns the child's exit code: 1 when it died as planned, 2 on an exception, 3 when body returned.
[[noreturn]] void die() { _exit(1); }

int run_in_child_that_dies(const std::function<void()>& body) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    try {
      body();
    } catch (...) {
      _exit(2);
    }
    _exit(3);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(TimeSeriesFile, CrashAfterFlushKeepsFlushedRows) {
  const std::filesystem::path file = path("crashed.h5");
  const int exit_code = run_in_child_that_dies([&] {
    Hdf5TimeSeriesWriter writer(file, three_channels(), 512);
    append_samples(writer, 0, 1000);  // the buffer fills once: 512 rows written and flushed
    writer.set_attribute("speed_rpm", 150000.0);
    writer.flush();                      // all 1000
    append_samples(writer, 1000, 1300);  // still in the buffer when the process dies
    die();
  });
  ASSERT_EQ(exit_code, 1);
  const TimeSeriesData data = read_hdf5_timeseries(file);
  expect_channels(data, three_channels());
  expect_incomplete_with_rows(data, 1000);
  EXPECT_EQ(data.number_attributes.at("speed_rpm"), 150000.0);
  EXPECT_EQ(data.string_attributes.at("software"), "turbodyn");
}

TEST_F(TimeSeriesFile, CrashKeepsEveryFullBuffer) {
  const std::filesystem::path file = path("crashed.h5");
  const int exit_code = run_in_child_that_dies([&] {
    Hdf5TimeSeriesWriter writer(file, three_channels(), 512);
    append_samples(writer, 0, 1030);  // two full buffers, no explicit flush
    die();
  });
  ASSERT_EQ(exit_code, 1);
  const TimeSeriesData data = read_hdf5_timeseries(file);
  expect_incomplete_with_rows(data, 1024);
}

TEST_F(TimeSeriesFile, CrashBeforeAnyFlushLeavesAnEmptyReadableFile) {
  const std::filesystem::path file = path("crashed.h5");
  const int exit_code = run_in_child_that_dies([&] {
    Hdf5TimeSeriesWriter writer(file, three_channels(), 4096);
    append_samples(writer, 0, 10);
    die();
  });
  ASSERT_EQ(exit_code, 1);
  const TimeSeriesData data = read_hdf5_timeseries(file);
  expect_channels(data, three_channels());
  EXPECT_FALSE(data.complete);
  EXPECT_TRUE(data.time.empty());
}

TEST_F(TimeSeriesFile, OpensWithH5dumpAlsoAfterACrash) {
  ASSERT_EQ(std::system("command -v h5dump > /dev/null 2>&1"), 0)
      << "h5dump is not installed (scripts/install-deps.sh installs hdf5-tools)";
  const std::filesystem::path file = path("crashed.h5");
  ASSERT_EQ(run_in_child_that_dies([&] {
              Hdf5TimeSeriesWriter writer(file, three_channels(), 64);
              append_samples(writer, 0, 100);
              die();
            }),
            1);
  auto run = [](const std::string& command, std::string& output) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (pipe == nullptr) return -1;
    std::array<char, 4096> buffer;
    output.clear();
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) output.append(buffer.data(), n);
    return pclose(pipe);
  };
  std::string output;
  ASSERT_EQ(run("h5dump -A '" + file.string() + "'", output), 0) << output;
  EXPECT_THAT(output, AllOf(HasSubstr("DATASET \"disk.compressor.x\""), HasSubstr("ATTRIBUTE \"unit\""),
                            HasSubstr("\"rad/s\""), HasSubstr("ATTRIBUTE \"complete\""), HasSubstr("( 64 )")));
  ASSERT_EQ(run("h5dump -d /probes/ring.speed '" + file.string() + "'", output), 0) << output;
}

// ----------------------------------------------------------------------------------------------------------------
// CSV

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

TEST_F(TimeSeriesFile, CsvHeaderRowsAndExactRoundTrip) {
  const std::vector<Channel> channels = {{"x", "m", "d"},      {"omega", "rad/s", ""}, {"acc", "m/s^2", ""},
                                         {"torque", "N*m", ""}, {"count", "", ""}};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> time = {0.0, 5e-5};
  std::vector<std::vector<double>> columns = {{0.1, -0.0}, {-2.5, 1e300}, {1e-7, kInf}, {1.0 / 3.0, -kInf},
                                              {12345678.0, std::numeric_limits<double>::quiet_NaN()}};
  for (std::size_t r = 2; r < 500; ++r) {
    time.push_back(sample_time(r));
    for (std::size_t c = 0; c < columns.size(); ++c) columns[c].push_back(sample(r, c));
  }

  // A locale with a decimal comma must not change the file (only tried where such a locale is installed).
  const std::string old_c_locale = std::setlocale(LC_ALL, nullptr);
  const bool comma_locale = std::setlocale(LC_ALL, "de_DE.UTF-8") != nullptr;
  const std::filesystem::path file = path("run.csv");
  write_csv(file, channels, time, columns);
  std::setlocale(LC_ALL, old_c_locale.c_str());
  if (!comma_locale) std::cout << "[ note ] no de_DE.UTF-8 locale here: CSV checked in the C locale only\n";

  const std::vector<std::string> lines = lines_of(file);
  ASSERT_EQ(lines.size(), time.size() + 1);
  EXPECT_EQ(lines[0], "time_s,x_m,omega_rad_per_s,acc_m_per_s2,torque_N_m,count");
  EXPECT_EQ(lines[1], "0,0.10000000000000001,-2.5,9.9999999999999995e-08,0.33333333333333331,12345678");
  EXPECT_EQ(lines[2], "5.0000000000000002e-05,-0,1.0000000000000001e+300,inf,-inf,nan");

  for (std::size_t r = 0; r < time.size(); ++r) {
    const std::vector<std::string> fields = split(lines[r + 1]);
    ASSERT_EQ(fields.size(), channels.size() + 1) << lines[r + 1];
    for (std::size_t f = 0; f < fields.size(); ++f) {
      double value = 0.0;
      const auto result = std::from_chars(fields[f].data(), fields[f].data() + fields[f].size(), value);
      ASSERT_EQ(result.ec, std::errc()) << fields[f];
      ASSERT_EQ(result.ptr, fields[f].data() + fields[f].size()) << fields[f];
      const double expected = f == 0 ? time[r] : columns[f - 1][r];
      if (std::isnan(expected))
        EXPECT_TRUE(std::isnan(value)) << "row " << r << " field " << f;
      else
        EXPECT_TRUE(same_bits(value, expected)) << "row " << r << " field " << f << ": " << fields[f];
    }
  }
}

TEST_F(TimeSeriesFile, CsvColumnNames) {
  EXPECT_EQ(csv_column_name({"ring.speed", "rad/s", ""}), "ring.speed_rad_per_s");
  EXPECT_EQ(csv_column_name({"k", "N/m", ""}), "k_N_per_m");
  EXPECT_EQ(csv_column_name({"c", "N s/m", ""}), "c_N_s_per_m");
  EXPECT_EQ(csv_column_name({"u", "kg*m", ""}), "u_kg_m");
  EXPECT_EQ(csv_column_name({"i", "kg*m^2", ""}), "i_kg_m2");
  EXPECT_EQ(csv_column_name({"n", "", ""}), "n");
}

TEST_F(TimeSeriesFile, CsvErrors) {
  const std::vector<Channel> channels = {{"x", "m", ""}};
  EXPECT_THAT(timeseries_error_of([&] { write_csv(path("a.csv"), channels, {0.0, 1.0}, {{1.0}}); }),
              AllOf(HasSubstr("a.csv"), HasSubstr("column 0 ('x') has 1 rows, time has 2")));
  EXPECT_THAT(timeseries_error_of([&] { write_csv(path("a.csv"), channels, {0.0}, {}); }),
              HasSubstr("1 channels but 0 columns"));
  EXPECT_THAT(timeseries_error_of([&] { write_csv("/nonexistent/dir/x.csv", channels, {0.0}, {{1.0}}); }),
              AllOf(HasSubstr("'/nonexistent/dir/x.csv'"), HasSubstr("cannot create the file"),
                    HasSubstr("does not exist")));
  EXPECT_THAT(timeseries_error_of([&] { write_csv(path("a.csv"), {{"x,y", "m", ""}}, {0.0}, {{1.0}}); }),
              HasSubstr("contains ','"));
}

// ----------------------------------------------------------------------------------------------------------------
// Errors

TEST_F(TimeSeriesFile, UnwritablePath) {
  EXPECT_THAT(timeseries_error_of([] { Hdf5TimeSeriesWriter writer("/nonexistent/dir/x.h5", three_channels()); }),
              AllOf(HasSubstr("'/nonexistent/dir/x.h5'"), HasSubstr("cannot create the file"),
                    HasSubstr("directory '/nonexistent/dir' does not exist")));
  // A path that is a directory: HDF5's own error stack explains it, and nothing is printed on stderr.
  ::testing::internal::CaptureStderr();
  const std::string message = timeseries_error_of([&] { Hdf5TimeSeriesWriter writer(dir_, three_channels()); });
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(message, AllOf(HasSubstr(dir_.string()), HasSubstr("cannot create the file"), HasSubstr("H5Fcreate")));
  EXPECT_EQ(printed, "");
}

TEST_F(TimeSeriesFile, HdfErrorPrintingIsRestored) {
  H5E_auto2_t before_func = nullptr;
  void* before_data = nullptr;
  ASSERT_GE(H5Eget_auto2(H5E_DEFAULT, &before_func, &before_data), 0);
  timeseries_error_of([] { Hdf5TimeSeriesWriter writer("/nonexistent/dir/x.h5", three_channels()); });
  timeseries_error_of([&] { read_hdf5_timeseries(path("missing.h5")); });
  H5E_auto2_t after_func = nullptr;
  void* after_data = nullptr;
  ASSERT_GE(H5Eget_auto2(H5E_DEFAULT, &after_func, &after_data), 0);
  EXPECT_EQ(after_func, before_func);
  EXPECT_EQ(after_data, before_data);
}

TEST_F(TimeSeriesFile, InvalidChannelNames) {
  auto error_for = [&](const std::string& name) {
    return timeseries_error_of([&] {
      Hdf5TimeSeriesWriter writer(path("x.h5"), {{"ok", "m", ""}, {name, "m", ""}});
    });
  };
  EXPECT_THAT(error_for("disk compressor.x"),
              AllOf(HasSubstr("x.h5"), HasSubstr("channel 1 name 'disk compressor.x' contains ' '")));
  EXPECT_THAT(error_for("a/b"), HasSubstr("contains '/'"));
  EXPECT_THAT(error_for("\xc2\xb5m"), HasSubstr("contains 0xc2"));
  EXPECT_THAT(error_for(""), HasSubstr("channel 1 has an empty name"));
  EXPECT_THAT(error_for(".."), HasSubstr("must start with a letter, a digit or '_'"));
  EXPECT_THAT(error_for("-x"), HasSubstr("must start with a letter, a digit or '_'"));
  EXPECT_THAT(error_for(std::string(256, 'a')), HasSubstr("longer than 255"));
  EXPECT_FALSE(std::filesystem::exists(path("x.h5"))) << "names are checked before the file is created";
  EXPECT_EQ(error_for("_Disk-2.x_y"), "");
}

TEST_F(TimeSeriesFile, DuplicateChannelNames) {
  EXPECT_THAT(timeseries_error_of([&] {
                Hdf5TimeSeriesWriter writer(path("x.h5"), {{"a", "m", ""}, {"b", "m", ""}, {"a", "N", ""}});
              }),
              HasSubstr("duplicate channel name 'a' (channels 0 and 2)"));
}

TEST_F(TimeSeriesFile, ZeroBufferRows) {
  EXPECT_THAT(timeseries_error_of([&] { Hdf5TimeSeriesWriter writer(path("x.h5"), three_channels(), 0); }),
              HasSubstr("buffer_rows must be at least 1"));
}

TEST_F(TimeSeriesFile, UseAfterFinish) {
  Hdf5TimeSeriesWriter writer(path("x.h5"), three_channels(), 16);
  append_samples(writer, 0, 5);
  writer.finish(true);
  const std::array<double, 3> row = {1.0, 2.0, 3.0};
  EXPECT_THAT(timeseries_error_of([&] { writer.append(1.0, row.data()); }),
              AllOf(HasSubstr("x.h5"), HasSubstr("append() after finish()")));
  EXPECT_THAT(timeseries_error_of([&] { writer.flush(); }), HasSubstr("flush() after finish()"));
  EXPECT_THAT(timeseries_error_of([&] { writer.finish(true); }), HasSubstr("finish() after finish()"));
  EXPECT_THAT(timeseries_error_of([&] { writer.set_attribute("a", 1.0); }),
              HasSubstr("set_attribute() after finish()"));
  EXPECT_EQ(read_hdf5_timeseries(path("x.h5")).time.size(), 5u);
}

TEST_F(TimeSeriesFile, ReservedAttributeNames) {
  Hdf5TimeSeriesWriter writer(path("x.h5"), three_channels());
  EXPECT_THAT(timeseries_error_of([&] { writer.set_attribute("complete", 1.0); }), HasSubstr("'complete' is reserved"));
  EXPECT_THAT(timeseries_error_of([&] { writer.set_attribute("software", "other"); }),
              HasSubstr("'software' is reserved"));
  EXPECT_THAT(timeseries_error_of([&] { writer.set_attribute("", "x"); }), HasSubstr("must not be empty"));
}

TEST_F(TimeSeriesFile, ReadErrors) {
  EXPECT_THAT(timeseries_error_of([&] { read_hdf5_timeseries(path("missing.h5")); }),
              AllOf(HasSubstr("missing.h5"), HasSubstr("does not exist")));

  std::ofstream(path("text.h5")) << "time_s,x_m\n0,1\n";
  EXPECT_THAT(timeseries_error_of([&] { read_hdf5_timeseries(path("text.h5")); }),
              AllOf(HasSubstr("text.h5"), HasSubstr("cannot open the file as HDF5"), HasSubstr("H5Fopen")));

  const hid_t other = H5Fcreate(path("other.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(other, 0);
  H5Fclose(other);
  EXPECT_THAT(timeseries_error_of([&] { read_hdf5_timeseries(path("other.h5")); }), HasSubstr("no dataset '/time'"));
}

}  // namespace
}  // namespace turbodyn

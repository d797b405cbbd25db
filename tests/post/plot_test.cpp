// Pictures: the files are real PNGs of the requested size; bad data, a missing gnuplot and a failing gnuplot give
// clear errors; rendering from several threads at once works; text is passed to gnuplot literally.
#include "post/plot.h"
#include "tests/support/text_checks.h"
#include "model/spec/constants.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#if __has_include(<unistd.h>)
#include <unistd.h>
#endif

namespace turbodyn::plot {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// gnuplot is a dependency (scripts/install-deps.sh installs gnuplot-nox): its absence fails, it does not skip.
#define REQUIRE_GNUPLOT() \
  ASSERT_TRUE(gnuplot_available()) << "gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox)"

struct PngInfo {
  bool signature = false;
  int width = -1, height = -1;
};

// Signature, and width and height from the IHDR chunk (big-endian at bytes 16..23).
PngInfo png_info(const fs::path& f) {
  PngInfo info;
  std::ifstream in(f, std::ios::binary);
  std::array<unsigned char, 24> h{};
  if (!in.read(reinterpret_cast<char*>(h.data()), h.size())) return info;
  const std::array<unsigned char, 8> sig = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  info.signature = std::equal(sig.begin(), sig.end(), h.begin());
  const std::string chunk(h.begin() + 12, h.begin() + 16);
  if (!info.signature || chunk != "IHDR") return info;
  auto be = [&](int o) {
    return static_cast<int>((static_cast<unsigned>(h[o]) << 24) | (static_cast<unsigned>(h[o + 1]) << 16) |
                            (static_cast<unsigned>(h[o + 2]) << 8) | static_cast<unsigned>(h[o + 3]));
  };
  info.width = be(16);
  info.height = be(20);
  return info;
}

// Sets (or unsets) an environment variable for the lifetime of the object.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) ::setenv(name, value, 1);
    else ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_.c_str(), old_->c_str(), 1);
    else ::unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

class PlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           ("turbodyn_plot_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path file(const std::string& name) const { return dir_ / name; }

  fs::path dir_;
};

LineChart two_series() {
  LineChart c;
  c.title = "Campbell diagram";
  c.xlabel = "rotor speed f_d [Hz]";
  c.ylabel = "natural frequency [Hz]";
  c.series.push_back({"forward whirl", {0, 10, 20, 30}, {40, 42, 45, 49}, Series::Style::LinesPoints, "", 1.5});
  c.series.push_back({"backward whirl", {0, 10, 20, 30}, {40, kNaN, 36, 33}, Series::Style::Points, "#d62728", 1.5});
  c.vertical_lines = {25.0};
  c.annotations.push_back({25.0, 45.0, "critical"});
  return c;
}

Heatmap ridge(bool uniform_x = true) {
  Heatmap m;
  m.title = "Spectrogram";
  m.xlabel = "rotor speed f_d [Hz]";
  m.ylabel = "frequency f [Hz]";
  m.zlabel = "amplitude [µm]";
  for (int i = 0; i < 60; ++i) m.x.push_back(uniform_x ? 1.0 * i : 1.0 * i + 0.01 * i * i);
  for (int j = 0; j < 40; ++j) m.y.push_back(2.0 * j);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 60; ++i) m.z.push_back(std::exp(-std::pow((m.y[j] - m.x[i]) / 4.0, 2)));
  m.logz = true;
  m.overlays.push_back({"1x", {m.x.front(), m.x.back()}, {m.x.front(), m.x.back()}, Series::Style::Dashed, "white", 1.0});
  return m;
}

// Expects f() to throw PlotError and returns its message.
template <class F>
std::string plot_error_of(F f) {
  try {
    f();
  } catch (const PlotError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no PlotError thrown";
  return {};
}

// Temporary directories of this process left behind by render_png.
int leftover_temp_dirs() {
  const std::string prefix = "turbodyn-plot-" + std::to_string(::getpid()) + "-";
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    if (e.path().filename().string().rfind(prefix, 0) == 0) ++n;
  return n;
}

// ----------------------------------------------------------------------------------------------------------------
// Rendering

TEST_F(PlotTest, LineChartWithTwoSeriesIsAPngOfTheDefaultSize) {
  REQUIRE_GNUPLOT();
  const fs::path f = file("line.png");
  render_png(two_series(), f);
  ASSERT_TRUE(fs::exists(f));
  const PngInfo info = png_info(f);
  EXPECT_TRUE(info.signature);
  EXPECT_EQ(info.width, 1000);
  EXPECT_EQ(info.height, 700);
  EXPECT_GT(fs::file_size(f), 5000u);  // not blank
  EXPECT_EQ(leftover_temp_dirs(), 0);
}

TEST_F(PlotTest, LineChartOfAnotherSizeLogAxisAndEqualAxes) {
  REQUIRE_GNUPLOT();
  LineChart c = two_series();
  c.logy = true;
  c.series[0].y[1] = 0.0;  // a gap on the log axis, no failure
  c.legend_position = "outside right top";
  render_png(c, file("log.png"), Size{640, 480});
  const PngInfo info = png_info(file("log.png"));
  EXPECT_TRUE(info.signature);
  EXPECT_EQ(info.width, 640);
  EXPECT_EQ(info.height, 480);

  LineChart orbit;
  orbit.xlabel = "x [µm]";
  orbit.ylabel = "y [µm]";
  orbit.equal_axes = true;
  Series s;
  for (int k = 0; k <= 100; ++k) {
    s.x.push_back(3 * std::cos(0.0628 * k));
    s.y.push_back(std::sin(0.0628 * k));
  }
  orbit.series.push_back(s);  // no label: no legend
  render_png(orbit, file("sub/dir/orbit.png"), Size{800, 800});
  EXPECT_EQ(png_info(file("sub/dir/orbit.png")).width, 800);
}

TEST_F(PlotTest, BarChartIsAPng) {
  REQUIRE_GNUPLOT();
  BarChart b;
  b.title = "Tornado";
  b.bars = {{"a", 0.9, "", "+0.90"}, {"b", -0.2, "", "-0.20"}};
  render_png(b, file("bars.png"), Size{800, 400});
  const PngInfo info = png_info(file("bars.png"));
  EXPECT_TRUE(info.signature);
  EXPECT_EQ(info.width, 800);
  EXPECT_EQ(info.height, 400);
}

TEST_F(PlotTest, HeatmapWithOverlayIsAPngOfTheRequestedSize) {
  REQUIRE_GNUPLOT();
  const fs::path f = file("heat.png");
  render_png(ridge(), f, Size{900, 600});
  const PngInfo info = png_info(f);
  EXPECT_TRUE(info.signature);
  EXPECT_EQ(info.width, 900);
  EXPECT_EQ(info.height, 600);
  EXPECT_EQ(leftover_temp_dirs(), 0);
}

TEST_F(PlotTest, HeatmapOnAnUnevenGridWithBlankCellsAndZeros) {
  REQUIRE_GNUPLOT();
  Heatmap m = ridge(false);
  m.z[5] = kNaN;
  m.z[6] = 0.0;  // clipped on the log scale
  m.z[7] = -1.0;
  render_png(m, file("uneven.png"));
  const PngInfo info = png_info(file("uneven.png"));
  EXPECT_TRUE(info.signature);
  EXPECT_EQ(info.width, 1000);
  EXPECT_EQ(info.height, 700);

  m.logz = false;
  m.zrange = std::make_pair(0.0, 0.5);
  m.overlays.clear();
  render_png(m, file("linear.png"));
  EXPECT_TRUE(png_info(file("linear.png")).signature);
}

TEST_F(PlotTest, ExistingFileIsReplaced) {
  REQUIRE_GNUPLOT();
  const fs::path f = file("old.png");
  std::ofstream(f) << "not a picture";
  render_png(two_series(), f);
  EXPECT_TRUE(png_info(f).signature);
}

TEST_F(PlotTest, TwoThreadsRenderAtTheSameTime) {
  REQUIRE_GNUPLOT();
  std::string e1, e2;
  std::thread a([&] {
    try {
      for (int k = 0; k < 3; ++k) render_png(two_series(), file("t1_" + std::to_string(k) + ".png"));
    } catch (const std::exception& e) {
      e1 = e.what();
    }
  });
  std::thread b([&] {
    try {
      for (int k = 0; k < 3; ++k) render_png(ridge(k % 2 == 0), file("t2_" + std::to_string(k) + ".png"), Size{700, 500});
    } catch (const std::exception& e) {
      e2 = e.what();
    }
  });
  a.join();
  b.join();
  ASSERT_EQ(e1, "");
  ASSERT_EQ(e2, "");
  for (int k = 0; k < 3; ++k) {
    const PngInfo i1 = png_info(file("t1_" + std::to_string(k) + ".png"));
    const PngInfo i2 = png_info(file("t2_" + std::to_string(k) + ".png"));
    EXPECT_TRUE(i1.signature && i2.signature);
    EXPECT_EQ(i1.width, 1000);
    EXPECT_EQ(i1.height, 700);
    EXPECT_EQ(i2.width, 700);
    EXPECT_EQ(i2.height, 500);
  }
  EXPECT_EQ(leftover_temp_dirs(), 0);
}

TEST_F(PlotTest, AwkwardTextIsDrawnLiterally) {
  REQUIRE_GNUPLOT();
  LineChart c = two_series();
  c.title = "it's a \"test\" with `echo injected` @macro $var \\n and a\nsecond line";
  c.series[0].label = "f_d's ^{} 'label'";
  c.annotations.push_back({10, 44, "note: 'x' `y`"});
  render_png(c, file("text.png"));
  EXPECT_TRUE(png_info(file("text.png")).signature);
}

// ----------------------------------------------------------------------------------------------------------------
// Script text (no gnuplot needed)

TEST(PlotScript, TextIsQuotedAndNumbersAreExact) {
  LineChart c = two_series();
  c.xlabel = "it's `date` [Hz]";
  c.series[0].x[1] = 0.1;
  c.series[0].y[1] = 1.0 / 3.0;
  const std::string s = gnuplot_script(c, "/tmp/out.png");
  turbodyn::testing::expect_contains(s, {
      "set xlabel 'it''s `date` [Hz]' noenhanced",
      "\n0.1 0.3333333333333333\n",
      "set output '/tmp/out.png'",
      "pngcairo size 1000,700",
      "title 'forward whirl'",
  });
  // The NaN of the second series breaks its line with a blank line.
  EXPECT_THAT(s, HasSubstr("\n0 40\n\n20 36\n"));
}

TEST(PlotScript, HeatmapUsesImageWithPaletteAndColourBarLabel) {
  const std::string s = gnuplot_script(ridge(), "/tmp/h.png");
  turbodyn::testing::expect_contains(s, {
      "with image",
      "set palette defined",
      "set cblabel 'amplitude [µm]'",
      "set logscale cb",
      "title '1x'",
  });
  // Pixels are centred on the cell centres: the range reaches half a cell beyond the outer centres.
  EXPECT_THAT(s, HasSubstr("set xrange [-0.5:59.5]"));
  EXPECT_THAT(s, HasSubstr("set yrange [-1:79]"));
}

TEST(PlotScript, LongTitlesAreBrokenToFitThePicture) {
  const std::string t = "Sensitivity of max_compressor_bearing_force (standardised regression coefficients, R² = 0.93)";
  const std::string fitted = fit_title(t, 600);
  EXPECT_THAT(fitted, HasSubstr("\n"));
  for (std::size_t start = 0, end = 0; end != std::string::npos; start = end + 1) {
    end = fitted.find('\n', start);
    EXPECT_LE(fitted.substr(start, end == std::string::npos ? end : end - start).size(), (600u - 40u) / 11u + 2u);
  }
  EXPECT_EQ(fit_title("Short title", 1000), "Short title");
  EXPECT_EQ(fit_title("two\nlines", 1000), "two\nlines");
  LineChart c = two_series();
  c.title = t;
  EXPECT_THAT(gnuplot_script(c, "/tmp/t.png", Size{600, 400}), HasSubstr("'Sensitivity of max_compressor_bearing_force'.\"\\n\".'"));
}

TEST(PlotScript, StepsCrossesTrianglesLevelsAndDefaultLegend) {
  LineChart c = two_series();
  c.series[0].style = Series::Style::Steps;
  c.series[1].style = Series::Style::Crosses;
  std::string s = gnuplot_script(c, "/tmp/s.png");
  turbodyn::testing::expect_contains(s, {
      "with steps lw",
      "with points pt 2",
      "set key below",
  });
  c.series[0].style = Series::Style::Triangles;
  s = gnuplot_script(c, "/tmp/s.png");
  EXPECT_THAT(s, HasSubstr("with points pt 9"));
  EXPECT_THAT(s, HasSubstr("set offsets graph 0.03"));  // points only: kept off the border
  Heatmap m = ridge();
  m.levels = 12;
  EXPECT_THAT(gnuplot_script(m, "/tmp/h.png"), HasSubstr("set palette maxcolors 12"));
  m.levels = 1;
  EXPECT_THROW(gnuplot_script(m, "/tmp/h.png"), PlotError);
}

TEST(PlotScript, BarChartDrawsHorizontalBarsTopDownWithLabelsAndLegend) {
  BarChart b;
  b.title = "Sensitivity";
  b.xlabel = "coefficient [-]";
  b.bars = {{"stiffness\n2e7 … 4e7 N/m", -0.8, "#ff7f0e", "-0.80"}, {"unbalance", 0.3, "#1f77b4", "+0.30"}};
  b.legend = {{"#1f77b4", "raises the metric"}};
  const std::string s = gnuplot_script(b, "/tmp/b.png");
  turbodyn::testing::expect_contains(s, {
      "with boxxyerror lc rgb variable",
      "set ytics scale 0 ('stiffness'.\"\\n\".'2e7 … 4e7 N/m' 2, 'unbalance' 1)",
      "\n-0.8 2 -0.8 0 ",  // first bar on top, from -0.8 to 0
      " 16744206\n",      // #ff7f0e as an integer
      "set xrange [-",  // symmetric about 0
  });
  b.xrange = std::make_pair(-1.0, 1.0);
  EXPECT_THAT(gnuplot_script(b, "/tmp/b.png"), HasSubstr("set xrange [-1:1]"));
  EXPECT_THAT(s, HasSubstr("keyentry with boxes fc rgb '#1f77b4' title 'raises the metric'"));
  b.bars[0].color = "orange";
  EXPECT_THROW(gnuplot_script(b, "/tmp/b.png"), PlotError);
  b.bars.clear();
  EXPECT_THROW(gnuplot_script(b, "/tmp/b.png"), PlotError);
}

TEST(PlotScript, UnevenHeatmapAxisIsResampledOntoCells) {
  Heatmap m;
  m.x = {0, 1, 3};  // cells [-0.5, 0.5), [0.5, 2), [2, 4]
  m.y = {0, 1};
  m.z = {1, 2, 3, 4, 5, 6};
  const std::string s = gnuplot_script(m, "/tmp/u.png", Size{100, 100});
  EXPECT_THAT(s, HasSubstr("set xrange [-0.5:4]"));
  // Every pixel shows the value of the cell it lies in.
  std::istringstream in(s.substr(s.find("$map << EOD\n") + 12));
  std::string line;
  int rows = 0;
  while (std::getline(in, line) && line != "EOD") {
    if (line.empty()) continue;
    double x = 0, y = 0, z = 0;
    std::istringstream(line) >> x >> y >> z;
    const int i = x < 0.5 ? 0 : x < 2 ? 1 : 2;
    const int j = y < 0.5 ? 0 : 1;
    ASSERT_EQ(z, m.z[j * 3 + i]) << line;
    ++rows;
  }
  EXPECT_GE(rows, 2 * 18);  // at least 4 samples across the narrowest cell
}

// ----------------------------------------------------------------------------------------------------------------
// Errors (no gnuplot needed: data are checked first)

TEST_F(PlotTest, SizeMismatchIsAnError) {
  LineChart c = two_series();
  c.series[1].y.pop_back();
  const std::string msg = plot_error_of([&] { render_png(c, file("bad.png")); });
  turbodyn::testing::expect_contains(msg, {
      "size mismatch",
      "backward whirl",
      "4 x values but 3 y values",
      "bad.png",
  });
  EXPECT_FALSE(fs::exists(file("bad.png")));

  Heatmap m = ridge();
  m.z.pop_back();
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("bad.png")); }),
              HasSubstr("heat map z has 2399 values, expected ny * nx = 40 * 60 = 2400"));
  m = ridge();
  m.overlays[0].x.push_back(3);
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("bad.png")); }),
              HasSubstr("overlay series 1 ('1x'): size mismatch"));
}

TEST_F(PlotTest, EmptyDataIsAnError) {
  EXPECT_THAT(plot_error_of([&] { render_png(LineChart{}, file("e.png")); }), HasSubstr("no series"));
  LineChart c = two_series();
  c.series.push_back(Series{"nothing", {}, {}, Series::Style::Lines, "", 1.5});
  EXPECT_THAT(plot_error_of([&] { render_png(c, file("e.png")); }), HasSubstr("series 3 ('nothing') is empty"));
  LineChart all_nan;
  all_nan.series.push_back({"nan", {1, 2}, {kNaN, kNaN}, Series::Style::Lines, "", 1.5});
  EXPECT_THAT(plot_error_of([&] { render_png(all_nan, file("e.png")); }), HasSubstr("no finite data points"));
  EXPECT_THAT(plot_error_of([&] { render_png(Heatmap{}, file("e.png")); }), HasSubstr("no x values"));
  Heatmap m = ridge();
  std::fill(m.z.begin(), m.z.end(), kNaN);
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("e.png")); }), HasSubstr("no finite z values"));
  m = ridge();
  std::fill(m.z.begin(), m.z.end(), 0.0);
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("e.png")); }), HasSubstr("no positive z values"));
}

TEST_F(PlotTest, NonAscendingOrNonFiniteHeatmapAxisIsAnError) {
  Heatmap m = ridge();
  std::swap(m.x[3], m.x[4]);
  const std::string msg = plot_error_of([&] { render_png(m, file("h.png")); });
  EXPECT_THAT(msg, HasSubstr("x values are not strictly ascending"));
  EXPECT_THAT(msg, HasSubstr("x[3] = 4, x[4] = 3"));
  m = ridge();
  m.y[7] = m.y[6];
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("h.png")); }), HasSubstr("y values are not strictly ascending"));
  m = ridge();
  m.x[0] = kNaN;
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("h.png")); }), HasSubstr("x[0] = NaN is not finite"));
}

TEST_F(PlotTest, BadRangesAndOptionsAreErrors) {
  LineChart c = two_series();
  c.xrange = std::make_pair(1.0, 1.0);
  EXPECT_THAT(plot_error_of([&] { render_png(c, file("r.png")); }), HasSubstr("x range"));
  c = two_series();
  c.logy = true;
  c.yrange = std::make_pair(0.0, 10.0);
  EXPECT_THAT(plot_error_of([&] { render_png(c, file("r.png")); }), HasSubstr("positive on a logarithmic scale"));
  c = two_series();
  c.legend_position = "top; system 'rm x'";
  EXPECT_THAT(plot_error_of([&] { render_png(c, file("r.png")); }), HasSubstr("legend position"));
  EXPECT_THAT(plot_error_of([&] { render_png(two_series(), file("r.png"), Size{0, 700}); }), HasSubstr("picture size"));
  Heatmap m = ridge();
  m.zrange = std::make_pair(0.0, 1.0);  // log scale
  EXPECT_THAT(plot_error_of([&] { render_png(m, file("r.png")); }), HasSubstr("z range"));
}

TEST_F(PlotTest, MissingGnuplotIsAClearError) {
  ScopedEnv env("TURBODYN_GNUPLOT", "/nonexistent/gnuplot");
  EXPECT_FALSE(gnuplot_available());
  EXPECT_THROW(gnuplot_executable(), PlotError);
  const std::string msg = plot_error_of([&] { render_png(two_series(), file("none.png")); });
  turbodyn::testing::expect_contains(msg, {
      "gnuplot not found",
      "/nonexistent/gnuplot",
      "none.png",
  });
  EXPECT_THAT(plot_error_of([&] { render_png(ridge(), file("none.png")); }), HasSubstr("gnuplot"));
  EXPECT_FALSE(fs::exists(file("none.png")));
}

TEST_F(PlotTest, MissingGnuplotByNameIsAClearError) {
  ScopedEnv env("TURBODYN_GNUPLOT", "no-such-gnuplot-program");
  EXPECT_FALSE(gnuplot_available());
  EXPECT_THAT(plot_error_of([&] { render_png(two_series(), file("none.png")); }),
              HasSubstr("'no-such-gnuplot-program' is not on PATH"));
}

TEST_F(PlotTest, GnuplotFailureReportsItsMessages) {
  REQUIRE_GNUPLOT();
  LineChart c = two_series();
  c.series[0].color = "no-such-colour";
  const std::string msg = plot_error_of([&] { render_png(c, file("fail.png")); });
  turbodyn::testing::expect_contains(msg, {
      "fail.png",
      "gnuplot",
      "exited with status",
      "no-such-colour",  // gnuplot's own message quotes the script line
  });
  EXPECT_FALSE(fs::exists(file("fail.png")));
  EXPECT_EQ(leftover_temp_dirs(), 0);
}

TEST_F(PlotTest, AProgramThatIsNotGnuplotFails) {
  // 'true' exits 0 but writes no picture.
  ScopedEnv env("TURBODYN_GNUPLOT", "true");
  ASSERT_TRUE(gnuplot_available()) << "no 'true' program on PATH";
  const std::string msg = plot_error_of([&] { render_png(two_series(), file("fake.png")); });
  EXPECT_THAT(msg, HasSubstr("wrote no PNG picture"));
  EXPECT_THAT(msg, Not(HasSubstr("gnuplot not found")));
}

}  // namespace
}  // namespace turbodyn::plot

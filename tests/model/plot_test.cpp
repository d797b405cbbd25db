// Pictures: files are real PNGs of the requested size; bad data and a missing gnuplot give clear errors.
#include "model/plot.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace turbodyn::plot {
namespace {

using ::testing::HasSubstr;

std::filesystem::path temp(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "turbodyn_plot_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

// Width and height from the PNG IHDR chunk (big-endian at bytes 16..23).
std::pair<int, int> png_size(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), 24);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!std::equal(sig, sig + 8, h)) return {-1, -1};
  auto be = [&](int o) { return (h[o] << 24) | (h[o + 1] << 16) | (h[o + 2] << 8) | h[o + 3]; };
  return {be(16), be(20)};
}

LineChart two_series() {
  LineChart c;
  c.title = "test";
  c.xlabel = "rotor speed [rpm]";
  c.ylabel = "frequency [Hz]";
  Series a{"a", {0, 1, 2}, {1, 2, 3}, Series::Style::Lines, "", 1.5};
  Series b{"b's", {0, 1, 2}, {3, NAN, 1}, Series::Style::Points, "#ff0000", 1.0};
  c.series = {a, b};
  return c;
}

Heatmap ridge() {
  Heatmap m;
  m.title = "spectrogram";
  m.xlabel = "rotor speed f_d [Hz]";
  m.ylabel = "frequency f [Hz]";
  m.zlabel = "amplitude [um]";
  for (int i = 0; i < 60; ++i) m.x.push_back(10.0 * i + 0.01 * i * i);  // non-uniform, ascending
  for (int j = 0; j < 40; ++j) m.y.push_back(15.0 * j);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 60; ++i) m.z.push_back(std::exp(-std::pow((m.y[j] - m.x[i]) / 20.0, 2)) + 1e-4);
  m.logz = true;
  m.overlays.push_back({"1x", {0, 600}, {0, 600}, Series::Style::Dashed, "white", 1.0});
  return m;
}

TEST(Plot, LineChartIsAPngOfTheRequestedSize) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  const auto f = temp("line.png");
  render_png(two_series(), f, Size{640, 480});
  EXPECT_EQ(png_size(f), std::make_pair(640, 480));
}

TEST(Plot, HeatmapIsAPngOfTheRequestedSize) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  const auto f = temp("heat.png");
  render_png(ridge(), f, Size{800, 600});
  EXPECT_EQ(png_size(f), std::make_pair(800, 600));
}

TEST(Plot, ConcurrentRendering) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  std::thread a([] { render_png(two_series(), temp("t1.png")); });
  std::thread b([] { render_png(ridge(), temp("t2.png")); });
  a.join();
  b.join();
  EXPECT_EQ(png_size(temp("t1.png")).first, 1000);
  EXPECT_EQ(png_size(temp("t2.png")).first, 1000);
}

TEST(Plot, BadDataIsRejected) {
  LineChart c = two_series();
  c.series[0].y.pop_back();
  try {
    render_png(c, temp("bad.png"));
    FAIL();
  } catch (const PlotError& e) {
    EXPECT_THAT(e.what(), HasSubstr("3 x values but 2 y values"));
  }
  LineChart empty;
  EXPECT_THROW(render_png(empty, temp("bad.png")), PlotError);
  Heatmap m = ridge();
  std::swap(m.x[3], m.x[4]);
  try {
    render_png(m, temp("bad.png"));
    FAIL();
  } catch (const PlotError& e) {
    EXPECT_THAT(e.what(), HasSubstr("strictly ascending"));
  }
  m = ridge();
  m.z.pop_back();
  EXPECT_THROW(render_png(m, temp("bad.png")), PlotError);
}

TEST(Plot, MissingGnuplotIsAClearError) {
  setenv("TURBODYN_GNUPLOT", "/nonexistent/gnuplot", 1);
  EXPECT_FALSE(gnuplot_available());
  try {
    render_png(two_series(), temp("none.png"));
    ADD_FAILURE() << "no error";
  } catch (const PlotError& e) {
    EXPECT_THAT(e.what(), HasSubstr("gnuplot"));
    EXPECT_THAT(e.what(), HasSubstr("none.png"));
  }
  unsetenv("TURBODYN_GNUPLOT");
}

}  // namespace
}  // namespace turbodyn::plot

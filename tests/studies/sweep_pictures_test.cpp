// The pictures of a study: the interpolation of the contour maps, and the three kinds of picture drawn from a
// small two-parameter study with an incomplete and a failed run.
#include "studies/sweep_pictures.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "post/plot.h"

namespace turbodyn::studies {
namespace {

TEST(SweepPictures, ShepardInterpolationHonoursEveryPointAndStaysBetweenThem) {
  const std::vector<double> xs{0, 1, 0, 1}, ys{0, 0, 1, 1}, zs{1, 2, 3, 4};
  for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_DOUBLE_EQ(shepard(xs, ys, zs, xs[i], ys[i], 1, 1), zs[i]);
  EXPECT_DOUBLE_EQ(shepard(xs, ys, zs, 0.5, 0.5, 1, 1), 2.5);  // equidistant: the mean
  const double v = shepard(xs, ys, zs, 0.1, 0.2, 1, 1);
  EXPECT_GT(v, 1.0);
  EXPECT_LT(v, 4.0);
  // Scaled axes: a parameter in N/m and one in mg*mm weigh alike.
  EXPECT_DOUBLE_EQ(shepard({0, 1e7}, {0, 0}, {1, 2}, 5e6, 0, 1e7, 1), 1.5);
}

TEST(SweepPictures, TornadoScatterAndMapOfATwoParameterStudy) {
  ASSERT_TRUE(plot::gnuplot_available()) << "gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox)";
  const auto dir = std::filesystem::temp_directory_path() / "turbodyn_sweep_pictures_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  StudySpec study;
  study.name = "test";
  study.parameter_units = {"N/m", "mg*mm"};
  study.design.kind = DesignKind::FullFactorial;
  MetricSpec m;
  m.name = "max_x";
  study.metrics = {m};
  Design design;
  design.paths = {"bearings.a.k", "disks.b.unbalance"};
  std::vector<RunRecord> runs;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      RunRecord r;
      r.index = runs.size();
      r.parameters = {1e7 * (2 + i), 290.0 * (1 + j)};
      design.values.push_back(r.parameters);
      r.metrics = {1e-6 * (90 - 30 * i + 5 * j)};
      r.status = "ok";
      runs.push_back(r);
    }
  runs[4].status = "incomplete";
  runs[8].status = "failed";
  runs[8].metrics = {NAN};
  runs[2].metrics = {NAN};  // ran, but the metric has no value (grey, not a failed run)
  Sensitivity s;
  s.src = {-0.9, 0.2};
  s.r_squared = 0.95;
  draw_tornado(study, design, 0, s, dir / "tornado.png");
  EXPECT_TRUE(draw_metric_scatter(study, design, runs, 0, 0, "m", dir / "scatter.png"));
  EXPECT_TRUE(draw_metric_map(study, design, runs, 0, "m", dir / "map.png"));
  for (const char* f : {"tornado.png", "scatter.png", "map.png"})
    EXPECT_GT(std::filesystem::file_size(dir / f), 5000u) << f;
  // No value in any run: nothing drawn.
  for (RunRecord& r : runs) r.metrics = {NAN};
  EXPECT_FALSE(draw_metric_scatter(study, design, runs, 0, 1, "m", dir / "none.png"));
  EXPECT_FALSE(draw_metric_map(study, design, runs, 0, "m", dir / "none.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "none.png"));
  std::filesystem::remove_all(dir);
}

TEST(SweepPictures, ResponseSurfaceRecoversAQuadraticAndMapsThreeParameters) {
  // y = 3 + 2a - b + 0.5 a^2 + a c (scaled parameters): the fit is exact, R^2 = 1, and needs terms + 3 runs.
  const std::vector<double> lo{1.0, 10.0, 0.0}, hi{3.0, 30.0, 4.0};
  auto scaled = [&](const std::vector<double>& x, std::size_t i) { return (2 * x[i] - lo[i] - hi[i]) / (hi[i] - lo[i]); };
  auto truth = [&](const std::vector<double>& x) {
    const double a = scaled(x, 0), b = scaled(x, 1), c = scaled(x, 2);
    return 3 + 2 * a - b + 0.5 * a * a + a * c;
  };
  std::vector<std::vector<double>> xs;
  std::vector<double> ys;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        xs.push_back({1.0 + i, 10.0 + 10 * j, 2.0 * k});
        ys.push_back(truth(xs.back()));
      }
  const QuadraticSurface s = fit_quadratic_surface(xs, ys, lo, hi);
  EXPECT_NEAR(s.r_squared, 1.0, 1e-12);
  EXPECT_EQ(s.runs, 27u);
  EXPECT_NEAR(s({2.5, 17.0, 1.0}), truth({2.5, 17.0, 1.0}), 1e-10);
  // A run without a value is skipped; too few runs for the 10 terms is an error.
  ys[0] = NAN;
  EXPECT_EQ(fit_quadratic_surface(xs, ys, lo, hi).runs, 26u);
  xs.resize(12);
  ys.resize(12);
  EXPECT_THROW(fit_quadratic_surface(xs, ys, lo, hi), std::invalid_argument);

  ASSERT_TRUE(plot::gnuplot_available()) << "gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox)";
  const auto dir = std::filesystem::temp_directory_path() / "turbodyn_sweep_pictures_surface";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  StudySpec study;
  study.parameter_units = {"um", "um", "degC"};
  study.design.kind = DesignKind::LatinHypercube;
  MetricSpec m;
  m.name = "max_x";
  study.metrics = {m};
  Design design;
  design.paths = {"bearings.a.inner_clearance", "bearings.a.outer_clearance", "oil.temperature"};
  std::vector<RunRecord> runs;
  for (int i = 0; i < 20; ++i) {
    RunRecord r;
    r.index = runs.size();
    auto u = [&](int salt) { return std::fmod(std::sin(12.9898 * (i + 1) + 78.233 * salt) * 43758.5453, 1.0) * 0.5 + 0.5; };
    r.parameters = {11.0 + 8.0 * u(1), 30.0 + 20.0 * u(2), 70.0 + 40.0 * u(3)};
    design.values.push_back(r.parameters);
    r.metrics = {1e-6 * (40 + r.parameters[0] - 0.3 * r.parameters[1] + 0.01 * r.parameters[2] * r.parameters[0])};
    r.status = "ok";
    runs.push_back(r);
  }
  EXPECT_TRUE(draw_metric_map(study, design, runs, 0, "m", dir / "map.png"));
  EXPECT_GT(std::filesystem::file_size(dir / "map.png"), 5000u);
  runs.resize(10);  // fewer runs than the 10 terms + 3: no map
  design.values.resize(10);
  EXPECT_FALSE(draw_metric_map(study, design, runs, 0, "m", dir / "few.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace turbodyn::studies

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

}  // namespace
}  // namespace turbodyn::studies

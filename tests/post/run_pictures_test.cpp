// The pictures of a run: spectrogram heat maps (columns, rows, scaling, the peak), the spectrogram of a run's
// channel against speed or time, and the files draw_run_pictures writes for a synthetic run-up.
#include "post/run_pictures.h"
#include "tests/support/temp_dir.h"

#include <cmath>
#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace turbodyn::post {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;

// A run-up from 0 to `top` (100 Hz) in 2 s sampled at `fs` (2 kHz), with a disk whirling forward at 1x with radius
// 1 µm and, from 1 s on, with `whirl` at 0.4x.
RunupResult synthetic_runup(double fs = 2000.0, double top = 100.0, double whirl = 0.0) {
  constexpr double kDuration = 2.0;  // s
  constexpr double kRadius = 1e-6;   // m
  RunupResult r;
  r.complete = true;
  r.channels = {{"speed", "Hz", "rotor speed", ProbeChannel::Kind::Speed, 0, 0},
                {"angle", "rad", "rotor angle", ProbeChannel::Kind::Angle, 0, 0},
                {"disk.a.x", "m", "", ProbeChannel::Kind::RotorDof, 0, 0},
                {"disk.a.y", "m", "", ProbeChannel::Kind::RotorDof, 1, 0}};
  r.columns.resize(4);
  const auto n = static_cast<std::size_t>(kDuration * fs) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs;
    const double speed = top * t / kDuration, angle = M_PI * top * t * t / kDuration, w = t >= 1.0 ? whirl : 0.0;
    r.time.push_back(t);
    r.columns[0].push_back(speed);
    r.columns[1].push_back(angle);
    r.columns[2].push_back(kRadius * std::cos(angle) + w * std::cos(0.4 * angle));
    r.columns[3].push_back(kRadius * std::sin(angle) + w * std::sin(0.4 * angle));
  }
  return r;
}

OutputSpec output() {
  OutputSpec o;
  o.sample_rate = 2000.0;
  o.spectrogram_segment = 256;
  return o;
}

TEST(RunPictures, HeatmapDropsRepeatedColumnsCutsRowsAndScales) {
  signal::Spectrogram sg;
  sg.frequencies = {0.0, 10.0, 20.0, 30.0};
  sg.times = {0.1, 0.2, 0.3};
  sg.amplitude = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};  // 3 segments x 4 bins
  const plot::Heatmap hm = spectrogram_heatmap(sg, {5.0, 5.0, 6.0}, 20.0, 2.0, 60.0);
  EXPECT_THAT(hm.x, ElementsAre(300.0, 360.0));  // the second segment repeats the first's speed
  EXPECT_THAT(hm.y, ElementsAre(0.0, 10.0, 20.0));
  EXPECT_THAT(hm.z, ElementsAre(2, 18, 4, 20, 6, 22));  // z[bin * 2 + column], x 2

  const HeatmapPeak p = heatmap_peak(hm);
  EXPECT_EQ(p.value, 22.0);
  EXPECT_EQ(p.row, 2u);
  EXPECT_EQ(p.column, 1u);
  EXPECT_EQ(heatmap_peak(plot::Heatmap{}).value, 0.0);
}

TEST(RunPictures, DisplayAndFileNames) {
  EXPECT_EQ(display_of("m").factor, 1e6);
  EXPECT_EQ(display_of("m").unit, "µm");
  EXPECT_EQ(display_of("N").factor, 1.0);
  EXPECT_EQ(display_of("N").unit, "N");
  EXPECT_EQ(display_of("Pa").factor, 1e-6);
  EXPECT_EQ(display_of("Pa").unit, "MPa");
  EXPECT_EQ(display_of("N/m").factor, 1e-6);
  EXPECT_EQ(display_of("N/m").unit, "N/µm");
  EXPECT_EQ(file_safe("disk a/x:1.5-b_c"), "disk_a_x_1.5-b_c");
  EXPECT_EQ(file_safe("max(disk.x) [m]"), "max_disk.x___m_");
}

TEST(RunPictures, RunSpectrogramFollowsTheRotorSpeed) {
  const RunupResult r = synthetic_runup();
  const OutputSpec out = output();
  EXPECT_DOUBLE_EQ(spectrogram_frequency_max(out, 100.0), 110.0);
  const std::optional<plot::Heatmap> hm = run_spectrogram(out, r, 2);
  ASSERT_TRUE(hm);
  EXPECT_EQ(hm->xlabel, "rotor speed f_d [Hz]");
  EXPECT_EQ(hm->zlabel, "amplitude [µm]");
  EXPECT_TRUE(hm->logz);
  ASSERT_EQ(hm->overlays.size(), 2u);
  EXPECT_EQ(hm->overlays[0].label, "1x");
  EXPECT_EQ(hm->overlays[1].label, "0.5x");
  EXPECT_LE(hm->y.back(), 110.0);
  // In every column the largest bin lies at the rotor speed, within a bin and the speed change over a segment.
  const std::size_t nx = hm->x.size();
  ASSERT_GT(nx, 10u);
  for (std::size_t i = nx / 4; i < nx; ++i) {
    std::size_t best = 0;
    for (std::size_t j = 0; j < hm->y.size(); ++j)
      if (hm->z[j * nx + i] > hm->z[best * nx + i]) best = j;
    EXPECT_NEAR(hm->y[best], hm->x[i], 2 * 2000.0 / 256) << "column " << i;
  }
  EXPECT_NEAR(heatmap_peak(*hm).value, 1.0, 0.2);  // µm; the Hann window's scalloping loss is below 16 %

  const std::optional<plot::Heatmap> by_time = run_spectrogram(out, r, 2, true);
  ASSERT_TRUE(by_time);
  EXPECT_EQ(by_time->xlabel, "time [s]");
  EXPECT_TRUE(by_time->overlays.empty());
  EXPECT_LT(by_time->x.back(), 2.0);

  RunupResult short_run = r;
  for (auto& c : short_run.columns) c.resize(100);
  short_run.time.resize(100);
  EXPECT_FALSE(run_spectrogram(out, short_run, 2));
}

TEST(RunPictures, DrawsSpectrogramsOrderTracksAndOrbits) {
  if (!plot::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const fs::path dir = turbodyn::testing::fresh_temp_dir("run_pictures_test");
  MachineSpec spec;
  spec.output = output();
  std::vector<std::string> written, warnings;
  nlohmann::json spectral = nlohmann::json::object();
  draw_run_pictures(spec, synthetic_runup(), dir, written, warnings, spectral,
                    {{"forward modes", {40.0, 60.0}, {50.0, 50.0}, plot::Series::Style::Points, "#ff5050", 1.2}});
  EXPECT_THAT(written, ElementsAre("spectrogram_disk.a.x.png", "spectrogram_disk.a.y.png", "order1x_disk.a.png",
                                   "orbits_disk.a.png"));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  for (const std::string& f : written) EXPECT_GT(fs::file_size(dir / f), 1000u) << f;
  ASSERT_TRUE(spectral.contains("disk.a.x"));
  EXPECT_EQ(spectral["disk.a.x"]["unit"], "m");
  EXPECT_NEAR(spectral["disk.a.x"]["amplitude"].get<double>(), 1e-6, 0.2e-6);
  EXPECT_NEAR(spectral["disk.a.x"]["frequency_hz"].get<double>(), spectral["disk.a.x"]["speed_hz"].get<double>(),
              2 * 2000.0 / 256);
}

TEST(RunPictures, SpectralMaximaNameTheLargestSubsynchronousLines) {
  if (!plot::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const fs::path dir = turbodyn::testing::fresh_temp_dir("run_pictures_test_subsynchronous");
  MachineSpec spec;
  spec.output.sample_rate = 8000.0;
  spec.output.spectrogram_segment = 1024;
  for (const double whirl : {0.0, 0.2e-6}) {
    std::vector<std::string> written, warnings;
    nlohmann::json spectral = nlohmann::json::object();
    // 0 to 1,000 Hz at 8 kHz: without a whirl the sub-synchronous lines are the 1x line's leakage.
    draw_run_pictures(spec, synthetic_runup(8000.0, 1000.0, whirl), dir, written, warnings, spectral);
    ASSERT_TRUE(spectral["disk.a.x"].contains("subsynchronous")) << spectral.dump();
    const nlohmann::json& all = spectral["disk.a.x"]["subsynchronous"];
    const nlohmann::json& end = spectral["disk.a.x"]["subsynchronous_at_end"];
    if (whirl == 0.0) {
      EXPECT_LT(all["amplitude"].get<double>(), kSubsynchronousLeakage * 1e-6);
      EXPECT_LT(end["amplitude"].get<double>(), kSubsynchronousLeakage * 1e-6);
    } else {
      for (const nlohmann::json* l : {&all, &end}) {
        EXPECT_GT((*l)["amplitude"].get<double>(), 0.5 * whirl) << l->dump();
        EXPECT_LE((*l)["amplitude"].get<double>(), whirl) << l->dump();
        EXPECT_NEAR((*l)["order"].get<double>(), 0.4, 0.03) << l->dump();
        EXPECT_NEAR((*l)["speed_hz"].get<double>(), 500.0 * (*l)["time_s"].get<double>(), 1e-6);
      }
      EXPECT_GE(all["time_s"].get<double>(), 1.0);
      EXPECT_GT(end["time_s"].get<double>(), 1.9);
    }
  }
  fs::remove_all(dir);
}

TEST(RunPictures, SpectrogramMaximaWithoutPicturesAreThoseOfThePictures) {
  MachineSpec spec;
  spec.output.sample_rate = 8000.0;
  spec.output.spectrogram_segment = 1024;
  const RunupResult r = synthetic_runup(8000.0, 1000.0, 0.2e-6);
  const nlohmann::json m = spectrogram_maxima(spec, r);
  // Both probes, not the speed and the angle; the 1x whirl of 1 µm at its largest (read low: it sweeps 64 Hz, eight
  // bins, through a segment); the 0.4x whirl below it.
  EXPECT_EQ(m.size(), 2u) << m.dump();
  ASSERT_TRUE(m.contains("disk.a.y")) << m.dump();
  EXPECT_GT(m["disk.a.y"]["amplitude"].get<double>(), 0.5e-6);
  EXPECT_LE(m["disk.a.y"]["amplitude"].get<double>(), 1e-6);
  EXPECT_NEAR(m["disk.a.y"]["subsynchronous_at_end"]["order"].get<double>(), 0.4, 0.03);
  // Too short for one STFT segment, or no speed channel: nothing.
  RunupResult short_run = synthetic_runup(8000.0, 1000.0);
  for (std::vector<double>& col : short_run.columns) col.resize(1000);
  short_run.time.resize(1000);
  EXPECT_TRUE(spectrogram_maxima(spec, short_run).empty());
  RunupResult no_speed = r;
  no_speed.channels[0].kind = ProbeChannel::Kind::Element;
  EXPECT_TRUE(spectrogram_maxima(spec, no_speed).empty());
  if (!plot::gnuplot_available()) return;
  const fs::path dir = turbodyn::testing::fresh_temp_dir("run_pictures_test_maxima");
  std::vector<std::string> written, warnings;
  nlohmann::json spectral = nlohmann::json::object();
  draw_run_pictures(spec, r, dir, written, warnings, spectral);
  EXPECT_EQ(m, spectral);
  fs::remove_all(dir);
}

// The synthetic run-up with two floating rings' slow channels: ring speed ratios 0.30 and 0.25 with a whirl ripple
// of +-0.05 at 37 Hz, and an inner-film temperature rising from 363.15 K (90 degC) by 10 K per 100 Hz of speed.
RunupResult with_floating_rings() {
  RunupResult r = synthetic_runup();
  r.channels.push_back({"bearing.c.ring_speed_ratio", "1", "", ProbeChannel::Kind::Element, 0, 0});
  r.channels.push_back({"bearing.t.ring_speed_ratio", "1", "", ProbeChannel::Kind::Element, 0, 0});
  r.channels.push_back({"bearing.c.inner_temperature", "K", "", ProbeChannel::Kind::Element, 0, 0});
  r.columns.resize(r.channels.size());
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    const double ripple = 0.05 * std::sin(2.0 * M_PI * 37.0 * r.time[i]);
    r.columns[4].push_back(0.30 + ripple);
    r.columns[5].push_back(0.25 + ripple);
    r.columns[6].push_back(363.15 + 0.1 * r.columns[0][i]);
  }
  return r;
}

TEST(RunPictures, SlowChannelsAgainstSpeedAreBlockMeans) {
  const RunupResult r = with_floating_rings();
  // Blocks of 1000 samples (0.5 s, 18.5 ripple periods): the ripple averages out to within 0.05 / 18.5 / pi.
  const std::optional<plot::LineChart> ratio = against_speed_chart(r, {".ring_speed_ratio"}, 1000);
  ASSERT_TRUE(ratio);
  ASSERT_EQ(ratio->series.size(), 2u);
  EXPECT_EQ(ratio->series[0].label, "bearing.c.ring_speed_ratio");
  EXPECT_EQ(ratio->xlabel, "rotor speed f_d [Hz]");
  ASSERT_EQ(ratio->series[0].x.size(), 4u);  // 4001 samples: 4 whole blocks
  for (std::size_t b = 0; b < 4; ++b) {
    EXPECT_NEAR(ratio->series[0].x[b], 25.0 * b + 12.4875, 1e-9);  // mean speed of samples 1000 b .. 1000 b + 999
    EXPECT_NEAR(ratio->series[0].y[b], 0.30, 1e-3);
    EXPECT_NEAR(ratio->series[1].y[b], 0.25, 1e-3);
  }
  const std::optional<plot::LineChart> temperature =
      against_speed_chart(r, {".inner_temperature", ".outer_temperature"}, 1000, -273.15);
  ASSERT_TRUE(temperature);
  ASSERT_EQ(temperature->series.size(), 1u);
  EXPECT_NEAR(temperature->series[0].y[3], 90.0 + 0.1 * 87.4875, 1e-9);  // degC, linear in speed
  EXPECT_FALSE(against_speed_chart(r, {".outer_power_loss"}, 1000));    // no such channel
  EXPECT_FALSE(against_speed_chart(r, {".ring_speed_ratio"}, 3000));    // fewer than two blocks
}

TEST(RunPictures, FloatingRingsGetTheirOperatingPointAgainstSpeed) {
  if (!plot::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const fs::path dir = turbodyn::testing::fresh_temp_dir("run_pictures_rings");
  MachineSpec spec;
  spec.output = output();
  std::vector<std::string> written, warnings;
  nlohmann::json spectral = nlohmann::json::object();
  draw_run_pictures(spec, with_floating_rings(), dir, written, warnings, spectral);
  EXPECT_THAT(written, ::testing::IsSupersetOf({"ring_speed_ratio.png", "film_temperatures.png"}));
  EXPECT_THAT(written, ::testing::Not(::testing::Contains("film_power_loss.png")));
  EXPECT_GT(fs::file_size(dir / "ring_speed_ratio.png"), 1000u);
}

TEST(RunPictures, FilmThicknessesAreDrawnAsBlockMinimaAgainstTheirLimitWithoutSpectrograms) {
  // Two films 5 µm thick less a whirl of 2 µm at 37 Hz: every block's minimum is 3 µm (to the sampling: 2 µm times
  // 1 - cos(pi 37 / 2000) < 4 nm). The second carries a permissible minimum of 4 µm.
  RunupResult r = with_floating_rings();
  r.channels.push_back({"bearing.c.inner_min_film_thickness", "m", "", ProbeChannel::Kind::Element, 0, 0});
  r.channels.push_back({"bearing.t.outer_min_film_thickness", "m", "", ProbeChannel::Kind::Element, 0, 0, 4e-6,
                        "the permissible minimum", true});
  r.columns.resize(r.channels.size());
  for (std::size_t i = 0; i < r.time.size(); ++i)
    for (std::size_t c : {r.channels.size() - 2, r.channels.size() - 1})
      r.columns[c].push_back(5e-6 - 2e-6 * std::sin(2.0 * M_PI * 37.0 * r.time[i]));
  const std::optional<plot::LineChart> chart =
      against_speed_chart(r, {"min_film_thickness"}, 1000, 0.0, Block::Min, 1e6);
  ASSERT_TRUE(chart);
  ASSERT_EQ(chart->series.size(), 2u);
  for (const plot::Series& s : chart->series) {
    ASSERT_EQ(s.y.size(), 4u);
    for (double y : s.y) EXPECT_NEAR(y, 3.0, 0.004);  // µm
  }
  if (!plot::gnuplot_available()) return;
  const fs::path dir = turbodyn::testing::fresh_temp_dir("run_pictures_films");
  MachineSpec spec;
  spec.output = output();
  std::vector<std::string> written, warnings;
  nlohmann::json spectral = nlohmann::json::object();
  draw_run_pictures(spec, r, dir, written, warnings, spectral);
  EXPECT_THAT(written, ::testing::Contains("film_thickness.png"));
  EXPECT_GT(fs::file_size(dir / "film_thickness.png"), 1000u);
  // A film's thinnest point is read as a level, with or without a limit: no spectrogram.
  for (const std::string& f : written) EXPECT_EQ(f.find("min_film_thickness"), std::string::npos) << f;
  EXPECT_FALSE(spectral.contains("bearing.c.inner_min_film_thickness"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace turbodyn::post

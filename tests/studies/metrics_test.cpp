// Sub-synchronous study metrics on synthetic run-ups with known lines (studies/metrics.cpp).
#include "studies/metrics.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "model/spec/constants.h"

namespace turbodyn::studies {
namespace {

// Speed ramp 100 -> 900 Hz in 2 s at 20 kHz. The probe carries 1x (1 um) plus a sub-synchronous line: below
// 500 Hz rotor speed at 0.45 f_d (2 um, an inner-film whirl), from 500 Hz on at a fixed 350 Hz (3 um, the next
// rotor mode), so the dominant line jumps at 500 Hz = 30,000 rpm.
RunupResult jumping_whirl(double whirl_amplitude) {
  RunupResult r;
  auto channel = [](const std::string& name, ProbeChannel::Kind kind) {
    ProbeChannel c;
    c.name = name;
    c.kind = kind;
    return c;
  };
  r.channels = {channel("speed", ProbeChannel::Kind::Speed), channel("spin_angle", ProbeChannel::Kind::Angle),
                channel("disk.compressor.x", ProbeChannel::Kind::RotorDof)};
  r.columns.assign(3, {});
  const double fs = 20000.0;
  double whirl_phase = 0.0;
  for (int i = 0; i < 40000; ++i) {
    const double t = i / fs, fd = 100.0 + 400.0 * t;
    const double angle = 2.0 * kPi * (100.0 * t + 200.0 * t * t);
    const bool jumped = fd >= 500.0;
    whirl_phase += 2.0 * kPi * (jumped ? 350.0 : 0.45 * fd) / fs;
    const double a = whirl_amplitude * (jumped ? 3e-6 : 2e-6);
    r.time.push_back(t);
    r.columns[0].push_back(fd);
    r.columns[1].push_back(angle);
    r.columns[2].push_back(1e-6 * std::cos(angle) + a * std::cos(whirl_phase));
  }
  return r;
}

MetricSpec threshold_metric(const std::string& kind, double threshold) {
  MetricSpec m;
  m.kind = kind;
  m.probe = "disk.compressor.x";
  m.threshold = threshold;
  return m;
}

TEST(Metrics, JumpSpeedIsWhereTheDominantSubsynchronousLineChangesItsFrequency) {
  const RunupResult r = jumping_whirl(1.0);
  const double jump = evaluate_metric(threshold_metric("subsync_jump_speed", 0.5e-6), r, {}, 20000.0);
  // One STFT segment (2048 samples, 0.1 s) spans 40 Hz of rotor speed, 2,400 rpm.
  EXPECT_NEAR(jump, 30000.0, 3000.0);
  const double onset = evaluate_metric(threshold_metric("subsync_onset_speed", 0.5e-6), r, {}, 20000.0);
  EXPECT_LT(onset, 9000.0);  // present from the first segments (f_d about 120 Hz)
  const double top = evaluate_metric(threshold_metric("subsync_max", 0.0), r, {}, 20000.0);
  EXPECT_NEAR(top, 3e-6, 0.6e-6);
  EXPECT_NEAR(evaluate_metric(threshold_metric("subsync_frequency", 0.0), r, {}, 20000.0), 350.0, 15.0);
}

TEST(Metrics, MinIsTheSmallestSignedValueInTheWindowAndMaxTheLargestMagnitude) {
  // 1 µm of 1x plus 2 µm of whirl below 500 Hz, 3 µm from there on: the two lines line up somewhere in the
  // thousands of cycles, so the smallest value lies within 2.5 % of -4 µm (of -3 µm below 30,000 rpm).
  const RunupResult r = jumping_whirl(1.0);
  MetricSpec m = threshold_metric("min", 0.0);
  const double least = evaluate_metric(m, r, {}, 20000.0);
  EXPECT_LT(least, -3.9e-6);
  EXPECT_GE(least, -4e-6);
  m.kind = "max";
  EXPECT_NEAR(evaluate_metric(m, r, {}, 20000.0), -least, 0.05e-6);
  m.kind = "min";
  m.speed_max = 29000.0 * 2.0 * kPi / 60.0;  // rad/s: the 2-µm whirl alone
  const double early = evaluate_metric(m, r, {}, 20000.0);
  EXPECT_LT(early, -2.9e-6);
  EXPECT_GE(early, -3e-6);
}

TEST(Metrics, JumpSpeedNeedsALineAboveTheThreshold) {
  const RunupResult r = jumping_whirl(0.1);  // lines of 0.2 and 0.3 um
  EXPECT_TRUE(std::isnan(evaluate_metric(threshold_metric("subsync_jump_speed", 0.5e-6), r, {}, 20000.0)));
  EXPECT_TRUE(std::isnan(evaluate_metric(threshold_metric("subsync_onset_speed", 0.5e-6), r, {}, 20000.0)));
  // With the threshold below both lines the jump is found again.
  EXPECT_NEAR(evaluate_metric(threshold_metric("subsync_jump_speed", 0.1e-6), r, {}, 20000.0), 30000.0, 3000.0);
}

// Two whirls at once, as in a floating-ring bearing: an inner-film whirl at 0.55 f_d from the start (2 um) and an
// outer-film whirl at 0.15 f_d from f_d = 600 Hz (36,000 rpm) on (1.5 um), on the ramp 100 -> 900 Hz in 2 s.
RunupResult two_whirls() {
  RunupResult r = jumping_whirl(0.0);
  double inner = 0.0, outer = 0.0;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    const double fd = r.columns[0][i];
    inner += 2.0 * kPi * 0.55 * fd / 20000.0;
    outer += 2.0 * kPi * 0.15 * fd / 20000.0;
    r.columns[2][i] += 2e-6 * std::cos(inner) + (fd >= 600.0 ? 1.5e-6 * std::cos(outer) : 0.0);
  }
  return r;
}

TEST(Metrics, AnOrderBandPicksOneOfTwoWhirls) {
  const RunupResult r = two_whirls();
  MetricSpec onset = threshold_metric("subsync_onset_speed", 0.5e-6);
  EXPECT_LT(evaluate_metric(onset, r, {}, 20000.0), 9000.0);  // the default band sees the inner whirl at once
  onset.order_min = 0.05;
  onset.order_max = 0.3;
  // One STFT segment spans 2,400 rpm; the segment that first holds enough of the new line is within one of 36,000.
  EXPECT_NEAR(evaluate_metric(onset, r, {}, 20000.0), 36000.0, 2500.0);
  MetricSpec frequency = threshold_metric("subsync_frequency", 0.0);
  frequency.order_min = 0.05;
  frequency.order_max = 0.3;
  frequency.speed_min = 2.0 * kPi * 800.0;  // near 800 Hz rotor speed: 0.15 f_d = 120 Hz
  frequency.speed_max = 2.0 * kPi * 810.0;
  EXPECT_NEAR(evaluate_metric(frequency, r, {}, 20000.0), 120.0, 6.0);
  MetricSpec top = threshold_metric("subsync_max", 0.0);
  top.order_min = 0.05;
  top.order_max = 0.3;
  EXPECT_NEAR(evaluate_metric(top, r, {}, 20000.0), 1.5e-6, 0.3e-6);
  top.order_min = 0.4;  // the inner whirl alone
  top.order_max = 0.7;
  EXPECT_NEAR(evaluate_metric(top, r, {}, 20000.0), 2e-6, 0.4e-6);
}

}  // namespace
}  // namespace turbodyn::studies

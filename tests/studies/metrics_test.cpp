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

MetricSpec metric(const std::string& kind, double threshold) {
  MetricSpec m;
  m.kind = kind;
  m.probe = "disk.compressor.x";
  m.threshold = threshold;
  return m;
}

TEST(Metrics, JumpSpeedIsWhereTheDominantSubsynchronousLineChangesItsFrequency) {
  const RunupResult r = jumping_whirl(1.0);
  const double jump = evaluate_metric(metric("subsync_jump_speed", 0.5e-6), r, {}, 20000.0);
  // One STFT segment (2048 samples, 0.1 s) spans 40 Hz of rotor speed, 2,400 rpm.
  EXPECT_NEAR(jump, 30000.0, 3000.0);
  const double onset = evaluate_metric(metric("subsync_onset_speed", 0.5e-6), r, {}, 20000.0);
  EXPECT_LT(onset, 9000.0);  // present from the first segments (f_d about 120 Hz)
  const double top = evaluate_metric(metric("subsync_max", 0.0), r, {}, 20000.0);
  EXPECT_NEAR(top, 3e-6, 0.6e-6);
  EXPECT_NEAR(evaluate_metric(metric("subsync_frequency", 0.0), r, {}, 20000.0), 350.0, 15.0);
}

TEST(Metrics, JumpSpeedNeedsALineAboveTheThreshold) {
  const RunupResult r = jumping_whirl(0.1);  // lines of 0.2 and 0.3 um
  EXPECT_TRUE(std::isnan(evaluate_metric(metric("subsync_jump_speed", 0.5e-6), r, {}, 20000.0)));
  EXPECT_TRUE(std::isnan(evaluate_metric(metric("subsync_onset_speed", 0.5e-6), r, {}, 20000.0)));
  // With the threshold below both lines the jump is found again.
  EXPECT_NEAR(evaluate_metric(metric("subsync_jump_speed", 0.1e-6), r, {}, 20000.0), 30000.0, 3000.0);
}

}  // namespace
}  // namespace turbodyn::studies

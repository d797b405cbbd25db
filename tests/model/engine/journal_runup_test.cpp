// A rigid symmetric rotor in plain journal bearings: stable below the classical oil-whirl threshold, unstable
// above it with a whirl at about half the rotor speed (docs/references.md §2).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "model/engine/integrator.h"
#include "post/signal.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// Rotor: solid steel shaft Ø 30 mm x 100 mm (first bending mode ~14 kHz: rigid here), journals at both ends in
// short plain bearings L/D = 1/4, c = 30 um, eta = 10 mPa s, a small unbalanced disk at mid-span as the seed.
constexpr double kEta = 0.01, kR = 0.015, kL = 0.0075, kC = 30e-6;

MachineSpec rotor_in_journal_bearings(double speed) {
  MachineSpec s = testing::uniform_beam(0.1, 0.03, 4, true, true);
  s.gravity = 9.81;
  s.oil.viscosity = kEta;
  DiskSpec d;
  d.name = "mid";
  d.z = 0.05;
  d.mass = 1e-3;
  d.unbalance = 2e-8;  // kg m: a synchronous orbit of a fraction of a micrometre
  s.disks.push_back(d);
  for (double z : {0.0, 0.1}) {
    BearingSpec b;
    b.name = z == 0.0 ? "left" : "right";
    b.type = BearingType::Journal;
    b.z = z;
    b.journal.diameter = 2 * kR;
    b.journal.length = kL;
    b.journal.clearance = kC;
    b.journal.n_circ = 40;
    b.journal.n_axial = 8;
    s.bearings.push_back(b);
  }
  s.speed.kind = SpeedProfile::Kind::Table;
  s.speed.times = {0.0, 1.0};
  s.speed.speeds = {speed, speed};
  s.speed.start = s.speed.end = speed;
  s.speed.duration = 1.0;
  return s;
}

// Classical threshold from the linearised short-bearing coefficients (docs/references.md §2, Friswell et
// al. 2010 §5.5) and the stability condition of a rigid rotor on two identical bearings (Lund 1966; e.g. Friswell
// §5.8): unstable when m c w^2 / W > kappa / nu^2, kappa the equivalent stiffness and nu the whirl-frequency ratio.
struct Threshold {
  double speed, whirl_ratio;
};
Threshold classical_threshold(double mass_per_bearing) {
  const double W = mass_per_bearing * 9.81;
  auto load = [&](double e, double w) {
    const double fr = kEta * w * kR * std::pow(kL, 3) * e * e / (kC * kC * std::pow(1 - e * e, 2));
    const double ft = M_PI * kEta * w * kR * std::pow(kL, 3) * e / (4 * kC * kC * std::pow(1 - e * e, 1.5));
    return std::hypot(fr, ft);
  };
  auto margin = [&](double w, double* nu) {
    double lo = 1e-9, hi = 0.999;
    for (int i = 0; i < 200; ++i) (load(0.5 * (lo + hi), w) < W ? lo : hi) = 0.5 * (lo + hi);
    const double e = 0.5 * (lo + hi), s = std::sqrt(1 - e * e), pi2 = M_PI * M_PI;
    const double h0 = std::pow(pi2 * (1 - e * e) + 16 * e * e, -1.5);
    const double auu = 4 * h0 * (pi2 * (2 - e * e) + 16 * e * e);
    const double auv = M_PI * h0 * (pi2 * std::pow(1 - e * e, 2) - 16 * std::pow(e, 4)) / (e * s);
    const double avu = -M_PI * h0 * (pi2 * (1 - e * e) * (1 + 2 * e * e) + 32 * e * e * (1 + e * e)) / (e * s);
    const double avv = 4 * h0 * (pi2 * (1 + 2 * e * e) + 32 * e * e * (1 + e * e) / (1 - e * e));
    const double buu = 2 * M_PI * h0 * s * (pi2 * (1 + 2 * e * e) - 16 * e * e) / e;
    const double buv = -8 * h0 * (pi2 * (1 + 2 * e * e) - 16 * e * e), bvu = buv;
    const double bvv = 2 * M_PI * h0 * (pi2 * std::pow(1 - e * e, 2) + 48 * e * e) / (e * s);
    const double kappa = (auu * bvv + avv * buu - auv * bvu - avu * buv) / (buu + bvv);
    const double g2 = ((auu - kappa) * (avv - kappa) - auv * avu) / (buu * bvv - buv * bvu);
    *nu = std::sqrt(g2);
    return mass_per_bearing * kC * w * w / W - kappa / g2;  // > 0: unstable
  };
  double lo = 10.0, hi = 1e5, nu = 0.5;
  for (int i = 0; i < 100; ++i) (margin(0.5 * (lo + hi), &nu) < 0 ? lo : hi) = 0.5 * (lo + hi);
  margin(lo, &nu);
  return {lo, nu};
}

struct Outcome {
  double early, late;  // largest orbit radius of the mid-span in an early and in the last window, m
  double whirl_hz;     // dominant frequency in the last window
};

Outcome journal_run(double speed, double duration) {
  MachineSpec spec = rotor_in_journal_bearings(speed);
  spec.output.sample_rate = 20000;
  const auto model = make_runup_model(spec);
  RunupOptions o = runup_options(spec);
  o.t_end = duration;
  const RunupResult r = simulate_runup(*model, o);
  EXPECT_TRUE(r.complete) << r.message;
  int cx = 0, cy = 0;
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    if (r.channels[c].name == "disk.mid.x") cx = static_cast<int>(c);
    if (r.channels[c].name == "disk.mid.y") cy = static_cast<int>(c);
  }
  const std::size_t n = r.time.size();
  auto radius = [&](std::size_t a, std::size_t b) {
    // Orbit about the window's mean position (the static sag is not a vibration).
    double mx = 0, my = 0;
    for (std::size_t i = a; i < b; ++i) {
      mx += r.columns[cx][i];
      my += r.columns[cy][i];
    }
    mx /= double(b - a);
    my /= double(b - a);
    double m = 0;
    for (std::size_t i = a; i < b; ++i) m = std::max(m, std::hypot(r.columns[cx][i] - mx, r.columns[cy][i] - my));
    return m;
  };
  Outcome out{radius(n / 10, n / 5), radius(3 * n / 5, n), 0.0};
  // Whirl frequency from the zero crossings of x about its mean over the last 40 % of the run.
  const std::size_t a = 3 * n / 5;
  double mean = 0;
  for (std::size_t i = a; i < n; ++i) mean += r.columns[cx][i];
  mean /= double(n - a);
  std::size_t crossings = 0, first = 0, last = 0;
  for (std::size_t i = a + 1; i < n; ++i)
    if ((r.columns[cx][i - 1] - mean) * (r.columns[cx][i] - mean) < 0) {
      if (crossings == 0) first = i;
      last = i;
      ++crossings;
    }
  if (crossings > 2) out.whirl_hz = 0.5 * double(crossings - 1) / (r.time[last] - r.time[first]);
  return out;
}

TEST(JournalRunup, OilWhirlThresholdAndHalfSpeedWhirl) {
  const MachineSpec spec = rotor_in_journal_bearings(1000.0);
  const double mass_per_bearing = 0.5 * build_rotor(spec).total_mass;
  const Threshold th = classical_threshold(mass_per_bearing);
  ASSERT_GT(th.speed, 500.0);
  ASSERT_LT(th.speed, 5000.0);
  // Margins generous enough for the finite-length film (L/D = 1/4 carries ~10 % less than the short-bearing
  // formulas, which shifts the threshold by a similar amount).
  // Above the threshold the whirl grows within a few tens of revolutions; the runs stop before the limit cycle
  // close to the clearance, where the stiff film makes the integration slow.
  const Outcome below = journal_run(0.6 * th.speed, 0.12);
  const Outcome above = journal_run(1.6 * th.speed, 0.06);
  std::cout << "[ validation ] threshold " << th.speed << " rad/s (whirl ratio " << th.whirl_ratio << "); below: "
            << below.early * 1e6 << " -> " << below.late * 1e6 << " um; above: " << above.early * 1e6 << " -> "
            << above.late * 1e6 << " um, whirl " << above.whirl_hz << " Hz at "
            << 1.6 * th.speed / (2 * M_PI) << " Hz rotor speed\n";
  EXPECT_LT(below.late, 1.5 * below.early);         // no growth below the threshold
  EXPECT_GT(above.late, 10.0 * above.early);        // growth above it ...
  EXPECT_GT(above.late, 100.0 * below.late);        // ... far beyond the unbalance response ...
  EXPECT_GT(above.late, 0.05 * kC);                 // ... to a whirl orbit of a noticeable part of the clearance
  const double ratio = above.whirl_hz / (1.6 * th.speed / (2 * M_PI));
  EXPECT_NEAR(ratio, 0.5, 0.06);                    // at about half the rotor speed
}

}  // namespace
}  // namespace turbodyn

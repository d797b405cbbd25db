// The journal-bearing force element: restoring tilt moments, and a closing film as an error rather than a crash.
#include "model/elements/journal_bearing_element.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using testing::short_bearing_spec;

TEST(JournalBearing, TiltedJournalFeelsARestoringMoment) {
  // theta_y > 0 tilts the journal axis towards +x at +z (dx/dz = theta_y): the film pushes that end back, a
  // negative moment about y. theta_x > 0 tilts it towards -y at +z: pushed back in +y there, M_x = -z F_y < 0.
  // Both oppose the tilt.
  const OilSpec oil = testing::oil_of_viscosity(0.0108);
  const JournalBearingSpec j = short_bearing_spec();
  const JournalBearingElement e("test", j, oil, 0);
  auto ws = e.make_workspace();
  const SpinState s{0.0, 5000.0, 0.0, 0.0};
  const double tilt = 0.5 * j.clearance / (0.5 * j.length);  // ends at half the clearance
  const double v[4] = {0, 0, 0, 0};
  double f[4] = {0, 0, 0, 0};
  const double qy[4] = {0, 0, 0, tilt};
  e.calc_and_add_forces(s, qy, v, nullptr, *ws, f, nullptr);
  EXPECT_LT(f[3], 0.0);
  double g[4] = {0, 0, 0, 0};
  const double qx[4] = {0, 0, tilt, 0};
  e.calc_and_add_forces(s, qx, v, nullptr, *ws, g, nullptr);
  EXPECT_LT(g[2], 0.0);
  // Axisymmetric film: the same restoring moment turned by 90 degrees (to the solver's tolerance).
  EXPECT_NEAR(g[2], f[3], 1e-3 * std::abs(f[3]));
}

TEST(JournalBearing, ThinnestFilmProbeIsTheClearanceLessTheEndOffsetAndCarriesTheModelFilesLimit) {
  const OilSpec oil = testing::oil_of_viscosity(0.0108);
  JournalBearingSpec j = short_bearing_spec();
  const double c = j.clearance;
  // Journal 0.4 c off in +x, tilted in the x-z plane so that one end lies 0.3 c further out: 0.3 c of film left.
  const double q[4] = {0.4 * c, 0, 0, 0.3 * c / (0.5 * j.length)}, v[4] = {0, 0, 0, 0};
  const auto thinnest = [&](const JournalBearingElement& e) {
    const std::vector<ProbeInfo> info = e.probes();
    std::vector<double> out(info.size());
    auto ws = e.make_workspace();
    e.eval_probes(SpinState{0.0, 5000.0, 0.0, 0.0}, q, v, nullptr, *ws, out.data());
    for (std::size_t i = 0; i < info.size(); ++i)
      if (info[i].name == "min_film_thickness") return std::make_pair(info[i], out[i]);
    ADD_FAILURE() << "no min_film_thickness probe";
    return std::make_pair(info[0], 0.0);
  };
  const auto [none, h] = thinnest(JournalBearingElement("test", j, oil, 0));
  EXPECT_NEAR(h, 0.3 * c, 1e-12 * c);
  EXPECT_EQ(none.unit, "m");
  EXPECT_FALSE(std::isfinite(none.limit));  // no film_thickness_limit, no limit
  j.film_thickness_limit = 2e-6;
  const auto [limited, h2] = thinnest(JournalBearingElement("test", j, oil, 0));
  EXPECT_EQ(h2, h);
  EXPECT_EQ(limited.limit, 2e-6);
  EXPECT_TRUE(limited.limit_below);
  EXPECT_NE(limited.limit_note.find("film_thickness_limit"), std::string::npos);
}

TEST(JournalBearing, ClosingFilmIsAnErrorNotACrash) {
  OilSpec oil;
  const JournalBearingElement e("compressor", short_bearing_spec(), oil, 0);
  auto ws = e.make_workspace();
  const double q[4] = {20e-6, 0, 0, 0}, v[4] = {0, 0, 0, 0};
  double f[4] = {0, 0, 0, 0};
  try {
    e.calc_and_add_forces(SpinState{0.1, 100.0, 0.0, 0.0}, q, v, nullptr, *ws, f, nullptr);
    FAIL() << "no error";
  } catch (const std::runtime_error& err) {
    EXPECT_NE(std::string(err.what()).find("compressor"), std::string::npos) << err.what();
  }
}

}  // namespace
}  // namespace turbodyn

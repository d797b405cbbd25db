// Squeeze-film dampers around linear bearings in a run-up: the damper cuts the force transmitted at the first
// critical speeds, and the energy balance closes.
#include "model/elements/damper_element.h"

#include <cmath>

#include <gtest/gtest.h>

#include "model/io/model_file.h"
#include "model/engine/integrator.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// Tangential and radial force on the housing of a damper whose ring runs a centred circular orbit.
struct OrbitForce {
  double radial, tangential, eccentricity;
};
TEST(Damper, RunUpThroughTheFirstCriticalsWithLowerForceAndClosedEnergyBalance) {
  // The paper's observation for its variant III (§3.3): the damper lowers the bearing forces. Here the reference
  // rotor on its linear bearings, rigidly held or in dampers with a soft centring spring, 0 -> 40,000 rpm at the
  // paper's acceleration (past the forward criticals at 30,700 and 42,000 rpm of the rigid mounting).
  std::vector<Override> base = {{"speed.end", "40000 rpm"}, {"speed.duration", "1.0667"}};
  std::vector<Override> damped = base;
  for (const char* b : {"compressor", "turbine"}) {
    const std::string p = std::string("bearings.") + b + ".damper.";
    for (auto [k, v] : std::vector<std::pair<const char*, const char*>>{{"diameter", "20.5 mm"},
                                                                        {"length", "6 mm"},
                                                                        {"clearance", "51 um"},
                                                                        {"ring_mass", "15 g"},
                                                                        {"centring_stiffness", "1e6"}})
      damped.push_back({p + k, v});
  }
  auto run = [](const std::vector<Override>& o) {
    const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_linear.toml", o);
    const auto model = make_runup_model(spec);
    return simulate_runup(*model, runup_options(spec));
  };
  const RunupResult rigid = run(base), sfd = run(damped);
  ASSERT_TRUE(rigid.complete && sfd.complete) << rigid.message << sfd.message;
  auto peak = [](const RunupResult& r, const std::string& name) {
    for (std::size_t c = 0; c < r.channels.size(); ++c)
      if (r.channels[c].name == name) {
        double m = 0;
        for (double x : r.columns[c]) m = std::max(m, std::abs(x));
        return m;
      }
    return -1.0;
  };
  EXPECT_LT(peak(sfd, "bearing.compressor.fx"), 0.2 * peak(rigid, "bearing.compressor.fx"));
  EXPECT_LT(peak(sfd, "bearing.compressor.damper_eccentricity"), 0.9);
  // Film dissipation enters the energy balance through the element's dissipated_power.
  const double error = sfd.energy_final - sfd.energy_initial - sfd.work_in + sfd.dissipated;
  EXPECT_LT(std::abs(error), 1e-3 * sfd.work_in);
}

TEST(Damper, StaticStartWithoutACentringSpringSaysWhatToChange) {
  // A squeeze film has no static stiffness: without a centring spring the rings have no static equilibrium, and
  // the Newton search drives them through the film. The run stops at t = 0 with a message that names the search,
  // the film's own error and the setting to change, not the film's error alone.
  std::vector<Override> o = {{"speed.end", "1000 rpm"}, {"speed.duration", "0.01"}};
  for (const char* b : {"compressor", "turbine"})
    o.push_back({std::string("bearings.") + b + ".damper.centring_stiffness", "0"});
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_damper.toml", o);
  ASSERT_TRUE(spec.solver.static_start);
  const auto model = make_runup_model(spec);
  const RunupResult r = simulate_runup(*model, runup_options(spec));
  EXPECT_FALSE(r.complete);
  EXPECT_NE(r.message.find("the static equilibrium under gravity was not found (Newton iteration"), std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("film closes"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("set static_start = false"), std::string::npos) << r.message;
  // With static_start = false the same model starts centred and runs.
  o.push_back({"solver.static_start", "false"});
  const MachineSpec settle = load_model(testing::source_dir() + "/examples/reference_damper.toml", o);
  const auto model2 = make_runup_model(settle);
  const RunupResult r2 = simulate_runup(*model2, runup_options(settle));
  EXPECT_TRUE(r2.complete) << r2.message;
}

}  // namespace
}  // namespace turbodyn

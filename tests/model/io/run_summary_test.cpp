// A run's summary.json marks where a probe with a limit (a ball bearing's contact pressure) first passes it, and
// the run's warnings say so.
#include "model/io/run_summary.h"

#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/engine/runup.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using ::testing::HasSubstr;

TEST(RunSummary, AProbeThatPassesItsLimitIsMarkedWhereItFirstDoesAndWarnedOf) {
  const MachineSpec spec = load_model(testing::example("reference_linear.toml"));
  const std::unique_ptr<RunupModel> model = make_runup_model(spec);
  RunupResult r;
  r.complete = true;
  r.time = {0.0, 0.1, 0.2, 0.3, 0.4};
  ProbeChannel speed{"speed", "Hz", "rotor speed f_d", ProbeChannel::Kind::Speed, 0, 0};
  ProbeChannel pressure{"bearing.b.max_contact_pressure", "Pa", "largest Hertz pressure", ProbeChannel::Kind::Element,
                        0, 0, 4.2e9, "ISO 76's static limit"};
  ProbeChannel below = pressure;
  below.name = "bearing.c.max_contact_pressure";
  ProbeChannel force{"bearing.b.fx", "N", "force", ProbeChannel::Kind::Element, 0, 1};
  r.channels = {speed, pressure, below, force};
  r.columns = {{0.0, 100.0, 200.0, 300.0, 400.0},
               {1e9, 3e9, 4.3e9, 5e9, 4.0e9},  // first above 4.2 GPa at t = 0.2 s, 200 Hz; largest 5 GPa
               {1e9, 4.2e9, 2e9, 1e9, 0.0},    // reaches the limit, does not pass it
               {1.0, 2.0, 3.0, 2.0, 1.0}};
  const nlohmann::json j = run_summary(spec, *model, RunupOptions{}, r, {});

  const nlohmann::json& p = j["probes"]["bearing.b.max_contact_pressure"];
  EXPECT_EQ(p["limit"].get<double>(), 4.2e9);
  EXPECT_EQ(p["limit_note"].get<std::string>(), "ISO 76's static limit");
  EXPECT_EQ(p["over_limit"]["time_s"].get<double>(), 0.2);
  EXPECT_EQ(p["over_limit"]["speed_rpm"].get<double>(), 12000.0);
  EXPECT_EQ(p["max_abs"].get<double>(), 5e9);
  EXPECT_TRUE(j["probes"]["bearing.c.max_contact_pressure"]["over_limit"].is_null());
  EXPECT_FALSE(j["probes"]["bearing.b.fx"].contains("limit"));  // no limit, no entry

  const std::vector<std::string> w = probe_limit_warnings(j);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("bearing.b.max_contact_pressure is first above its limit of 4200 MPa at 12000 rpm "
                              "(t = 0.2000 s), largest 5000 MPa at 18000 rpm. The limit: ISO 76's static limit."));
  EXPECT_TRUE(probe_limit_warnings(nlohmann::json::object()).empty());
  // A study's run carries it in one line (results.csv's note), without the time.
  EXPECT_EQ(probe_limit_note(j),
            "bearing.b.max_contact_pressure is first above its limit of 4200 MPa at 12000 rpm, largest 5000 MPa at "
            "18000 rpm");
  EXPECT_EQ(probe_limit_note(nlohmann::json::object()), "");
}

}  // namespace
}  // namespace turbodyn

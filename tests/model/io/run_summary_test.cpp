// A run's summary.json marks where a probe with a limit (a ball bearing's contact pressure) first passes it, and
// the run's warnings say so.
#include "model/io/run_summary.h"

#include <limits>
#include <memory>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/engine/runup.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using ::testing::HasSubstr;

// The summary of a run of five samples, 0.1 s apart at rotor speeds 0, 100, ..., 400 Hz, of `probes` (after the
// speed) with the values `columns`.
nlohmann::json five_sample_summary(const std::vector<ProbeChannel>& probes,
                                   const std::vector<std::vector<double>>& columns) {
  const MachineSpec spec = load_model(testing::example("reference_linear.toml"));
  const std::unique_ptr<RunupModel> model = make_runup_model(spec);
  RunupResult r;
  r.complete = true;
  r.time = {0.0, 0.1, 0.2, 0.3, 0.4};
  r.channels = {{"speed", "Hz", "rotor speed f_d", ProbeChannel::Kind::Speed, 0, 0}};
  r.channels.insert(r.channels.end(), probes.begin(), probes.end());
  r.columns = {{0.0, 100.0, 200.0, 300.0, 400.0}};
  r.columns.insert(r.columns.end(), columns.begin(), columns.end());
  return run_summary(spec, *model, RunupOptions{}, r, {});
}

TEST(RunSummary, AProbeThatPassesItsLimitIsMarkedWhereItFirstDoesAndWarnedOf) {
  ProbeChannel pressure{"bearing.b.max_contact_pressure", "Pa", "largest Hertz pressure", ProbeChannel::Kind::Element,
                        0, 0, 4.2e9, "ISO 76's static limit"};
  ProbeChannel below = pressure;
  below.name = "bearing.c.max_contact_pressure";
  ProbeChannel force{"bearing.b.fx", "N", "force", ProbeChannel::Kind::Element, 0, 1};
  const nlohmann::json j =
      five_sample_summary({pressure, below, force}, {{1e9, 3e9, 4.3e9, 5e9, 4.0e9},  // first above 4.2 GPa at
                                                                                   // 0.2 s, 200 Hz; largest 5 GPa
                                                     {1e9, 4.2e9, 2e9, 1e9, 0.0},  // reaches it, does not pass it
                                                     {1.0, 2.0, 3.0, 2.0, 1.0}});

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

TEST(RunSummary, AFilmThatFallsBelowItsPermissibleThicknessIsMarkedWhereItFirstDoes) {
  // A limit that is a smallest value (a fluid film's permissible minimum thickness): passed when the value falls
  // below it; the summary gives every probe's smallest value and where it is reached.
  ProbeChannel film{"bearing.b.min_film_thickness", "m", "thinnest film", ProbeChannel::Kind::Element, 0, 0,
                    2e-6, "the permissible minimum", true};
  ProbeChannel touching = film;
  touching.name = "bearing.c.min_film_thickness";
  const nlohmann::json j = five_sample_summary(
      {film, touching}, {{10e-6, 5e-6, 1.5e-6, 0.6e-6, 3e-6},  // first below 2 µm at t = 0.2 s; smallest 0.6 µm
                         {10e-6, 2e-6, 4e-6, 8e-6, 9e-6}});    // reaches the limit, does not pass it

  const nlohmann::json& p = j["probes"]["bearing.b.min_film_thickness"];
  EXPECT_TRUE(p["limit_below"].get<bool>());
  EXPECT_EQ(p["over_limit"]["time_s"].get<double>(), 0.2);
  EXPECT_EQ(p["over_limit"]["speed_rpm"].get<double>(), 12000.0);
  EXPECT_EQ(p["min"].get<double>(), 0.6e-6);
  EXPECT_EQ(p["time_at_min_s"].get<double>(), 0.3);
  EXPECT_EQ(p["speed_at_min_rpm"].get<double>(), 18000.0);
  EXPECT_EQ(p["max_abs"].get<double>(), 10e-6);  // the largest |value| as for every probe
  EXPECT_TRUE(j["probes"]["bearing.c.min_film_thickness"]["over_limit"].is_null());
  EXPECT_FALSE(j["probes"].contains("speed"));  // the speed is no probe of the summary

  const std::vector<std::string> w = probe_limit_warnings(j);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("bearing.b.min_film_thickness is first below its limit of 2.0 µm at 12000 rpm "
                              "(t = 0.2000 s), smallest 0.6 µm at 18000 rpm. The limit: the permissible minimum."));
  EXPECT_EQ(probe_limit_note(j),
            "bearing.b.min_film_thickness is first below its limit of 2.0 µm at 12000 rpm, smallest 0.6 µm at "
            "18000 rpm");
}

}  // namespace
}  // namespace turbodyn

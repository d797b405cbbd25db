// Model files: values, units, overrides, and the errors a new user meets.
#include "model/io/model_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/temp_dir.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::source_dir;
using testing::example;

std::string bad(const std::string& name) { return source_dir() + "/tests/data/bad_models/" + name; }

// The message of the ModelError thrown by loading `file` with `overrides` ("" if none is thrown).
// The text of an example without its lines that start with `key` (a key it names, to see the default).
std::string example_without(const std::string& name, const std::string& key) {
  std::ifstream in(example(name));
  std::string text, line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) != 0) text += line + "\n";
  return text;
}

std::string model_error_of(const std::string& file, const std::vector<Override>& overrides = {}) {
  try {
    load_model(file, overrides);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

// The feed rules every film table shares (feed_groove_width beside feed_hole_diameter and supply_pressure): `prefix`
// the table's keys ("bearings.NAME." or "bearings.NAME.damper."), `groove_of` the width read from it, `too_wide` a
// groove as wide as the film and `width_message` how the refusal names the film's width.
void expect_feed_groove_rules(const std::string& f, const std::string& prefix,
                              const std::function<double(const MachineSpec&)>& groove_of, const std::string& too_wide,
                              const std::string& width_message) {
  const Override no_hole = parse_override(prefix + "feed_hole_diameter=0 mm");
  EXPECT_DOUBLE_EQ(groove_of(load_model(f, {no_hole, parse_override(prefix + "feed_groove_width=2 mm")})), 2e-3);
  EXPECT_DOUBLE_EQ(groove_of(load_model(f)), 0.0);  // none unless given
  EXPECT_THAT(model_error_of(f, {parse_override(prefix + "feed_groove_width=2 mm")}),
              AllOf(HasSubstr(prefix + "feed_groove_width"), HasSubstr("not both")));
  EXPECT_THAT(model_error_of(f, {no_hole, parse_override(prefix + "feed_groove_width=" + too_wide)}),
              AllOf(HasSubstr("feed_groove_width"), HasSubstr(width_message)));
  EXPECT_THAT(model_error_of(f, {no_hole, parse_override(prefix + "feed_groove_width=-1 mm")}),
              HasSubstr("feed_groove_width"));
  EXPECT_THAT(model_error_of(f, {no_hole}),
              AllOf(HasSubstr(prefix + "supply_pressure"), HasSubstr("feed_groove_width")));
}

TEST(ModelFile, ReferenceExampleValuesInSI) {
  const MachineSpec s = load_model(example("reference_linear.toml"));
  EXPECT_EQ(s.shaft.size(), 1u);
  EXPECT_DOUBLE_EQ(s.shaft_length(), 0.140);
  ASSERT_EQ(s.disks.size(), 2u);
  const DiskSpec& c = s.disks[0].name == "compressor" ? s.disks[0] : s.disks[1];
  EXPECT_NEAR(c.unbalance, 3.9e-7, 1e-20);
  EXPECT_NEAR(c.unbalance_phase, M_PI / 2, 1e-15);
  EXPECT_NEAR(c.z, 0.012, 1e-15);
  EXPECT_NEAR(s.speed.end, 150000 * 2 * M_PI / 60, 1e-9);
  EXPECT_DOUBLE_EQ(s.speed.duration, 4.0);
  EXPECT_DOUBLE_EQ(s.output.sample_rate, 20000.0);
  ASSERT_EQ(s.bearings.size(), 2u);
  EXPECT_DOUBLE_EQ(s.bearings[0].linear.k[0][0], 3e7);
  EXPECT_DOUBLE_EQ(s.bearings[0].linear.k[3][0], 3e7);
  EXPECT_DOUBLE_EQ(s.bearings[0].linear.k[1][0], 0.0);
}

TEST(ModelFile, DiskInertiaFromGeometry) {
  // Friswell Ex. 5.9.1 disk 1: rho pi w (do^2 - di^2) / 4 with rho 7810, w 0.07, do 0.28, di 0.05.
  const MachineSpec s = load_model(example("friswell_5_9_1.toml"));
  const double m = 7810 * M_PI * 0.07 * (0.28 * 0.28 - 0.05 * 0.05) / 4;
  EXPECT_NEAR(s.disks[0].mass, m, 1e-12);
  EXPECT_NEAR(s.disks[0].polar_inertia, m * (0.28 * 0.28 + 0.05 * 0.05) / 8, 1e-14);
  EXPECT_NEAR(s.materials.at("steel").poisson_ratio, 211.0 / (2 * 81.2) - 1, 1e-14);
}

TEST(ModelFile, OverridesUseTheFileSyntax) {
  const MachineSpec s = load_model(example("reference_linear.toml"),
                                   {parse_override("bearings.compressor.k=1e7"),
                                    parse_override("disks.turbine.unbalance = 1 g*mm"),
                                    parse_override("shaft[0].outer_diameter=12 mm"),
                                    parse_override("damping.beta=1e-6"),
                                    parse_override("modal.orders=[1.0, 2.0]")});
  const BearingSpec& b = s.bearings[0].name == "compressor" ? s.bearings[0] : s.bearings[1];
  EXPECT_DOUBLE_EQ(b.linear.k[0][0], 1e7);
  const DiskSpec& t = s.disks[0].name == "turbine" ? s.disks[0] : s.disks[1];
  EXPECT_NEAR(t.unbalance, 1e-6, 1e-20);
  EXPECT_DOUBLE_EQ(s.shaft[0].outer_diameter, 0.012);
  EXPECT_DOUBLE_EQ(s.damping.beta, 1e-6);
  EXPECT_EQ(s.modal.orders, (std::vector<double>{1.0, 2.0}));
}

TEST(ModelFile, OverrideErrorsNameTheOverride) {
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("bearings.compressor.kxz=1")}),
              AllOf(HasSubstr("--set bearings.compressor.kxz=1"), HasSubstr("unknown key"), HasSubstr("kxx")));
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("shaft[3].length=1")}),
              HasSubstr("out of range"));
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("disks.compressor.mass=3 m")}),
              AllOf(HasSubstr("--set disks.compressor.mass=3 m"), HasSubstr("mass (kg)")));
  EXPECT_THROW(parse_override("no-equals-sign"), ModelError);
}

TEST(ModelFile, LubricatedTractionTakesTheModelsOilUnlessGivenAndItsKeysNeedIt) {
  const std::string f = example("reference_ball.toml");
  const MachineSpec s = load_model(f, {parse_override("bearings.compressor.traction_law=\"eyring\""),
                                       parse_override("bearings.turbine.traction_law=\"eyring\""),
                                       parse_override("bearings.turbine.lubricant_viscosity=5 mPa*s"),
                                       parse_override("bearings.turbine.eyring_stress=3 MPa"),
                                       parse_override("bearings.turbine.lubricant_shear_modulus=0.3 GPa")});
  EXPECT_EQ(s.bearings[0].ball.traction_law, TractionLaw::Eyring);
  EXPECT_DOUBLE_EQ(s.bearings[0].ball.lubricant_shear_modulus, 1e9);
  EXPECT_DOUBLE_EQ(s.bearings[1].ball.lubricant_shear_modulus, 3e8);
  EXPECT_DOUBLE_EQ(s.bearings[0].ball.lubricant_viscosity, s.oil.viscosity_at(s.oil.temperature));
  EXPECT_DOUBLE_EQ(s.bearings[1].ball.lubricant_viscosity, 5e-3);
  EXPECT_DOUBLE_EQ(s.bearings[1].ball.eyring_stress, 3e6);
  EXPECT_DOUBLE_EQ(s.bearings[1].ball.pressure_viscosity, 2e-8);
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.eyring_stress=3 MPa")}),
              HasSubstr("bearings.compressor.eyring_stress: needs traction_law = \"eyring\""));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.lubricant_shear_modulus=1 GPa")}),
              HasSubstr("needs traction_law = \"eyring\""));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.traction_law=\"eyring\""),
                           parse_override("bearings.compressor.lubricant_shear_modulus=-1 GPa")}),
              HasSubstr("lubricant_shear_modulus"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.traction_law=\"eyring\""),
                           parse_override("bearings.compressor.lubricant_shear_modulus=1 m")}),
              HasSubstr("lubricant_shear_modulus"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.traction_law=\"eyring\""),
                           parse_override("bearings.compressor.pressure_viscosity=1e-6")}),
              HasSubstr("pressure_viscosity"));
}

TEST(ModelFile, ThePapersHertzLawIsAChoiceWithItsCoefficient) {
  // hertz_law = "paper": Eq. 20 with the paper's mu* = 0.171 unless hertz_coefficient says otherwise; the default is
  // the exact Hertz ellipse (hertz_coefficient 0 in the spec), and the coefficient alone is an error.
  const std::string f = example("reference_ball.toml");
  const MachineSpec s = load_model(f, {parse_override("bearings.compressor.hertz_law=\"paper\""),
                                       parse_override("bearings.turbine.hertz_law=\"paper\""),
                                       parse_override("bearings.turbine.hertz_coefficient=0.5")});
  EXPECT_DOUBLE_EQ(s.bearings[0].ball.hertz_coefficient, 0.171);
  EXPECT_DOUBLE_EQ(s.bearings[1].ball.hertz_coefficient, 0.5);
  EXPECT_EQ(load_model(f).bearings[0].ball.hertz_coefficient, 0.0);
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.hertz_coefficient=0.3")}),
              HasSubstr("bearings.compressor.hertz_coefficient: needs hertz_law = \"paper\""));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.hertz_law=\"paper\""),
                           parse_override("bearings.compressor.hertz_coefficient=1.5")}),
              AllOf(HasSubstr("bearings.compressor.hertz_coefficient"), HasSubstr("(0, 1]")));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.hertz_law=\"paper\""),
                           parse_override("bearings.compressor.hertz_coefficient=0")}),
              HasSubstr("hertz_coefficient"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.hertz_law=\"hertz\"")}), HasSubstr("hertz_law"));
}

TEST(ModelFile, ABallBearingThatNamesNoTractionLawGetsTheLubricatedOne) {
  // The default race traction of a model file is the lubricated (EHL) law with the model's oil; the examples name
  // the paper's Eq. 23 ("coulomb") to reproduce the paper. The example without its traction_law lines:
  const MachineSpec s = load_model_from_string(example_without("reference_ball.toml", "traction_law"),
                                               "reference_ball_without_traction_law.toml");
  ASSERT_EQ(s.bearings.size(), 2u);
  for (const BearingSpec& b : s.bearings) {
    EXPECT_EQ(b.ball.traction_law, TractionLaw::Eyring) << b.name;
    EXPECT_DOUBLE_EQ(b.ball.lubricant_viscosity, s.oil.viscosity_at(s.oil.temperature)) << b.name;
  }
  EXPECT_EQ(load_model(example("reference_ball.toml")).bearings[0].ball.traction_law, TractionLaw::Coulomb);
}

TEST(ModelFile, ABallBearingThatNamesNoContactDampingRatioGetsTheLubricantsDamping) {
  // The default contact damping ratio of a model file is the lower end of Kraemer's range for lubricated rolling
  // bearings, 0.25e-5 s; the examples name "0 s" (the paper's Eq. 21 alone). Bad values name the key.
  const MachineSpec s = load_model_from_string(example_without("reference_ball.toml", "contact_damping_ratio"),
                                               "reference_ball_without_contact_damping_ratio.toml");
  ASSERT_EQ(s.bearings.size(), 2u);
  for (const BearingSpec& b : s.bearings) EXPECT_DOUBLE_EQ(b.ball.contact_damping_ratio, 0.25e-5) << b.name;
  const std::string f = example("reference_ball.toml");
  EXPECT_EQ(load_model(f).bearings[0].ball.contact_damping_ratio, 0.0);
  const MachineSpec t = load_model(f, {parse_override("bearings.turbine.contact_damping_ratio=20 us")});
  EXPECT_DOUBLE_EQ(t.bearings[1].ball.contact_damping_ratio, 2e-5);
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.contact_damping_ratio=-1e-5")}),
              HasSubstr("bearings.compressor.contact_damping_ratio"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.contact_damping_ratio=1e-5 N*s/m")}),
              HasSubstr("bearings.compressor.contact_damping_ratio"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.contact_damping_ratio=0.01 s")}),
              AllOf(HasSubstr("bearings.compressor.contact_damping_ratio"), HasSubstr("Kraemer")));
}

TEST(ModelFile, DamperEndSealsNeedGapAndLengthAndAGapBelowTheClearance) {
  const std::string f = example("reference_ball_sfd.toml");
  const MachineSpec s = load_model(f, {parse_override("bearings.compressor.damper.end_seal_gap=20 um"),
                                       parse_override("bearings.compressor.damper.end_seal_length=1 mm")});
  EXPECT_DOUBLE_EQ(s.bearings.at(0).damper.end_seal_gap, 20e-6);
  EXPECT_DOUBLE_EQ(s.bearings.at(0).damper.end_seal_length, 1e-3);
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.damper.end_seal_gap=20 um")}),
              AllOf(HasSubstr("end_seal_gap"), HasSubstr("end_seal_length")));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.damper.end_seal_length=1 mm")}),
              AllOf(HasSubstr("end_seal_length"), HasSubstr("end_seal_gap")));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.damper.end_seal_gap=80 um"),
                           parse_override("bearings.compressor.damper.end_seal_length=1 mm")}),
              HasSubstr("larger than the damper clearance"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.damper.end_seal_gap=-1 um"),
                           parse_override("bearings.compressor.damper.end_seal_length=1 mm")}),
              HasSubstr("end_seal_gap"));
}

TEST(ModelFile, AFeedGrooveReplacesTheFeedHoleAndIsNarrowerThanTheLand) {
  // feed_groove_width: a full circumferential groove at mid-width at the supply pressure, instead of the feed hole.
  const std::string f = example("reference_ball_sfd.toml");
  expect_feed_groove_rules(f, "bearings.compressor.damper.",
                           [](const MachineSpec& s) { return s.bearings.at(0).damper.feed_groove_width; }, "6 mm",
                           "narrower than the land width");
  const Override no_hole = parse_override("bearings.compressor.damper.feed_hole_diameter=0 mm");
  // The land's 6 even rows lie 0.86 mm apart about mid-width: a groove of 0.5 mm holds none of them.
  EXPECT_THAT(model_error_of(f, {no_hole, parse_override("bearings.compressor.damper.feed_groove_width=0.5 mm")}),
              AllOf(HasSubstr("bearings.compressor.damper.feed_groove_width"), HasSubstr("holds no node"),
                    HasSubstr("n_axial = 6")));
  EXPECT_NO_THROW(load_model(f, {no_hole, parse_override("bearings.compressor.damper.feed_groove_width=0.5 mm"),
                                 parse_override("bearings.compressor.damper.n_axial=7")}));
  EXPECT_THAT(model_error_of(f, {no_hole, parse_override("bearings.compressor.damper.feed_groove_width=5.9 mm")}),
              AllOf(HasSubstr("bearings.compressor.damper.feed_groove_width"), HasSubstr("leaves no land")));
}

TEST(ModelFile, APermissibleFilmThicknessIsPositiveAndThinnerThanTheClearance) {
  // Every fluid film takes film_thickness_limit: a floating ring's (both films), a damper's, a journal bearing's.
  const std::string ring = example("reference_floating_ring.toml");
  EXPECT_DOUBLE_EQ(load_model(ring).bearings.at(0).ring.film_thickness_limit, 0.0);  // none unless given
  EXPECT_DOUBLE_EQ(load_model(ring, {parse_override("bearings.compressor.film_thickness_limit=2 um")})
                       .bearings.at(0).ring.film_thickness_limit,
                   2e-6);
  // Thinner than both films' clearances (15 and 40 µm): the centred inner film would otherwise be below it.
  EXPECT_THAT(model_error_of(ring, {parse_override("bearings.compressor.film_thickness_limit=15 um")}),
              AllOf(HasSubstr("bearings.compressor.film_thickness_limit"), HasSubstr("thinner than the radial")));
  EXPECT_THAT(model_error_of(ring, {parse_override("bearings.compressor.film_thickness_limit=-1 um")}),
              HasSubstr("bearings.compressor.film_thickness_limit"));
  EXPECT_THAT(model_error_of(ring, {parse_override("bearings.compressor.film_thickness_limit=1 bar")}),
              HasSubstr("bearings.compressor.film_thickness_limit"));
  const std::string sfd = example("reference_ball_sfd.toml");
  EXPECT_DOUBLE_EQ(load_model(sfd, {parse_override("bearings.turbine.damper.film_thickness_limit=3 um")})
                       .bearings.at(1).damper.film_thickness_limit,
                   3e-6);
  EXPECT_THAT(model_error_of(sfd, {parse_override("bearings.turbine.damper.film_thickness_limit=51 um")}),
              HasSubstr("bearings.turbine.damper.film_thickness_limit"));
  const std::string journal = example("reference_journal.toml");
  EXPECT_DOUBLE_EQ(load_model(journal, {parse_override("bearings.compressor.film_thickness_limit=1 um")})
                       .bearings.at(0).journal.film_thickness_limit,
                   1e-6);
}

TEST(ModelFile, ExamplesLoad) {
  EXPECT_NO_THROW(load_model(example("reference_linear.toml")));
  EXPECT_NO_THROW(load_model(example("friswell_5_9_1.toml")));
}

TEST(ModelFile, FloatingRingDrillHolesAndMassConservingFilms) {
  const std::filesystem::path f = example("reference_floating_ring.toml");
  const MachineSpec s = load_model(f);
  EXPECT_EQ(s.bearings[0].ring.drill_holes, 4);
  EXPECT_DOUBLE_EQ(s.bearings[0].ring.drill_hole_diameter, 0.002);
  EXPECT_TRUE(s.bearings[0].ring.ring_tilt);
  // The mass-conserving model needs a supply in both films: the inner one is fed through the drill holes.
  EXPECT_NO_THROW(load_model(f, {parse_override("bearings.compressor.cavitation=mass-conserving")}));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.cavitation=mass-conserving"),
                           parse_override("bearings.compressor.drill_holes=0"),
                           parse_override("bearings.compressor.drill_hole_diameter=0")}),
              HasSubstr("drill_holes through the ring"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.drill_holes=9")}), HasSubstr("from 0 to 8"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.drill_hole_diameter=8 mm")}),
              HasSubstr("smaller than inner_length"));
}

TEST(ModelFile, AFloatingRingsOuterFilmIsFedThroughAHoleOrAGroove) {
  const std::string f = example("reference_floating_ring.toml");
  expect_feed_groove_rules(f, "bearings.turbine.",
                           [](const MachineSpec& s) { return s.bearings.at(1).ring.feed_groove_width; }, "10 mm",
                           "narrower than outer_length");
  const Override no_hole = parse_override("bearings.turbine.feed_hole_diameter=0 mm");
  // The mass-conserving model takes the groove as the outer film's supply.
  EXPECT_NO_THROW(load_model(f, {no_hole, parse_override("bearings.turbine.feed_groove_width=2 mm"),
                                 parse_override("bearings.turbine.cavitation=mass-conserving")}));
}

TEST(ModelFile, FloatingRingThermalFilmsAndTheirErrors) {
  // The example's isothermal films; "bulk" derives its conductances from the geometry and refuses what it cannot use.
  const std::filesystem::path f = example("reference_floating_ring.toml");
  const MachineSpec iso = load_model(f);
  EXPECT_EQ(iso.bearings[0].ring.thermal.model, FilmThermal::Isothermal);
  const Override bulk = parse_override("bearings.compressor.thermal=bulk");
  const MachineSpec s = load_model(f, {bulk, parse_override("bearings.compressor.shaft_temperature=120 degC")});
  const RingThermalSpec& t = s.bearings[0].ring.thermal;
  EXPECT_EQ(t.model, FilmThermal::Bulk);
  EXPECT_DOUBLE_EQ(t.shaft_temperature, 393.15);
  EXPECT_DOUBLE_EQ(t.housing_temperature, 363.15);
  // 6 k pi D L / c for the inner film: 6 * 0.13 * pi * 10 mm * 7 mm / 15 um.
  EXPECT_NEAR(t.inner_shaft_conductance, 6 * 0.13 * M_PI * 0.010 * 0.007 / 15e-6, 1e-12);
  EXPECT_GT(t.ring_conductance, 0.0);
  EXPECT_LT(t.ring_conductance, t.inner_shaft_conductance);
  EXPECT_THAT(model_error_of(f, {bulk, parse_override("bearings.compressor.ring_conductance=-1 W/K")}),
              AllOf(HasSubstr("bearings.compressor.ring_conductance"), HasSubstr("negative")));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.shaft_temperature=400 K")}),
              AllOf(HasSubstr("bearings.compressor.shaft_temperature"), HasSubstr("thermal = \"bulk\"")));
  EXPECT_THAT(model_error_of(f, {bulk, parse_override("oil.temperature=210 degC")}),
              AllOf(HasSubstr("bearings.compressor.thermal"), HasSubstr("max_temperature")));
  EXPECT_THAT(model_error_of(f, {bulk, parse_override("bearings.compressor.housing_temperature=250 degC")}),
              AllOf(HasSubstr("bearings.compressor.housing_temperature"), HasSubstr("max_temperature")));
  EXPECT_THAT(model_error_of(f, {bulk, parse_override("oil.viscosity=10 mPa*s")}),
              AllOf(HasSubstr("bearings.compressor.thermal"), HasSubstr("fixed [oil] viscosity")));
  EXPECT_THAT(model_error_of(f, {bulk, parse_override("bearings.compressor.inner_oil_temperature=100 degC")}),
              AllOf(HasSubstr("bearings.compressor.inner_oil_temperature"), HasSubstr("states of the run")));
  EXPECT_THAT(model_error_of(f, {bulk, parse_override("bearings.compressor.oil_specific_heat=2 kJ/kg")}),
              HasSubstr("bearings.compressor.oil_specific_heat"));
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.compressor.thermal=adiabatic")}),
              AllOf(HasSubstr("bearings.compressor.thermal"), HasSubstr("'isothermal', 'bulk'")));
}

// Without the key the films are bulk, unless the file fixes their viscosity or temperatures (docs/thermal-films.md).
TEST(ModelFile, FloatingRingFilmsAreThermalUnlessTheFileFixesThem) {
  std::ifstream in(example("reference_floating_ring.toml"));
  std::string text, line;
  while (std::getline(in, line))
    if (line.rfind("thermal = ", 0) != 0 && line.rfind("                                   #", 0) != 0)
      text += line + "\n";
  const std::filesystem::path f = turbodyn::testing::fresh_temp_dir("thermal_default") / "no_thermal_key.toml";
  std::ofstream(f) << text;
  EXPECT_EQ(load_model(f).bearings[0].ring.thermal.model, FilmThermal::Bulk);
  EXPECT_EQ(load_model(f).bearings[1].ring.thermal.model, FilmThermal::Bulk);
  const MachineSpec fixed_viscosity = load_model(f, {parse_override("oil.viscosity=10 mPa*s")});
  EXPECT_EQ(fixed_viscosity.bearings[0].ring.thermal.model, FilmThermal::Isothermal);
  const MachineSpec fixed_temperature =
      load_model(f, {parse_override("bearings.compressor.inner_oil_temperature=100 degC")});
  EXPECT_EQ(fixed_temperature.bearings[0].ring.thermal.model, FilmThermal::Isothermal);
  EXPECT_EQ(fixed_temperature.bearings[1].ring.thermal.model, FilmThermal::Bulk);
  // The example says "isothermal", the paper's model.
  EXPECT_EQ(load_model(example("reference_floating_ring.toml")).bearings[1].ring.thermal.model,
            FilmThermal::Isothermal);
}

TEST(ModelFile, MissingFile) {
  EXPECT_THAT(model_error_of(bad("does_not_exist.toml")), HasSubstr("cannot open"));
}

// One case per mistake a new user makes. Each message names the file and line, the key and the cause.
struct BadCase {
  const char* file;
  int line;
  std::vector<const char*> must_contain;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.file; }

class BadModel : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadModel, ClearError) {
  const BadCase& c = GetParam();
  const std::string msg = model_error_of(bad(c.file));
  ASSERT_FALSE(msg.empty()) << c.file << " was accepted";
  EXPECT_THAT(msg, HasSubstr(std::string(c.file) + ":" + std::to_string(c.line) + ":"));
  for (const char* s : c.must_contain) EXPECT_THAT(msg, HasSubstr(s));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadModel,
    ::testing::Values(
        BadCase{"missing_key.toml", 6, {"shaft[0].length", "missing required key", "length (m)"}},
        BadCase{"typo_key.toml", 8, {"shaft[0].outer_diamter", "unknown key", "did you mean 'outer_diameter'"}},
        BadCase{"negative_length.toml", 7, {"shaft[0].length", "must be positive", "-140 mm"}},
        BadCase{"wrong_unit.toml", 7, {"shaft[0].length", "'140 kg'", "mass (kg)", "expected a length (m)"}},
        BadCase{"unknown_unit.toml", 8, {"shaft[0].outer_diameter", "unknown unit 'mmm'"}},
        BadCase{"disk_outside_shaft.toml", 11, {"disks.turbine.z", "outside the shaft", "200 mm", "140 mm"}},
        BadCase{"bearing_type_typo.toml", 11, {"bearings.compressor.type", "'lineer'", "did you mean 'linear'"}},
        BadCase{"negative_stiffness.toml", 13, {"bearings.compressor.kxx", "must not be negative"}},
        BadCase{"syntax_error.toml", 8, {"TOML syntax error"}},
        BadCase{"atol_scaling_typo.toml", 12, {"solver.atol_scaling", "'typcal'", "did you mean 'typical'"}},
        BadCase{"wrong_type.toml", 7, {"shaft[0].length", "expected a length (m)", "got true"}}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string n = info.param.file;
      return n.substr(0, n.find('.'));
    });

TEST(ModelFile, AxialGradingOfTheFilms) {
  // Read for every film kind (docs/model-format.md); out of [0, 1) it is refused with the key.
  const MachineSpec m =
      load_model(example("reference_floating_ring.toml"), {parse_override("bearings.compressor.axial_grading=0.4")});
  ASSERT_EQ(m.bearings.size(), 2u);
  for (const BearingSpec& b : m.bearings)
    EXPECT_EQ(b.ring.axial_grading, b.name == "compressor" ? 0.4 : 0.0) << b.name;
  EXPECT_THAT(
      model_error_of(example("reference_floating_ring.toml"), {parse_override("bearings.turbine.axial_grading=1")}),
      AllOf(HasSubstr("bearings.turbine.axial_grading"), HasSubstr("[0, 1)")));
  EXPECT_THAT(
      model_error_of(example("reference_journal.toml"), {parse_override("bearings.compressor.axial_grading=-0.2")}),
      HasSubstr("bearings.compressor.axial_grading"));
}

TEST(ModelFile, DidYouMean) {
  EXPECT_EQ(closest_match("outer_diamter", {"length", "outer_diameter", "inner_diameter"}), "outer_diameter");
  EXPECT_EQ(closest_match("zzzzzz", {"length", "outer_diameter"}), "");
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

// ----------------------------------------------------------------------------------------------- limits
// Issue 20: nonsense input ends in a located error naming the key, never in a crash, a hang or a huge allocation
// (docs/model-format.md, "Limits").

TEST(ModelFileLimits, IntegersAreReadAs64BitAndRangeChecked) {
  // 2^31 once became -2^31 (a SIGSEGV in `modal`), and 4294967304 = 2^32 + 8 ran as 8 balls.
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("modal.n_speeds=2147483648")}),
              AllOf(HasSubstr("--set modal.n_speeds=2147483648"), HasSubstr("modal.n_speeds"),
                    HasSubstr("from 2 to 100000"), HasSubstr("got 2147483648")));
  EXPECT_THAT(
      model_error_of(example("reference_ball.toml"), {parse_override("bearings.compressor.n_balls=4294967304")}),
      AllOf(HasSubstr("bearings.compressor.n_balls"), HasSubstr("got 4294967304")));
  EXPECT_THAT(
      model_error_of(example("reference_journal.toml"), {parse_override("bearings.compressor.n_circ=2147483648")}),
      AllOf(HasSubstr("bearings.compressor.n_circ"), HasSubstr("from 8 to")));
  EXPECT_THAT(model_error_of(example("reference_journal.toml"), {parse_override("bearings.compressor.n_circ=2048"),
                                                           parse_override("bearings.compressor.n_axial=512")}),
              AllOf(HasSubstr("bearings.compressor.n_circ"), HasSubstr("2048 x 512")));
  EXPECT_THAT(model_error_of(example("reference_floating_ring.toml"),
                       {parse_override("bearings.compressor.drill_holes=4294967300")}),
              AllOf(HasSubstr("bearings.compressor.drill_holes"), HasSubstr("from 0 to 8")));
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("solver.max_order=4294967297")}),
              AllOf(HasSubstr("solver.max_order"), HasSubstr("from 1 to 5")));
}

TEST(ModelFile, NewtonToleranceIsAFractionOfTheErrorTestsBound) {
  EXPECT_DOUBLE_EQ(load_model(example("reference_linear.toml")).solver.newton_tolerance, 0.1);  // CVODE's default
  EXPECT_DOUBLE_EQ(
      load_model(example("reference_linear.toml"), {parse_override("solver.newton_tolerance=0.3")}).solver.newton_tolerance,
      0.3);
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("solver.newton_tolerance=-0.3")}),
              AllOf(HasSubstr("solver.newton_tolerance"), HasSubstr("must be positive, got -0.3")));  // not -0.2999...
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("solver.newton_tolerance=1.5")}),
              AllOf(HasSubstr("solver.newton_tolerance"), HasSubstr("at most 1")));
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("solver.newton_tolerance=0.3 s")}),
              HasSubstr("solver.newton_tolerance"));
}

TEST(ModelFileLimits, ImplausibleMagnitudesAreRefusedWithTheKey) {
  // Each of these once ran: an endless loop in the eigen-solver's balancing, or "shaft length inf mm".
  const std::string f = example("friswell_5_9_1.toml");
  EXPECT_THAT(model_error_of(f, {parse_override("bearings.left.kxx=1e+306 N/m")}),
              AllOf(HasSubstr("--set bearings.left.kxx"), HasSubstr("implausibly large"), HasSubstr("N/m")));
  EXPECT_THAT(model_error_of(f, {parse_override("materials.steel.rho=7.81e-297 kg/m^3")}),
              AllOf(HasSubstr("materials.steel.rho"), HasSubstr("implausibly small")));
  const std::string r = example("reference_linear.toml");
  EXPECT_THAT(model_error_of(r, {parse_override("shaft[0].length=1e308")}),
              AllOf(HasSubstr("shaft[0].length"), HasSubstr("implausibly large")));
  EXPECT_THAT(model_error_of(r, {parse_override("shaft[0].outer_diameter=1e-299 mm")}),
              AllOf(HasSubstr("shaft[0].outer_diameter"), HasSubstr("implausibly small")));
  EXPECT_THAT(model_error_of(r, {parse_override("materials.steel.rho=1.8e308")}), HasSubstr("materials.steel.rho"));
  EXPECT_THAT(model_error_of(r, {parse_override("shaft[0].length=1e302 mm")}), HasSubstr("shaft[0].length"));
}

TEST(ModelFileLimits, DerivedQuantitiesAreChecked) {
  // Each value plausible, their product not: a disk of 10 km diameter at 100 000 kg/m^3 weighs 7e13 kg.
  EXPECT_THAT(model_error_of(example("friswell_5_9_1.toml"), {parse_override("materials.steel.rho=1e5"),
                                                         parse_override("disks.disk1.outer_diameter=1e4"),
                                                         parse_override("disks.disk1.width=1e3")}),
              AllOf(HasSubstr("disks.disk1.outer_diameter"), HasSubstr("mass")));
}

TEST(ModelFileLimits, MeshElementCountIsRefusedUpFront) {
  // "1e-9 m" took 2 GB before std::bad_alloc; <= 1e-12 m was silently ignored (an int overflow).
  for (const char* h : {"1e-9 m", "100 um"})
    EXPECT_THAT(
        model_error_of(example("reference_linear.toml"), {parse_override(std::string("mesh.max_element_length=") + h)}),
        AllOf(HasSubstr("mesh.max_element_length"), HasSubstr("elements, more than the limit of 1000")))
        << h;
  EXPECT_THAT(model_error_of(example("reference_linear.toml"), {parse_override("mesh.max_element_length=1e-13 m")}),
              AllOf(HasSubstr("mesh.max_element_length"), HasSubstr("implausibly small")));
  EXPECT_EQ(model_error_of(example("reference_linear.toml"), {parse_override("mesh.max_element_length=1 mm")}), "");
}

TEST(ModelFileLimits, OilTemperatureAtTheViscosityPoleIsRefusedAtLoadTime) {
  // -70.56 degC is the pole of the default Vogel fit: `check` passed and `run` failed.
  for (const char* t : {"-70.56 degC", "-71 degC", "-70.5 degC"})
    EXPECT_THAT(model_error_of(example("reference_journal.toml"),
                         {parse_override(std::string("bearings.compressor.oil_temperature=") + t)}),
                AllOf(HasSubstr("bearings.compressor.oil_temperature"), HasSubstr("viscosity")))
        << t;
  EXPECT_THAT(model_error_of(example("reference_journal.toml"), {parse_override("oil.temperature=-70.56 degC")}),
              HasSubstr("oil.temperature"));
  EXPECT_EQ(model_error_of(example("reference_journal.toml"),
                           {parse_override("bearings.compressor.oil_temperature=40 degC")}),
            "");
}

TEST(ModelFileLimits, ADirectoryIsNotAModelFile) {
  EXPECT_THAT(model_error_of(source_dir() + "/examples"), AllOf(HasSubstr("examples"), HasSubstr("is a directory")));
}

TEST(ModelFileLimits, EveryExampleIsWithinTheLimits) {
  for (const char* f : {"reference_linear.toml", "reference_journal.toml", "reference_ball.toml",
                        "reference_ball_sfd.toml", "reference_damper.toml", "reference_floating_ring.toml",
                        "friswell_5_9_1.toml", "bench_rotor_journal.toml", "rigid_rotor_oil_whirl.toml"})
    EXPECT_EQ(model_error_of(example(f)), "") << f;
}

TEST(ModelFileLimits, NumericKeysAreTheKeysAStudyMayVary) {
  const std::vector<std::string> keys = numeric_model_keys(example("reference_linear.toml"), {});
  auto has = [&](const std::string& k) { return std::binary_search(keys.begin(), keys.end(), k); };
  EXPECT_TRUE(has("bearings.compressor.k"));
  EXPECT_TRUE(has("shaft[0].outer_diameter"));
  EXPECT_TRUE(has("disks.turbine.unbalance"));
  EXPECT_FALSE(has("name"));
  EXPECT_FALSE(has("shaft[0].material"));
  EXPECT_FALSE(has("bearings.compressor.type"));
}

}  // namespace
}  // namespace turbodyn

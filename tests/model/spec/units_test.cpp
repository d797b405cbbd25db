#include "model/spec/units.h"
#include "model/spec/text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

namespace turbodyn {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

using std::numbers::pi;

// Relative tolerance 1e-12, for values whose computation and expectation may round differently.
void expect_close(double actual, double expected) { EXPECT_NEAR(actual, expected, 1e-12 * std::abs(expected)); }

// Each text parses as the SI value: exactly (EXPECT_DOUBLE_EQ), or to 1e-12 relative (expect_parses_close).
struct Parse {
  std::string_view text;
  Dimension expected;
  double si;
};
void expect_parses(std::initializer_list<Parse> cases) {
  for (const Parse& c : cases) EXPECT_DOUBLE_EQ(parse_quantity(c.text, c.expected), c.si) << "'" << c.text << "'";
}
void expect_parses_close(std::initializer_list<Parse> cases) {
  for (const Parse& c : cases) {
    SCOPED_TRACE(std::string(c.text));
    expect_close(parse_quantity(c.text, c.expected), c.si);
  }
}

// The message of the UnitError parse_quantity throws; fails the test if it throws nothing.
std::string unit_error_of(std::string_view text, const Dimension& expected) {
  try {
    const double value = parse_quantity(text, expected);
    ADD_FAILURE() << "'" << text << "' parsed as " << value << ", expected a UnitError";
  } catch (const UnitError& e) {
    return e.what();
  }
  return {};
}

// ---------------------------------------------------------------------------------------------------------------
// Examples from model files

TEST(ParseQuantity, ExamplesFromModelFiles) {
  EXPECT_DOUBLE_EQ(parse_quantity("15 um", dim::length), 15e-6);
  expect_close(parse_quantity("150000 rpm", dim::angular_speed), 150000 * 2 * pi / 60);
  expect_parses({
      {"390 mg*mm", dim::unbalance, 390e-9},
      {"90 degC", dim::temperature, 363.15},
      {"7850 kg/m^3", dim::density, 7850},
      {"2e7 N/m", dim::stiffness, 2e7},
      {"200 N*s/m", dim::damping, 200},
      {"4.5 bar", dim::pressure, 4.5e5},
      {"210 GPa", dim::pressure, 210e9},
      {"90 deg", dim::angle, pi / 2},
      {"10.8 mPa*s", dim::viscosity, 10.8e-3},
      {"2500 Hz", dim::frequency, 2500},
      {"9.81 m/s^2", dim::acceleration, 9.81},
      {"1.5e-5 kg*m^2", dim::inertia, 1.5e-5},
  });
}

TEST(ParseQuantity, DecimalPrefixesAreExact) {
  // Scaling by an exact power of ten rounds once, so these equal the literals bit for bit.
  EXPECT_EQ(parse_quantity("15 um", dim::length), 15e-6);
  EXPECT_EQ(parse_quantity("390 mg*mm", dim::unbalance), 390e-9);
  EXPECT_EQ(parse_quantity("210 GPa", dim::pressure), 210e9);
  EXPECT_EQ(parse_quantity("1 kg", dim::mass), 1.0);
  EXPECT_EQ(parse_quantity("150000 rpm", dim::frequency), 2500.0);
}

TEST(ParseQuantity, PrefixesAndUnits) {
  expect_parses({
      {"3 mm", dim::length, 3e-3},
      {"2.5 cm", dim::length, 0.025},
      {"1.2 km", dim::length, 1200},
      {"40 nm", dim::length, 40e-9},
      {"2 in", dim::length, 0.0508},
      {"1 inch", dim::length, 0.0254},
      {"12 g", dim::mass, 0.012},
      {"5 mg", dim::mass, 5e-6},
      {"3 ms", dim::time, 3e-3},
      {"7 us", dim::time, 7e-6},
      {"2 min", dim::time, 120},
      {"1.5 h", dim::time, 5400},
      {"3 kN", dim::force, 3000},
      {"12 MPa", dim::pressure, 12e6},
      {"101.3 kPa", dim::pressure, 101300},
      {"1013 mbar", dim::pressure, 101300},
      {"2 kJ", dim::moment, 2000},
      {"3 kW", dim::moment / dim::time, 3000},
      {"10.8 cP", dim::viscosity, 10.8e-3},
      {"2 P", dim::viscosity, 0.2},
      {"300 K", dim::temperature, 300},
      {"5 mrad", dim::angle, 5e-3},
      {"1 rev", dim::angle, 2 * pi},
      {"1.2 MHz", dim::frequency, 1.2e6},
  });
}

TEST(ParseQuantity, CompoundUnits) {
  expect_parses({
      {"3 N*m", dim::moment, 3},
      {"5e4 N*m/rad", dim::rotational_stiffness, 5e4},
      {"2 N*m*s/rad", dim::rotational_damping, 2},
      {"0.2 kg*mm", dim::unbalance, 2e-4},
      {"7.85 g/cm^3", dim::density, 7850},
      {"2 N/mm", dim::stiffness, 2000},
      {"30 m/s", dim::velocity, 30},
      {"4 mm^2", dim::area, 4e-6},
      {"3 kg*m^2", dim::inertia, 3},
      {"3 kg/m/s", dim::viscosity, 3},        // left to right: (kg/m)/s
      {"3 kg*m^-1*s^-1", dim::viscosity, 3},  // negative exponents
      {"100 rad/s^2", dim::angular_acceleration, 100},
      {"3 kg*m/s^2", dim::force, 3},
  });
}

TEST(ParseQuantity, Reciprocals) {
  expect_parses({
      {"2500 1/s", dim::frequency, 2500},
      {"2500/s", dim::frequency, 2500},
      {"2500 s^-1", dim::frequency, 2500},
      {"2500 s^+1", dim::time, 2500},
      {"3 1/ms", dim::frequency, 3000},
      {"1/s", dim::frequency, 1},
  });
}

TEST(ParseQuantity, UnicodeSpellings) {
  expect_parses({
      {"15 \u00B5m", dim::length, 15e-6},  // MICRO SIGN
      {"15 \u03BCm", dim::length, 15e-6},  // GREEK SMALL LETTER MU
      {"15\u00B5m", dim::length, 15e-6},
      {"4 \u03BCs", dim::time, 4e-6},
      {"390 mg\u00B7mm", dim::unbalance, 390e-9},  // MIDDLE DOT
      {"200 N\u00B7s/m", dim::damping, 200},
      {"90 \u00B0C", dim::temperature, 363.15},  // DEGREE SIGN
      {"90\u00B0", dim::angle, pi / 2},
      {"7850 kg/m\u00B3", dim::density, 7850},  // SUPERSCRIPT THREE
      {"4 mm\u00B2", dim::area, 4e-6},
      {"15\u00A0um", dim::length, 15e-6},  // NO-BREAK SPACE
  });
}

TEST(ParseQuantity, Whitespace) {
  expect_parses({
      {"15um", dim::length, 15e-6},
      {"  15 um  ", dim::length, 15e-6},
      {"15\tum", dim::length, 15e-6},
      {"15   um", dim::length, 15e-6},
      {"200 N * s / m", dim::damping, 200},
      {"200N*s/m", dim::damping, 200},
      {"2e7N/m", dim::stiffness, 2e7},
  });
}

TEST(ParseQuantity, BareNumbersAreSI) {
  expect_parses({
      {"1e-3", dim::length, 1e-3},
      {"-2", dim::force, -2},
      {"+3.5", dim::mass, 3.5},
      {"1.5E+3", dim::pressure, 1500},
      {"0", dim::angular_speed, 0},
      {".5", dim::dimensionless, 0.5},
      {" 42 ", dim::temperature, 42},  // kelvin, no Celsius offset
      {"-1.5e-3 mm", dim::length, -1.5e-6},
      {"+1.5 mm", dim::length, 1.5e-3},
  });
}

TEST(ParseQuantity, Temperature) {
  expect_parses({
      {"90 degC", dim::temperature, 363.15},
      {"0 degC", dim::temperature, 273.15},
      {"-40 degC", dim::temperature, 233.15},
      {"90degC", dim::temperature, 363.15},
      {"363.15 K", dim::temperature, 363.15},
      {"2 K/s", dim::temperature / dim::time, 2},  // rates are written in K
  });
}

// ---------------------------------------------------------------------------------------------------------------
// Angle rule: a missing angle exponent counts whole turns of 2*pi rad.

TEST(AngleRule, CyclesToRadians) {
  expect_parses_close({
      {"2500 Hz", dim::angular_speed, 2500 * 2 * pi},
      {"150000 rpm", dim::angular_speed, 5000 * pi},
      {"1 1/s", dim::angular_speed, 2 * pi},
      {"60 rev/min", dim::angular_speed, 2 * pi},
      {"10 rev/s^2", dim::angular_acceleration, 20 * pi},
      {"1 rad/s", dim::angular_speed, 1},
      {"180 deg/s", dim::angular_speed, pi},
  });
}

TEST(AngleRule, RadiansToCycles) {
  expect_parses({
      {"150000 rpm", dim::frequency, 2500},
      {"10 kHz", dim::frequency, 1e4},
      {"2500 Hz", dim::frequency, 2500},
  });
  expect_close(parse_quantity("1 rad/s", dim::frequency), 1 / (2 * pi));
  EXPECT_DOUBLE_EQ(parse_quantity("60 rev/min", dim::frequency), 1);
}

TEST(AngleRule, OnlyBetweenRatesOfTime) {
  // A torsional stiffness written "N*m" or a plain number written in degrees is a mistake, not a count of turns.
  EXPECT_THAT(unit_error_of("1 N*m", dim::rotational_stiffness), HasSubstr("expected a rotational stiffness"));
  EXPECT_THAT(unit_error_of("90 deg", dim::dimensionless), HasSubstr("expected a dimensionless number"));
  expect_close(parse_quantity("1 rev", dim::angle), 2 * pi);
  expect_close(parse_quantity("60 rpm/s", dim::angular_acceleration), 2 * pi);
}

TEST(AngleRule, QuantitiesWithoutAnglesUnchanged) {
  expect_parses({
      {"15 mm", dim::length, 15e-3},
      {"3 s", dim::time, 3},
      {"2.5", dim::angular_speed, 2.5},  // bare numbers are SI (rad/s)
  });
}

// ---------------------------------------------------------------------------------------------------------------
// Errors

TEST(ParseQuantityErrors, Empty) {
  EXPECT_THAT(unit_error_of("", dim::length), AllOf(HasSubstr("empty"), HasSubstr("''"), HasSubstr("a length (m)")));
  EXPECT_THAT(unit_error_of("   ", dim::length), AllOf(HasSubstr("empty"), HasSubstr("a length (m)")));
}

TEST(ParseQuantityErrors, MissingNumber) {
  EXPECT_THAT(unit_error_of("um", dim::length),
              AllOf(HasSubstr("missing number"), HasSubstr("'um'"), HasSubstr("a length (m)")));
  EXPECT_THAT(unit_error_of("N/m", dim::stiffness),
              AllOf(HasSubstr("missing number"), HasSubstr("'N/m'"), HasSubstr("a stiffness (N/m)")));
}

TEST(ParseQuantityErrors, Garbage) {
  EXPECT_THAT(unit_error_of("fifteen um", dim::length),
              AllOf(HasSubstr("'fifteen um'"), HasSubstr("does not start with a number"), HasSubstr("a length (m)")));
  EXPECT_THAT(unit_error_of("++3", dim::length), AllOf(HasSubstr("'++3'"), HasSubstr("a length (m)")));
  EXPECT_THAT(unit_error_of("+-3", dim::length), AllOf(HasSubstr("'+-3'"), HasSubstr("a length (m)")));
  EXPECT_THAT(unit_error_of("- 3", dim::length), HasSubstr("'- 3'"));
  EXPECT_THAT(unit_error_of("15 m$", dim::length), AllOf(HasSubstr("unexpected '$'"), HasSubstr("'15 m$'")));
  EXPECT_THAT(unit_error_of("15 N m", dim::moment),
              AllOf(HasSubstr("missing '*' or '/'"), HasSubstr("'15 N m'"), HasSubstr("a moment (N*m)")));
  EXPECT_THAT(unit_error_of("15 m*", dim::area), AllOf(HasSubstr("unit missing after '*'"), HasSubstr("'15 m*'")));
  EXPECT_THAT(unit_error_of("15 m/", dim::length), AllOf(HasSubstr("unit missing after '/'"), HasSubstr("'15 m/'")));
  EXPECT_THAT(unit_error_of("15 m**m", dim::area), HasSubstr("unexpected '*'"));
  EXPECT_THAT(unit_error_of("15 1", dim::dimensionless), HasSubstr("leading 1 must be followed by '/'"));
  EXPECT_THAT(unit_error_of("3 m2", dim::area), AllOf(HasSubstr("'3 m2'"), HasSubstr("m^2")));
  EXPECT_THAT(unit_error_of("15 um um", dim::length), HasSubstr("missing '*' or '/'"));
}

TEST(ParseQuantityErrors, NonFinite) {
  for (const char* text : {"nan", "inf", "-inf", "infinity", "nan m", "inf um"}) {
    EXPECT_THAT(unit_error_of(text, dim::length),
                AllOf(HasSubstr("'" + std::string(text) + "'"), HasSubstr("finite"), HasSubstr("a length (m)")))
        << text;
  }
  EXPECT_THAT(unit_error_of("1e999 m", dim::length), AllOf(HasSubstr("out of range"), HasSubstr("'1e999 m'")));
  EXPECT_THAT(unit_error_of("1e300 GPa^2", dim::pressure * dim::pressure), HasSubstr("out of range"));
}

TEST(ParseQuantityErrors, UnknownUnitSuggestsCloseOnes) {
  const std::string message = unit_error_of("15 umm", dim::length);
  EXPECT_THAT(message,
              AllOf(HasSubstr("unknown unit 'umm'"), HasSubstr("'15 umm'"), HasSubstr("a length (m)"),
                    HasSubstr("'um'"), HasSubstr("'mm'"), HasSubstr("known units: m, "), Not(HasSubstr("'um*m'"))));

  EXPECT_THAT(unit_error_of("150000 rmp", dim::angular_speed),
              AllOf(HasSubstr("'rmp'"), HasSubstr("did you mean 'rpm'")));
  EXPECT_THAT(unit_error_of("3 mpa", dim::pressure), HasSubstr("did you mean 'mPa'"));
  EXPECT_THAT(unit_error_of("3 HZ", dim::frequency), HasSubstr("did you mean 'Hz'"));
  EXPECT_THAT(unit_error_of("1000 Nm", dim::moment), HasSubstr("did you mean 'N*m'"));
  EXPECT_THAT(unit_error_of("3 RPM", dim::angular_speed), HasSubstr("did you mean 'rpm'"));
  EXPECT_THAT(unit_error_of("0.2 kgmm", dim::unbalance), HasSubstr("did you mean 'kg*mm'"));
  EXPECT_THAT(unit_error_of("2 cg", dim::mass), AllOf(HasSubstr("unknown unit 'cg'"), HasSubstr("c only in cm")));
  EXPECT_THAT(unit_error_of("2 kmin", dim::time), HasSubstr("unknown unit 'kmin'"));  // no prefixes on minutes
  // The message quotes the unit as written, micro sign included.
  EXPECT_THAT(unit_error_of("15 \u00B5mm", dim::length), HasSubstr("unknown unit '\u00B5mm'"));
  EXPECT_THAT(unit_error_of("15 xyzzy", dim::length),
              AllOf(HasSubstr("unknown unit 'xyzzy'"), Not(HasSubstr("did you mean"))));
}

TEST(ParseQuantityErrors, DimensionMismatch) {
  EXPECT_EQ(unit_error_of("15 kg", dim::length), "'15 kg' is a mass (kg), expected a length (m)");
  EXPECT_EQ(unit_error_of("2e7 N", dim::stiffness), "'2e7 N' is a force (N), expected a stiffness (N/m)");
  EXPECT_EQ(unit_error_of("3 rad", dim::angular_speed), "'3 rad' is an angle (rad), expected an angular speed (rad/s)");
  EXPECT_EQ(unit_error_of("90 degC", dim::length), "'90 degC' is a temperature (K), expected a length (m)");
  EXPECT_EQ(unit_error_of("1 Hz", dim::dimensionless),
            "'1 Hz' is an angular speed (rad/s), expected a dimensionless number (1)");
  EXPECT_EQ(unit_error_of("1 m*K", dim::length), "'1 m*K' is a quantity in m*K, expected a length (m)");
}

TEST(ParseQuantityErrors, CelsiusOnlyAsWholeUnit) {
  for (const char* text : {"1 degC/s", "1 N/degC", "1 degC^2", "1 1/degC", "1 \u00B0C/s"}) {
    EXPECT_THAT(
        unit_error_of(text, dim::temperature / dim::time),
        AllOf(HasSubstr("only allowed as the whole unit"), HasSubstr("'" + std::string(text) + "'"), HasSubstr("in K")))
        << text;
  }
}

TEST(ParseQuantityErrors, ExponentMustBeInteger) {
  for (const char* text : {"1 m^2.5", "1 m^x", "1 m^", "1 m^2,5", "1 m^1000", "1 m^+-2", "1 m^ 2"}) {
    EXPECT_THAT(unit_error_of(text, dim::area), AllOf(HasSubstr("must be an integer"),
                                                 HasSubstr("'" + std::string(text) + "'"), HasSubstr("an area (m^2)")))
        << text;
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Dimensions

TEST(Dimension, SiUnit) {
  EXPECT_EQ(dim::dimensionless.si_unit(), "1");
  EXPECT_EQ(dim::length.si_unit(), "m");
  EXPECT_EQ(dim::inertia.si_unit(), "kg*m^2");
  EXPECT_EQ(dim::density.si_unit(), "kg/m^3");
  EXPECT_EQ(dim::angular_speed.si_unit(), "rad/s");
  EXPECT_EQ(dim::angular_acceleration.si_unit(), "rad/s^2");
  EXPECT_EQ(dim::stiffness.si_unit(), "N/m");
  EXPECT_EQ(dim::rotational_damping.si_unit(), "N*m*s/rad");
  EXPECT_EQ((Dimension{0, 0, -2}).si_unit(), "1/s^2");
  EXPECT_EQ((Dimension{1, 2, -4}).si_unit(), "kg*m^2/s^4");
  EXPECT_EQ(dim::power.si_unit(), "W");  // the thermal films' quantities have names of their own
  EXPECT_EQ(dim::thermal_conductance.si_unit(), "W/K");
  EXPECT_EQ(dim::thermal_conductivity.si_unit(), "W/m/K");
  EXPECT_EQ(dim::specific_heat.si_unit(), "J/kg/K");
  EXPECT_EQ((Dimension{0, 1, -1, -1}).si_unit(), "m/s/K");
}

TEST(Dimension, Describe) {
  EXPECT_EQ(describe(dim::length), "a length (m)");
  EXPECT_EQ(describe(dim::stiffness), "a stiffness (N/m)");
  EXPECT_EQ(describe(dim::angular_speed), "an angular speed (rad/s)");
  EXPECT_EQ(describe(dim::frequency), "a frequency (Hz)");
  EXPECT_EQ(describe(dim::viscosity), "a dynamic viscosity (Pa*s)");
  EXPECT_EQ(describe(dim::dimensionless), "a dimensionless number (1)");
  EXPECT_EQ(describe(Dimension{0, 0, 0, 1, 1}), "a quantity in K*rad");
}

TEST(Dimension, Constants) {
  EXPECT_EQ(dim::force, (Dimension{1, 1, -2}));
  EXPECT_EQ(dim::pressure, (Dimension{1, -1, -2}));
  EXPECT_EQ(dim::damping, (Dimension{1, 0, -1}));
  EXPECT_EQ(dim::viscosity, (Dimension{1, -1, -1}));
  EXPECT_EQ(dim::rotational_stiffness, (Dimension{1, 2, -2, 0, -1}));
  EXPECT_EQ(dim::frequency, (Dimension{0, 0, -1}));
  EXPECT_EQ(dim::angular_speed, (Dimension{0, 0, -1, 0, 1}));
}

TEST(Dimension, SiUnitParsesBackToOne) {
  // Each SI spelling is itself valid input and means exactly one SI unit.
  for (const Dimension& d : {dim::length,
                             dim::thermal_conductance,
                             dim::thermal_conductivity,
                             dim::specific_heat,
                             dim::mass,
                             dim::time,
                             dim::temperature,
                             dim::angle,
                             dim::angular_speed,
                             dim::angular_acceleration,
                             dim::frequency,
                             dim::force,
                             dim::pressure,
                             dim::stiffness,
                             dim::damping,
                             dim::density,
                             dim::inertia,
                             dim::unbalance,
                             dim::viscosity,
                             dim::acceleration,
                             dim::velocity,
                             dim::area,
                             dim::moment,
                             dim::rotational_stiffness,
                             dim::rotational_damping,
                             Dimension{1, 2, -3, -1, 1}}) {
    EXPECT_DOUBLE_EQ(parse_quantity("2.5 " + d.si_unit(), d), 2.5) << d.si_unit();
  }
}

TEST(Units, QuantityUnitIsTheTextAfterTheNumberParseQuantityReads) {
  EXPECT_EQ(quantity_unit(" 150000 rpm "), std::optional<std::string>("rpm"));
  EXPECT_EQ(quantity_unit("7850 kg/m^3"), std::optional<std::string>("kg/m^3"));
  EXPECT_EQ(quantity_unit("1e-3"), std::optional<std::string>(""));
  EXPECT_EQ(quantity_unit("+30000"), std::optional<std::string>(""));  // a leading '+' as parse_quantity takes it
  EXPECT_EQ(quantity_unit("rpm"), std::nullopt);
  EXPECT_EQ(quantity_unit(""), std::nullopt);
  EXPECT_EQ(quantity_unit("1e999 rpm"), std::nullopt);  // out of range: parse_quantity reports it
}

TEST(Text, TrimBlanksStripsSpacesTabsAndLineEndsAtBothEndsOnly) {
  EXPECT_EQ(trim_blanks(" \t150000 rpm\r\n"), "150000 rpm");
  EXPECT_EQ(trim_blanks("a b"), "a b");
  EXPECT_EQ(trim_blanks(" \t\r\n"), "");
  EXPECT_EQ(trim_blanks(""), "");
}

}  // namespace
}  // namespace turbodyn

#include "model/spec/model_spec.h"

#include <cmath>
#include <utility>

#include "model/spec/enum_names.h"

namespace turbodyn {

namespace {

// Each enum's model-file names in one table, so that to_string and from_string cannot disagree.
constexpr EnumName<Cavitation> kCavitations[] = {
    {Cavitation::None, "none"}, {Cavitation::Gumbel, "gumbel"}, {Cavitation::MassConserving, "mass-conserving"}};
constexpr EnumName<FilmThermal> kFilmThermals[] = {{FilmThermal::Isothermal, "isothermal"}, {FilmThermal::Bulk, "bulk"}};
constexpr EnumName<BearingType> kBearingTypes[] = {{BearingType::Linear, "linear"},
                                               {BearingType::Journal, "journal"},
                                               {BearingType::FloatingRing, "floating-ring"},
                                               {BearingType::Ball, "ball"}};
constexpr EnumName<Integrator> kIntegrators[] = {
    {Integrator::Auto, "auto"}, {Integrator::CvodeBdf, "cvode-bdf"}, {Integrator::ArkodeErk, "arkode-erk"}};
constexpr EnumName<AtolScaling> kAtolScalings[] = {{AtolScaling::Uniform, "uniform"}, {AtolScaling::Typical, "typical"}};
constexpr EnumName<SpectrogramWindow> kWindows[] = {{SpectrogramWindow::Hann, "hann"},
                                                {SpectrogramWindow::Hamming, "hamming"},
                                                {SpectrogramWindow::Blackman, "blackman"},
                                                {SpectrogramWindow::FlatTop, "flattop"},
                                                {SpectrogramWindow::Rectangular, "rectangular"}};

}  // namespace

bool SolverSpec::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (name_of(kIntegrators, integrator) == "unknown") return fail("unknown integrator (auto, cvode-bdf or arkode-erk)");
  if (name_of(kAtolScalings, atol_scaling) == "unknown") return fail("unknown atol_scaling (uniform or typical)");
  if (!(rtol > 0.0 && rtol < 1.0)) return fail("rtol must lie between 0 and 1");
  if (!(atol > 0.0)) return fail("atol must be positive");
  if (!(max_step >= 0.0)) return fail("max_step must not be negative");
  if (max_steps < 1) return fail("max_steps must be at least 1");
  if (max_order < 1 || max_order > 5) return fail("max_order: BDF orders go from 1 to 5");
  if (!(newton_tolerance > 0.0 && newton_tolerance <= 1.0))
    return fail("newton_tolerance must lie in (0, 1] (a fraction of the local error test's bound)");
  return true;
}

std::string to_string(Cavitation c) { return name_of(kCavitations, c); }
bool from_string(std::string_view name, Cavitation& c) { return value_of(kCavitations, name, c); }
std::string to_string(FilmThermal t) { return name_of(kFilmThermals, t); }
bool from_string(std::string_view name, FilmThermal& t) { return value_of(kFilmThermals, name, t); }
std::string to_string(BearingType t) { return name_of(kBearingTypes, t); }
bool from_string(std::string_view name, BearingType& t) { return value_of(kBearingTypes, name, t); }
std::string to_string(Integrator i) { return name_of(kIntegrators, i); }
bool from_string(std::string_view name, Integrator& i) { return value_of(kIntegrators, name, i); }
std::string to_string(AtolScaling a) { return name_of(kAtolScalings, a); }
bool from_string(std::string_view name, AtolScaling& a) { return value_of(kAtolScalings, name, a); }
std::string to_string(SpectrogramWindow w) { return name_of(kWindows, w); }
bool from_string(std::string_view name, SpectrogramWindow& w) { return value_of(kWindows, name, w); }

void derive_ring_thermal(FloatingRingSpec& f, const OilSpec& oil) {
  RingThermalSpec& t = f.thermal;
  t.supply_temperature = oil.temperature;
  t.shaft_temperature = t.housing_temperature = oil.temperature;
  t.max_temperature = oil.max_temperature;
  const double ai = M_PI * f.inner_diameter * f.inner_length, ao = M_PI * f.outer_diameter * f.outer_length;
  const double gi = kFilmWallNusselt * t.oil_thermal_conductivity / f.inner_clearance * ai;
  const double go = kFilmWallNusselt * t.oil_thermal_conductivity / f.outer_clearance * ao;
  // The ring's wall between its bore and its outer surface, as wide as the outer film (a radial conduction
  // resistance ln(r2/r1) / (2 pi k b)).
  const double r1 = 0.5 * f.inner_diameter + f.inner_clearance, r2 = 0.5 * f.outer_diameter - f.outer_clearance;
  const double gw = 2.0 * M_PI * t.ring_thermal_conductivity * f.outer_length / std::log(r2 / r1);
  t.inner_shaft_conductance = gi;
  t.outer_housing_conductance = go;
  t.ring_conductance = 1.0 / (1.0 / gi + 1.0 / gw + 1.0 / go);
  const double ring = 0.5 * f.ring_mass * t.ring_specific_heat;
  t.inner_heat_capacity = oil.density * t.oil_specific_heat * ai * f.inner_clearance + ring;
  t.outer_heat_capacity = oil.density * t.oil_specific_heat * ao * f.outer_clearance + ring;
}

}  // namespace turbodyn

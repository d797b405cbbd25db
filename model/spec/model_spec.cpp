#include "model/spec/model_spec.h"

#include <utility>

#include "model/spec/enum_names.h"

namespace turbodyn {

namespace {

// Each enum's model-file names in one table, so that to_string and from_string cannot disagree.
constexpr EnumName<Cavitation> kCavitations[] = {
    {Cavitation::None, "none"}, {Cavitation::Gumbel, "gumbel"}, {Cavitation::MassConserving, "mass-conserving"}};
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
  return true;
}

std::string to_string(Cavitation c) { return name_of(kCavitations, c); }
bool from_string(std::string_view name, Cavitation& c) { return value_of(kCavitations, name, c); }
std::string to_string(BearingType t) { return name_of(kBearingTypes, t); }
bool from_string(std::string_view name, BearingType& t) { return value_of(kBearingTypes, name, t); }
std::string to_string(Integrator i) { return name_of(kIntegrators, i); }
bool from_string(std::string_view name, Integrator& i) { return value_of(kIntegrators, name, i); }
std::string to_string(AtolScaling a) { return name_of(kAtolScalings, a); }
bool from_string(std::string_view name, AtolScaling& a) { return value_of(kAtolScalings, name, a); }
std::string to_string(SpectrogramWindow w) { return name_of(kWindows, w); }
bool from_string(std::string_view name, SpectrogramWindow& w) { return value_of(kWindows, name, w); }

}  // namespace turbodyn

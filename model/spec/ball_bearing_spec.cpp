#include "model/spec/ball_bearing_spec.h"

#include <cmath>
#include <sstream>

#include "model/spec/constants.h"

namespace turbodyn {

namespace {

template <typename T>
bool fail(std::string* error, const char* field, const char* rule, T value) {
  if (error) {
    std::ostringstream os;
    os << "BallBearingSpec." << field << " must be " << rule << " (got " << value << ")";
    *error = os.str();
  }
  return false;
}

}  // namespace

bool BallBearingSpec::IsValid(std::string* error) const {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  const auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  const auto poisson = [](double x) { return std::isfinite(x) && x > -1.0 && x < 0.5; };
  if (n_balls < 3) return fail(error, "n_balls", ">= 3", n_balls);
  if (!positive(ball_diameter)) return fail(error, "ball_diameter", "> 0", ball_diameter);
  if (!positive(pitch_diameter) || pitch_diameter <= ball_diameter)
    return fail(error, "pitch_diameter", "> ball_diameter", pitch_diameter);
  if (n_balls * ball_diameter >= kPi * pitch_diameter)
    return fail(error, "n_balls", "small enough for the balls to fit on the pitch circle", n_balls);
  if (!(inner_groove_ratio > 0.5) || !std::isfinite(inner_groove_ratio))
    return fail(error, "inner_groove_ratio", "> 0.5", inner_groove_ratio);
  if (!(outer_groove_ratio > 0.5) || !std::isfinite(outer_groove_ratio))
    return fail(error, "outer_groove_ratio", "> 0.5", outer_groove_ratio);
  if (!(contact_angle >= 0.0 && contact_angle < 0.5 * kPi))
    return fail(error, "contact_angle", "in [0, pi/2) rad", contact_angle);
  if (side != 1 && side != -1) return fail(error, "side", "+1 or -1", side);
  // The material and damping constants: each a finite number in its range.
  enum class Rule { Positive, NonNegative, PoissonRatio };
  struct Check {
    const char* field;
    double value;
    Rule rule;
  };
  const Check checks[] = {
      {"ball_youngs_modulus", ball_youngs_modulus, Rule::Positive},
      {"ball_poisson_ratio", ball_poisson_ratio, Rule::PoissonRatio},
      {"ball_density", ball_density, Rule::Positive},
      {"ring_youngs_modulus", ring_youngs_modulus, Rule::Positive},
      {"ring_poisson_ratio", ring_poisson_ratio, Rule::PoissonRatio},
      {"cage_mass", cage_mass, Rule::Positive},
      {"cage_polar_inertia", cage_polar_inertia, Rule::NonNegative},
      {"cage_diametral_inertia", cage_diametral_inertia, Rule::NonNegative},
      {"cage_youngs_modulus", cage_youngs_modulus, Rule::Positive},
      {"cage_poisson_ratio", cage_poisson_ratio, Rule::PoissonRatio},
      {"pocket_damping", pocket_damping, Rule::NonNegative},
      {"contact_damping", contact_damping, Rule::NonNegative},
      {"contact_damping_ratio", contact_damping_ratio, Rule::NonNegative},
      {"friction_static", friction_static, Rule::NonNegative},
      {"friction_sliding", friction_sliding, Rule::NonNegative},
      {"friction_v1", friction_v1, Rule::Positive},
      {"friction_v2", friction_v2, Rule::Positive},
      {"lubricant_viscosity", lubricant_viscosity, Rule::NonNegative},
      {"pressure_viscosity", pressure_viscosity, Rule::NonNegative},
      {"eyring_stress", eyring_stress, Rule::Positive},
      {"limiting_shear_coefficient", limiting_shear_coefficient, Rule::Positive},
      {"lubricant_shear_modulus", lubricant_shear_modulus, Rule::Positive},
      {"preload", preload, Rule::NonNegative},
      {"preload_stiffness", preload_stiffness, Rule::NonNegative},
      {"outer_ring_mass", outer_ring_mass, Rule::Positive},
      {"outer_ring_damping", outer_ring_damping, Rule::NonNegative},
  };
  for (const Check& c : checks) {
    const bool ok = c.rule == Rule::Positive      ? positive(c.value)
                    : c.rule == Rule::NonNegative ? non_negative(c.value)
                                                  : poisson(c.value);
    if (!ok)
      return fail(error, c.field, c.rule == Rule::Positive ? "> 0" : c.rule == Rule::NonNegative ? ">= 0" : "in (-1, 0.5)",
                  c.value);
  }
  if (!(hertz_coefficient == 0.0 || (hertz_coefficient > 0.0 && hertz_coefficient <= 1.0)))
    return fail(error, "hertz_coefficient", "in (0, 1] (paper Eq. 20's mu*), or 0 for the exact Hertz ellipse",
                hertz_coefficient);
  if (!(contact_damping_ratio <= kMaxContactDampingRatio))
    return fail(error, "contact_damping_ratio",
                "<= 1e-3 s (rolling bearings: 0.25e-5 to 2.5e-5 s of their stiffness, Kraemer)", contact_damping_ratio);
  if (!positive(pocket_clearance) || pocket_clearance >= 0.5 * ball_diameter)
    return fail(error, "pocket_clearance", "> 0 and < ball_diameter / 2", pocket_clearance);
  if (traction_law == TractionLaw::Eyring && !positive(lubricant_viscosity))
    return fail(error, "lubricant_viscosity", "> 0 for the lubricated (Eyring) traction law", lubricant_viscosity);
  if (traction_law == TractionLaw::Eyring && !(pressure_viscosity > 0.0 && pressure_viscosity <= 5e-8))
    return fail(error, "pressure_viscosity", "> 0 and <= 5e-8 1/Pa for the lubricated law (oils: 1e-8 to 3e-8)",
                pressure_viscosity);
  if (outer_ring_mode == OuterRingMode::Spring && !positive(outer_ring_stiffness))
    return fail(error, "outer_ring_stiffness", "> 0 for the spring outer-ring mode", outer_ring_stiffness);
  return true;
}

}  // namespace turbodyn

#include "model/spec/ball_bearing_spec.h"

#include <cmath>
#include <sstream>

namespace turbodyn {

namespace {

constexpr double kPi = 3.14159265358979323846;

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
  if (!positive(ball_youngs_modulus)) return fail(error, "ball_youngs_modulus", "> 0", ball_youngs_modulus);
  if (!poisson(ball_poisson_ratio)) return fail(error, "ball_poisson_ratio", "in (-1, 0.5)", ball_poisson_ratio);
  if (!positive(ball_density)) return fail(error, "ball_density", "> 0", ball_density);
  if (!positive(ring_youngs_modulus)) return fail(error, "ring_youngs_modulus", "> 0", ring_youngs_modulus);
  if (!poisson(ring_poisson_ratio)) return fail(error, "ring_poisson_ratio", "in (-1, 0.5)", ring_poisson_ratio);
  if (!positive(cage_mass)) return fail(error, "cage_mass", "> 0", cage_mass);
  if (!non_negative(cage_polar_inertia)) return fail(error, "cage_polar_inertia", ">= 0", cage_polar_inertia);
  if (!non_negative(cage_diametral_inertia))
    return fail(error, "cage_diametral_inertia", ">= 0", cage_diametral_inertia);
  if (!positive(pocket_clearance) || pocket_clearance >= 0.5 * ball_diameter)
    return fail(error, "pocket_clearance", "> 0 and < ball_diameter / 2", pocket_clearance);
  if (!positive(cage_youngs_modulus)) return fail(error, "cage_youngs_modulus", "> 0", cage_youngs_modulus);
  if (!poisson(cage_poisson_ratio)) return fail(error, "cage_poisson_ratio", "in (-1, 0.5)", cage_poisson_ratio);
  if (!non_negative(pocket_damping)) return fail(error, "pocket_damping", ">= 0", pocket_damping);
  if (!non_negative(contact_damping)) return fail(error, "contact_damping", ">= 0", contact_damping);
  if (!non_negative(friction_static)) return fail(error, "friction_static", ">= 0", friction_static);
  if (!non_negative(friction_sliding)) return fail(error, "friction_sliding", ">= 0", friction_sliding);
  if (!positive(friction_v1)) return fail(error, "friction_v1", "> 0", friction_v1);
  if (!positive(friction_v2)) return fail(error, "friction_v2", "> 0", friction_v2);
  if (!non_negative(preload)) return fail(error, "preload", ">= 0", preload);
  if (!non_negative(preload_stiffness)) return fail(error, "preload_stiffness", ">= 0", preload_stiffness);
  if (!positive(outer_ring_mass)) return fail(error, "outer_ring_mass", "> 0", outer_ring_mass);
  if (outer_ring_mode == OuterRingMode::Spring && !positive(outer_ring_stiffness))
    return fail(error, "outer_ring_stiffness", "> 0 for the spring outer-ring mode", outer_ring_stiffness);
  if (!non_negative(outer_ring_damping)) return fail(error, "outer_ring_damping", ">= 0", outer_ring_damping);
  return true;
}

}  // namespace turbodyn

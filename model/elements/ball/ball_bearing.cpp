#include "model/elements/ball/ball_bearing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/elements/ball/race_geometry.h"
#include "model/spec/constants.h"

namespace turbodyn {

namespace {

using Vec3 = Eigen::Vector3d;
using namespace ball_detail;

}  // namespace

// ------------------------------------------------------------------------------------------------- Hertz

double eyring_traction_per_slip(const EyringLubricant& lub, const HertzPointContact& hz, double Q, double u,
                                double v) {
  if (!(Q > 0.0)) return 0.0;
  const double radius = hz.radius_factor * std::cbrt(Q), area = kPi * radius * radius, p = Q / area;
  const double Rx = 1.0 / hz.curvature_x, E = hz.modulus;
  const double U = lub.viscosity * std::max(std::abs(u), kMinEntrainmentSpeed) / (E * Rx);
  const double G = lub.pressure_viscosity * E, W = Q / (E * Rx * Rx);
  const double h = Rx * 2.69 * std::pow(U, 0.67) * std::pow(G, 0.53) * std::pow(W, -0.067) *
                   (1.0 - 0.61 * std::exp(-0.73 * hz.ellipticity));
  double eta = lub.viscosity * std::exp(std::min(lub.pressure_viscosity * p, 300.0));
  if (lub.shear_modulus < std::numeric_limits<double>::infinity()) {
    // Maxwell film over the transit time along the rolling direction (the ellipse's shorter semi-axis).
    const double transit = 2.0 * radius / std::sqrt(hz.ellipticity) / std::max(std::abs(u), kMinEntrainmentSpeed);
    const double r = transit * lub.shear_modulus / eta;
    eta *= r < 1e-3 ? r * (0.5 - r * (1.0 / 6.0 - r / 24.0)) : 1.0 - (1.0 - std::exp(-r)) / r;
  }
  // tau / v = (eta / h) (asinh(x) / x) (tanh(y) / y), x = eta v / (tau_0 h), y = tau_E / tau_L: finite at v = 0.
  const double x = eta * std::abs(v) / (lub.eyring_stress * h);
  const double asinh_x = x < 1e-4 ? 1.0 - x * x / 6.0 : std::asinh(x) / x;
  const double tau_e = lub.eyring_stress * x * asinh_x, tau_l = lub.limiting_shear * p;
  const double y = tau_e / tau_l;
  const double tanh_y = y < 1e-4 ? 1.0 - y * y / 3.0 : std::tanh(y) / y;
  return area * (eta / h) * asinh_x * tanh_y;
}

HertzPointContact SolveHertzPointContact(double curvature_x, double curvature_y, double modulus) {
  if (!(curvature_x > 0.0 && curvature_y > 0.0 && modulus > 0.0))
    throw std::invalid_argument("Hertz point contact: curvature sums and modulus must be > 0");
  HertzPointContact h;
  h.curvature_sum = curvature_x + curvature_y;
  // R_y / R_x >= 1 with x the direction of the larger curvature (the shorter semi-axis b).
  const double ratio = std::max(curvature_x, curvature_y) / std::min(curvature_x, curvature_y);
  // Hertz's relation between the curvature ratio and the ellipse (Johnson 1985, §4.2, rewritten with
  // k = a/b): k^2 E(e) - (1 + ratio) K(e) + ratio E(e) = 0, e^2 = 1 - 1/k^2. It is negative just above k = 1
  // and grows without bound; bisection in log k is robust and only runs in the constructor.
  const auto residual = [ratio](double k) {
    const double e = std::sqrt(1.0 - 1.0 / (k * k));
    const double K = std::comp_ellint_1(e), E = std::comp_ellint_2(e);
    return k * k * E - (1.0 + ratio) * K + ratio * E;
  };
  double k = 1.0;
  if (ratio > 1.0 + 1e-12) {
    double lo = 1.0 + 1e-12, hi = 2.0;
    while (residual(hi) < 0.0) hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
      const double mid = std::sqrt(lo * hi);
      (residual(mid) < 0.0 ? lo : hi) = mid;
    }
    k = 0.5 * (lo + hi);
  }
  const double e = std::sqrt(std::max(0.0, 1.0 - 1.0 / (k * k)));
  h.curvature_x = curvature_x;
  h.modulus = modulus;
  h.ellipticity = k;
  h.integral_k = std::comp_ellint_1(e);
  h.integral_e = std::comp_ellint_2(e);
  const double R = 1.0 / h.curvature_sum;
  // delta = K(e) [ (9 / (2 E(e) R)) (F / (pi k E'))^2 ]^(1/3) (Hamrock & Dowson 1981, ch. 3), inverted.
  h.stiffness = kPi * k * modulus * std::sqrt(2.0 * h.integral_e * R / 9.0) / std::pow(h.integral_k, 1.5);
  // Semi-axes a = (6 k^2 E F R / (pi E'))^(1/3), b = (6 E F R / (pi k E'))^(1/3) (same source).
  h.cbrt_stiffness = std::cbrt(h.stiffness);
  h.radius_factor = std::cbrt(6.0 * h.integral_e * R / (kPi * modulus)) * std::pow(k, 1.0 / 6.0);
  return h;
}

double HertzPeakPressure(const HertzPointContact& hz, double Q) {
  if (!(Q > 0.0)) return 0.0;
  const double mean_radius = hz.radius_factor * std::cbrt(Q);  // sqrt(a b)
  return 1.5 * Q / (kPi * mean_radius * mean_radius);
}

ProbeInfo MaxContactPressureProbe() {
  return {"max_contact_pressure", "Pa", "largest Hertz pressure of the ball-race contacts", kStaticContactPressureLimit,
          "ISO 76's static limit for ball bearings, above which balls and races take a permanent deformation of more "
          "than 1/10,000 of the ball diameter (brinelling), which rigid bodies with Hertz contacts do not describe"};
}

double PaperHertzConstant(double curvature_sum, double modulus, double mu_star) {
  if (!(curvature_sum > 0.0 && modulus > 0.0 && mu_star > 0.0))
    throw std::invalid_argument("paper Eq. 20: curvature sum, modulus and mu* must be > 0");
  return modulus * std::sqrt(3.0 / curvature_sum) * std::pow(2.0 / (3.0 * mu_star), 1.5);
}

void RaceCurvatures(double D, double d_m, double f, double alpha, bool inner, double* curvature_x,
                    double* curvature_y) {
  const double c = std::cos(alpha);
  // Rolling direction: ball 2/D plus the race, convex (inner) or concave (outer), of radius
  // (d_m -+ D cos a) / (2 cos a) measured along the contact normal to the bearing axis.
  *curvature_x = 2.0 / D + (inner ? 2.0 * c / (d_m - D * c) : -2.0 * c / (d_m + D * c));
  *curvature_y = 2.0 / D - 1.0 / (f * D);  // the groove, concave
}

// ------------------------------------------------------------------------------------------------ element

namespace {

struct BallBearingWorkspace : ElementWorkspace {
  BallBearingWorkspace(int n, int n_balls)
      : zdot(n, 0.0), in(8 + n + 4, 0.0), out0(4 + n + 4, 0.0), out1(4 + n + 4, 0.0), share0(n_balls), share1(n_balls),
        step(n_balls, 0.0), key(4, n) {
    contacts.parts.resize(3 * static_cast<std::size_t>(n_balls));
  }
  std::vector<double> zdot;
  // add_jacobian scratch: inputs [q; v; z], outputs [f; zdot] (base and perturbed), the balls' shares, steps;
  // room for the 4 radial outer-ring states of a wrapping element (add_jacobian_of).
  std::vector<double> in, out0, out1;
  std::vector<BallShare> share0, share1;
  std::vector<double> step;
  BallContactCache contacts;  // the base state's contacts
  // The loads of the last evaluation for the engine and its inputs (speed, q, v, z), so that the powers and the
  // probes at the same state (every right-hand side asks for both powers) do not evaluate the bearing again.
  EvaluationKey key;
  BallBearingLoads loads;
};

}  // namespace

BallBearingElement::BallBearingElement(const std::string& name, const BallBearingSpec& spec, int node_dof,
                                       double gravity)
    : ForceElement(name, {node_dof, node_dof + 1, node_dof + 2, node_dof + 3},
                   BallBearingElement::kBallStates * spec.n_balls + kCageStates + 2 +
                       (spec.outer_ring_mode == OuterRingMode::Spring ? 4 : 0)),
      spec_(spec),
      gravity_(gravity) {
  std::string error;
  if (!spec.IsValid(&error)) throw std::invalid_argument("ball bearing '" + name + "': " + error);
  if (!std::isfinite(gravity)) throw std::invalid_argument("ball bearing '" + name + "': gravity must be finite");
  n_core_ = kBallStates * spec.n_balls + kCageStates + 2;
  const double D = spec.ball_diameter, dm = spec.pitch_diameter, a0 = spec.contact_angle, s = spec.side;
  pitch_radius_ = 0.5 * dm;
  pocket_cos_.resize(spec.n_balls);
  pocket_sin_.resize(spec.n_balls);
  for (int j = 0; j < spec.n_balls; ++j) {
    pocket_cos_[j] = std::cos(2.0 * kPi * j / spec.n_balls);
    pocket_sin_[j] = std::sin(2.0 * kPi * j / spec.n_balls);
  }
  m_ball_ = spec.ball_density * kPi * D * D * D / 6.0;
  i_ball_ = m_ball_ * D * D / 10.0;
  i_cage_ = spec.cage_polar_inertia > 0.0 ? spec.cage_polar_inertia : spec.cage_mass * pitch_radius_ * pitch_radius_;

  // Groove curvature centres (Harris & Kotzalas 2007, ch. 2): crossed, the inner one beyond the ball centre.
  inner_r_ = (spec.inner_groove_ratio - 0.5) * D;
  outer_r_ = (spec.outer_groove_ratio - 0.5) * D;
  inner_dr_ = inner_r_ * std::cos(a0);
  inner_z_ = s * inner_r_ * std::sin(a0);
  outer_dr_ = -outer_r_ * std::cos(a0);
  outer_z_ = -s * outer_r_ * std::sin(a0);

  // Hertz constants at the free contact angle (the change with the loaded angle is neglected, see the doc).
  const double e_br = 2.0 / ((1.0 - spec.ball_poisson_ratio * spec.ball_poisson_ratio) / spec.ball_youngs_modulus +
                             (1.0 - spec.ring_poisson_ratio * spec.ring_poisson_ratio) / spec.ring_youngs_modulus);
  double cx = 0.0, cy = 0.0;
  RaceCurvatures(D, dm, spec.inner_groove_ratio, a0, true, &cx, &cy);
  lubricant_ = EyringLubricant{spec.lubricant_viscosity, spec.pressure_viscosity, spec.eyring_stress,
                               spec.limiting_shear_coefficient, spec.lubricant_shear_modulus};
  hertz_inner_ = SolveHertzPointContact(cx, cy, e_br);
  RaceCurvatures(D, dm, spec.outer_groove_ratio, a0, false, &cx, &cy);
  hertz_outer_ = SolveHertzPointContact(cx, cy, e_br);
  if (spec.hertz_coefficient > 0.0) {
    // The paper's Eq. 20 sets the load-deflection law; the contact ellipse's size at a load (spin moment, lubricated
    // traction) stays the exact one's.
    for (HertzPointContact* h : {&hertz_inner_, &hertz_outer_}) {
      h->stiffness = PaperHertzConstant(h->curvature_sum, e_br, spec.hertz_coefficient);
      h->cbrt_stiffness = std::cbrt(h->stiffness);
    }
  }

  // Ball in a spherical pocket of radius D/2 + c_p: sphere in a conforming sphere, F = (4/3) E* sqrt(R) delta^1.5
  // with 1/R = 2/D - 1/(D/2 + c_p) (Johnson 1985, §4.2).
  const double e_star = 1.0 / ((1.0 - spec.ball_poisson_ratio * spec.ball_poisson_ratio) / spec.ball_youngs_modulus +
                               (1.0 - spec.cage_poisson_ratio * spec.cage_poisson_ratio) / spec.cage_youngs_modulus);
  const double r_pocket = 0.5 * D + spec.pocket_clearance;
  k_pocket_ = 4.0 / 3.0 * e_star * std::sqrt(0.5 * D * r_pocket / spec.pocket_clearance);

  // Static preload equilibrium without gravity and speed: every ball on the line of its groove centres
  // (two-force body), Q = K_n delta_n^1.5 with 1/K_n^(2/3) = 1/K_i^(2/3) + 1/K_o^(2/3) (Harris & Kotzalas 2007,
  // ch. 7); the outer ring moves by x towards -side until Z Q sin(a) = F_p - k_p x.
  const double Kn =
      std::pow(std::pow(hertz_inner_.stiffness, -2.0 / 3.0) + std::pow(hertz_outer_.stiffness, -2.0 / 3.0), -1.5);
  const double A = inner_r_ + outer_r_;
  const auto state = [&](double x, double* Q, double* dr, double* dz, double* L) {
    *dr = inner_dr_ - outer_dr_;
    *dz = inner_z_ - (outer_z_ - s * x);
    *L = std::sqrt(*dr * *dr + *dz * *dz);
    const double dn = *L - A;
    *Q = dn > 0.0 ? Kn * dn * std::sqrt(dn) : 0.0;
  };
  const auto h = [&](double x) {
    double Q, dr, dz, L;
    state(x, &Q, &dr, &dz, &L);
    return spec.n_balls * Q * s * dz / L - spec.preload + spec.preload_stiffness * x;
  };
  double x = 0.0;
  if (h(0.0) < 0.0) {
    double lo = 0.0, hi = 1e-9;
    for (int i = 0; i < 200 && h(hi) < 0.0; ++i) lo = hi, hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-16 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (h(mid) < 0.0 ? lo : hi) = mid;
    }
    x = 0.5 * (lo + hi);
  }
  double Q, dr, dz, L;
  state(x, &Q, &dr, &dz, &L);
  zo_eq_ = -s * x;
  const double to_ball = outer_r_ + std::pow(Q / hertz_outer_.stiffness, 2.0 / 3.0);
  rho_eq_ = outer_dr_ + to_ball * dr / L;
  zeta_eq_ = outer_z_ + zo_eq_ + to_ball * dz / L;
}

OuterRingKinematics BallBearingElement::outer_from_states(const double* z) const {
  OuterRingKinematics o;
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    o.x = z[n_core_];
    o.y = z[n_core_ + 1];
    o.vx = z[n_core_ + 2];
    o.vy = z[n_core_ + 3];
  }
  return o;
}

void BallBearingElement::initial_states(double* z) const {
  std::fill(z, z + n_states(), 0.0);
  for (int j = 0; j < spec_.n_balls; ++j) {
    double* b = z + ball_offset(j);
    b[0] = 2.0 * kPi * j / spec_.n_balls;
    b[1] = rho_eq_;
    b[2] = zeta_eq_;
  }
  z[outer_offset()] = zo_eq_;
}

void BallBearingElement::initial_states_at_speed(double speed, double* z) const {
  initial_states(z);
  if (speed != 0.0) steady_states(speed, z);
}

void BallBearingElement::steady_states(double speed, double* z) const {
  const double D = spec_.ball_diameter, dm = spec_.pitch_diameter;
  double cage = 0.0;
  for (int j = 0; j < spec_.n_balls; ++j) {
    double* b = z + ball_offset(j);
    // Outer contact normal from the outer groove centre to the ball centre (outer ring radially centred).
    const double dr = b[1] - outer_dr_, dz = b[2] - (outer_z_ + z[outer_offset()]);
    const double L = std::sqrt(dr * dr + dz * dz);
    const double ur = dr / L, uz = dz / L;  // cos(a), side * sin(a)
    // No slip at either contact, cage speed (W/2)(1 - (D/d_m) cos a) (docs/references.md §5); with no spin
    // at the outer contact the ball's absolute angular velocity is normal to the contact line,
    // w = w_c (d_m / D) (side sin a, 0, -cos a) in (e_r, e_psi, e_z).
    const double wc = 0.5 * speed * (1.0 - D / dm * ur);
    b[3] = wc;
    b[4] = b[5] = 0.0;
    b[6] = wc * dm / D * uz;
    b[7] = 0.0;
    b[8] = -wc * dm / D * ur;
    cage += wc / spec_.n_balls;
  }
  double* c = z + cage_offset();
  c[4] = c[5] = c[6] = 0.0;
  c[7] = cage;
}

bool BallBearingElement::steady_rotation_layout(SteadyRotationLayout* layout) const {
  if (spec_.outer_ring_mode == OuterRingMode::External || gravity_ != 0.0) return false;
  core_rotation_layout(layout);
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    const int o = n_core_;
    layout->planar_pairs.emplace_back(o, o + 1);
    layout->planar_pairs.emplace_back(o + 2, o + 3);
  }
  return true;
}

void BallBearingElement::core_rotation_layout(SteadyRotationLayout* layout) const {
  layout->planar_pairs.clear();
  layout->turning_angles.clear();
  for (int j = 0; j < spec_.n_balls; ++j) layout->turning_angles.emplace_back(ball_offset(j), ball_offset(j) + 3);
  const int c = cage_offset();
  layout->phase_angle = static_cast<int>(layout->turning_angles.size());
  layout->turning_angles.emplace_back(c + 3, c + 7);
  layout->planar_pairs.emplace_back(c, c + 1);
  layout->planar_pairs.emplace_back(c + 4, c + 5);
  // The paper's friction (Eq. 23) saturates over a creep range of millimetres per second: its steady states lie
  // close together, and steps of 250 rad/s (125 from rest) reached another of them in 3-4 of 48 designs of high
  // preload, half those steps the same state as a quarter (docs/ball-bearing.md, "Steps and nearby steady
  // states"). The lubricated traction's creep is wider: the regular steps find the state of a quarter of them.
  layout->continuation_step_factor = spec_.traction_law == TractionLaw::Coulomb ? 0.5 : 1.0;
}

std::unique_ptr<ElementWorkspace> BallBearingElement::make_workspace() const {
  return std::make_unique<BallBearingWorkspace>(n_states(), spec_.n_balls);
}

double BallBearingElement::state_scale(int i) const {
  const double v_ang = 1e-3 / pitch_radius_;  // 1 mm/s at the pitch circle in rad/s
  const int nb = kBallStates * spec_.n_balls;
  if (i < nb) {
    static constexpr double kLengths[kBallStates] = {0, 1e-6, 1e-6, 0, 1e-3, 1e-3, 0, 0, 0};
    const int k = i % kBallStates;
    if (k == 0) return 1e-6 / pitch_radius_;
    if (k == 3) return v_ang;
    if (k >= 6) return 1e-3 / (0.5 * spec_.ball_diameter);
    return kLengths[k];
  }
  i -= nb;
  if (i < kCageStates) {
    static constexpr double kCage[kCageStates] = {1e-6, 1e-6, 1e-6, 0, 1e-3, 1e-3, 1e-3, 0};
    if (i == 3) return 1e-6 / pitch_radius_;
    if (i == 7) return v_ang;
    return kCage[i];
  }
  i -= kCageStates;
  if (i < 2) return i == 0 ? 1e-6 : 1e-3;
  return (i - 2) < 2 ? 1e-6 : 1e-3;
}

double BallBearingElement::tolerance_scale(int i) const {
  const int c = i - cage_offset();
  if (c < 0) {
    const int k = i % kBallStates;
    if (k == 4 || k == 5) return kBallVelocityTolerance;                       // radial, axial velocity
    if (k >= 6) return kBallVelocityTolerance / (0.5 * spec_.ball_diameter);  // spin rates
  } else if (c >= 4 && c <= 6) {
    return kCageVelocityTolerance;  // the cage's translational velocities
  }
  return state_scale(i);
}

void BallBearingElement::calc_bearing(const SpinState& st, const double* q, const double* v, const double* z,
                                     const OuterRingKinematics& outer, BallBearingLoads& loads, double* zdot,
                                     BallShare* shares, BallContactCache* cache, unsigned redo) const {
  loads = BallBearingLoads{};
  const int Z = spec_.n_balls;
  const bool store = cache != nullptr && redo == kAllContacts;
  if (cache != nullptr ? cache->parts.size() != static_cast<std::size_t>(3 * Z) : redo != kAllContacts)
    throw std::logic_error("ball bearing '" + name() + "': partial evaluation without a contact cache of 3 Z parts");
  const double Rp = pitch_radius_, Rb = 0.5 * spec_.ball_diameter, m = m_ball_, I = i_ball_, g = gravity_;
  const double side = spec_.side;
  const double d_pocket = spec_.pocket_damping, cp = spec_.pocket_clearance;
  const double mu0 = spec_.friction_static, mur = spec_.friction_sliding;
  const double v1 = spec_.friction_v1, v2 = spec_.friction_v2;
  const bool eyring = spec_.traction_law == TractionLaw::Eyring;
  const bool friction = eyring || mu0 > 0.0 || mur > 0.0;
  const bool spin = friction && spec_.spin_friction;
  const bool planar = spec_.race_traction == RaceTraction::Planar;
  // mu(v)/v of paper Eq. 23 for v >= 0, finite at v = 0: the friction force is -Q (mu(|v_t|)/|v_t|) v_t.
  const auto mu_over_v = [=](double vt) { return eq23_mu_over_slip(vt, mu0, mur, v1, v2); };
  constexpr double kSpinMoment = 3.0 * kPi / 16.0;  // M = (3 pi / 16) mu Q a: uniform mu, Hertz pressure

  // Shaft: inner ring centre, tilt and angular velocity (spin about the tilted axis) in the housing frame.
  const double W = st.speed;
  const Vec3 wi_h(v[2] + W * q[3], v[3] - W * q[2], W);
  // Cage and outer ring.
  const double* cg = z + cage_offset();
  const double zo = z[outer_offset()], vzo = z[outer_offset() + 1];
  const double cage_c = std::cos(cg[3]), cage_s = std::sin(cg[3]);  // the pockets' angles: cg[3] + 2 pi j / Z

  Vec3 F_shaft = Vec3::Zero(), M_shaft = Vec3::Zero();  // housing frame
  Vec3 F_outer = Vec3::Zero(), F_cage = Vec3::Zero();
  double T_cage = 0.0, diss = 0.0;
  double qmax[2] = {0.0, 0.0};  // largest normal force at the inner and at the outer races
  double ai_r = 0.0, ai_z = 0.0, ao_r = 0.0, ao_z = 0.0;

  Race inner, outer_race;
  inner.dr = inner_dr_, inner.dz = inner_z_, inner.r0 = inner_r_;
  outer_race.dr = outer_dr_, outer_race.dz = outer_z_, outer_race.r0 = outer_r_;

  // One ball's state as its contacts see it.
  struct Ball {
    double c, sn, R, rho, zeta, psid;
    Vec3 Vb, wb;
  };

  // The ball being evaluated: the sums of its contacts' force and moment (orbital basis) and its share of the sums
  // over the balls.
  Vec3 F_ball = Vec3::Zero(), M_ball = Vec3::Zero();
  BallShare* share = nullptr;
  // Contact k (0 inner race, 1 outer race, 2 pocket) of the ball adds its force and moment on the ball and, on the
  // other body (housing frame, BallContactPart::body), to the sums; a contact being cached is also stored (dst).
  const auto take = [&](int k, const Vec3& F, const Vec3& M, const double* body, BallContactPart* dst) {
    F_ball += F;
    M_ball += M;
    if (k == 0) {
      F_shaft += Vec3(body[0], body[1], body[2]);
      M_shaft += Vec3(body[3], body[4], body[5]);
      if (share) {
        share->shaft[0] = body[0];
        share->shaft[1] = body[1];
        for (int i = 0; i < 3; ++i) share->shaft[2 + i] = body[3 + i];
      }
    } else if (k == 1) {
      F_outer += Vec3(body[0], body[1], body[2]);
      if (share)
        for (int i = 0; i < 3; ++i) share->outer[i] = body[i];
    } else {
      F_cage += Vec3(body[0], body[1], body[2]);
      T_cage += body[3];
      if (share)
        for (int i = 0; i < 4; ++i) share->cage[i] = body[i];
    }
    if (dst) {
      for (int i = 0; i < 3; ++i) dst->ball[i] = F(i), dst->ball[3 + i] = M(i);
      for (int i = 0; i < 6; ++i) dst->body[i] = body[i];
    }
  };

  // Ball-race contact k (0 inner, 1 outer): Hertz + damping (Eq. 21 with d + beta k_c, k_c = 1.5 K delta^0.5 the
  // tangent Hertz stiffness; clipped so that it never pulls), friction
  // (Eqs. 22-23) at the slip velocity of the contact centre, spin moment.
  const auto race_contact = [&](int k, const Ball& bl, BallContactPart* dst) {
    if (dst) *dst = BallContactPart{};
    const Race& race = k == 0 ? inner : outer_race;
    const HertzPointContact& hz = k == 0 ? hertz_inner_ : hertz_outer_;
    RaceGeometry geo;
    if (!race_geometry(race, bl.R, bl.rho, bl.zeta, geo)) return;
    const Vec3& Vb = bl.Vb;
    const Vec3& wb = bl.wb;
    const double root_delta = std::sqrt(geo.delta);
    const double QH = hz.stiffness * geo.delta * root_delta;
    const double ddot = geo.u.dot(Vb - race.velocity) - geo.u_l.dot(race.tilt_rate.cross(geo.p));
    const double Q = std::max(0.0, QH + race_contact_damping(hz, root_delta) * ddot);
    diss += (Q - QH) * ddot;
    Vec3 Fr = Q * geo.u;                 // on the ring
    Vec3 Mr = geo.p.cross(Q * geo.u_l);  // about the ring centre (generalised force of the small rotation)
    Vec3 F = -Q * geo.u, M = Vec3::Zero();  // on the ball
    if (k == 0) loads.shaft_power_normal += Fr.dot(race.velocity) + Mr.dot(race.tilt_rate);
    double& friction_loss = k == 0 ? loads.friction_loss_inner : loads.friction_loss_outer;
    if (friction && Q > 0.0) {
      const Vec3 arm = Rb * geo.u;
      const Vec3 lever = geo.p + arm;  // contact point from the ring centre
      const Vec3 vrel = Vb + wb.cross(arm) - race.velocity - race.omega.cross(lever);
      Vec3 vt = vrel - vrel.dot(geo.u) * geo.u;
      if (planar) {
        // The paper's planar contact: only the slip along the rolling direction, e_psi in the tangent plane.
        const Vec3 roll = (Vec3(0.0, 1.0, 0.0) - geo.u.y() * geo.u).normalized();
        vt = vt.dot(roll) * roll;
      }
      double per_slip = 0.0, u_entrain = 0.0;  // |F_t| / |v_t| in N s/m, entrainment speed in m/s
      if (eyring) {
        // Entrainment speed: the mean of the two surfaces' speeds relative to the contact point, which moves
        // with the ball's orbit.
        const Vec3 v_contact(0.0, bl.psid * (bl.R + arm.x()), 0.0);
        Vec3 ue = 0.5 * ((Vb + wb.cross(arm) - v_contact) + (race.velocity + race.omega.cross(lever) - v_contact));
        ue -= ue.dot(geo.u) * geo.u;
        u_entrain = ue.norm();
        per_slip = eyring_traction_per_slip(lubricant_, hz, Q, u_entrain, vt.norm());
      } else {
        per_slip = Q * mu_over_v(vt.norm());
      }
      const Vec3 Ft = -per_slip * vt;
      F += Ft;
      M += arm.cross(Ft);
      Fr -= Ft;
      Mr -= lever.cross(Ft);
      diss -= Ft.dot(vt);
      friction_loss -= Ft.dot(vt);
      if (k == 0) loads.shaft_power_friction -= Ft.dot(race.velocity) + lever.cross(Ft).dot(race.tilt_rate);
      if (spin) {
        const double a = hz.radius_factor * load_cbrt(Q, QH, hz.cbrt_stiffness * root_delta);
        const double ws = (wb - race.omega).dot(geo.u);
        // Coulomb: (3 pi / 16) mu Q a; lubricated: the traction at the slip a |w_s| gives the same moment
        // with mu = F / Q.
        const double per_slip_spin = eyring ? eyring_traction_per_slip(lubricant_, hz, Q, u_entrain, std::abs(ws) * a)
                                            : Q * mu_over_v(std::abs(ws) * a);
        const double Ms = kSpinMoment * a * a * per_slip_spin * ws;
        M -= Ms * geo.u;
        Mr += Ms * geo.u;
        diss += Ms * ws;
        friction_loss += Ms * ws;
        if (k == 0) loads.shaft_power_friction += Ms * geo.u.dot(race.tilt_rate);
      }
    }
    qmax[k] = std::max(qmax[k], Q);
    if (k == 0) {
      if (Q > 0.0) ai_r -= geo.u.x(), ai_z -= side * geo.u.z();
    } else {
      if (Q > 0.0) ao_r += geo.u.x(), ao_z += side * geo.u.z();
    }
    double body[6] = {0, 0, 0, 0, 0, 0};
    Vec3::Map(body) = to_housing(Fr, bl.c, bl.sn);
    if (k == 0) Vec3::Map(body + 3) = to_housing(Mr, bl.c, bl.sn);
    take(k, F, M, body, dst);
  };

  // Ball-pocket contact (ball-guided cage, spherical pocket of clearance c_p).
  const auto pocket_contact = [&](int j, const Ball& bl, BallContactPart* dst) {
    if (dst) *dst = BallContactPart{};
    const Vec3 cage_centre = to_orbital(cg[0], cg[1], cg[2], bl.c, bl.sn);
    PocketGeometry pg;
    double sd, cd;
    pocket_offset(bl.c, bl.sn, pocket_cos(j, cage_c, cage_s), pocket_sin(j, cage_c, cage_s), sd, cd);
    pocket_geometry(bl.rho, bl.zeta, sd, cd, Rp, cage_centre, pg);
    const double delta = pg.dist - cp;
    if (!(delta > 0.0)) return;
    const Vec3& Vb = bl.Vb;
    const Vec3 n = pg.delta_vec / pg.dist;
    const Vec3 Vc = to_orbital(cg[4], cg[5], cg[6], bl.c, bl.sn);
    const double wc = cg[7];
    const Vec3 Vpocket = Vc + wc * Vec3(-pg.pocket.y(), pg.pocket.x(), 0.0);
    const double QH = k_pocket_ * delta * std::sqrt(delta);
    const double ddot = n.dot(Vb - Vpocket);
    const double Q = std::max(0.0, QH + d_pocket * ddot);
    diss += (Q - QH) * ddot;
    Vec3 Fc = Q * n;  // on the cage
    double Tc = Q * (pg.pocket.x() * n.y() - pg.pocket.y() * n.x());
    Vec3 F = -Q * n, M = Vec3::Zero();  // on the ball
    if (friction && Q > 0.0) {
      const Vec3 arm = Rb * n;
      const Vec3 lever = pg.pocket + pg.delta_vec + arm;  // contact point from the cage centre
      const Vec3 vrel = Vb + bl.wb.cross(arm) - Vc - wc * Vec3(-lever.y(), lever.x(), 0.0);
      const Vec3 vt = vrel - vrel.dot(n) * n;
      const Vec3 Ft = (-Q * mu_over_v(vt.norm())) * vt;
      F += Ft;
      M += arm.cross(Ft);
      Fc -= Ft;
      Tc -= lever.x() * Ft.y() - lever.y() * Ft.x();
      diss -= Ft.dot(vt);
      loads.friction_loss_pocket -= Ft.dot(vt);
    }
    double body[6] = {0, 0, 0, Tc, 0, 0};
    Vec3::Map(body) = to_housing(Fc, bl.c, bl.sn);
    take(2, F, M, body, dst);
  };

  for (int j = 0; j < Z; ++j) {
    const double* b = z + ball_offset(j);
    double* bd = zdot + ball_offset(j);
    Ball bl;
    bl.psid = b[3];
    bl.c = std::cos(b[0]);
    bl.sn = std::sin(b[0]);
    bl.rho = b[1];
    bl.zeta = b[2];
    bl.R = Rp + bl.rho;
    bl.Vb = Vec3(b[4], bl.R * bl.psid, b[5]);
    bl.wb = Vec3(b[6], b[7], b[8]);
    const double c = bl.c, sn = bl.sn, psid = bl.psid, R = bl.R;

    // Each contact anew (into the cache when it is being filled), or the cached one; gravity along -y.
    F_ball = Vec3(-m * g * sn, -m * g * c, 0.0);
    M_ball = Vec3::Zero();
    share = shares ? &shares[j] : nullptr;
    if (share) *share = BallShare{};
    BallContactPart* kept = cache != nullptr ? &cache->parts[3 * static_cast<std::size_t>(j)] : nullptr;
    const auto cached = [&](int k) {
      const BallContactPart& p = kept[k];
      take(k, Vec3(p.ball[0], p.ball[1], p.ball[2]), Vec3(p.ball[3], p.ball[4], p.ball[5]), p.body, nullptr);
    };
    for (int k = 0; k < 2; ++k) {
      if (!(redo & (k == 0 ? kInnerContacts : kOuterContacts))) {
        cached(k);
        continue;
      }
      if (k == 0) {
        inner.centre = to_orbital(q[0], q[1], 0.0, c, sn);
        inner.velocity = to_orbital(v[0], v[1], 0.0, c, sn);
        inner.tilt = to_orbital(q[2], q[3], 0.0, c, sn);
        inner.tilt_rate = to_orbital(v[2], v[3], 0.0, c, sn);
        inner.omega = to_orbital(wi_h.x(), wi_h.y(), wi_h.z(), c, sn);
      } else {
        outer_race.centre = to_orbital(outer.x, outer.y, zo, c, sn);
        outer_race.velocity = to_orbital(outer.vx, outer.vy, vzo, c, sn);
      }
      race_contact(k, bl, store ? &kept[k] : nullptr);
    }
    if (redo & kPocketContacts)
      pocket_contact(j, bl, store ? &kept[2] : nullptr);
    else
      cached(2);

    // Newton in cylindrical coordinates, Euler for a sphere in the orbital frame.
    const Vec3& F = F_ball;
    const Vec3& M = M_ball;
    bd[0] = psid;
    bd[1] = b[4];
    bd[2] = b[5];
    bd[3] = (F.y() / m - 2.0 * b[4] * psid) / R;
    bd[4] = F.x() / m + R * psid * psid;
    bd[5] = F.z() / m;
    bd[6] = M.x() / I + psid * bl.wb.y();
    bd[7] = M.y() / I - psid * bl.wb.x();
    bd[8] = M.z() / I;
  }

  // Cage: translation and spin (tilt neglected).
  double* cd = zdot + cage_offset();
  const double mc = spec_.cage_mass;
  cd[0] = cg[4];
  cd[1] = cg[5];
  cd[2] = cg[6];
  cd[3] = cg[7];
  cd[4] = F_cage.x() / mc;
  cd[5] = F_cage.y() / mc - g;
  cd[6] = F_cage.z() / mc;
  cd[7] = T_cage / i_cage_;

  // Outer ring, axial: balls and the preload spring, force -side F_p - k_p z_o.
  double* od = zdot + outer_offset();
  od[0] = vzo;
  od[1] = (F_outer.z() - side * spec_.preload - spec_.preload_stiffness * zo) / spec_.outer_ring_mass;

  loads.shaft[0] = F_shaft.x();
  loads.shaft[1] = F_shaft.y();
  loads.shaft[2] = M_shaft.x();
  loads.shaft[3] = M_shaft.y();
  loads.shaft_torque = M_shaft.z();
  loads.outer_ring[0] = F_outer.x();
  loads.outer_ring[1] = F_outer.y();
  loads.outer_ring[2] = F_outer.z();
  loads.max_race_contact_force[0] = qmax[0];
  loads.max_race_contact_force[1] = qmax[1];
  loads.dissipated_power = diss;
  loads.inner_contact_angle = (ai_r != 0.0 || ai_z != 0.0) ? std::atan2(ai_z, ai_r) : 0.0;
  loads.outer_contact_angle = (ao_r != 0.0 || ao_z != 0.0) ? std::atan2(ao_z, ao_r) : 0.0;
}

void BallBearingElement::do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z,
                                            ElementWorkspace& ws, double* f, double* zdot) const {
  auto& w = static_cast<BallBearingWorkspace&>(ws);
  w.key.invalidate();
  Evaluate(s, q, v, z, f, zdot, nullptr, &w.loads);
  w.key.set(s.speed, q, v, z);
}

const BallBearingLoads& BallBearingElement::loads_at(const SpinState& s, const double* q, const double* v,
                                                    const double* z, ElementWorkspace& ws) const {
  auto& w = static_cast<BallBearingWorkspace&>(ws);
  if (w.key.matches(s.speed, q, v, z)) return w.loads;
  w.key.invalidate();
  calc_bearing(s, q, v, z, outer_from_states(z), w.loads, w.zdot.data());
  w.key.set(s.speed, q, v, z);
  return w.loads;
}

void BallBearingElement::add_jacobian(const SpinState& s, const double* q, const double* v, const double* z,
                                     ElementWorkspace& ws, double* J) const {
  struct Own final : JacobianEvaluator {
    Own(const BallBearingElement& e, const SpinState& st) : e(e), st(st) {}
    void operator()(const double* q, const double* v, const double* z, double* f, double* zdot,
                    BallShare* shares, BallContactCache* cache, unsigned redo) const override {
      e.Evaluate(st, q, v, z, f, zdot, shares, nullptr, cache, redo);
    }
    const BallBearingElement& e;
    const SpinState& st;
  };
  add_jacobian_of(*this, Own(*this, s), n_states(), q, v, z, ws, J);
}

void BallBearingElement::add_jacobian_of(const ForceElement& owner, const JacobianEvaluator& eval, int m,
                                       const double* q, const double* v, const double* z, ElementWorkspace& ws,
                                       double* J) const {
  auto& w = static_cast<BallBearingWorkspace&>(ws);
  constexpr int d = 4;
  const int rows = d + m, Z = spec_.n_balls;
  double* in = w.in.data();
  std::copy(q, q + d, in);
  std::copy(v, v + d, in + d);
  std::copy(z, z + m, in + 2 * d);
  const auto evaluate = [&](std::vector<double>& out, BallShare* shares, BallContactCache* cache, unsigned redo) {
    std::fill(out.begin(), out.begin() + rows, 0.0);
    eval(in, in + d, in + 2 * d, out.data(), out.data() + d, shares, cache, redo);
  };
  const auto column = [&](int j) { return J + static_cast<std::size_t>(j) * rows; };
  evaluate(w.out0, w.share0.data(), &w.contacts, kAllContacts);

  // The shaft's displacements and velocities, then the cage, the outer ring and any states after the core (the
  // inputs after the balls): one input at a time, each evaluating only the contacts it moves (the shaft the inner
  // races', the cage the pockets', the outer ring the outer races'), the others from the base state.
  const auto one_at_a_time = [&](int j, unsigned redo) {
    const double saved = in[j];
    const double h = owner.fd_step(j, d, saved);
    in[j] = saved + h;
    evaluate(w.out1, nullptr, &w.contacts, redo);
    in[j] = saved;
    double* col = column(j);
    for (int r = 0; r < rows; ++r) col[r] += (w.out1[r] - w.out0[r]) / h;
  };
  for (int j = 0; j < 2 * d; ++j) one_at_a_time(j, kInnerContacts);
  const int cage_in = 2 * d + cage_offset(), outer_in = 2 * d + outer_offset();
  for (int j = cage_in; j < outer_in; ++j) one_at_a_time(j, kPocketContacts);
  for (int j = outer_in; j < 2 * d + m; ++j) one_at_a_time(j, kOuterContacts);

  // State i of every ball at once: a ball's own rows depend on no other ball, and the rows of the sums (shaft
  // forces, cage, outer ring) are told apart by each ball's share.
  const double mc = spec_.cage_mass, mo = spec_.outer_ring_mass;
  const int rc = d + cage_offset(), ro = d + outer_offset(), rs = d + n_core_;
  const bool radial = m > n_core_;  // the outer ring's radial states follow the core
  for (int i = 0; i < kBallStates; ++i) {
    for (int b = 0; b < Z; ++b) {
      const int k = ball_offset(b) + i;
      w.step[b] = owner.fd_step(2 * d + k, d, z[k]);
      in[2 * d + k] = z[k] + w.step[b];
    }
    evaluate(w.out1, w.share1.data(), nullptr, kAllContacts);
    for (int b = 0; b < Z; ++b) {
      const int k = ball_offset(b) + i;
      in[2 * d + k] = z[k];
      const double h = w.step[b];
      double* col = column(2 * d + k);
      for (int r = d + ball_offset(b); r < d + ball_offset(b) + kBallStates; ++r)
        col[r] += (w.out1[r] - w.out0[r]) / h;
      const BallShare& p = w.share1[b];
      const BallShare& p0 = w.share0[b];
      for (int r = 0; r < 4; ++r) col[r] += (p.shaft[r] - p0.shaft[r]) / h;
      for (int r = 0; r < 3; ++r) col[rc + 4 + r] += (p.cage[r] - p0.cage[r]) / (mc * h);
      col[rc + 7] += (p.cage[3] - p0.cage[3]) / (i_cage_ * h);
      col[ro + 1] += (p.outer[2] - p0.outer[2]) / (mo * h);
      if (radial) {
        col[rs + 2] += (p.outer[0] - p0.outer[0]) / (mo * h);
        col[rs + 3] += (p.outer[1] - p0.outer[1]) / (mo * h);
      }
    }
  }
}

void BallBearingElement::Evaluate(const SpinState& s, const double* q, const double* v, const double* z, double* f,
                                  double* zdot, BallShare* shares, BallBearingLoads* loads_out,
                                  BallContactCache* cache, unsigned redo) const {
  BallBearingLoads local;
  BallBearingLoads& loads = loads_out ? *loads_out : local;
  calc_bearing(s, q, v, z, outer_from_states(z), loads, zdot, shares, cache, redo);
  for (int i = 0; i < 4; ++i) f[i] += loads.shaft[i];
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    const double* o = z + n_core_;
    double* od = zdot + n_core_;
    const double k = spec_.outer_ring_stiffness, c = spec_.outer_ring_damping, mo = spec_.outer_ring_mass;
    od[0] = o[2];
    od[1] = o[3];
    od[2] = (loads.outer_ring[0] - k * o[0] - c * o[2]) / mo;
    od[3] = (loads.outer_ring[1] - k * o[1] - c * o[3]) / mo - gravity_;
  }
}

double BallBearingElement::max_contact_pressure(const BallBearingLoads& loads) const {
  return std::max(HertzPeakPressure(hertz_inner_, loads.max_race_contact_force[0]),
                  HertzPeakPressure(hertz_outer_, loads.max_race_contact_force[1]));
}

std::vector<ProbeInfo> BallBearingElement::probes() const {
  const std::string who = "ball bearing '" + name() + "': ";
  return housing_force_probes(who, "", {{"cage_speed_ratio", "1", "cage speed / rotor speed"},
                                        {"max_contact_force", "N", "largest ball-race normal force"},
                                        MaxContactPressureProbe(),
                                        {"outer_ring_axial", "m", "axial displacement of the outer ring"},
                                        {"inner_contact_angle", "rad", "mean loaded inner contact angle"},
                                        {"outer_contact_angle", "rad", "mean loaded outer contact angle"},
                                        {"shaft_power_normal", "W",
                                         "power of the inner-race normal forces on the shaft's lateral motion"},
                                        {"shaft_power_friction", "W",
                                         "power of the inner-race friction on the shaft's lateral motion"},
                                        {"friction_loss_inner", "W", "friction loss at the inner-race contacts"},
                                        {"friction_loss_outer", "W", "friction loss at the outer-race contacts"},
                                        {"friction_loss_pocket", "W", "friction loss at the cage pockets"},
                                        {"cage_x", "m", "cage centre, x"},
                                        {"cage_y", "m", "cage centre, y"},
                                        {"ball_set_offset", "m",
                                         "distance of the balls' mass centre from the bearing axis (uneven spacing)"}});
}

void BallBearingElement::eval_probes(const SpinState& s, const double* q, const double* v, const double* z,
                                    ElementWorkspace& ws, double* out) const {
  const BallBearingLoads& loads = loads_at(s, q, v, z, ws);
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    const double* o = z + n_core_;
    out[0] = spec_.outer_ring_stiffness * o[0] + spec_.outer_ring_damping * o[2];
    out[1] = spec_.outer_ring_stiffness * o[1] + spec_.outer_ring_damping * o[3];
  } else {
    out[0] = loads.outer_ring[0];
    out[1] = loads.outer_ring[1];
  }
  out[2] = s.speed != 0.0 ? z[cage_offset() + 7] / s.speed : 0.0;
  out[3] = loads.max_contact_force();
  out[4] = max_contact_pressure(loads);
  out[5] = z[outer_offset()];
  out[6] = loads.inner_contact_angle;
  out[7] = loads.outer_contact_angle;
  out[8] = loads.shaft_power_normal;
  out[9] = loads.shaft_power_friction;
  out[10] = loads.friction_loss_inner;
  out[11] = loads.friction_loss_outer;
  out[12] = loads.friction_loss_pocket;
  out[13] = z[cage_offset()];
  out[14] = z[cage_offset() + 1];
  // Mass centre of the ball set: zero for equally spaced balls on one radius; a ball set that bunches in its
  // pockets is a rotating unbalance of Z m times this offset, turning with the balls.
  double sx = 0.0, sy = 0.0;
  for (int j = 0; j < spec_.n_balls; ++j) {
    const double* b = z + ball_offset(j);
    const double r = pitch_radius_ + b[1];
    sx += r * std::cos(b[0]);
    sy += r * std::sin(b[0]);
  }
  out[15] = std::hypot(sx, sy) / spec_.n_balls;
}

double BallBearingElement::core_kinetic_energy(const double* z) const {
  double T = 0.0;
  for (int j = 0; j < spec_.n_balls; ++j) {
    const double* b = z + ball_offset(j);
    const double R = pitch_radius_ + b[1];
    T += 0.5 * m_ball_ * (b[4] * b[4] + R * R * b[3] * b[3] + b[5] * b[5]) +
         0.5 * i_ball_ * (b[6] * b[6] + b[7] * b[7] + b[8] * b[8]);
  }
  const double* c = z + cage_offset();
  T += 0.5 * spec_.cage_mass * (c[4] * c[4] + c[5] * c[5] + c[6] * c[6]) + 0.5 * i_cage_ * c[7] * c[7];
  const double vzo = z[outer_offset() + 1];
  return T + 0.5 * spec_.outer_ring_mass * vzo * vzo;
}

double BallBearingElement::kinetic_energy(const double* z) const {
  double T = core_kinetic_energy(z);
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    const double* o = z + n_core_;
    T += 0.5 * spec_.outer_ring_mass * (o[2] * o[2] + o[3] * o[3]);
  }
  return T;
}

double BallBearingElement::core_potential_energy(const double* q, const double* z,
                                               const OuterRingKinematics& outer) const {
  const int Z = spec_.n_balls;
  const double Rp = pitch_radius_;
  const double* cg = z + cage_offset();
  const double zo = z[outer_offset()];
  const double cage_c = std::cos(cg[3]), cage_s = std::sin(cg[3]);
  Race inner, outer_race;
  inner.dr = inner_dr_, inner.dz = inner_z_, inner.r0 = inner_r_;
  outer_race.dr = outer_dr_, outer_race.dz = outer_z_, outer_race.r0 = outer_r_;
  double V = 0.0;
  for (int j = 0; j < Z; ++j) {
    const double* b = z + ball_offset(j);
    const double c = std::cos(b[0]), sn = std::sin(b[0]);
    const double R = Rp + b[1];
    inner.centre = to_orbital(q[0], q[1], 0.0, c, sn);
    inner.tilt = to_orbital(q[2], q[3], 0.0, c, sn);
    outer_race.centre = to_orbital(outer.x, outer.y, zo, c, sn);
    RaceGeometry geo;
    if (race_geometry(inner, R, b[1], b[2], geo))
      V += 0.4 * hertz_inner_.stiffness * geo.delta * geo.delta * std::sqrt(geo.delta);
    if (race_geometry(outer_race, R, b[1], b[2], geo))
      V += 0.4 * hertz_outer_.stiffness * geo.delta * geo.delta * std::sqrt(geo.delta);
    PocketGeometry pg;
    double sd, cd;
    pocket_offset(c, sn, pocket_cos(j, cage_c, cage_s), pocket_sin(j, cage_c, cage_s), sd, cd);
    pocket_geometry(b[1], b[2], sd, cd, Rp, to_orbital(cg[0], cg[1], cg[2], c, sn), pg);
    const double dp = pg.dist - spec_.pocket_clearance;
    if (dp > 0.0) V += 0.4 * k_pocket_ * dp * dp * std::sqrt(dp);
    V += m_ball_ * gravity_ * R * sn;
  }
  V += spec_.cage_mass * gravity_ * cg[1];
  V += spec_.side * spec_.preload * zo + 0.5 * spec_.preload_stiffness * zo * zo;
  return V;
}

double BallBearingElement::potential_energy(const double* q, const double* z) const {
  double V = core_potential_energy(q, z, outer_from_states(z));
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    const double* o = z + n_core_;
    V += 0.5 * spec_.outer_ring_stiffness * (o[0] * o[0] + o[1] * o[1]) + spec_.outer_ring_mass * gravity_ * o[1];
  }
  return V;
}

double BallBearingElement::dissipated_power(const SpinState& s, const double* q, const double* v, const double* z,
                                           ElementWorkspace& ws) const {
  double P = loads_at(s, q, v, z, ws).dissipated_power;
  if (spec_.outer_ring_mode == OuterRingMode::Spring) {
    const double* o = z + n_core_;
    P += spec_.outer_ring_damping * (o[2] * o[2] + o[3] * o[3]);
  }
  return P;
}

double BallBearingElement::drive_power(const SpinState& s, const double* q, const double* v, const double* z,
                                      ElementWorkspace& ws) const {
  return -loads_at(s, q, v, z, ws).shaft_torque * s.speed;
}

}  // namespace turbodyn

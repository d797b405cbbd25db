#include "model/elements/floating_ring_steady.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "model/spec/errors.h"

namespace turbodyn {
namespace {

using E = FloatingRingElement;

// Unknowns: 0, 1 journal relative to the ring (in inner clearances); 2, 3 ring in the housing (outer clearances);
// 4 ring speed / rotor speed; 5, 6 film temperatures above the supply (K, thermal films only).
constexpr int kJx = 0, kJy = 1, kRx = 2, kRy = 3, kRatio = 4, kTi = 5, kTo = 6;
constexpr double kMaxEccentricity = 0.995;  // Newton steps are shortened to stay inside both films

}  // namespace

FloatingRingSteady::FloatingRingSteady(const FloatingRingElement& element, SteadyPointOptions options)
    : e_(element), options_(options), ws_(element.make_workspace()) {
  n_ = element.thermal() ? 7 : 5;
  const int holes = element.spec().drill_holes;
  pitch_ = holes > 0 ? 2.0 * M_PI / holes : 0.0;
  if (holes == 0) options_.angles = 1;
  options_.angles = std::max(options_.angles, 1);
}

void FloatingRingSteady::state(double speed, const Eigen::VectorXd& u, double angle, double* q, double* z) const {
  const FloatingRingSpec& f = e_.spec();
  e_.initial_states(z);
  z[E::kX] = u[kRx] * f.outer_clearance;
  z[E::kY] = u[kRy] * f.outer_clearance;
  z[E::kSpin] = u[kRatio] * speed;
  z[E::kAngle] = angle;
  if (e_.thermal()) {
    z[E::kInnerTemperature] = f.thermal.supply_temperature + u[kTi];
    z[E::kOuterTemperature] = f.thermal.supply_temperature + u[kTo];
  }
  q[0] = z[E::kX] + u[kJx] * f.inner_clearance;
  q[1] = z[E::kY] + u[kJy] * f.inner_clearance;
  q[2] = q[3] = 0.0;
}

// Scaled balances averaged over the ring angles: forces over the load scale, the ring's torque over the inner
// film's Petroff drag at the supply viscosity, heat over that drag's power.
void FloatingRingSteady::residual(double speed, const Eigen::Vector2d& load, const Eigen::VectorXd& u,
                                  Eigen::VectorXd& r) const {
  const FloatingRingSpec& f = e_.spec();
  const double m = f.ring_mass;
  const double fscale = std::max(load.norm(), 1e-3) + m * 9.81;
  const double d = f.inner_diameter;
  const double tscale = 1e-3 * M_PI * d * d * d * f.inner_length * speed / (4.0 * f.inner_clearance);
  const SpinState s{0.0, speed, 0.0, 0.0};
  r.setZero(n_);
  const double v[4] = {0, 0, 0, 0};
  for (int a = 0; a < options_.angles; ++a) {
    double q[4], z[E::kMaxStates], fs[4] = {0, 0, 0, 0}, zd[E::kMaxStates];
    state(speed, u, pitch_ * a / options_.angles, q, z);
    e_.calc_and_add_forces(s, q, v, z, *ws_, fs, zd);
    r[0] += (fs[0] + load[0]) / fscale;
    r[1] += (fs[1] + load[1]) / fscale;
    r[2] += m * zd[E::kVx] / fscale;
    r[3] += m * zd[E::kVy] / fscale;
    r[4] += f.ring_polar_inertia * zd[E::kSpin] / tscale;
    if (e_.thermal()) {
      r[5] += f.thermal.inner_heat_capacity * zd[E::kInnerTemperature] / (tscale * speed);
      r[6] += f.thermal.outer_heat_capacity * zd[E::kOuterTemperature] / (tscale * speed);
    }
  }
  r /= options_.angles;
}

FloatingRingOperatingPoint FloatingRingSteady::solve(double speed, const Eigen::Vector2d& load,
                                                     const FloatingRingOperatingPoint* start) const {
  const FloatingRingSpec& f = e_.spec();
  auto fail = [&](const std::string& why) -> SteadyPointError {
    std::ostringstream os;
    os << "floating-ring bearing '" << e_.name() << "' at " << speed * 60.0 / (2.0 * M_PI) << " rpm, load ("
       << load[0] << ", " << load[1] << ") N: " << why;
    return SteadyPointError(os.str());
  };
  if (!(speed > 0.0)) throw fail("the rotor speed must be positive");
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n_);
  if (start) {
    const double ts = f.thermal.supply_temperature;
    u[kJx] = (start->journal[0] - start->ring[0]) / f.inner_clearance;
    u[kJy] = (start->journal[1] - start->ring[1]) / f.inner_clearance;
    u[kRx] = start->ring[0] / f.outer_clearance;
    u[kRy] = start->ring[1] / f.outer_clearance;
    u[kRatio] = start->ring_speed / start->speed;
    if (e_.thermal()) {
      u[kTi] = start->inner_temperature - ts;
      u[kTo] = start->outer_temperature - ts;
    }
  } else {
    // Both films a little eccentric along the total load, the ring at the Petroff ratio of the supply viscosity.
    Eigen::Vector2d dir = load + Eigen::Vector2d(0.0, -f.ring_mass * 9.81);
    dir = dir.norm() > 0.0 ? Eigen::Vector2d(dir / dir.norm()) : Eigen::Vector2d(0.0, -1.0);
    u.segment<2>(kJx) = 0.2 * dir;
    u.segment<2>(kRx) = 0.2 * dir;
    u[kRatio] = 1.0 / (1.0 + (f.outer_length / f.inner_length) * std::pow(f.outer_diameter / f.inner_diameter, 3) *
                                 (f.inner_clearance / f.outer_clearance));
  }
  auto inside = [&](const Eigen::VectorXd& x) {
    return x.segment<2>(kJx).norm() < kMaxEccentricity && x.segment<2>(kRx).norm() < kMaxEccentricity &&
           x[kRatio] > -1.0 && x[kRatio] < 2.0;
  };
  auto eval = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    if (!inside(x)) return false;
    try {
      residual(speed, load, x, r);
    } catch (const std::runtime_error&) {
      return false;
    }
    return r.allFinite();
  };
  Eigen::VectorXd r(n_), r1(n_), trial(n_);
  if (!eval(u, r)) throw fail("the start point is outside the films");
  Eigen::MatrixXd J(n_, n_);
  int it = 0;
  for (; it < options_.max_iterations && r.norm() > options_.tolerance; ++it) {
    for (int j = 0; j < n_; ++j) {
      const double h = j >= kTi ? 1e-4 : 1e-7;
      trial = u;
      trial[j] += h;
      if (!eval(trial, r1)) {
        trial[j] = u[j] - h;
        if (!eval(trial, r1)) throw fail("the films close next to the current point");
        J.col(j) = (r - r1) / h;
      } else {
        J.col(j) = (r1 - r) / h;
      }
    }
    const Eigen::VectorXd du = J.fullPivLu().solve(-r);
    if (!du.allFinite()) throw fail("singular balance (is the ring free to turn?)");
    double t = 1.0;
    bool accepted = false;
    for (int k = 0; k < 30; ++k, t *= 0.5) {
      trial = u + t * du;
      if (eval(trial, r1) && r1.norm() < (1.0 - 1e-4 * t) * r.norm()) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    u = trial;
    r = r1;
  }
  if (!(r.norm() <= options_.tolerance) && !(it < options_.max_iterations && r.norm() <= options_.stall_tolerance)) {
    std::ostringstream os;
    os << "Newton's method did not converge (scaled residual " << r.norm() << " after " << it << " iterations)";
    throw fail(os.str());
  }
  FloatingRingOperatingPoint p;
  p.speed = speed;
  p.load = load;
  p.iterations = it;
  finish(p, u);
  return p;
}

void FloatingRingSteady::finish(FloatingRingOperatingPoint& p, const Eigen::VectorXd& u) const {
  const FloatingRingSpec& f = e_.spec();
  const double speed = p.speed;
  const SpinState s{0.0, speed, 0.0, 0.0};
  const int na = options_.angles;
  p.ring_speed = u[kRatio] * speed;
  double q[4], z[E::kMaxStates];
  state(speed, u, 0.0, q, z);
  p.journal = Eigen::Vector2d(q[0], q[1]);
  p.ring = Eigen::Vector2d(z[E::kX], z[E::kY]);
  p.inner_eccentricity = u.segment<2>(kJx).norm();
  p.outer_eccentricity = u.segment<2>(kRx).norm();
  const Eigen::Vector2d total = p.load + Eigen::Vector2d(0.0, -f.ring_mass * 9.81);
  const double load_angle = std::atan2(p.load[1], p.load[0]), total_angle = std::atan2(total[1], total[0]);
  p.inner_attitude = std::remainder(std::atan2(u[kJy], u[kJx]) - load_angle, 2.0 * M_PI);
  p.outer_attitude = std::remainder(std::atan2(u[kRy], u[kRx]) - total_angle, 2.0 * M_PI);
  // Heat and flows, the drill holes' pressure, and the linearised films, averaged over the ring angles.
  const double v0[4] = {0, 0, 0, 0};
  for (int a = 0; a < na; ++a) {
    state(speed, u, pitch_ * a / na, q, z);
    const FloatingRingElement::Heat h = e_.heat(s, q, v0, z, *ws_);
    p.drill_hole_pressure += h.drill_hole_pressure / na;
    p.inner_temperature += h.films.inner_temperature / na;
    p.outer_temperature += h.films.outer_temperature / na;
    p.inner_power += h.films.inner_power / na;
    p.outer_power += h.films.outer_power / na;
    p.inner_flow += std::max(h.films.inner_flow, 0.0) / na;
    p.outer_flow += std::max(h.films.outer_flow, 0.0) / na;
    p.heat_to_oil += h.flows.oil() / na;
    p.heat_conducted += h.flows.conducted() / na;
    // Forces of the inner film on the journal (f) and of the outer film on the ring (m zdot_v + f, the ring's
    // weight a constant): journal moved alone for the inner film, ring and journal together for the outer one.
    auto forces = [&](const double* qq, const double* vv, const double* zz, Eigen::Vector2d& inner,
                      Eigen::Vector2d& outer) {
      double fs[4] = {0, 0, 0, 0}, zd[E::kMaxStates];
      e_.calc_and_add_forces(s, qq, vv, zz, *ws_, fs, zd);
      inner = Eigen::Vector2d(fs[0], fs[1]);
      outer = Eigen::Vector2d(f.ring_mass * zd[E::kVx] + fs[0], f.ring_mass * zd[E::kVy] + fs[1]);
    };
    Eigen::Vector2d fi0, fo0, fi1, fo1;
    forces(q, v0, z, fi0, fo0);
    const double hx = 1e-6 * f.inner_clearance, hv = 1e-6 * f.inner_clearance * std::max(speed, 1.0);
    for (int c = 0; c < 2; ++c) {
      double qq[4], vv[4] = {0, 0, 0, 0}, zz[E::kMaxStates];
      std::copy(q, q + 4, qq);
      std::copy(z, z + E::kMaxStates, zz);
      qq[c] += hx;  // inner film: the journal alone
      forces(qq, vv, zz, fi1, fo1);
      p.k_inner.col(c) -= (fi1 - fi0) / hx / na;
      qq[c] -= hx;
      vv[c] = hv;
      forces(qq, vv, zz, fi1, fo1);
      p.c_inner.col(c) -= (fi1 - fi0) / hv / na;
      vv[c] = 0.0;
      const int zx = c == 0 ? E::kX : E::kY, zv = c == 0 ? E::kVx : E::kVy;
      qq[c] += hx;  // outer film: the ring with the journal
      zz[zx] += hx;
      forces(qq, vv, zz, fi1, fo1);
      p.k_outer.col(c) -= (fo1 - fo0) / hx / na;
      qq[c] -= hx;
      zz[zx] -= hx;
      vv[c] = hv;
      zz[zv] = hv;
      forces(qq, vv, zz, fi1, fo1);
      p.c_outer.col(c) -= (fo1 - fo0) / hv / na;
    }
  }
}

std::vector<FloatingRingOperatingPoint> FloatingRingSteady::sweep(const std::vector<double>& speeds,
                                                                  const Eigen::Vector2d& load) const {
  std::vector<FloatingRingOperatingPoint> out;
  for (double w : speeds) out.push_back(solve(w, load, out.empty() ? nullptr : &out.back()));
  return out;
}

void add_floating_ring_linearisations(const MachineSpec& machine, Rotor& rotor, const std::vector<double>& table_speeds) {
  std::vector<const BearingSpec*> rings;
  for (const BearingSpec& b : machine.bearings)
    if (b.type == BearingType::FloatingRing) rings.push_back(&b);
  if (rings.empty()) return;
  const std::string file = machine.source.string();
  if (rings.size() != 2 || machine.bearings.size() != 2)
    throw ModelError(file + ": the modal analysis takes floating-ring bearings as a pair carrying the rotor's weight "
                     "(the static load of each from a rigid beam on two supports): the model needs exactly two "
                     "bearings, both floating rings");
  // Weight and centre of gravity of shaft and disks.
  double mass = 0.0, moment = 0.0;
  for (const ShaftSection& s : machine.shaft) {
    const double m = machine.materials.at(s.material).density * M_PI / 4.0 *
                     (s.outer_diameter * s.outer_diameter - s.inner_diameter * s.inner_diameter) * s.length;
    mass += m;
    moment += m * (s.z_start + 0.5 * s.length);
  }
  for (const DiskSpec& d : machine.disks) {
    mass += d.mass;
    moment += d.mass * d.z;
  }
  const double za = rings[0]->z, zb = rings[1]->z, zcg = moment / mass, weight = mass * machine.gravity;
  if (!(std::abs(zb - za) > 0.0)) throw ModelError(file + ": the two floating-ring bearings sit at the same z");
  const double load[2] = {weight * (zb - zcg) / (zb - za), weight * (zcg - za) / (zb - za)};
  const double length = machine.shaft_length();
  for (int k = 0; k < 2; ++k) {
    const BearingSpec& b = *rings[k];
    const std::string where = file + ": bearings." + b.name;
    if (b.pedestal_mass > 0.0)
      throw ModelError(where + ".pedestal_mass: pedestal masses are part of the run-up model only");
    FloatingRingElement element(b.name, b.ring, machine.oil, 0, machine.gravity);
    std::vector<FloatingRingOperatingPoint> points;
    try {
      points = FloatingRingSteady(element).sweep(table_speeds, Eigen::Vector2d(0.0, -load[k]));
    } catch (const std::runtime_error& e) {
      throw ModelError(where + ": no steady operating point for the modal analysis (load " + std::to_string(load[k]) +
                       " N from the rotor's weight): " + e.what());
    }
    FloatingRingLinearisation lin;
    lin.name = b.name;
    lin.node = rotor.node_at(std::clamp(b.z, 0.0, length));
    lin.ring_mass = b.ring.ring_mass;
    lin.films = [points](double speed, Eigen::Matrix2d& ki, Eigen::Matrix2d& ci, Eigen::Matrix2d& ko,
                         Eigen::Matrix2d& co) {
      std::size_t i = 0;
      while (i + 1 < points.size() && points[i + 1].speed <= speed) ++i;
      const FloatingRingOperatingPoint& a = points[i];
      const FloatingRingOperatingPoint& c = points[std::min(i + 1, points.size() - 1)];
      const double w = c.speed > a.speed ? std::clamp((speed - a.speed) / (c.speed - a.speed), 0.0, 1.0) : 0.0;
      ki = (1 - w) * a.k_inner + w * c.k_inner;
      ci = (1 - w) * a.c_inner + w * c.c_inner;
      ko = (1 - w) * a.k_outer + w * c.k_outer;
      co = (1 - w) * a.c_outer + w * c.c_outer;
    };
    rotor.rings.push_back(std::move(lin));
  }
}

}  // namespace turbodyn

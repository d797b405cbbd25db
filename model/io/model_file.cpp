#include "model/io/model_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "model/films/reynolds.h"
#include "model/io/overrides_toml.h"
#include "model/io/toml_reader.h"
#include "model/spec/units.h"

namespace turbodyn {
namespace {

using namespace input;

// ----------------------------------------------------------------------------------------------- checks

// The film grid keys shared by every film spec (JournalBearingSpec, DamperSpec, FloatingRingSpec): n_circ x n_axial
// nodes, each range-checked and together within limits::kMaxFilmNodes, and the axial grading in [0, 1).
template <class Film>
void read_film_grid(Reader& r, Film& f) {
  f.n_circ = static_cast<int>(r.integer_or("n_circ", f.n_circ, 8, limits::kMaxFilmCirc));
  f.n_axial = static_cast<int>(r.integer_or("n_axial", f.n_axial, 4, limits::kMaxFilmAxial));
  const long nodes = static_cast<long>(f.n_circ) * f.n_axial;
  if (nodes > limits::kMaxFilmNodes)
    r.fail("n_circ", "a film grid of " + std::to_string(f.n_circ) + " x " + std::to_string(f.n_axial) + " = " +
                         std::to_string(nodes) + " nodes is more than the limit of " +
                         std::to_string(limits::kMaxFilmNodes) + " (docs/model-format.md, Limits)");
  f.axial_grading = r.quantity_or("axial_grading", dim::dimensionless, f.axial_grading, Bound::NonNegative);
  if (!(f.axial_grading >= 0.0 && f.axial_grading < 1.0))
    r.fail("axial_grading", "must be in [0, 1) (0: uniform axial nodes)");
}

// A quantity the loader derives from several keys (a disk's mass from its geometry, the viscosity at a film's
// temperature) is finite and plausible too; the message names the derivation and blames `key`.
void check_derived(Reader& r, std::string_view key, double value, const Dimension& d, const std::string& what) {
  if (const std::string why = limits::implausible(value, d); !why.empty()) r.fail(key, what + ": " + why);
}

// The oil's viscosity at a film temperature `T` (K; 0 = the [oil] temperature) must be finite and plausible: the
// Vogel equation has a pole at T = -vogel_c and grows without bound above it.
void check_viscosity(Reader& r, std::string_view key, const OilSpec& oil, double T) {
  if (oil.viscosity > 0.0 || !(T > 0.0)) return;  // a fixed viscosity, or the [oil] temperature: checked in [oil]
  std::ostringstream at, pole;
  at << T - 273.15 << " degC";
  pole << "the pole of the oil's Vogel equation ([oil] vogel_c) at " << -oil.vogel_c << " degC";
  if (T - 273.15 + oil.vogel_c <= 0.0) r.fail(key, at.str() + " lies at or below " + pole.str() + ": no viscosity there");
  const double eta = oil.viscosity_at(T);
  if (!std::isfinite(eta)) r.fail(key, "the oil's viscosity at " + at.str() + ", just above " + pole.str() + ", overflows");
  std::ostringstream what;
  what << "the oil's viscosity at " << at.str() << " (Vogel equation of [oil])";
  check_derived(r, key, eta, dim::viscosity, what.str());
}

// ----------------------------------------------------------------------------------------------- sections

Material read_material(Reader& r) {
  Material m;
  m.name = r.path().substr(r.path().find('.') + 1);
  m.youngs_modulus = r.quantity("E", dim::pressure, Bound::Positive);
  m.density = r.quantity("rho", dim::density, Bound::Positive);
  const bool has_g = r.has("G"), has_nu = r.has("nu");
  if (has_g == has_nu) r.fail_table("give exactly one of G (shear modulus) and nu (Poisson's ratio)");
  if (has_g) {
    m.shear_modulus = r.quantity("G", dim::pressure, Bound::Positive);
    m.poisson_ratio = m.youngs_modulus / (2.0 * m.shear_modulus) - 1.0;
  } else {
    m.poisson_ratio = r.quantity("nu", dim::dimensionless);
    m.shear_modulus = m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
  }
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    r.fail(has_g ? "G" : "nu", "Poisson's ratio must lie in (-1, 0.5), got " + std::to_string(m.poisson_ratio));
  r.finish();
  return m;
}

void read_disk(Reader& r, const MachineSpec& spec, DiskSpec& d) {
  d.z = r.quantity("z", dim::length);
  const bool by_mass = r.has("mass");
  const bool by_geometry = r.has("width") || r.has("outer_diameter");
  if (by_mass == by_geometry)
    r.fail_table("give either mass (with polar_inertia and diametral_inertia) or the geometry "
                 "(width, outer_diameter, inner_diameter, material)");
  if (by_mass) {
    d.mass = r.quantity("mass", dim::mass, Bound::Positive);
    d.polar_inertia = r.quantity_or("polar_inertia", dim::inertia, 0.0, Bound::NonNegative);
    d.diametral_inertia = r.quantity_or("diametral_inertia", dim::inertia, 0.0, Bound::NonNegative);
  } else {
    // Thin cylinder formulas as in Friswell et al. (2010), Example 5.9.1.
    const double w = r.quantity("width", dim::length, Bound::Positive);
    const double dout = r.quantity("outer_diameter", dim::length, Bound::Positive);
    const double din = r.quantity_or("inner_diameter", dim::length, 0.0, Bound::NonNegative);
    if (din >= dout) r.fail("inner_diameter", "must be smaller than outer_diameter");
    const std::string mat = r.text_or("material", "");
    if (mat.empty()) r.fail("material", "missing required key (the material of the disk, e.g. \"steel\")");
    const auto it = spec.materials.find(mat);
    if (it == spec.materials.end()) r.fail("material", "no material '" + mat + "' in [materials]");
    const double rho = it->second.density;
    d.mass = rho * M_PI * w * (dout * dout - din * din) / 4.0;
    d.polar_inertia = d.mass * (dout * dout + din * din) / 8.0;
    d.diametral_inertia = d.polar_inertia / 2.0 + d.mass * w * w / 12.0;
    const std::string from = "width, outer_diameter, inner_diameter and the density of '" + mat + "' give ";
    check_derived(r, "outer_diameter", d.mass, dim::mass, from + "a mass of " + std::to_string(d.mass) + " kg");
    check_derived(r, "outer_diameter", d.polar_inertia, dim::inertia, from + "a polar inertia");
    check_derived(r, "outer_diameter", d.diametral_inertia, dim::inertia, from + "a diametral inertia");
  }
  d.unbalance = r.quantity_or("unbalance", dim::unbalance, 0.0, Bound::NonNegative);
  d.unbalance_phase = r.quantity_or("unbalance_phase", dim::angle, 0.0);
  r.finish();
}

void read_linear_bearing(Reader& r, BearingSpec& b) {
  LinearBearingSpec& lin = b.linear;
  lin.speeds = r.quantity_list("speeds", dim::angular_speed, Bound::NonNegative);
  for (std::size_t i = 1; i < lin.speeds.size(); ++i)
    if (!(lin.speeds[i] > lin.speeds[i - 1])) r.fail("speeds", "speeds must be strictly increasing");
  const std::size_t n = lin.speeds.empty() ? 1 : lin.speeds.size();

  auto read_set = [&](const char* iso, const char* const names[4], const Dimension& d,
                      std::array<std::vector<double>, 4>& out) {
    const bool has_iso = r.has(iso);
    bool has_any = false;
    for (int i = 0; i < 4; ++i) has_any = has_any || r.has(names[i]);
    if (has_iso && has_any)
      r.fail(iso, std::string("give either ") + iso + " (isotropic) or the four " + names[0] + "... keys, not both");
    for (int i = 0; i < 4; ++i) {
      const bool diagonal = i == 0 || i == 3;
      const char* key = has_iso && diagonal ? iso : names[i];
      out[i] = (has_iso && !diagonal) ? std::vector<double>{} : r.quantity_list(key, d);
      if (out[i].empty()) out[i].assign(n, 0.0);
      if (out[i].size() == 1 && n > 1) out[i].assign(n, out[i][0]);
      if (out[i].size() != n)
        r.fail(key, "has " + std::to_string(out[i].size()) + " values but 'speeds' has " + std::to_string(n));
    }
  };
  static const char* const k_names[4] = {"kxx", "kxy", "kyx", "kyy"};
  static const char* const c_names[4] = {"cxx", "cxy", "cyx", "cyy"};
  read_set("k", k_names, dim::stiffness, lin.k);
  read_set("c", c_names, dim::damping, lin.c);
  for (std::size_t j = 0; j < n; ++j) {
    if (lin.k[0][j] < 0 || lin.k[3][j] < 0)
      r.fail(lin.k[0][j] < 0 ? "kxx" : "kyy", "direct stiffness must not be negative");
    if (lin.c[0][j] < 0 || lin.c[3][j] < 0)
      r.fail(lin.c[0][j] < 0 ? "cxx" : "cyy", "direct damping must not be negative");
  }
}

// The enum value a string key names, one of `names` (model-file spelling, all known to from_string); a missing key
// means `fallback`, and "" makes the key required.
template <class Enum>
Enum read_choice(Reader& r, std::string_view key, const std::vector<std::string>& names, const std::string& fallback) {
  Enum value{};
  if (!from_string(r.choice(key, names, fallback), value))
    throw std::logic_error("read_choice: '" + std::string(key) + "' has a name from_string does not know");
  return value;
}

// The optional permissible minimum film thickness of a film of radial clearance `clearance` (0: none): positive
// and thinner than the centred film, which would otherwise be below it at rest.
double read_film_thickness_limit(Reader& r, double clearance) {
  const double h = r.quantity_or("film_thickness_limit", dim::length, 0.0, Bound::Positive);
  if (h >= clearance)
    r.fail("film_thickness_limit", "is not thinner than the radial clearance: the centred film would be below it");
  return h;
}

// feed_groove_width of a film `width_value` wide (`width` names it in messages): a full circumferential groove at
// mid-width instead of the feed hole (`hole`, already read), and a supply pressure needs one of them to enter `film`.
// The groove must hold a node of the film's axial grid (`grid`, already read; the film solver's own rule).
template <class Grid>
double read_feed_groove(Reader& r, double width_value, const std::string& width, double hole, double supply,
                        const std::string& film, const Grid& grid) {
  const double groove = r.quantity_or("feed_groove_width", dim::length, 0.0, Bound::NonNegative);
  if (groove >= width_value) r.fail("feed_groove_width", "must be narrower than " + width);
  if (groove > 0.0) {
    reynolds::FilmGeometry g;
    g.radius = 1.0;  // the grid's rows depend on the width and the node counts alone
    g.length = width_value;
    g.clearance = 1e-4;
    g.n_circ = grid.n_circ;
    g.n_axial = grid.n_axial;
    g.grooves = {reynolds::Groove{0.0, groove, 0.0}};
    reynolds::SolverOptions o;
    o.axial_grading = grid.axial_grading;
    try {
      reynolds::FilmSolver check(g, 1.0, o);
    } catch (const reynolds::GrooveGridError& e) {
      r.fail("feed_groove_width", e.reason() + " (n_axial = " + std::to_string(grid.n_axial) + ")");
    }
  }
  if (groove > 0.0 && hole > 0.0)
    r.fail("feed_groove_width", "the oil enters the " + film + " through a feed hole or a feed groove: give "
                                "feed_hole_diameter or feed_groove_width, not both");
  if (supply > 0.0 && !(hole > 0.0 || groove > 0.0))
    r.fail("supply_pressure", "needs a feed hole (feed_hole_diameter) or a feed groove (feed_groove_width) to enter "
                              "the " + film);
  return groove;
}

// Keys shared by the single-film specs (JournalBearingSpec, DamperSpec); `width` names the film's length in
// messages.
template <class Film>
void read_film(Reader& r, const OilSpec& oil, Film& f, const std::string& width) {
  f.diameter = r.quantity("diameter", dim::length, Bound::Positive);
  f.length = r.quantity("length", dim::length, Bound::Positive);
  f.clearance = r.quantity("clearance", dim::length, Bound::Positive);
  if (f.clearance >= 0.05 * f.diameter)
    r.fail("clearance", "is not small against the diameter (the film model needs c << D): a unit mistake?");
  f.cavitation =
      read_choice<Cavitation>(r, "cavitation", {"gumbel", "mass-conserving", "none"}, to_string(f.cavitation));
  read_film_grid(r, f);
  f.oil_temperature = r.quantity_or("oil_temperature", dim::temperature, 0.0, Bound::Positive);
  check_viscosity(r, "oil_temperature", oil, f.oil_temperature);
  f.supply_pressure = r.quantity_or("supply_pressure", dim::pressure, 0.0, Bound::NonNegative);
  f.feed_hole_diameter = r.quantity_or("feed_hole_diameter", dim::length, 0.0, Bound::NonNegative);
  f.feed_hole_angle = r.quantity_or("feed_hole_angle", dim::angle, f.feed_hole_angle);
  if (f.feed_hole_diameter >= f.length) r.fail("feed_hole_diameter", "must be smaller than the " + width);
  f.feed_groove_width =
      read_feed_groove(r, f.length, "the " + width, f.feed_hole_diameter, f.supply_pressure, "film", f);
  const bool fed = f.feed_hole_diameter > 0.0 || f.feed_groove_width > 0.0;
  if (f.cavitation == Cavitation::MassConserving && !(fed && f.supply_pressure > 0.0))
    r.fail("cavitation", "the mass-conserving model needs an oil supply: a feed hole (feed_hole_diameter) or groove "
                         "(feed_groove_width) with supply_pressure > 0");
  f.film_thickness_limit = read_film_thickness_limit(r, f.clearance);
}

void read_journal_bearing(Reader& r, const OilSpec& oil, BearingSpec& b) { read_film(r, oil, b.journal, "bearing length"); }

void read_damper(Reader& r, const OilSpec& oil, DamperSpec& d, bool needs_ring_mass) {
  d.enabled = true;
  read_film(r, oil, d, "land width");
  if (needs_ring_mass)
    d.ring_mass = r.quantity("ring_mass", dim::mass, Bound::Positive);
  else if (r.has("ring_mass"))
    r.fail("ring_mass", "the damper's ring is the ball bearing's outer ring: give its outer_ring_mass instead");
  d.centring_stiffness = r.quantity_or("centring_stiffness", dim::stiffness, 0.0, Bound::NonNegative);
  d.end_seal_gap = r.quantity_or("end_seal_gap", dim::length, 0.0, Bound::NonNegative);
  d.end_seal_length = r.quantity_or("end_seal_length", dim::length, 0.0, Bound::NonNegative);
  if (d.end_seal_gap > 0.0 && d.end_seal_length == 0.0)
    r.fail("end_seal_gap", "an end seal needs its axial length too (end_seal_length)");
  if (d.end_seal_length > 0.0 && d.end_seal_gap == 0.0)
    r.fail("end_seal_length", "an end seal needs its radial gap too (end_seal_gap; open ends: give neither)");
  if (d.end_seal_gap > d.clearance)
    r.fail("end_seal_gap", "is larger than the damper clearance: such a seal seals nothing (open ends: give neither)");
  r.finish();
}

// The thermal keys of a floating-ring bearing (docs/thermal-films.md): thermal = "bulk" (lumped energy balances of
// both films) or "isothermal" (the films at fixed temperatures, the run-up paper's model). Without the key the films
// are bulk, unless the file fixes their viscosity (a fixed [oil] viscosity) or temperatures (inner_oil_temperature,
// outer_oil_temperature): then they are isothermal. The parameters' defaults are derived from the geometry
// (derive_ring_thermal); they are refused with isothermal films, where nothing would use them.
void read_ring_thermal(Reader& r, const OilSpec& oil, FloatingRingSpec& f) {
  RingThermalSpec& t = f.thermal;
  const bool fixed_films = oil.viscosity > 0.0 || r.has("inner_oil_temperature") || r.has("outer_oil_temperature");
  t.model = read_choice<FilmThermal>(r, "thermal", {"isothermal", "bulk"}, fixed_films ? "isothermal" : "bulk");
  const bool bulk = t.model == FilmThermal::Bulk;
  static const char* const kThermalKeys[] = {"oil_specific_heat", "oil_thermal_conductivity",
                                             "ring_thermal_conductivity", "ring_specific_heat", "shaft_temperature",
                                             "housing_temperature", "inner_shaft_conductance", "ring_conductance",
                                             "outer_housing_conductance"};
  if (!bulk) {
    for (const char* k : kThermalKeys)
      if (r.has(k)) r.fail(k, "is a parameter of thermal films: it needs thermal = \"bulk\" (isothermal films use "
                              "inner_oil_temperature and outer_oil_temperature)");
  }
  t.oil_specific_heat = r.quantity_or("oil_specific_heat", dim::specific_heat, t.oil_specific_heat, Bound::Positive);
  t.oil_thermal_conductivity =
      r.quantity_or("oil_thermal_conductivity", dim::thermal_conductivity, t.oil_thermal_conductivity, Bound::Positive);
  t.ring_thermal_conductivity = r.quantity_or("ring_thermal_conductivity", dim::thermal_conductivity,
                                              t.ring_thermal_conductivity, Bound::Positive);
  t.ring_specific_heat = r.quantity_or("ring_specific_heat", dim::specific_heat, t.ring_specific_heat, Bound::Positive);
  derive_ring_thermal(f, oil);
  t.shaft_temperature = r.quantity_or("shaft_temperature", dim::temperature, t.shaft_temperature, Bound::Positive);
  t.housing_temperature = r.quantity_or("housing_temperature", dim::temperature, t.housing_temperature, Bound::Positive);
  t.inner_shaft_conductance = r.quantity_or("inner_shaft_conductance", dim::thermal_conductance,
                                            t.inner_shaft_conductance, Bound::NonNegative);
  t.ring_conductance = r.quantity_or("ring_conductance", dim::thermal_conductance, t.ring_conductance, Bound::NonNegative);
  t.outer_housing_conductance = r.quantity_or("outer_housing_conductance", dim::thermal_conductance,
                                              t.outer_housing_conductance, Bound::NonNegative);
  if (!bulk) return;
  if (oil.viscosity > 0.0)
    r.fail("thermal", "\"bulk\" films need a viscosity that depends on temperature: remove the fixed [oil] viscosity "
                      "(the Vogel constants vogel_a, vogel_b, vogel_c give the law)");
  for (const char* k : {"inner_oil_temperature", "outer_oil_temperature"})
    if (r.has(k))
      r.fail(k, "with thermal = \"bulk\" the film temperatures are states of the run (supplied at the [oil] "
                "temperature): remove it, or use thermal = \"isothermal\"");
  auto above = [&](double T) {
    std::ostringstream os;
    os << T - 273.15 << " degC is above [oil] max_temperature = " << oil.max_temperature - 273.15
       << " degC, the highest temperature the oil's viscosity law is used at";
    return os.str();
  };
  if (t.supply_temperature >= oil.max_temperature)
    r.fail("thermal", "the supply (the [oil] temperature) at " + above(t.supply_temperature) +
                          ": the films, hotter still, would leave the viscosity law");
  for (const char* k : {"shaft_temperature", "housing_temperature"}) {
    const double T = std::string_view(k) == "shaft_temperature" ? t.shaft_temperature : t.housing_temperature;
    if (T >= oil.max_temperature) r.fail(k, above(T));
    check_viscosity(r, k, oil, T);
  }
}

void read_floating_ring(Reader& r, const OilSpec& oil, BearingSpec& b) {
  FloatingRingSpec& f = b.ring;
  f.inner_diameter = r.quantity("inner_diameter", dim::length, Bound::Positive);
  f.inner_length = r.quantity("inner_length", dim::length, Bound::Positive);
  f.inner_clearance = r.quantity("inner_clearance", dim::length, Bound::Positive);
  f.outer_diameter = r.quantity("outer_diameter", dim::length, Bound::Positive);
  f.outer_length = r.quantity("outer_length", dim::length, Bound::Positive);
  f.outer_clearance = r.quantity("outer_clearance", dim::length, Bound::Positive);
  if (f.outer_diameter <= f.inner_diameter) r.fail("outer_diameter", "must be larger than inner_diameter");
  for (const char* k : {"inner_clearance", "outer_clearance"})
    if (r.quantity(k, dim::length) >= 0.05 * f.inner_diameter)
      r.fail(k, "is not small against the diameter (the film model needs c << D): a unit mistake?");
  f.ring_mass = r.quantity("ring_mass", dim::mass, Bound::Positive);
  f.ring_polar_inertia = r.quantity("ring_polar_inertia", dim::inertia, Bound::Positive);
  f.ring_diametral_inertia = r.quantity_or("ring_diametral_inertia", dim::inertia, 0.0, Bound::Positive);
  f.ring_tilt = r.flag_or("ring_tilt", f.ring_tilt);
  f.cavitation =
      read_choice<Cavitation>(r, "cavitation", {"gumbel", "mass-conserving", "none"}, to_string(f.cavitation));
  read_film_grid(r, f);
  f.inner_oil_temperature = r.quantity_or("inner_oil_temperature", dim::temperature, 0.0, Bound::Positive);
  f.outer_oil_temperature = r.quantity_or("outer_oil_temperature", dim::temperature, 0.0, Bound::Positive);
  check_viscosity(r, "inner_oil_temperature", oil, f.inner_oil_temperature);
  check_viscosity(r, "outer_oil_temperature", oil, f.outer_oil_temperature);
  f.supply_pressure = r.quantity_or("supply_pressure", dim::pressure, 0.0, Bound::NonNegative);
  f.feed_hole_diameter = r.quantity_or("feed_hole_diameter", dim::length, 0.0, Bound::NonNegative);
  f.feed_hole_angle = r.quantity_or("feed_hole_angle", dim::angle, f.feed_hole_angle);
  if (f.feed_hole_diameter >= f.outer_length) r.fail("feed_hole_diameter", "must be smaller than outer_length");
  f.feed_groove_width =
      read_feed_groove(r, f.outer_length, "outer_length", f.feed_hole_diameter, f.supply_pressure, "outer film", f);
  f.drill_holes = static_cast<int>(r.integer_or("drill_holes", f.drill_holes, 0, limits::kMaxDrillHoles));
  f.drill_hole_diameter = r.quantity_or("drill_hole_diameter", dim::length, 0.0, Bound::NonNegative);
  f.drill_hole_angle = r.quantity_or("drill_hole_angle", dim::angle, f.drill_hole_angle);
  f.drill_hole_centrifugal = r.flag_or("drill_hole_centrifugal", f.drill_hole_centrifugal);
  if (f.drill_holes > 0 && f.drill_hole_diameter == 0.0)
    r.fail("drill_holes", "needs drill_hole_diameter");
  if (f.drill_holes == 0 && f.drill_hole_diameter > 0.0)
    r.fail("drill_hole_diameter", "given without drill_holes (the number of holes)");
  if (f.drill_hole_diameter >= f.inner_length) r.fail("drill_hole_diameter", "must be smaller than inner_length");
  if (f.drill_holes > 0 && f.drill_hole_diameter * f.drill_holes >= M_PI * f.inner_diameter)
    r.fail("drill_hole_diameter", "the drill holes overlap around the bore");
  if (f.cavitation == Cavitation::MassConserving && (f.supply_pressure == 0.0 || f.drill_holes == 0))
    r.fail("cavitation", "the mass-conserving model needs an oil supply in each film: a supply_pressure at the feed "
                         "hole or groove (outer film) and drill_holes through the ring (inner film)");
  f.film_thickness_limit = read_film_thickness_limit(r, std::min(f.inner_clearance, f.outer_clearance));
  read_ring_thermal(r, oil, f);
}

void read_ball_bearing(Reader& r, const OilSpec& oil, BearingSpec& b) {
  BallBearingSpec& s = b.ball;
  s.n_balls = static_cast<int>(r.integer_or("n_balls", s.n_balls, 3, limits::kMaxBalls));
  s.ball_diameter = r.quantity_or("ball_diameter", dim::length, s.ball_diameter, Bound::Positive);
  s.pitch_diameter = r.quantity_or("pitch_diameter", dim::length, s.pitch_diameter, Bound::Positive);
  s.inner_groove_ratio = r.quantity_or("inner_groove_ratio", dim::dimensionless, s.inner_groove_ratio, Bound::Positive);
  s.outer_groove_ratio = r.quantity_or("outer_groove_ratio", dim::dimensionless, s.outer_groove_ratio, Bound::Positive);
  s.contact_angle = r.quantity_or("contact_angle", dim::angle, s.contact_angle, Bound::NonNegative);
  const long side = r.integer_or("side", s.side, -1, 1);
  if (side != 1 && side != -1) r.fail("side", "must be 1 or -1 (the side of the outer contact, see the manual)");
  s.side = static_cast<int>(side);
  s.ball_youngs_modulus = r.quantity_or("ball_modulus", dim::pressure, s.ball_youngs_modulus, Bound::Positive);
  s.ball_poisson_ratio = r.quantity_or("ball_poisson_ratio", dim::dimensionless, s.ball_poisson_ratio, Bound::NonNegative);
  s.ball_density = r.quantity_or("ball_density", dim::density, s.ball_density, Bound::Positive);
  s.ring_youngs_modulus = r.quantity_or("ring_modulus", dim::pressure, s.ring_youngs_modulus, Bound::Positive);
  s.ring_poisson_ratio = r.quantity_or("ring_poisson_ratio", dim::dimensionless, s.ring_poisson_ratio, Bound::NonNegative);
  s.cage_mass = r.quantity_or("cage_mass", dim::mass, s.cage_mass, Bound::Positive);
  s.cage_polar_inertia = r.quantity_or("cage_polar_inertia", dim::inertia, 0.0, Bound::Positive);
  s.pocket_clearance = r.quantity_or("pocket_clearance", dim::length, s.pocket_clearance, Bound::Positive);
  s.cage_youngs_modulus = r.quantity_or("cage_modulus", dim::pressure, s.cage_youngs_modulus, Bound::Positive);
  s.cage_poisson_ratio = r.quantity_or("cage_poisson_ratio", dim::dimensionless, s.cage_poisson_ratio, Bound::NonNegative);
  s.pocket_damping = r.quantity_or("pocket_damping", dim::damping, s.pocket_damping, Bound::NonNegative);
  s.contact_damping = r.quantity_or("contact_damping", dim::damping, s.contact_damping, Bound::NonNegative);
  // The lubricant's damping of the race contacts, beta x each contact's tangent stiffness: by default the lower end
  // of Kraemer's range for lubricated rolling bearings; "0 s" leaves the paper's Eq. 21 alone (docs/ball-bearing.md).
  s.contact_damping_ratio =
      r.quantity_or("contact_damping_ratio", dim::time, kDefaultContactDampingRatio, Bound::NonNegative);
  if (!(s.contact_damping_ratio <= kMaxContactDampingRatio))
    r.fail("contact_damping_ratio", "must be at most 1e-3 s: a rolling bearing's damping is 0.25e-5 to 2.5e-5 s times "
                                    "its stiffness (Kraemer)");
  // The race contacts' Hertz law: the exact ellipse of their curvatures, or the paper's Eq. 20 with its mu*
  // (docs/ball-bearing.md, "Contacts").
  if (r.choice("hertz_law", {"ellipse", "paper"}, "ellipse") == "paper") {
    s.hertz_coefficient = r.quantity_or("hertz_coefficient", dim::dimensionless, 0.171, Bound::Positive);
    if (!(s.hertz_coefficient <= 1.0))
      r.fail("hertz_coefficient", "must lie in (0, 1]: paper Eq. 20's mu*, 1 for a sphere on a flat, less for a "
                                  "conforming groove");
  } else if (r.has("hertz_coefficient")) {
    r.fail("hertz_coefficient", "needs hertz_law = \"paper\" (paper Eq. 20's mu*)");
  }
  s.friction_static = r.quantity_or("friction_static", dim::dimensionless, s.friction_static, Bound::NonNegative);
  s.friction_sliding = r.quantity_or("friction_sliding", dim::dimensionless, s.friction_sliding, Bound::NonNegative);
  s.friction_v1 = r.quantity_or("friction_v1", dim::velocity, s.friction_v1, Bound::Positive);
  s.friction_v2 = r.quantity_or("friction_v2", dim::velocity, s.friction_v2, Bound::Positive);
  s.spin_friction = r.flag_or("spin_friction", s.spin_friction);
  s.race_traction =
      r.choice("race_traction", {"spatial", "planar"}, "spatial") == "planar" ? RaceTraction::Planar : RaceTraction::Spatial;
  // The default is the lubricated law, the one a bearing engineer defends for an oil-lubricated bearing; the paper's
  // Eq. 23 is "coulomb", which the examples name to reproduce the paper (docs/ball-bearing.md).
  s.traction_law =
      r.choice("traction_law", {"coulomb", "eyring"}, "eyring") == "eyring" ? TractionLaw::Eyring : TractionLaw::Coulomb;
  // The lubricated law's inlet viscosity: given, or the model's oil at its temperature.
  s.lubricant_viscosity = r.quantity_or("lubricant_viscosity", dim::viscosity, 0.0, Bound::Positive);
  if (s.traction_law == TractionLaw::Eyring && s.lubricant_viscosity == 0.0)
    s.lubricant_viscosity = oil.viscosity_at(oil.temperature);
  if (s.traction_law != TractionLaw::Eyring)
    for (const char* key : {"lubricant_viscosity", "pressure_viscosity", "eyring_stress", "limiting_shear_coefficient",
                            "lubricant_shear_modulus"})
      if (r.has(key)) r.fail(key, "needs traction_law = \"eyring\"");
  s.pressure_viscosity =
      r.quantity_or("pressure_viscosity", dim::dimensionless / dim::pressure, s.pressure_viscosity, Bound::NonNegative);
  s.eyring_stress = r.quantity_or("eyring_stress", dim::pressure, s.eyring_stress, Bound::Positive);
  s.limiting_shear_coefficient =
      r.quantity_or("limiting_shear_coefficient", dim::dimensionless, s.limiting_shear_coefficient, Bound::Positive);
  s.lubricant_shear_modulus =
      r.quantity_or("lubricant_shear_modulus", dim::pressure, s.lubricant_shear_modulus, Bound::Positive);
  s.preload = r.quantity_or("preload", dim::force, s.preload, Bound::NonNegative);
  s.preload_stiffness = r.quantity_or("preload_stiffness", dim::stiffness, s.preload_stiffness, Bound::NonNegative);
  s.outer_ring_mass = r.quantity_or("outer_ring_mass", dim::mass, s.outer_ring_mass, Bound::Positive);
  s.outer_ring_mode =
      r.choice("outer_ring", {"fixed", "spring"}, "fixed") == "spring" ? OuterRingMode::Spring : OuterRingMode::Fixed;
  s.outer_ring_stiffness =
      r.quantity_or("outer_ring_stiffness", dim::stiffness, s.outer_ring_stiffness, Bound::Positive);
  s.outer_ring_damping = r.quantity_or("outer_ring_damping", dim::damping, s.outer_ring_damping, Bound::NonNegative);
  if (s.outer_ring_mode == OuterRingMode::Fixed && (r.has("outer_ring_stiffness") || r.has("outer_ring_damping")))
    r.fail("outer_ring", "outer_ring_stiffness/outer_ring_damping need outer_ring = \"spring\"");
  std::string why;
  if (!s.IsValid(&why)) r.fail("type", "ball bearing: " + why);
}

void read_bearing(Reader& r, const OilSpec& oil, BearingSpec& b) {
  b.type = read_choice<BearingType>(r, "type", {"linear", "journal", "floating-ring", "ball"}, "");
  b.z = r.quantity("z", dim::length);
  switch (b.type) {
    case BearingType::Linear: read_linear_bearing(r, b); break;
    case BearingType::Journal: read_journal_bearing(r, oil, b); break;
    case BearingType::FloatingRing: read_floating_ring(r, oil, b); break;
    case BearingType::Ball: read_ball_bearing(r, oil, b); break;
  }
  if (b.type == BearingType::Linear || b.type == BearingType::Ball) {
    if (const toml::table* damper = r.table("damper")) {
      Reader d(*damper, r.key_path("damper"), r.sources());
      read_damper(d, oil, b.damper, b.type == BearingType::Linear);
    }
  }
  if (b.type == BearingType::Ball && b.damper.enabled && b.ball.outer_ring_mode == OuterRingMode::Spring)
    r.fail("outer_ring", "\"spring\" and a [damper] both hold the outer ring: choose one");
  b.pedestal_mass = r.quantity_or("pedestal_mass", dim::mass, 0.0, Bound::NonNegative);
  b.pedestal_stiffness = r.quantity_or("pedestal_stiffness", dim::stiffness, 0.0, Bound::NonNegative);
  b.pedestal_damping = r.quantity_or("pedestal_damping", dim::damping, 0.0, Bound::NonNegative);
  if (b.pedestal_mass > 0.0 && b.pedestal_stiffness <= 0.0)
    r.fail("pedestal_stiffness", "a pedestal mass needs a positive pedestal_stiffness to ground");
  if (b.pedestal_mass == 0.0 && (r.has("pedestal_stiffness") || r.has("pedestal_damping")))
    r.fail("pedestal_mass", "missing: pedestal_stiffness/pedestal_damping need a pedestal_mass");
  if (b.pedestal_mass > 0.0 && b.damper.enabled)
    r.fail("damper", "a bearing sits either on a pedestal or in a squeeze-film damper, not both");
  r.finish();
}

void read_speed(Reader& r, SpeedProfile& s) {
  const std::string profile = r.choice("profile", {"ramp", "table"}, "ramp");
  if (profile == "ramp") {
    s.kind = SpeedProfile::Kind::Ramp;
    s.start = r.quantity_or("start", dim::angular_speed, 0.0, Bound::NonNegative);
    s.end = r.quantity("end", dim::angular_speed, Bound::NonNegative);
    s.duration = r.quantity("duration", dim::time, Bound::Positive);
  } else {
    s.kind = SpeedProfile::Kind::Table;
    s.times = r.quantity_list("times", dim::time, Bound::NonNegative);
    s.speeds = r.quantity_list("speeds", dim::angular_speed, Bound::NonNegative);
    if (s.times.size() < 2) r.fail("times", "a speed table needs at least two points");
    if (s.times.size() != s.speeds.size())
      r.fail("speeds", "has " + std::to_string(s.speeds.size()) + " values but 'times' has " +
                           std::to_string(s.times.size()));
    for (std::size_t i = 1; i < s.times.size(); ++i)
      if (!(s.times[i] > s.times[i - 1])) r.fail("times", "times must be strictly increasing");
    s.start = s.speeds.front();
    s.end = s.speeds.back();
    s.duration = s.times.back();
  }
  r.finish();
}

void read_mesh(Reader& r, MeshSpec& m) {
  m.max_element_length = r.quantity_or("max_element_length", dim::length, m.max_element_length, Bound::Positive);
  m.shear_deformation = r.flag_or("shear_deformation", m.shear_deformation);
  m.rotary_inertia = r.flag_or("rotary_inertia", m.rotary_inertia);
  m.gyroscopic = r.flag_or("gyroscopic", m.gyroscopic);
  if (const toml::node* n = r.get("shear_factor")) {
    if (n->is_number()) {
      m.shear_factor_formula = ShearFactorFormula::Given;
      m.shear_factor = r.quantity("shear_factor", dim::dimensionless, Bound::Positive);
      if (m.shear_factor > 1.0) r.fail("shear_factor", "a shear factor lies in (0, 1]");
    } else {
      const std::string f = r.choice("shear_factor", {"cowper", "hutchinson"}, "cowper");
      m.shear_factor_formula = f == "cowper" ? ShearFactorFormula::Cowper : ShearFactorFormula::Hutchinson;
    }
  }
  r.finish();
}

void read_modal(Reader& r, ModalSpec& m) {
  m.speed_min = r.quantity_or("speed_min", dim::angular_speed, m.speed_min, Bound::NonNegative);
  m.speed_max = r.quantity_or("speed_max", dim::angular_speed, m.speed_max, Bound::NonNegative);
  m.n_speeds = static_cast<int>(r.integer_or("n_speeds", m.n_speeds, 2, limits::kMaxModalSpeeds));
  m.n_modes = static_cast<int>(r.integer_or("n_modes", m.n_modes, 1, limits::kMaxModes));
  if (r.has("orders")) m.orders = r.quantity_list("orders", dim::dimensionless, Bound::Positive);
  m.frequency_max = r.quantity_or("frequency_max", dim::frequency, m.frequency_max, Bound::NonNegative);
  m.mode_shape_speeds = r.quantity_list("mode_shape_speeds", dim::angular_speed, Bound::NonNegative);
  m.torsion = r.flag_or("torsion", m.torsion);
  if (r.has("speed_max") && m.speed_max <= m.speed_min) r.fail("speed_max", "must be larger than speed_min");
  r.finish();
}

MachineSpec read_machine(const toml::table& root, const Sources& src) {
  const std::string& file = src.file;
  MachineSpec spec;
  spec.source = file;
  // A study, optimisation or identification file given where a model file belongs: say so and name the command.
  struct OtherFile {
    const char *table, *kind, *command;
  };
  for (const OtherFile& o : {OtherFile{"study", "a study", "turbodyn sweep"},
                             OtherFile{"optimize", "an optimisation", "turbodyn optimize"},
                             OtherFile{"identify", "an identification", "turbodyn identify"}})
    if (root.contains(o.table) && !root.contains("materials") && !root.contains("shaft"))
      throw ModelError(file + ": this is " + o.kind + " file ([" + o.table + "]), not a model file: run it with " +
                       o.command + " " + file);
  Reader top(root, "", src);
  spec.name = top.text_or("name", std::filesystem::path(file).stem().string());
  spec.description = top.text_or("description", "");
  spec.gravity = top.quantity_or("gravity", dim::acceleration, 9.81, Bound::NonNegative);

  // Materials first: sections and disks refer to them.
  if (const toml::table* mats = top.table("materials")) {
    for (auto&& [k, v] : *mats) {
      const std::string key(k.str());
      if (!v.is_table())
        throw ModelError(where(v, src, file) + ": materials." + key + ": expected a table [materials." + key + "]");
      Reader r(*v.as_table(), "materials." + key, src);
      spec.materials[key] = read_material(r);
    }
  }
  if (spec.materials.empty()) top.fail("materials", "missing: at least one [materials.NAME] table is needed");

  const toml::array* shaft = top.array("shaft");
  if (!shaft || shaft->empty())
    top.fail("shaft", "missing: the shaft is given as [[shaft]] sections (length, outer_diameter, material)");
  double z = 0.0;
  for (std::size_t i = 0; i < shaft->size(); ++i) {
    const std::string path = "shaft[" + std::to_string(i) + "]";
    const toml::node& node = (*shaft)[i];
    if (!node.is_table()) throw ModelError(where(node, src, file) + ": " + path + ": expected a table");
    Reader r(*node.as_table(), path, src);
    ShaftSection s;
    s.length = r.quantity("length", dim::length, Bound::Positive);
    s.outer_diameter = r.quantity("outer_diameter", dim::length, Bound::Positive);
    s.inner_diameter = r.quantity_or("inner_diameter", dim::length, 0.0, Bound::NonNegative);
    if (s.inner_diameter >= s.outer_diameter) r.fail("inner_diameter", "must be smaller than outer_diameter");
    s.material = r.text_or("material", spec.materials.size() == 1 ? spec.materials.begin()->first : "");
    if (s.material.empty()) r.fail("material", "missing (several materials are defined, say which)");
    if (!spec.materials.count(s.material)) {
      std::vector<std::string> names;
      for (const auto& [n, m] : spec.materials) names.push_back(n);
      const std::string hint = closest_match(s.material, names);
      r.fail("material", "no material '" + s.material + "' in [materials]" +
                             (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
    }
    s.z_start = z;
    z += s.length;
    {
      const Material& m = spec.materials.at(s.material);
      const double mass = m.density * M_PI / 4.0 *
                          (s.outer_diameter * s.outer_diameter - s.inner_diameter * s.inner_diameter) * s.length;
      check_derived(r, "outer_diameter", mass, dim::mass, "the section's mass (from length, diameters, density)");
      const double I = M_PI / 64.0 * (std::pow(s.outer_diameter, 4) - std::pow(s.inner_diameter, 4));
      check_derived(r, "outer_diameter", m.youngs_modulus * I, dim::moment * dim::length,
                    "the section's bending stiffness E*I");
    }
    if (const std::string why = limits::implausible(z, dim::length); !why.empty())
      r.fail("length", "the shaft up to this section is " + why);
    r.finish();
    spec.shaft.push_back(s);
  }
  const double length = z;
  constexpr double kPositionTolerance = 1e-9;  // m; positions this close to the shaft ends count as on the shaft
  auto check_on_shaft = [&](Reader& r, double zpos, const std::string& what) {
    if (zpos < -kPositionTolerance || zpos > length + kPositionTolerance) {
      std::ostringstream os;
      os << what << " at z = " << zpos * 1e3 << " mm lies outside the shaft (0 to " << length * 1e3 << " mm)";
      r.fail("z", os.str());
    }
  };

  const toml::table* mesh = top.table("mesh");
  if (mesh) {
    Reader r(*mesh, "mesh", src);
    read_mesh(r, spec.mesh);
  }
  {
    // The rotor's matrices are dense (4 DOF per node): refuse a mesh beyond the limit before allocating it.
    double elements = 0.0;
    for (const ShaftSection& s : spec.shaft) elements += std::ceil(s.length / spec.mesh.max_element_length);
    if (elements > static_cast<double>(limits::kMaxShaftElements)) {
      std::ostringstream os;
      os << "the shaft of " << length << " m in elements of at most " << spec.mesh.max_element_length
         << " m needs about " << elements << " elements, more than the limit of " << limits::kMaxShaftElements
         << " (docs/model-format.md, Limits); choose a larger mesh.max_element_length";
      if (mesh) Reader(*mesh, "mesh", src).fail("max_element_length", os.str());
      top.fail("shaft", os.str());
    }
  }
  if (const toml::table* damping = top.table("damping")) {
    Reader r(*damping, "damping", src);
    spec.damping.alpha = r.quantity_or("alpha", dim::frequency, 0.0, Bound::NonNegative);
    spec.damping.beta = r.quantity_or("beta", dim::time, 0.0, Bound::NonNegative);
    r.finish();
  }
  if (const toml::table* disks = top.table("disks")) {
    for (auto&& [k, v] : *disks) {
      const std::string key(k.str());
      if (!v.is_table())
        throw ModelError(where(v, src, file) + ": disks." + key + ": expected a table [disks." + key + "]");
      Reader r(*v.as_table(), "disks." + key, src);
      DiskSpec d;
      d.name = key;
      read_disk(r, spec, d);
      check_on_shaft(r, d.z, "disk '" + key + "'");
      spec.disks.push_back(d);
    }
  }
  // [oil] before the bearings: their film temperatures are checked against its viscosity law.
  if (const toml::table* oil = top.table("oil")) {
    Reader r(*oil, "oil", src);
    OilSpec& o = spec.oil;
    o.vogel_a = r.quantity_or("vogel_a", dim::viscosity, o.vogel_a, Bound::Positive);
    o.vogel_b = r.quantity_or("vogel_b", dim::temperature, o.vogel_b, Bound::Positive);
    o.vogel_c = r.quantity_or("vogel_c", dim::temperature, o.vogel_c);
    o.viscosity = r.quantity_or("viscosity", dim::viscosity, 0.0, Bound::NonNegative);
    o.density = r.quantity_or("density", dim::density, o.density, Bound::Positive);
    o.temperature = r.quantity_or("temperature", dim::temperature, o.temperature, Bound::Positive);
    o.max_temperature = r.quantity_or("max_temperature", dim::temperature, o.max_temperature, Bound::Positive);
    if (o.max_temperature - 273.15 + o.vogel_c <= 0.0) r.fail("max_temperature", "lies below the Vogel pole T = -C");
    for (const char* key : {"vogel_b", "vogel_c"})
      if (r.has(key) && r.get(key)->is_string() && r.get(key)->value<std::string>()->find("degC") != std::string::npos)
        r.fail(key, "is a temperature difference: write it in K (or as a plain number)");
    if (o.temperature - 273.15 + o.vogel_c <= 0.0) r.fail("temperature", "lies below the Vogel pole T = -C");
    check_viscosity(r, "temperature", o, o.temperature);
    r.finish();
  }
  if (const toml::table* bearings = top.table("bearings")) {
    for (auto&& [k, v] : *bearings) {
      const std::string key(k.str());
      if (!v.is_table())
        throw ModelError(where(v, src, file) + ": bearings." + key + ": expected a table [bearings." + key +
                         "]");
      Reader r(*v.as_table(), "bearings." + key, src);
      BearingSpec b;
      b.name = key;
      read_bearing(r, spec.oil, b);
      check_on_shaft(r, b.z, "bearing '" + key + "'");
      spec.bearings.push_back(b);
    }
  }
  if (const toml::table* speed = top.table("speed")) {
    Reader r(*speed, "speed", src);
    read_speed(r, spec.speed);
  }
  if (const toml::table* solver = top.table("solver")) {
    Reader r(*solver, "solver", src);
    spec.solver.integrator = read_choice<Integrator>(r, "integrator", {"auto", "cvode-bdf", "arkode-erk"},
                                                     to_string(spec.solver.integrator));
    spec.solver.rtol = r.quantity_or("rtol", dim::dimensionless, spec.solver.rtol, Bound::Positive);
    spec.solver.atol = r.quantity_or("atol", dim::dimensionless, spec.solver.atol, Bound::Positive);
    spec.solver.atol_scaling =
        read_choice<AtolScaling>(r, "atol_scaling", {"uniform", "typical"}, to_string(spec.solver.atol_scaling));
    spec.solver.max_step = r.quantity_or("max_step", dim::time, spec.solver.max_step, Bound::NonNegative);
    spec.solver.static_start = r.flag_or("static_start", spec.solver.static_start);
    spec.solver.max_steps = r.integer_or("max_steps", spec.solver.max_steps, 1, limits::kMaxSteps);
    spec.solver.max_order = static_cast<int>(r.integer_or("max_order", spec.solver.max_order, 1, limits::kMaxBdfOrder));
    if (spec.solver.max_order > 5) r.fail("max_order", "BDF orders go from 1 to 5");
    spec.solver.newton_tolerance =
        r.quantity_or("newton_tolerance", dim::dimensionless, spec.solver.newton_tolerance, Bound::Positive);
    if (spec.solver.newton_tolerance > 1.0)
      r.fail("newton_tolerance", "a fraction of the local error test's bound, at most 1");
    if (const toml::node* n = r.get("reduction_cutoff"); n && n->is_string() && *n->value<std::string>() == "auto")
      spec.solver.reduction_cutoff = -1.0;
    else
      spec.solver.reduction_cutoff =
          r.quantity_or("reduction_cutoff", dim::frequency, spec.solver.reduction_cutoff, Bound::NonNegative);
    if (spec.solver.rtol >= 1.0) r.fail("rtol", "a relative tolerance must be below 1");
    r.finish();
  }
  if (const toml::table* output = top.table("output")) {
    Reader r(*output, "output", src);
    OutputSpec& o = spec.output;
    o.sample_rate = r.quantity_or("sample_rate", dim::frequency, o.sample_rate, Bound::Positive);
    o.csv = r.flag_or("csv", o.csv);
    o.spectrogram_segment = static_cast<int>(r.integer_or("spectrogram_segment", o.spectrogram_segment, 8, limits::kMaxSpectrogramSegment));
    o.spectrogram_overlap = r.quantity_or("spectrogram_overlap", dim::dimensionless, o.spectrogram_overlap,
                                          Bound::NonNegative);
    if (o.spectrogram_overlap >= 1.0) r.fail("spectrogram_overlap", "must be below 1");
    o.spectrogram_window = read_choice<SpectrogramWindow>(
        r, "spectrogram_window", {"hann", "hamming", "blackman", "flattop", "rectangular"},
        to_string(o.spectrogram_window));
    o.frequency_max = r.quantity_or("frequency_max", dim::frequency, o.frequency_max, Bound::NonNegative);
    o.orbit_speeds = r.quantity_list("orbit_speeds", dim::angular_speed, Bound::NonNegative);
    r.finish();
  }
  if (const toml::table* modal = top.table("modal")) {
    Reader r(*modal, "modal", src);
    read_modal(r, spec.modal);
  }
  top.finish();
  return spec;
}

MachineSpec load_parsed(toml::table root, const std::string& source_name, const std::vector<Override>& overrides) {
  Sources sources{source_name, {}};
  for (const Override& o : overrides) apply_override(root, o, &sources);
  return read_machine(root, sources);
}

}  // namespace

MachineSpec load_model(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  return load_model_from_string(input::read_text_file(file, "model file"), file.string(), overrides);
}

MachineSpec load_model_from_string(const std::string& toml_text, const std::string& source_name,
                                   const std::vector<Override>& overrides) {
  return load_parsed(input::parse_toml(toml_text, source_name), source_name, overrides);
}

std::vector<std::string> numeric_model_keys(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  return numeric_model_keys_from_string(input::read_text_file(file, "model file"), file.string(), overrides);
}

std::vector<std::string> numeric_model_keys_from_string(const std::string& toml_text, const std::string& source_name,
                                                        const std::vector<Override>& overrides) {
  std::vector<std::string> keys;
  {
    input::NumericKeyRecording recording(keys);
    (void)load_model_from_string(toml_text, source_name, overrides);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  // A plausible typo: at most a third of the word changed (at least one edit allowed).
  const std::size_t allowed = std::max<std::size_t>(1, word.size() / 3);
  return best_d <= allowed ? best : std::string();
}

// ----------------------------------------------------------------------------------------------- accepted keys

namespace {

// Tables the examples leave out: [damping] and a speed table.
constexpr const char* kKeyCoverageModel = R"(
name = "key coverage"
[materials.steel]
E = 2.1e11
rho = 7850
nu = 0.3
[[shaft]]
length = 0.1
outer_diameter = 0.01
[disks.wheel]
z = 0.05
mass = 0.1
[bearings.left]
type = "linear"
z = 0.0
k = 1e7
[bearings.right]
type = "linear"
z = 0.1
k = 1e7
[damping]
alpha = 1.0
[speed]
profile = "table"
times = [0.0, 1.0]
speeds = [0.0, 100.0]
)";

// "shaft[2].length" -> "shaft[].length"; "bearings.compressor.preload" -> "bearings.NAME[type=ball].preload".
std::string generic_key(const std::string& path, const toml::table& root) {
  std::string s;
  for (std::size_t i = 0; i < path.size(); ++i) {
    s += path[i];
    if (path[i] != '[') continue;
    std::size_t j = i + 1;
    while (j < path.size() && std::isdigit(static_cast<unsigned char>(path[j]))) ++j;
    if (j > i + 1 && j < path.size() && path[j] == ']') i = j - 1;
  }
  for (const std::string table : {"materials", "disks", "bearings"}) {
    if (s.rfind(table + ".", 0) != 0) continue;
    const std::size_t dot = s.find('.', table.size() + 1);
    if (dot == std::string::npos) break;
    const std::string name = s.substr(table.size() + 1, dot - table.size() - 1);
    const std::string rest = s.substr(dot);
    if (table != "bearings" || rest.rfind(".damper.", 0) == 0) return table + ".NAME" + rest;
    const std::string type = root["bearings"][name]["type"].value_or(std::string("?"));
    return table + ".NAME[type=" + type + "]" + rest;
  }
  return s;
}

void record_keys(const std::string& text, const std::string& source_name, std::set<std::string>& keys) {
  const toml::table root = input::parse_toml(text, source_name);
  if (!root.contains("shaft")) return;  // a study, optimisation or identification file
  std::vector<std::string> paths;
  {
    input::KeyRecording recording(paths);
    load_model_from_string(text, source_name);
  }
  for (const std::string& p : paths) keys.insert(generic_key(p, root));
}

}  // namespace

std::vector<std::string> accepted_model_keys(const std::filesystem::path& examples_dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(examples_dir))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  if (files.empty()) throw ModelError(examples_dir.string() + ": no model files (*.toml)");
  std::sort(files.begin(), files.end());
  std::set<std::string> keys;
  for (const auto& f : files) record_keys(input::read_text_file(f, "model file"), f.string(), keys);
  record_keys(kKeyCoverageModel, "accepted_model_keys (built-in)", keys);
  return {keys.begin(), keys.end()};
}

}  // namespace turbodyn

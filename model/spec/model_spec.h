// The machine as the model file describes it: plain data, SI units, validated by the loader (model_file.h).
// Nothing here is derived; the finite-element model is built from it by build_rotor() (rotor.h).
#pragma once

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "model/spec/ball_bearing_spec.h"
#include "model/spec/cavitation.h"
#include "model/spec/ring_thermal_spec.h"

namespace turbodyn {

/// Isotropic linear-elastic material.
struct Material {
  std::string name;
  double youngs_modulus = 0.0;  ///< E in Pa.
  double shear_modulus = 0.0;   ///< G in Pa (given, or E / (2(1 + nu))).
  double poisson_ratio = 0.0;   ///< nu [-] (given, or E / (2G) - 1).
  double density = 0.0;         ///< rho in kg/m^3.
};

/// A cylindrical (possibly hollow) length of shaft; sections follow each other along z from z = 0.
struct ShaftSection {
  double length = 0.0;          ///< m
  double outer_diameter = 0.0;  ///< m
  double inner_diameter = 0.0;  ///< m (0 = solid)
  std::string material;         ///< key into MachineSpec::materials
  double z_start = 0.0;         ///< m, derived from the lengths of the preceding sections
};

/// How the shaft is discretised and which beam effects are kept.
enum class ShearFactorFormula { Cowper, Hutchinson, Given };
struct MeshSpec {
  double max_element_length = 0.01;  ///< m; nodes are added so that no element is longer
  bool shear_deformation = true;     ///< Timoshenko (true) or Euler-Bernoulli (false)
  bool rotary_inertia = true;        ///< cross-section rotary inertia in M and the gyroscopic matrix
  bool gyroscopic = true;            ///< gyroscopic coupling of shaft and disks
  ShearFactorFormula shear_factor_formula = ShearFactorFormula::Cowper;
  double shear_factor = 0.0;         ///< kappa [-], used when the formula is Given
};

/// Rigid disk (wheel, collar, added mass) attached at one shaft node.
struct DiskSpec {
  std::string name;
  double z = 0.0;                ///< m, axial position (a node is placed there)
  double mass = 0.0;             ///< kg
  double polar_inertia = 0.0;    ///< Ip in kg m^2
  double diametral_inertia = 0.0;///< Id (transverse, about a diameter through the centre of mass) in kg m^2
  double unbalance = 0.0;        ///< m_u * e in kg m
  double unbalance_phase = 0.0;  ///< rad, angle of the unbalance in the rotor frame at spin angle 0
};

/// Linear bearing: force on the shaft F = -K u - C du/dt in the (x, y) plane; coefficients constant or tabulated
/// against rotor speed (linear interpolation, held constant outside the table).
struct LinearBearingSpec {
  std::vector<double> speeds;              ///< rad/s; empty for constant coefficients
  std::array<std::vector<double>, 4> k;    ///< kxx, kxy, kyx, kyy in N/m (one value, or one per speed)
  std::array<std::vector<double>, 4> c;    ///< cxx, cxy, cyx, cyy in N s/m
};

/// Lubricant: dynamic viscosity from the Vogel equation eta(T) = A exp(B / (T + C)), T in degC (Vogel 1921;
/// constants of an SAE 30 fit, docs/references.md §7), or a fixed viscosity.
struct OilSpec {
  double vogel_a = 9.722e-5;     ///< Pa s
  double vogel_b = 755.6;        ///< K (a temperature difference)
  double vogel_c = 70.56;        ///< K (a temperature difference)
  double viscosity = 0.0;        ///< Pa s; > 0 overrides the Vogel equation
  double density = 850.0;        ///< kg/m^3
  double temperature = 363.15;   ///< K
  double max_temperature = 473.15;  ///< K, highest temperature the viscosity law is used at (thermal films)
  /// Dynamic viscosity at temperature T (K), Pa s.
  double viscosity_at(double T) const;
  /// The temperature of a film that may set its own (K): `own` where it does (> 0), else the oil's.
  double temperature_or(double own) const { return own > 0.0 ? own : temperature; }
};

/// Plain hydrodynamic journal bearing: a journal (the shaft) in a fixed bush, Reynolds equation solved at every
/// call (model/films/reynolds.h).
struct JournalBearingSpec {
  double diameter = 0.0;        ///< m, journal diameter
  double length = 0.0;          ///< m, bush width
  double clearance = 0.0;       ///< m, radial clearance
  Cavitation cavitation = Cavitation::Gumbel;
  int n_circ = 60, n_axial = 12;
  double axial_grading = 0.0;   ///< film nodes drawn towards the ends (reynolds::SolverOptions::axial_grading)
  double oil_temperature = 0.0; ///< K; 0 = the [oil] temperature
  double supply_pressure = 0.0; ///< Pa gauge at the feed hole or groove
  double feed_hole_diameter = 0.0;  ///< m; 0 = no feed hole
  double feed_hole_angle = M_PI / 2;  ///< rad from +x towards +y (default: top)
  double feed_groove_width = 0.0;  ///< m, full circumferential feed groove at mid-width instead of a hole (0: none)
  double film_thickness_limit = 0.0;  ///< m, permissible minimum film thickness (0: none; min_film_probe)
};

/// Full-floating-ring bearing: a ring between the journal and the housing with two films, the ring translating,
/// tilting and spinning freely, driven by the film torques; oil supplied through a feed hole in the housing to the
/// outer film and through radial drill holes in the ring to the inner one (model/elements/floating_ring_element.h).
struct FloatingRingSpec {
  double inner_diameter = 0.0, inner_length = 0.0, inner_clearance = 0.0;  ///< m (journal diameter, width, radial)
  double outer_diameter = 0.0, outer_length = 0.0, outer_clearance = 0.0;  ///< m (ring outer diameter, ...)
  double ring_mass = 0.0;            ///< kg
  double ring_polar_inertia = 0.0;   ///< kg m^2
  double ring_diametral_inertia = 0.0;  ///< kg m^2; 0 = the thick-walled cylinder's
  bool ring_tilt = true;             ///< the ring tilts (2 DOF); false holds it aligned with the housing
  Cavitation cavitation = Cavitation::Gumbel;
  int n_circ = 60, n_axial = 12;
  double axial_grading = 0.0;   ///< film nodes drawn towards the ends (reynolds::SolverOptions::axial_grading)
  double inner_oil_temperature = 0.0, outer_oil_temperature = 0.0;  ///< K; 0 = the [oil] temperature
  double supply_pressure = 0.0;      ///< Pa gauge at the housing feed hole or groove (outer film)
  double feed_hole_diameter = 0.0;   ///< m
  double feed_hole_angle = M_PI / 2; ///< rad
  double feed_groove_width = 0.0;    ///< m, full circumferential groove in the housing bore at mid-width, fed at
                                     ///< supply_pressure, instead of the feed hole (0: none)
  int drill_holes = 0;               ///< radial holes through the ring at mid-width, evenly spaced (0-8)
  double drill_hole_diameter = 0.0;  ///< m
  double drill_hole_angle = 0.0;     ///< rad, first hole in the ring frame
  bool drill_hole_centrifugal = true;  ///< the oil column spinning in the holes lowers the inner-mouth pressure
  RingThermalSpec thermal;           ///< isothermal films (default) or bulk energy balances of both films
  double film_thickness_limit = 0.0; ///< m, permissible minimum film thickness of both films (0: none)
};

/// Nusselt number h c / k of a film to each of its walls: plane Couette flow with uniform viscous heating between
/// walls at one temperature has a parabolic profile whose mean lies q''' c^2 / (12 k) above the walls, which each
/// take q''' c / 2 (Bird, Stewart & Lightfoot, Transport Phenomena, 2nd ed. 2002, §10.4): h = 6 k / c.
inline constexpr double kFilmWallNusselt = 6.0;

/// Sets the derived parameters of f.thermal from the ring's geometry, mass and the thermal properties already in
/// f.thermal (docs/thermal-films.md): the conductances to shaft and housing (film-to-wall, kFilmWallNusselt), the
/// conductance from film to film through the ring (film, ring wall, film in series) and the heat capacities (the oil
/// in each film and half the ring each). The temperatures default to the oil's.
void derive_ring_thermal(FloatingRingSpec& f, const OilSpec& oil);

/// Squeeze-film damper around a linear bearing: the bearing's outer ring is a mass that moves in a non-rotating
/// oil film towards the housing, optionally held by a centring spring (run-up only).
struct DamperSpec {
  bool enabled = false;
  double diameter = 0.0;            ///< m, damper land diameter
  double length = 0.0;              ///< m, land width
  double clearance = 0.0;           ///< m, radial clearance
  double ring_mass = 0.0;           ///< kg, outer ring moving in the damper
  double centring_stiffness = 0.0;  ///< N/m, isotropic centring spring (0 = none)
  Cavitation cavitation = Cavitation::Gumbel;
  int n_circ = 60, n_axial = 12;
  double axial_grading = 0.0;   ///< film nodes drawn towards the ends (reynolds::SolverOptions::axial_grading)
  double oil_temperature = 0.0;     ///< K; 0 = the [oil] temperature
  double supply_pressure = 0.0;     ///< Pa gauge at the feed hole or groove
  double feed_hole_diameter = 0.0;  ///< m; 0 = none
  double feed_hole_angle = M_PI / 2;
  double feed_groove_width = 0.0;   ///< m, full circumferential feed groove at mid-width instead of a hole (0: none)
  double end_seal_gap = 0.0;        ///< m, radial gap of the end seals at both ends; 0 = open ends
  double end_seal_length = 0.0;     ///< m, axial length of the seals' gap
  double film_thickness_limit = 0.0;  ///< m, permissible minimum film thickness (0: none)
};

/// Model-file names: "linear", "journal", "floating-ring", "ball".
enum class BearingType { Linear, Journal, FloatingRing, Ball };
std::string to_string(BearingType t);
/// Sets t from its model-file name; false (t untouched) for any other name.
bool from_string(std::string_view name, BearingType& t);

struct BearingSpec {
  std::string name;
  BearingType type = BearingType::Linear;
  double z = 0.0;    ///< m
  LinearBearingSpec linear;
  JournalBearingSpec journal;
  DamperSpec damper;  ///< linear and ball bearings
  FloatingRingSpec ring;
  BallBearingSpec ball;
  double pedestal_mass = 0.0;       ///< kg; > 0 puts the bearing housing on a pedestal mass (run-up only)
  double pedestal_stiffness = 0.0;  ///< N/m, pedestal to ground
  double pedestal_damping = 0.0;    ///< N s/m, pedestal to ground
};

/// Prescribed rotor spin speed against time.
struct SpeedProfile {
  enum class Kind { Ramp, Table } kind = Kind::Ramp;
  double start = 0.0;     ///< rad/s (ramp)
  double end = 0.0;       ///< rad/s (ramp)
  double duration = 0.0;  ///< s (ramp)
  std::vector<double> times;   ///< s (table), strictly increasing
  std::vector<double> speeds;  ///< rad/s (table)
};

/// Model-file names: "auto", "cvode-bdf", "arkode-erk". Auto: the integrator measured fastest for the model's
/// bearing types (BDF for linear bearings; see bench/README.md and resolve_integrator()).
enum class Integrator { Auto, CvodeBdf, ArkodeErk };
std::string to_string(Integrator i);
/// Sets i from its model-file name; false (i untouched) for any other name.
bool from_string(std::string_view name, Integrator& i);

/// Model-file names: "uniform" (atol for every state in its own SI unit: m, m/s, rad, rad/s alike) and "typical"
/// (atol scaled by each state's typical magnitude, see SolverSpec::atol).
enum class AtolScaling { Uniform, Typical };
std::string to_string(AtolScaling a);
/// Sets a from its model-file name; false (a untouched) for any other name.
bool from_string(std::string_view name, AtolScaling& a);

/// Time-integration settings (used by `turbodyn run`).
struct SolverSpec {
  Integrator integrator = Integrator::Auto;
  double rtol = 1e-6;                    ///< relative tolerance [-]
  /// Absolute tolerance of the displacements (m). With atol_scaling Typical every other state gets atol
  /// times its typical magnitude over 1 um (velocities: 1 mm/s per um; element states as each element declares).
  double atol = 1e-9;
  AtolScaling atol_scaling = AtolScaling::Uniform;
  double max_step = 0.0;                 ///< s; 0 = no limit
  long max_steps = 50'000'000;           ///< integrator steps before the run is declared failed
  int max_order = 5;                     ///< BDF: highest order (1..5)
  /// BDF: the Newton iteration's convergence test (CVODE's nlscoef): an iterate is accepted when its estimated
  /// error is below this fraction of the local error test's bound, in (0, 1]. CVODE's default is 0.1.
  double newton_tolerance = 0.1;
  bool static_start = true;              ///< start from the static equilibrium under gravity
  /// Hz; Craig-Bampton reduction of the shaft keeping fixed-interface modes below this frequency;
  /// 0 = no reduction, < 0 = automatic (3 x the highest rotor speed frequency, at least 5 kHz).
  double reduction_cutoff = -1.0;

  /// True if every field is acceptable; otherwise *error names the first bad field and why.
  bool IsValid(std::string* error) const;
};

/// Window of the spectrograms' segments. Model-file names: "hann", "hamming", "blackman", "flattop",
/// "rectangular", the same as post/signal.h's windows.
enum class SpectrogramWindow { Hann, Hamming, Blackman, FlatTop, Rectangular };
std::string to_string(SpectrogramWindow w);
/// Sets w from its model-file name; false (w untouched) for any other name.
bool from_string(std::string_view name, SpectrogramWindow& w);

/// Output settings (used by `turbodyn run`).
struct OutputSpec {
  double sample_rate = 20000.0;      ///< samples per second of the written time series [1/s]
  bool csv = false;                  ///< also write timeseries.csv
  int spectrogram_segment = 2048;    ///< samples per STFT segment
  double spectrogram_overlap = 0.75; ///< fraction of a segment shared with the next
  SpectrogramWindow spectrogram_window = SpectrogramWindow::Hann;
  double frequency_max = 0.0;        ///< Hz, upper frequency of the spectrograms (0 = automatic)
  std::vector<double> orbit_speeds;  ///< rad/s; speeds at which orbits are drawn (empty = 4 evenly spaced)
};

/// Settings of the linear analyses (`turbodyn modal`).
struct ModalSpec {
  double speed_min = 0.0;               ///< rad/s
  double speed_max = 0.0;               ///< rad/s (0 = the end speed of the speed profile)
  int n_speeds = 31;                    ///< speeds in the Campbell diagram
  int n_modes = 8;                      ///< modes kept per speed
  std::vector<double> orders{1.0, 0.5}; ///< excitation orders drawn and intersected (1 = synchronous)
  double frequency_max = 0.0;           ///< Hz; upper frequency of the Campbell diagram (0 = automatic)
  std::vector<double> mode_shape_speeds;///< rad/s; speeds at which mode-shape pictures are drawn
  bool torsion = false;                 ///< include the free-free torsional modes
};

/// Rayleigh structural damping of the shaft and disks: D = alpha M + beta K.
struct DampingSpec {
  double alpha = 0.0;  ///< 1/s
  double beta = 0.0;   ///< s
};

struct MachineSpec {
  std::filesystem::path source;  ///< file the spec was read from
  std::string name;
  std::string description;
  std::map<std::string, Material> materials;
  std::vector<ShaftSection> shaft;
  MeshSpec mesh;
  DampingSpec damping;
  std::vector<DiskSpec> disks;
  std::vector<BearingSpec> bearings;
  double gravity = 9.81;  ///< m/s^2, acting in -y
  OilSpec oil;
  SpeedProfile speed;
  SolverSpec solver;
  OutputSpec output;
  ModalSpec modal;

  double shaft_length() const {
    return shaft.empty() ? 0.0 : shaft.back().z_start + shaft.back().length;
  }
};

}  // namespace turbodyn

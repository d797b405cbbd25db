// Lumped (bulk) energy balances of a floating ring's two films (docs/thermal-films.md). Each film is one
// well-mixed thermal node at its effective temperature, which sets its viscosity:
//
//   C_i dT_i/dt = P_i - rho c_p Q_i (T_i - T_in,i) - G_s (T_i - T_shaft) - G_r (T_i - T_o),
//   C_o dT_o/dt = P_o - rho c_p (Q_o + Q_d) (T_o - T_supply) + G_r (T_i - T_o) - G_h (T_o - T_housing),
//
// P the power the film dissipates (W), Q_i, Q_o the side leakage of each film (m^3/s, the oil that leaves it), Q_d
// the oil the drill holes take from the outer film to replace Q_i (Q_i with drill holes, else 0), T_in,i the
// temperature it arrives with (T_o with drill holes; without, the inner film draws oil at the supply temperature at
// its ends), G the conductances (W/K) and C the heat capacities (J/K) of RingThermalSpec. Adding both lines:
//
//   C_i dT_i/dt + C_o dT_o/dt = P_i + P_o - rho c_p (Q_i (T_i - T_supply) + Q_o (T_o - T_supply))
//                                        - G_s (T_i - T_shaft) - G_h (T_o - T_housing),
//
// the bearing's heat balance: dissipated = carried off by the oil + conducted to shaft and housing + stored.
#pragma once

#include "model/spec/ring_thermal_spec.h"

namespace turbodyn::thermal {

/// What the two films do at one instant (SI).
struct FilmHeatInputs {
  double inner_power = 0.0, outer_power = 0.0;  ///< W dissipated in each film
  double inner_flow = 0.0, outer_flow = 0.0;    ///< m^3/s side leakage of each film (negative values count as 0)
  double inner_temperature = 0.0, outer_temperature = 0.0;  ///< K
};

/// The heat flows of the balance above (W) and the temperature rates (K/s).
struct FilmHeatFlows {
  double inner_oil = 0.0;  ///< rho c_p Q_i (T_i - T_in,i): heat the inner film's oil carries off over its inlet
  double outer_oil = 0.0;  ///< rho c_p (Q_o + Q_d) (T_o - T_supply)
  double shaft = 0.0;      ///< G_s (T_i - T_shaft), into the shaft
  double housing = 0.0;    ///< G_h (T_o - T_housing), into the housing
  double ring = 0.0;       ///< G_r (T_i - T_o), from the inner film through the ring into the outer film
  double inner_rate = 0.0, outer_rate = 0.0;  ///< dT_i/dt, dT_o/dt in K/s
  /// Heat leaving the bearing by oil, rho c_p (Q_i (T_i - T_supply) + Q_o (T_o - T_supply)) (= inner_oil + outer_oil).
  double oil() const { return inner_oil + outer_oil; }
  /// Heat leaving the bearing by conduction (shaft + housing).
  double conducted() const { return shaft + housing; }
};

/// The balance of both films. `density` in kg/m^3; `drill_holes`: the inner film is fed from the outer one.
/// Allocation-free.
FilmHeatFlows film_heat_balance(const RingThermalSpec& t, double density, bool drill_holes, const FilmHeatInputs& in);

/// Thermal energy stored in the two nodes above the supply temperature, C_i (T_i - T_s) + C_o (T_o - T_s) (J).
double stored_heat(const RingThermalSpec& t, double inner_temperature, double outer_temperature);

}  // namespace turbodyn::thermal

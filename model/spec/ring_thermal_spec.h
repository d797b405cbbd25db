// The thermal model of a floating-ring bearing's two films (docs/thermal-films.md): isothermal films at fixed
// temperatures (the paper's model, the default) or lumped (bulk) energy balances of each film whose temperatures
// are states of the run.
#pragma once

#include <string>
#include <string_view>

namespace turbodyn {

/// Model-file names: "isothermal", "bulk".
enum class FilmThermal { Isothermal, Bulk };
std::string to_string(FilmThermal t);
/// Sets t from its model-file name; false (t untouched) for any other name.
bool from_string(std::string_view name, FilmThermal& t);

/// Heat-transfer parameters of a floating ring's films, SI units. The loader fills every value (defaults derived
/// from the geometry as docs/thermal-films.md states), so that the element and the reports use the same numbers.
struct RingThermalSpec {
  FilmThermal model = FilmThermal::Isothermal;
  double supply_temperature = 0.0;   ///< K, oil at the housing's feed hole (the [oil] temperature)
  double shaft_temperature = 0.0;    ///< K, journal surface (a boundary condition: the turbine heats the shaft)
  double housing_temperature = 0.0;  ///< K, housing bore
  double oil_specific_heat = 2000.0;        ///< c_p in J/(kg K)
  double oil_thermal_conductivity = 0.13;   ///< k in W/(m K)
  double ring_thermal_conductivity = 110.0; ///< W/(m K) (brass)
  double ring_specific_heat = 380.0;        ///< J/(kg K) (brass)
  /// Conductances (W/K, >= 0): inner film to the shaft, inner film to the outer film through the ring, outer film
  /// to the housing.
  double inner_shaft_conductance = 0.0, ring_conductance = 0.0, outer_housing_conductance = 0.0;
  /// Heat capacities of the two thermal nodes (J/K, > 0): the oil in each film and half the ring each.
  double inner_heat_capacity = 0.0, outer_heat_capacity = 0.0;
  double max_temperature = 473.15;  ///< K, upper end of the viscosity law ([oil] max_temperature)
};

}  // namespace turbodyn

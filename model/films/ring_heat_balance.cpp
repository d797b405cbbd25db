#include "model/films/ring_heat_balance.h"

#include <algorithm>

namespace turbodyn::thermal {

FilmHeatFlows film_heat_balance(const RingThermalSpec& t, double density, bool drill_holes, const FilmHeatInputs& in) {
  const double rc = density * t.oil_specific_heat;
  const double qi = std::max(in.inner_flow, 0.0), qo = std::max(in.outer_flow, 0.0);
  const double ti = in.inner_temperature, to = in.outer_temperature, ts = t.supply_temperature;
  FilmHeatFlows h;
  h.inner_oil = rc * qi * (ti - (drill_holes ? to : ts));
  h.outer_oil = rc * ((drill_holes ? qi : 0.0) + qo) * (to - ts);
  h.shaft = t.inner_shaft_conductance * (ti - t.shaft_temperature);
  h.housing = t.outer_housing_conductance * (to - t.housing_temperature);
  h.ring = t.ring_conductance * (ti - to);
  h.inner_rate = (in.inner_power - h.inner_oil - h.shaft - h.ring) / t.inner_heat_capacity;
  h.outer_rate = (in.outer_power - h.outer_oil + h.ring - h.housing) / t.outer_heat_capacity;
  return h;
}

double stored_heat(const RingThermalSpec& t, double inner_temperature, double outer_temperature) {
  return t.inner_heat_capacity * (inner_temperature - t.supply_temperature) +
         t.outer_heat_capacity * (outer_temperature - t.supply_temperature);
}

}  // namespace turbodyn::thermal

#include "model/films/film_linearisation.h"

#include <cmath>
#include <stdexcept>

namespace turbodyn::reynolds {

Linearisation linearise(FilmSolver& film, const FilmState& s) {
  Linearisation l;
  auto solve = [&](const FilmState& st, FilmResult& r) {
    if (!film.solve(st, r)) throw std::runtime_error("film linearisation: " + film.last_error());
  };
  solve(s, l.at);
  const double c = film.geometry().clearance;
  const double dx = 1e-4 * c;
  const double dv = 1e-4 * c * std::max(std::abs(s.omega_inner + s.omega_outer), 1.0);
  // Central differences of the force in each coordinate: columns of K from the position (ex, ey), of C from the
  // velocity (vx, vy).
  struct Column {
    double FilmState::*coordinate;
    double step;
    Eigen::Matrix2d* matrix;
    int j;
  };
  const Column columns[] = {{&FilmState::ex, dx, &l.K, 0}, {&FilmState::vx, dv, &l.C, 0},
                            {&FilmState::ey, dx, &l.K, 1}, {&FilmState::vy, dv, &l.C, 1}};
  FilmResult p, m;
  for (const Column& col : columns) {
    FilmState sp = s, sm = s;
    sp.*col.coordinate += col.step;
    sm.*col.coordinate -= col.step;
    solve(sp, p);
    solve(sm, m);
    (*col.matrix)(0, col.j) = -(p.fx - m.fx) / (2 * col.step);
    (*col.matrix)(1, col.j) = -(p.fy - m.fy) / (2 * col.step);
  }
  return l;
}

}  // namespace turbodyn::reynolds

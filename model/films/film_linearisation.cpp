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
  FilmResult p, m;
  for (int j = 0; j < 2; ++j) {
    FilmState sp = s, sm = s;
    (j == 0 ? sp.ex : sp.ey) += dx;
    (j == 0 ? sm.ex : sm.ey) -= dx;
    solve(sp, p);
    solve(sm, m);
    l.K(0, j) = -(p.fx - m.fx) / (2 * dx);
    l.K(1, j) = -(p.fy - m.fy) / (2 * dx);
    sp = s;
    sm = s;
    (j == 0 ? sp.vx : sp.vy) += dv;
    (j == 0 ? sm.vx : sm.vy) -= dv;
    solve(sp, p);
    solve(sm, m);
    l.C(0, j) = -(p.fx - m.fx) / (2 * dv);
    l.C(1, j) = -(p.fy - m.fy) / (2 * dv);
  }
  return l;
}

}  // namespace turbodyn::reynolds

// Accuracy of a film grid: forces, moments and torques of the reference floating ring's two films on coarser grids
// against a fine grid, over states of the kind a run-up visits (issue 19: a cheaper film must first show its
// accuracy). Not a timing benchmark; it prints tables.
//
//   build/bench/film_grid_accuracy [--damper] [--grading B] [--reference NCIRC NAXIAL] [NCIRC NAXIAL ...]
//   (default grids: 36 8  48 8  48 10  64 14  96 16; default reference 192 40)
//
// --grading B: the coarse grids' axial nodes drawn towards the ends (SolverOptions::axial_grading; the reference
// stays uniform). --reference: the grid the others are measured against, e.g. the examples' 48 x 10 to measure what
// a cheaper grid changes against today's default rather than against the converged film.
//
// Films (examples/reference_floating_ring.toml): inner Ø 10 × 7 mm, c = 15 µm, four Ø 2 mm drill holes at mid-width
// at 2 bar; outer Ø 16 × 10 mm, c = 40 µm, a Ø 3 mm feed hole at the top at 4.5 bar; 10.8 mPa s; journal (inner)
// 10,000 rad/s with the ring at 0.3 of it, the ring (outer film's journal) at 3,000 rad/s in a still housing.
// States: eccentricity ratios 0.3, 0.6, 0.8, 0.9, 0.95 at 8 attitude angles; without tilt, or tilted so that the
// eccentricity at one end is 1.5x (and at the other 0.5x) that at mid-width, in two directions; without squeeze, or
// with a radial velocity of 0.05 c omega and a forward whirl at 0.45 omega; Gumbel and mass-conserving cavitation.
// --damper: instead, the squeeze-film damper of examples/reference_ball_sfd.toml (Ø 20.5 × 6 mm, c = 51 µm, a Ø 2 mm
// feed hole at the top at 4 bar, no spin, no tilt): eccentricity ratios 0.3, 0.6, 0.8, 0.9, 0.95, 0.98 at 8
// attitude angles, each with no motion (the feed hole's pressure alone), a radial velocity of 0.05 c Omega outwards,
// a forward whirl at Omega, and that whirl with 0.05 c Omega inwards; Omega = 2 pi 1000 Hz.
// Reference: the same film on 192 x 40 nodes (or --reference). For each grid and film the table gives, over the states, the largest
// and the rms deviation of the force vector |dF|, of the moment vector (tilted states) and of the journal's friction
// torque, each relative to the largest value of the reference among the states of the same eccentricity ratio.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "model/films/reynolds.h"
#include "model/spec/constants.h"

namespace {

using namespace turbodyn::reynolds;
using turbodyn::kPi;

constexpr double kEta = 0.0108, kOmega = 10000.0;

struct Film {
  const char* name;
  FilmGeometry g;
  double omega_inner, omega_outer;
};

// A film of radius R, width L and clearance c on an nc x na grid, with its holes and surface speeds.
Film make_film(const char* name, double R, double L, double c, std::vector<Hole> holes, double w_inner, double w_outer,
               int nc, int na) {
  Film f{name, {}, w_inner, w_outer};
  f.g.radius = R;
  f.g.length = L;
  f.g.clearance = c;
  f.g.holes = std::move(holes);
  f.g.n_circ = nc;
  f.g.n_axial = na;
  return f;
}

Film inner_film(int nc, int na) {
  std::vector<Hole> holes;
  for (int k = 0; k < 4; ++k) holes.push_back(Hole{0.5 * kPi * k, 0.0, 0.002, 2e5});
  return make_film("inner", 0.005, 0.007, 15e-6, holes, kOmega, 0.3 * kOmega, nc, na);
}

Film outer_film(int nc, int na) {
  return make_film("outer", 0.008, 0.010, 40e-6, {Hole{0.5 * kPi, 0.0, 0.003, 4.5e5}}, 0.3 * kOmega, 0.0, nc, na);
}

Film damper_film(int nc, int na) {
  return make_film("damper", 0.01025, 0.006, 51e-6, {Hole{0.5 * kPi, 0.0, 0.002, 4e5}}, 0.0, 0.0, nc, na);
}

constexpr double kDamperWhirl = 2.0 * kPi * 1000.0;
const std::vector<double> kFilmEps = {0.3, 0.6, 0.8, 0.9, 0.95};
const std::vector<double> kDamperEps = {0.3, 0.6, 0.8, 0.9, 0.95, 0.98};

// The journal at eccentricity e in direction phi, moving radially at vr and whirling at whirl about the centre.
FilmState state_at(double e, double phi, double vr, double whirl) {
  FilmState s;
  s.ex = e * std::cos(phi);
  s.ey = e * std::sin(phi);
  s.vx = vr * std::cos(phi) - whirl * s.ey;
  s.vy = vr * std::sin(phi) + whirl * s.ex;
  return s;
}

std::vector<FilmState> damper_states(const Film& f) {
  std::vector<FilmState> out;
  const double c = f.g.clearance;
  for (double eps : kDamperEps)
    for (int a = 0; a < 8; ++a)
      for (int motion = 0; motion < 4; ++motion) {
        const double phi = 2.0 * kPi * (a + 0.25) / 8.0;
        const double vr = motion == 1 ? 0.05 * c * kDamperWhirl : motion == 3 ? -0.05 * c * kDamperWhirl : 0.0;
        out.push_back(state_at(eps * c, phi, vr, motion >= 2 ? kDamperWhirl : 0.0));
      }
  return out;
}

std::vector<FilmState> states(const Film& f) {
  std::vector<FilmState> out;
  const double c = f.g.clearance, L = f.g.length;
  for (double eps : kFilmEps)
    for (int a = 0; a < 8; ++a)
      for (int tilt = 0; tilt < 3; ++tilt)
        for (int squeeze = 0; squeeze < 2; ++squeeze) {
          const double phi = 2.0 * kPi * (a + 0.25) / 8.0, e = eps * c;
          const double vr = squeeze ? 0.05 * c * f.omega_inner : 0.0, whirl = squeeze ? 0.45 * f.omega_inner : 0.0;
          FilmState s = state_at(e, phi, vr, whirl);
          if (tilt > 0) {
            // End eccentricity 1.5x / 0.5x that at mid-width along the eccentricity (tilt 1), or a tilt across it
            // of the same size, limited so that the film stays open (|e_end| <= 0.97 c).
            const double slope = std::min(0.5 * e, 0.97 * c - e > 0 ? 0.97 * c - e : 0.0) / (0.5 * L);
            const double dir = tilt == 1 ? phi : phi + 0.5 * kPi;
            s.sx = slope * std::cos(dir);
            s.sy = slope * std::sin(dir);
          }
          s.omega_inner = f.omega_inner;
          s.omega_outer = f.omega_outer;
          out.push_back(s);
        }
  return out;
}

struct Stats {
  double max = 0, sum2 = 0;
  int n = 0;
  void add(double v) {
    max = std::max(max, v);
    sum2 += v * v;
    ++n;
  }
  double rms() const { return n ? std::sqrt(sum2 / n) : 0.0; }
};

std::vector<FilmResult> solve_all(const Film& f, Cavitation cav, const std::vector<FilmState>& ss,
                                  double grading = 0.0) {
  SolverOptions o;
  o.cavitation = cav;
  o.axial_grading = grading;
  FilmSolver solver(f.g, kEta, o);
  std::vector<FilmResult> out(ss.size());
  for (std::size_t k = 0; k < ss.size(); ++k) {
    solver.reset_warm_start();
    if (!solver.solve(ss[k], out[k])) {
      std::fprintf(stderr, "%s film, %d x %d: state %zu: %s\n", f.name, f.g.n_circ, f.g.n_axial, k,
                   solver.last_error().c_str());
      std::exit(1);
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::pair<int, int>> grids = {{36, 8}, {48, 8}, {48, 10}, {64, 14}, {96, 16}};
  double grading = 0.0;  // of the coarse grids (the reference is uniform)
  int first = 1, ref_nc = 192, ref_na = 40;
  bool damper = false;
  for (;;) {
    if (argc > first && std::string(argv[first]) == "--damper") {
      damper = true;
      ++first;
    } else if (argc > first + 1 && std::string(argv[first]) == "--grading") {
      grading = std::atof(argv[first + 1]);
      first += 2;
    } else if (argc > first + 2 && std::string(argv[first]) == "--reference") {
      ref_nc = std::atoi(argv[first + 1]);
      ref_na = std::atoi(argv[first + 2]);
      first += 3;
    } else {
      break;
    }
  }
  if (ref_nc < 8 || ref_na < 4) {
    std::fprintf(stderr, "film_grid_accuracy: the reference grid needs at least 8 x 4 nodes\n");
    return 2;
  }
  if (argc > first) {
    grids.clear();
    for (int k = first; k + 1 < argc; k += 2) grids.emplace_back(std::atoi(argv[k]), std::atoi(argv[k + 1]));
  }
  if (grading != 0.0) std::printf("coarse grids graded towards the ends, axial_grading = %g\n", grading);
  std::printf("deviation from %d x %d relative to the largest reference value at the same eccentricity: largest / rms "
              "over the states\n",
              ref_nc, ref_na);
  std::printf("%-6s %-16s %-8s %-19s %-19s %-19s\n", "film", "cavitation", "grid", "force", "moment (tilted)",
              "torque");
  const auto film = [&](int which, int nc, int na) {
    return which == 0 ? inner_film(nc, na) : which == 1 ? outer_film(nc, na) : damper_film(nc, na);
  };
  const std::vector<int> films = damper ? std::vector<int>{2} : std::vector<int>{0, 1};
  for (int which : films)
    for (Cavitation cav : {Cavitation::Gumbel, Cavitation::MassConserving}) {
      // Without surface speeds nothing carries oil into a cavitated zone, so the mass-conserving damper film is
      // the Gumbel one (the same numbers); only the Gumbel rows are printed for it.
      if (which == 2 && cav == Cavitation::MassConserving) continue;
      const Film fine = film(which, ref_nc, ref_na);
      const std::vector<FilmState> ss = which == 2 ? damper_states(fine) : states(fine);
      const std::vector<FilmResult> ref = solve_all(fine, cav, ss);
      for (const auto& [nc, na] : grids) {
        const Film f = film(which, nc, na);
        const std::vector<FilmResult> r = solve_all(f, cav, ss, grading);
        // Scales: the largest force, moment and torque of the reference at the state's eccentricity ratio (40
        // states each), so that states whose force nearly cancels (a whirl near half the mean speed) are measured
        // against the film's load at that eccentricity, not against their own small force.
        const std::size_t per_eps = ss.size() / (which == 2 ? kDamperEps.size() : kFilmEps.size());
        Stats force, moment, torque;
        std::vector<double> force_by_eps(ss.size() / per_eps, 0.0);
        for (std::size_t k = 0; k < ss.size(); ++k) {
          double fs = 0, ms = 0, ts = 0;
          for (std::size_t q = k / per_eps * per_eps; q < (k / per_eps + 1) * per_eps; ++q) {
            fs = std::max(fs, std::hypot(ref[q].fx, ref[q].fy));
            ms = std::max(ms, std::hypot(ref[q].mx, ref[q].my));
            ts = std::max(ts, std::abs(ref[q].torque_inner));
          }
          const double df = std::hypot(r[k].fx - ref[k].fx, r[k].fy - ref[k].fy) / fs;
          force.add(df);
          force_by_eps[k / per_eps] = std::max(force_by_eps[k / per_eps], df);
          if (ss[k].sx != 0.0 || ss[k].sy != 0.0) moment.add(std::hypot(r[k].mx - ref[k].mx, r[k].my - ref[k].my) / ms);
          if (ts > 0.0) torque.add(std::abs(r[k].torque_inner - ref[k].torque_inner) / ts);
        }
        std::printf("%-6s %-16s %3d x %-3d %7.2f %% %7.2f %%  %7.2f %% %7.2f %%  %7.2f %% %7.2f %%\n", fine.name,
                    cav == Cavitation::Gumbel ? "gumbel" : "mass-conserving", nc, na, 100 * force.max,
                    100 * force.rms(), 100 * moment.max, 100 * moment.rms(), 100 * torque.max, 100 * torque.rms());
        if (which == 2) {  // the damper: the largest force deviation at each eccentricity ratio
          std::printf("         largest force deviation by eccentricity ratio:");
          for (std::size_t e = 0; e < force_by_eps.size(); ++e)
            std::printf("  %.2f: %.2f %%", kDamperEps[e], 100 * force_by_eps[e]);
          std::printf("\n");
        }
      }
    }
}

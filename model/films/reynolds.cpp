#include "model/films/reynolds.h"

#include "model/films/bordered_band_ldlt.h"
#include "model/films/byte_flag.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include "model/spec/constants.h"

namespace turbodyn::reynolds {

namespace {

bool finite_state(const FilmState& s) {
  const double v[] = {s.ex, s.ey, s.vx, s.vy, s.sx, s.sy, s.dsx, s.dsy, s.omega_inner, s.omega_outer};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  if (s.use_override)
    for (double x : s.hole_pressure_override)
      if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

Closed short_bearing(double eta, double omega, double R, double L, double c, double eps) {
  if (!(eps >= 0.0 && eps < 1.0)) throw std::invalid_argument("short_bearing: eccentricity ratio must be in [0, 1)");
  const double q = 1.0 - eps * eps;
  const double aw = std::abs(omega);
  return {eta * aw * R * L * L * L * eps * eps / (c * c * q * q),
          kPi * eta * omega * R * L * L * L * eps / (4.0 * c * c * std::pow(q, 1.5))};
}

Closed long_bearing(double eta, double omega, double R, double L, double c, double eps) {
  if (!(eps >= 0.0 && eps < 1.0)) throw std::invalid_argument("long_bearing: eccentricity ratio must be in [0, 1)");
  const double q = 1.0 - eps * eps;
  const double aw = std::abs(omega);
  return {12.0 * eta * aw * R * R * R * L * eps * eps / (c * c * (2.0 + eps * eps) * q),
          6.0 * kPi * eta * omega * R * R * R * L * eps / (c * c * (2.0 + eps * eps) * std::sqrt(q))};
}

// Node states of the cavitation models (full film; cavitated: p = p_cav, and for the mass-conserving model a film
// fraction theta < 1; fallback of the mass-conserving model: p = p_cav, theta = 1, Swift-Stieber condition).
constexpr std::uint8_t kFull = 0, kCav = 1, kFallback = 2;

struct FilmSolver::Impl {
  FilmGeometry g;
  double eta = 0;
  SolverOptions o;
  int n = 0, nz = 0, nzf = 0;  // circumferential nodes, axial nodes, axial faces (nz + 1)
  double dth = 0, dx = 0, dz = 0;  // dz: the uniform grid's axial step L / (n_axial + 1)
  // Axial grid (uniform, or graded towards the ends, SolverOptions::axial_grading; axial_grid()): per node the
  // control volume's width wz, which is also the loads' quadrature weight (the trapezoidal rule in the mapped
  // coordinate), per face the distance dzf it conducts over, and the mapped step at the ends (hend, = dz when
  // uniform) for the loads' end terms.
  // The Couette shear (1/h, not zero at the ends) is summed over the cells' widths in z, wc (zf[j + 1] - zf[j]),
  // and the end strips, which add up to the film's width exactly (Petroff's torque exact on any grid).
  std::vector<double> wz, dzf, wc;
  double hend = 0;
  double seal_conductance = 0;  // m^3/(Pa s) per grid column of an end seal's slot (0: open ends)
  std::vector<double> th, ct, st, cte, ste, zn, zf;  // node angles, cos/sin at nodes and east faces, z nodes/faces
  std::vector<int> iwest, ieast;                     // neighbouring columns (periodic)
  // Dirichlet nodes (full grid): kind -1 free, h >= 0 hole h, -2 - k groove k.
  std::vector<int> kind, dir_nodes;
  bool mask_symmetric = false;

  // Per call, full grid (i * nz + j; faces i * nzf + jf).
  std::vector<double> hN, hE, aE, aF, cE, sq, dval;
  std::vector<double> h_col, he_col;  // an untilted film's thickness per column at the nodes and east faces
  std::vector<double> row_coef;       // geometry_arrays' per-row (per-face) coefficients, 7 arrays of nzf
  std::vector<double> end_slope_lo, end_slope_hi;  // per column, dp/dz at z = -L/2, +L/2 (outputs, open ends)
  std::vector<char> plain_column;                  // per column: no hole or groove node (fixed by the geometry)
  std::vector<double> p, theta, ff;  // pressure, film content used in fluxes, film fraction for output
  std::vector<ByteFlag> cav;     // node states of the last solve (kFull, kCav, kFallback): the warm start
  bool warm = false;
  bool forces_only = false;  // outputs(): the loads only (set_forces_only)
  // The full-grid fields p, theta, cav, ff do not hold the last solve's solution: outputs() read it from the
  // reduced fields pr, thr, cr (layout m, sym), which the next solve's warm start and the accessors expand when
  // they need it (ensure_fields).
  bool fields_stale = false;
  // The band holds the factorisation of the last successful None or Gumbel solve, for the cavitated set in cr and
  // the film thickness of (ex, ey, sx, sy) = factored_at (solve_same_matrix).
  bool factored = false;
  double factored_at[4] = {0, 0, 0, 0};

  // Reduced grid (i * m + j, j < m): the unknowns actually solved for.
  int m = 0;
  bool sym = false;
  double w_last = 1.0;  // row weight of the last reduced row (1/2 for the mid-width row when nz is odd)
  std::vector<double> Cw, Ce, Cs, Cn, Dg, FE, SQ, b0, pr, thr;
  std::vector<double> pr0, res;  // the factorisation's own solution (solve_linearised) and a residual
  std::vector<ByteFlag> dirr, cr, fr;
  std::vector<int> colcount, border_j;
  int i0 = 0, last_col = 0, na = 0;
  // Mass-conserving model: cavitated nodes feeding a full node, and GMRES storage.
  static constexpr int kGmresRestart = 40;
  std::vector<int> feed;
  int nfeed = 0;
  std::vector<double> gm_x, gm_f, gm_t, gm_v, gm_h, gm_g, gm_y, gm_cs, gm_sn;
  std::vector<int> mk_node, mk_up, mk_kw, mk_ke, mk_ks, mk_kn;
  std::vector<double> mk_alpha, mk_invden, mk_const;
  int mk_count = 0;
  bool mk_generic = false;
  static constexpr int kMaxSwitches = 6;
  std::vector<ByteFlag> switches;  // per cell and call
  BorderedBandLdlt band;
  double U = 0, pcav = 0, pamb = 0;
  double pscale = 1, fscale = 1;
  double amax = 0;  // largest diagonal of the couplings (reduced_system)
  // The thickness-dependent arrays (hN, hE, aE, aF, the couplings, dirr, amax) hold the thickness of the
  // factorisation (factored_at): solve() and solve_same_matrix() set it, solve_linearised() (it fills them for
  // another thickness) and set_viscosity() (aE, aF depend on it) clear it.
  bool thickness_current = false;
  // Faces between a free node and a hole or groove node, with the factor of their conductance (fitted_holes): east
  // faces by the full-grid node index k, axial faces by i * nzf + jf.
  std::vector<std::pair<int, double>> fit_east, fit_axial;
  int iterations = 0, solves = 0;
  std::string err;

  Impl(const FilmGeometry& geo, double viscosity, const SolverOptions& opt) : g(geo), eta(viscosity), o(opt) {
    auto bad = [](const std::string& what) { throw std::invalid_argument("reynolds::FilmSolver: " + what); };
    if (!(g.radius > 0.0) || !std::isfinite(g.radius)) bad("radius must be > 0");
    if (!(g.length > 0.0) || !std::isfinite(g.length)) bad("length must be > 0");
    if (!(g.clearance > 0.0) || !std::isfinite(g.clearance)) bad("clearance must be > 0");
    if (!(eta > 0.0) || !std::isfinite(eta)) bad("viscosity must be > 0");
    if (g.n_circ < 8 || g.n_axial < 4)
      bad("grid must be at least 8 x 4 (n_circ x n_axial), got " + std::to_string(g.n_circ) + " x " +
          std::to_string(g.n_axial));
    if (!std::isfinite(g.ambient_pressure) || !std::isfinite(g.cavitation_pressure))
      bad("ambient and cavitation pressures must be finite");
    if (g.holes.size() > 8) bad("at most 8 holes (FilmState::hole_pressure_override has 8 entries)");
    if (!(o.tolerance > 0.0) || o.tolerance >= 1.0) bad("tolerance must be in (0, 1)");
    if (o.max_iterations < 1) bad("max_iterations must be >= 1");
    if (!(o.axial_grading >= 0.0 && o.axial_grading < 1.0)) bad("axial_grading must be in [0, 1)");
    n = g.n_circ;
    nz = g.n_axial;
    nzf = nz + 1;
    dth = kTwoPi / n;
    dx = g.radius * dth;
    dz = g.length / (nz + 1);
    if (!(g.end_seal_gap >= 0.0) || !std::isfinite(g.end_seal_gap)) bad("end_seal_gap must be >= 0");
    if (g.end_seal_gap > 0.0) {
      if (!(g.end_seal_length > 0.0) || !std::isfinite(g.end_seal_length))
        bad("an end seal needs end_seal_length > 0");
      const double gap = g.end_seal_gap;
      seal_conductance = dx * gap * gap * gap / (12.0 * eta * g.end_seal_length);
    }
    th.resize(n);
    end_slope_lo.assign(n, 0.0);
    end_slope_hi.assign(n, 0.0);
    plain_column.assign(n, 1);
    ct.resize(n);
    st.resize(n);
    cte.resize(n);
    ste.resize(n);
    for (int i = 0; i < n; ++i) {
      th[i] = i * dth;
      ct[i] = std::cos(th[i]);
      st[i] = std::sin(th[i]);
      cte[i] = std::cos(th[i] + 0.5 * dth);
      ste[i] = std::sin(th[i] + 0.5 * dth);
    }
    iwest.resize(n);
    ieast.resize(n);
    for (int i = 0; i < n; ++i) {
      iwest[i] = (i + n - 1) % n;
      ieast[i] = (i + 1) % n;
    }
    axial_grid();

    const int N = n * nz;
    kind.assign(N, -1);
    const double half = 0.5 * g.length * (1.0 + 1e-12);
    // For the refusals below: how a groove is named, and how far apart the axial rows about a place z lie.
    auto groove_label = [&](std::size_t k) {
      std::ostringstream os;
      os << (g.grooves.size() == 1 ? "the groove" : "groove " + std::to_string(k)) << " (" << g.grooves[k].width * 1e3
         << " mm wide at z = " << g.grooves[k].z * 1e3 << " mm)";
      return os.str();
    };
    auto rows_apart = [&](double z) {
      int below = -1;
      for (int j = 0; j < nz; ++j)
        if (zn[j] < z) below = j;
      return below < 0 ? zn[0] + half : below + 1 < nz ? zn[below + 1] - zn[below] : half - zn[nz - 1];
    };
    for (std::size_t k = 0; k < g.grooves.size(); ++k) {
      const Groove& gr = g.grooves[k];
      if (!(gr.width > 0.0) || !std::isfinite(gr.z) || !std::isfinite(gr.pressure))
        bad("groove " + std::to_string(k) + ": width must be > 0 and position and pressure finite");
      if (std::abs(gr.z) + 0.5 * gr.width > half)
        bad("groove " + std::to_string(k) + " is not inside the film (|z| + width/2 > L/2)");
      bool any = false;
      for (int j = 0; j < nz; ++j) {
        if (std::abs(zn[j] - gr.z) <= 0.5 * gr.width) {
          any = true;
          for (int i = 0; i < n; ++i) kind[i * nz + j] = -2 - static_cast<int>(k);
        }
      }
      if (!any) {
        // Fixing a row outside the groove would put the supply pressure on the land (an even grid's two middle rows
        // about a narrow central groove: 10 % less squeeze damping with 12 rows). Refused, with the way out.
        std::ostringstream why;
        why << groove_label(k) << " holds no node of the axial grid, whose nodes lie " << rows_apart(gr.z) * 1e3
            << " mm apart there: more axial nodes, or for a groove at mid-width an odd number of them (a node at "
               "its centre)";
        throw GrooveGridError(why.str());
      }
    }
    // Each land beside a groove, to the film's end or to the next groove, must hold a row: else the groove's outer
    // row conducts to the end over the grid's step instead of the land, and the land's pressure, load and side flow
    // are not resolved (a groove 0.4 mm from the end of a film whose rows lie 0.64 mm apart). A groove over every
    // row (a central groove nearly as wide as the film) leaves no film at all and fails here too.
    for (std::size_t k = 0; k < g.grooves.size(); ++k) {
      const Groove& gr = g.grooves[k];
      for (const int side : {-1, 1}) {
        const double edge = gr.z + side * 0.5 * gr.width;
        double far = side * 0.5 * g.length;  // the land's other side: the film's end or the next groove's near edge
        std::size_t next = g.grooves.size();
        for (std::size_t q = 0; q < g.grooves.size(); ++q) {
          const double near_edge = g.grooves[q].z - side * 0.5 * g.grooves[q].width;
          if (q != k && side * (near_edge - edge) >= 0.0 && side * (far - near_edge) > 0.0) {
            far = near_edge;
            next = q;
          }
        }
        bool held = false;
        for (int j = 0; j < nz; ++j)
          held = held || (kind[j] == -1 && side * (zn[j] - edge) > 0.0 && side * (far - zn[j]) > 0.0);
        if (held) continue;
        std::ostringstream why;
        why << groove_label(k) << " leaves no land with a node of the axial grid between it and ";
        if (next < g.grooves.size())
          why << "groove " << next;
        else
          why << "the film's end at z = " << far * 1e3 << " mm";
        why << " (a land of " << std::abs(far - edge) * 1e3 << " mm, nodes " << rows_apart(edge) * 1e3
            << " mm apart there): a narrower groove, one further from the end, or more axial nodes";
        throw GrooveGridError(why.str());
      }
    }
    std::vector<char> caught(g.holes.size(), 0);  // the hole's circle holds a node (else its nearest node stands in)
    for (std::size_t h = 0; h < g.holes.size(); ++h) {
      const Hole& ho = g.holes[h];
      if (!(ho.diameter > 0.0) || !std::isfinite(ho.theta) || !std::isfinite(ho.z) || !std::isfinite(ho.pressure))
        bad("hole " + std::to_string(h) + ": diameter must be > 0 and position and pressure finite");
      if (std::abs(ho.z) + 0.5 * ho.diameter > half)
        bad("hole " + std::to_string(h) + " is not inside the film (|z| + diameter/2 > L/2)");
      if (ho.diameter >= kTwoPi * g.radius) bad("hole " + std::to_string(h) + " is wider than the circumference");
      const double r2 = 0.25 * ho.diameter * ho.diameter;
      int nearest = -1;
      double best = std::numeric_limits<double>::infinity();
      bool any = false;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < nz; ++j) {
          const auto [ddx, ddz] = from_hole_centre(ho, i, j);
          const double d2 = ddx * ddx + ddz * ddz;
          const int k = i * nz + j;
          if (d2 < best) {
            best = d2;
            nearest = k;
          }
          if (d2 <= r2) {
            if (kind[k] != -1) bad("hole " + std::to_string(h) + " overlaps another hole or a groove");
            kind[k] = static_cast<int>(h);
            any = true;
          }
        }
      if (!any) {
        if (kind[nearest] != -1) bad("hole " + std::to_string(h) + " overlaps another hole or a groove");
        kind[nearest] = static_cast<int>(h);
      }
      caught[h] = any;
    }
    if (o.fitted_holes) fit_hole_faces(caught);
    mask_symmetric = true;
    for (int k = 0; k < N; ++k) {
      if (kind[k] != -1) {
        dir_nodes.push_back(k);
        plain_column[k / nz] = 0;
      }
      const int i = k / nz, j = k % nz;
      if (kind[k] != kind[i * nz + (nz - 1 - j)]) {
        // Different holes at mirrored nodes are fine if their pressures agree (checked per call).
        if ((kind[k] == -1) != (kind[i * nz + (nz - 1 - j)] == -1)) mask_symmetric = false;
      }
    }

    hN.assign(N, 0.0);
    hE.assign(N, 0.0);
    h_col.assign(n, 0.0);
    he_col.assign(n, 0.0);
    row_coef.assign(7 * static_cast<std::size_t>(nzf), 0.0);
    aE.assign(N, 0.0);
    cE.assign(N, 0.0);
    sq.assign(N, 0.0);
    dval.assign(N, 0.0);
    aF.assign(n * nzf, 0.0);
    p.assign(N, g.ambient_pressure);
    theta.assign(N, 1.0);
    ff.assign(N, 1.0);
    cav.assign(N, 0);
    for (auto* v : {&Cw, &Ce, &Cs, &Cn, &Dg, &FE, &SQ, &b0, &thr}) v->assign(N, 0.0);
    dirr.assign(N, 0);
    cr.assign(N, 0);
    fr.assign(N, 0);
    colcount.assign(n, 0);
    border_j.assign(nz, -1);
    band.reserve(N, nz);
    feed.assign(N, 0);
    switches.assign(N, 0);
    for (auto* v : {&mk_node, &mk_up, &mk_kw, &mk_ke, &mk_ks, &mk_kn}) v->assign(N, 0);
    for (auto* v : {&mk_alpha, &mk_invden, &mk_const}) v->assign(N, 0.0);
    pr.assign(N + 1, 0.0);  // + sentinel
    pr0.assign(N + 1, 0.0);
    res.assign(N, 0.0);
    for (auto* v : {&gm_x, &gm_f, &gm_t}) v->assign(N, 0.0);
    gm_v.assign(static_cast<std::size_t>(kGmresRestart + 1) * N, 0.0);
    gm_h.assign((kGmresRestart + 1) * (kGmresRestart + 1), 0.0);
    for (auto* v : {&gm_g, &gm_y, &gm_cs, &gm_sn}) v->assign(kGmresRestart + 1, 0.0);
  }

  // The axial nodes z = (L/2) G(xi) at uniformly spaced xi = -1 + 2 (j + 1) / (n_axial + 1), with
  // G(xi) = (1 - b) xi + b sin(pi xi / 2): b = 0 is the uniform grid, b > 0 draws the nodes towards both ends (the
  // spacing there is (1 - b) times, at mid-width (1 - b + b pi / 2) times the uniform step). The equation is
  // discretised in xi, where the grid is uniform: faces at the half steps of xi, control volumes and face distances
  // dz/dxi times the step of xi (the transformed equation d/dxi (k / z' dp/dxi) z'... in conservation form), so the
  // scheme and the loads' end terms keep their uniform-grid form. From half-integer multiples of the step: exactly
  // antisymmetric about mid-width (mirrored holes find mirrored nodes).
  void axial_grid() {
    const double b = o.axial_grading, half = 0.5 * g.length, dxi = 2.0 / (nz + 1);
    auto z_at = [&](double k) {  // k: node index counted from mid-width (half-integers for even counts)
      const double xi = k * dxi;
      return half * ((1.0 - b) * xi + b * std::sin(0.5 * kPi * xi));
    };
    auto dz_dxi = [&](double k) { return half * ((1.0 - b) + b * 0.5 * kPi * std::cos(0.5 * kPi * k * dxi)); };
    zn.resize(nz);
    zf.resize(nzf);
    wz.resize(nz);
    dzf.resize(nzf);
    wc.resize(nz);
    const double mid = 0.5 * (nz + 1);
    for (int j = 0; j < nz; ++j) {
      zn[j] = b == 0.0 ? (j + 1 - mid) * dz : z_at(j + 1 - mid);
      wz[j] = b == 0.0 ? dz : dz_dxi(j + 1 - mid) * dxi;
    }
    for (int jf = 0; jf < nzf; ++jf) {
      zf[jf] = b == 0.0 ? (jf + 0.5 - mid) * dz : z_at(jf + 0.5 - mid);
      dzf[jf] = b == 0.0 ? dz : dz_dxi(jf + 0.5 - mid) * dxi;
    }
    hend = b == 0.0 ? dz : dz_dxi(mid) * dxi;
    for (int j = 0; j < nz; ++j) wc[j] = b == 0.0 ? dz : zf[j + 1] - zf[j];
  }

  // ---- per-call set-up -------------------------------------------------------------------------------------------

  // Fills the half j >= j_first of each full-grid field (n x nz) with its mirror image about mid-width.
  template <class... Fields>
  void mirror_axially(int j_first, Fields&... fields) const {
    for (int i = 0; i < n; ++i)
      for (int j = j_first; j < nz; ++j) {
        const int k = i * nz + j, km = i * nz + (nz - 1 - j);
        ((fields[k] = fields[km]), ...);
      }
  }

  bool symmetric_values() const {
    for (int k : dir_nodes) {
      const int i = k / nz, j = k % nz;
      if (dval[k] != dval[i * nz + (nz - 1 - j)]) return false;
    }
    return true;
  }

  // Node (i, j) from the centre of hole `ho` on the unrolled surface (m): circumferential (shortest way round) and
  // axial.
  std::pair<double, double> from_hole_centre(const Hole& ho, int i, int j) const {
    return {g.radius * std::remainder(th[i] - ho.theta, kTwoPi), zn[j] - ho.z};
  }

  // Shortley-Weller faces at the holes' edges. Along the grid line through a free node and its neighbour inside a
  // hole, the circle is crossed at distance delta from the free node (0 < delta <= step); the face then conducts
  // step / delta times its grid value, as if the hole's pressure sat on the circle. Holes that caught no node
  // inside their circle (`caught`; smaller than a cell: their nearest node) keep the grid faces.
  void fit_hole_faces(const std::vector<char>& caught) {
    auto factor = [&](int free_k, int hole_k, bool east) {
      const int h = kind[hole_k];
      if (!caught[h]) return 1.0;
      const Hole& ho = g.holes[h];
      const double a = 0.5 * ho.diameter;
      const auto [ux, uz] = from_hole_centre(ho, free_k / nz, free_k % nz);
      const int jf = std::max(free_k % nz, hole_k % nz);  // the axial face between the two (east: unused)
      const double across = east ? uz : ux, along = east ? ux : uz, step = east ? dx : dzf[jf];
      if (std::abs(across) >= a) return 1.0;
      const double delta = std::abs(along) - std::sqrt(a * a - across * across);
      return step / std::clamp(delta, 0.05 * step, step);
    };
    // A groove's edges, z = z_g -+ width/2, lie on no grid line in general: the axial face from a free node to a
    // groove row conducts over the node's distance to the edge, which lies between the two (a groove holds a row).
    auto groove_factor = [&](int free_k, int groove_k) {
      const Groove& gr = g.grooves[-2 - kind[groove_k]];
      const int jf = std::max(free_k % nz, groove_k % nz);
      const double step = dzf[jf], delta = std::abs(zn[free_k % nz] - gr.z) - 0.5 * gr.width;
      return step / std::clamp(delta, 0.05 * step, step);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < nz; ++j) {
        const int k = i * nz + j, ke = ((i + 1) % n) * nz + j;
        const bool hk = kind[k] >= 0, he = kind[ke] >= 0;
        if (hk != he) fit_east.push_back({k, hk ? factor(ke, k, true) : factor(k, ke, true)});
        if (j + 1 < nz) {
          const bool hn = kind[k + 1] >= 0;
          if (hk != hn) fit_axial.push_back({i * nzf + j + 1, hk ? factor(k + 1, k, false) : factor(k, k + 1, false)});
          const bool gk = kind[k] <= -2, gn = kind[k + 1] <= -2;
          if (gk && kind[k + 1] == -1) fit_axial.push_back({i * nzf + j + 1, groove_factor(k + 1, k)});
          if (gn && kind[k] == -1) fit_axial.push_back({i * nzf + j + 1, groove_factor(k, k + 1)});
        }
      }
  }

  // rates_only: the thickness is that of the last call (thickness_current), so only the Couette and squeeze
  // terms (speeds, velocities) are computed anew, by the same formulas as the full loop below (kept fused there:
  // a separate rates pass after the thickness cost about 1 % of variant I's window).
  void geometry_arrays(const FilmState& s, bool rates_only = false) {
    const double c = g.clearance;
    const int jn = sym ? m : nz;  // rows computed (the rest mirrored)
    if (rates_only) {
      for (int j = 0; j < jn; ++j) {
        const double z = zn[j];
        const double couette = 0.5 * U * wz[j], area = dx * wz[j];
        const double vxz = s.vx + z * s.dsx, vyz = s.vy + z * s.dsy;
        for (int i = 0; i < n; ++i) {
          const int k = i * nz + j;
          cE[k] = couette * hE[k];
          sq[k] = -(vxz * ct[i] + vyz * st[i]) * area;
        }
      }
      if (sym && !forces_only) mirror_axially(jn, cE, sq);
      return;
    }
    // Untilted (every damper, a journal that does not tilt): the thickness is the same in every axial row, so it
    // is computed once per column (the same values: exz = ex + z * 0 = ex).
    const bool untilted = s.sx == 0.0 && s.sy == 0.0;
    if (untilted) {
      for (int i = 0; i < n; ++i) {
        h_col[i] = c - s.ex * ct[i] - s.ey * st[i];
        he_col[i] = c - s.ex * cte[i] - s.ey * ste[i];
      }
    }
    // Per axial row (and face) the coefficients, then the nodes column by column: the node arrays are stored
    // axial-fastest, so the inner loops run over contiguous memory (the same values as row by row).
    double* __restrict rexz = row_coef.data();
    double* __restrict reyz = rexz + nzf;
    double* __restrict rkx = reyz + nzf;
    double* __restrict rcou = rkx + nzf;
    double* __restrict rarea = rcou + nzf;
    double* __restrict rvxz = rarea + nzf;
    double* __restrict rvyz = rvxz + nzf;
    for (int j = 0; j < jn; ++j) {
      const double z = zn[j];
      rkx[j] = wz[j] / (12.0 * eta * dx);
      rcou[j] = 0.5 * U * wz[j];
      rarea[j] = dx * wz[j];
      rexz[j] = s.ex + z * s.sx;
      reyz[j] = s.ey + z * s.sy;
      rvxz[j] = s.vx + z * s.dsx;
      rvyz[j] = s.vy + z * s.dsy;
    }
    {
      double* __restrict hN_ = hN.data();
      double* __restrict hE_ = hE.data();
      double* __restrict aE_ = aE.data();
      double* __restrict cE_ = cE.data();
      double* __restrict sq_ = sq.data();
      for (int i = 0; i < n; ++i) {
        const double cti = ct[i], sti = st[i], ctei = cte[i], stei = ste[i];
        const double hc = h_col[i], hec = he_col[i];
        const int k0 = i * nz;
        for (int j = 0; j < jn; ++j) {
          const double h = untilted ? hc : c - rexz[j] * cti - reyz[j] * sti;
          const double he = untilted ? hec : c - rexz[j] * ctei - reyz[j] * stei;
          hN_[k0 + j] = h;
          hE_[k0 + j] = he;
          aE_[k0 + j] = rkx[j] * he * he * he;
          cE_[k0 + j] = rcou[j] * he;
          sq_[k0 + j] = -(rvxz[j] * cti + rvyz[j] * sti) * rarea[j];
        }
      }
    }
    const int jfn = sym ? m + 1 : nzf;
    // Faces: rexz, reyz now hold the faces' eccentricities, rkx their conductance factors.
    for (int jf = 0; jf < jfn; ++jf) {
      const double z = zf[jf];
      rexz[jf] = s.ex + z * s.sx;
      reyz[jf] = s.ey + z * s.sy;
      rkx[jf] = dx / (12.0 * eta * dzf[jf]);
    }
    {
      double* __restrict aF_ = aF.data();
      const double seal = seal_conductance;
      for (int i = 0; i < n; ++i) {
        const double cti = ct[i], sti = st[i], hc = h_col[i];
        double* aFi = aF_ + i * nzf;
        for (int jf = 0; jf < jfn; ++jf) {
          const double h = untilted ? hc : c - rexz[jf] * cti - reyz[jf] * sti;
          aFi[jf] = rkx[jf] * h * h * h;
        }
        if (seal > 0.0) {
          // An end face with a seal: the land's last half cell and the seal's slot in series.
          aFi[0] = aFi[0] * seal / (aFi[0] + seal);
          if (jfn == nzf) aFi[nzf - 1] = aFi[nzf - 1] * seal / (aFi[nzf - 1] + seal);
        }
      }
    }
    // The mirrored half of the node arrays is read only by the full outputs (torques, flows); the loads alone
    // read the reduced system, i.e. the rows j < m and the faces, which are all mirrored (a seal's far end face).
    const bool node_mirror = sym && !forces_only;
    if (sym) {
      if (node_mirror) mirror_axially(jn, hN, hE, aE, cE, sq);
      for (int i = 0; i < n; ++i)
        for (int jf = jfn; jf < nzf; ++jf) aF[i * nzf + jf] = aF[i * nzf + nz - jf];
    }
    const int rows_written = node_mirror ? nz : jn;  // jn = nz without symmetry
    for (const auto& [k, f] : fit_east)
      if (k % nz < rows_written) aE[k] *= f;
    for (const auto& [kf, f] : fit_axial) aF[kf] *= f;
  }

  // Coefficients of the reduced system: per node west/east/south/north couplings, diagonal, Couette flux through
  // the east face for a full film (FE), squeeze volume rate (SQ), and the full-film source with the end terms (b0).
  // rates_only: the couplings (Cw, Ce, Cs, Cn, Dg) and their largest diagonal are those of the last call, only the
  // sources are new (geometry_arrays(s, true)).
  void reduced_system(bool rates_only = false) {
    // Local pointers (restrict: the arrays are distinct) and a local running maximum, so that the stores into the
    // arrays do not make the compiler reload the vectors' data pointers and the maximum at every node.
    double* __restrict cw_ = Cw.data();
    double* __restrict ce_ = Ce.data();
    double* __restrict cs_ = Cs.data();
    double* __restrict cn_ = Cn.data();
    double* __restrict dg_ = Dg.data();
    double* __restrict fe_ = FE.data();
    double* __restrict sq_ = SQ.data();
    double* __restrict b0_ = b0.data();
    ByteFlag* __restrict dirr_ = dirr.data();
    const double* __restrict aE_ = aE.data();
    const double* __restrict aF_ = aF.data();
    const double* __restrict cE_ = cE.data();
    const double* __restrict sqf_ = sq.data();
    const int* __restrict kind_ = kind.data();
    const int* __restrict iwest_ = iwest.data();
    double fmax = 0.0, dmax = rates_only ? amax : 0.0;
    const int last = sym ? m - 1 : -1;
    for (int i = 0; i < n; ++i) {
      const int iw = iwest_[i];
      const double* aEi = aE_ + i * nz;
      const double* aEw = aE_ + iw * nz;
      const double* aFi = aF_ + i * nzf;
      const double* cEi = cE_ + i * nz;
      const double* sqi = sqf_ + i * nz;
      const int* kindi = kind_ + i * nz;
      const int kr0 = i * m;
      if (!rates_only)
        for (int j = 0; j < m; ++j) {
          const int kr = kr0 + j;
          const double w = j == last ? w_last : 1.0;
          const double cw = w * aEw[j], ce = w * aEi[j], cs = aFi[j], cn = j == last ? 0.0 : aFi[j + 1];
          cw_[kr] = cw;
          ce_[kr] = ce;
          cs_[kr] = cs;
          cn_[kr] = cn;
          const double dg = cw + ce + cs + cn;
          dg_[kr] = dg;
          dmax = std::max(dmax, dg);
          dirr_[kr] = kindi[j] != -1;
        }
      for (int j = 0; j < m; ++j) {
        const int kr = kr0 + j;
        const double w = j == last ? w_last : 1.0;
        const double fe = w * cEi[j], sqk = w * sqi[j];
        fe_[kr] = fe;
        sq_[kr] = sqk;
        fmax = std::max(fmax, std::abs(fe) + std::abs(sqk));
      }
    }
    amax = dmax;
    for (int k : dir_nodes) {
      const int i = k / nz, j = k % nz;
      if (j < m) pr[i * m + j] = dval[k];
    }
    double bmax = 0.0;
    for (int i = 0; i < n; ++i) {
      const int iw = iwest_[i];
      const int kr0 = i * m, kw0 = iw * m;
      for (int j = 0; j < m; ++j) {
        const int kr = kr0 + j;
        const double b = -(fe_[kr] - fe_[kw0 + j]) - sq_[kr];
        b0_[kr] = b;
        bmax = std::max(bmax, std::abs(b));
      }
      b0_[kr0] += cs_[kr0] * pamb;
      if (!sym) b0_[kr0 + m - 1] += cn_[kr0 + m - 1] * pamb;
    }
    // Add the couplings to hole and groove nodes (fixed for the whole call) to the source of their neighbours.
    for (int k : dir_nodes) {
      const int i = k / nz, j = k % nz;
      if (j >= m) continue;
      const double v = dval[k];
      const int kr = i * m + j, kw = iwest_[i] * m + j, ke = ieast[i] * m + j;
      b0_[kw] += ce_[kw] * v;
      b0_[ke] += cw_[ke] * v;
      if (j > 0) b0_[kr - 1] += cn_[kr - 1] * v;
      if (j + 1 < m) b0_[kr + 1] += cs_[kr + 1] * v;
    }
    // Scales for the sign tests: pressure from the Dirichlet data (refined after the first solve), flux from the
    // sources and the couplings.
    double pd = std::abs(pamb - pcav);
    for (int k : dir_nodes) pd = std::max(pd, std::abs(dval[k] - pcav));
    pscale = std::max(pd, std::numeric_limits<double>::min());
    fscale = std::max({fmax, bmax, amax * pd, std::numeric_limits<double>::min()});
  }

  // ---- linear algebra on the reduced grid ------------------------------------------------------------------------

  // Factorises the system restricted to the free nodes (fr[kr] = 1); other nodes keep their value in pr.
  bool factor_free() {
    const ByteFlag* __restrict fr_ = fr.data();
    int* __restrict colcount_ = colcount.data();
    int best = 0;
    for (int i = 0; i < n; ++i) {
      int c = 0;
      for (int j = 0; j < m; ++j) c += fr_[i * m + j];
      colcount_[i] = c;
      if (c < colcount_[best]) best = i;
    }
    last_col = best;
    i0 = (best + 1) % n;
    na = 0;
    for (int j = 0; j < m; ++j) border_j[j] = fr_[last_col * m + j] ? na++ : -1;
    const int N1 = (n - 1) * m;
    band.reset(N1, m, na);
    const double* __restrict dg_ = Dg.data();
    const double* __restrict cn_ = Cn.data();
    const double* __restrict ce_ = Ce.data();
    const double* __restrict cw_ = Cw.data();
    double* __restrict bcol = band.column(0);
    ByteFlag* __restrict bfix = band.fixed_flags();
    const int stride = m + 1;
    for (int q = 0; q < n - 1; ++q) {
      const int i = i0 + q < n ? i0 + q : i0 + q - n, ie = i + 1 < n ? i + 1 : 0;
      for (int j = 0; j < m; ++j) {
        const int r = q * m + j, kr = i * m + j;
        double* col = bcol + static_cast<std::ptrdiff_t>(r) * stride;
        if (!fr_[kr]) {
          col[0] = 1.0;
          bfix[r] = 1;
          continue;
        }
        bfix[r] = 0;
        col[0] = dg_[kr];
        if (j + 1 < m && fr_[kr + 1]) col[1] = -cn_[kr];
        if (q + 1 < n - 1) {
          if (fr_[ie * m + j]) col[m] = -ce_[kr];
        } else if (border_j[j] >= 0) {
          band.border(r, border_j[j]) = -ce_[kr];
        }
        if (q == 0 && border_j[j] >= 0) band.border(r, border_j[j]) += -cw_[kr];
      }
    }
    for (int j = 0; j < m; ++j) {
      const int a = border_j[j];
      if (a < 0) continue;
      const int kr = last_col * m + j;
      band.corner(a, a) = Dg[kr];
      if (j + 1 < m && border_j[j + 1] >= 0) band.corner(border_j[j + 1], a) = -Cn[kr];
    }
    ++iterations;
    return band.factor();
  }

  // Couplings of free node kr to its cavitated neighbours (held at p_cav), times p_cav: zero for p_cav = 0.
  double cavitated_couplings(int i, int j, int kr) const {
    if (pcav == 0.0) return 0.0;
    const int kw = iwest[i] * m + j, ke = ieast[i] * m + j;
    double c = 0.0;
    if (cr[kw]) c += Cw[kr];
    if (cr[ke]) c += Ce[kr];
    if (j > 0 && cr[kr - 1]) c += Cs[kr];
    if (j + 1 < m && cr[kr + 1]) c += Cn[kr];
    return c * pcav;
  }

  // Solves for the free nodes (fr) with rhs(i, j, kr) the complete right-hand side of free node kr = i m + j
  // (sources and couplings to fixed nodes). Writes the solution into pr.
  template <class Rhs>
  void solve_free(Rhs rhs) {
    const int nn = n, mm = m, i00 = i0;
    const ByteFlag* fr_ = fr.data();
    const int* bj = border_j.data();
    {
      double* __restrict y = band.rhs();
      double* __restrict ya = band.rhs_border();
      for (int q = 0; q < nn; ++q) {
        const int i = q + i00 < nn ? q + i00 : q + i00 - nn;
        const int kr0 = i * mm;
        if (q < nn - 1) {
          double* yq = y + q * mm;
          for (int j = 0; j < mm; ++j) yq[j] = fr_[kr0 + j] ? rhs(i, j, kr0 + j) : 0.0;
        } else {
          for (int j = 0; j < mm; ++j)
            if (bj[j] >= 0) ya[bj[j]] = rhs(i, j, kr0 + j);
        }
      }
    }
    band.solve();
    ++solves;
    const double* __restrict y = band.rhs();
    const double* __restrict ya = band.rhs_border();
    double* __restrict pr_ = pr.data();
    for (int q = 0; q < nn; ++q) {
      const int i = q + i00 < nn ? q + i00 : q + i00 - nn;
      const int kr0 = i * mm;
      for (int j = 0; j < mm; ++j) {
        const int kr = kr0 + j;
        if (!fr_[kr]) continue;
        pr_[kr] = q < nn - 1 ? y[q * mm + j] : ya[bj[j]];
      }
    }
  }

  // Net volume outflow of the control volume of reduced node kr with the current pr (and thr for the
  // mass-conserving model): the residual (A p - b)_kr, the Lagrange multiplier of the Swift-Stieber problem.
  double outflow(int i, int j, bool jfo) const {
    const int kr = i * m + j;
    const int kw = iwest[i] * m + j, ke = ieast[i] * m + j;
    const double pk = pr[kr];
    const double ps = j > 0 ? pr[kr - 1] : pamb;
    const double pn = j + 1 < m ? pr[kr + 1] : pamb;  // sym: Cn = 0 on the last row
    double q = Cw[kr] * (pk - pr[kw]) + Ce[kr] * (pk - pr[ke]) + Cs[kr] * (pk - ps) + Cn[kr] * (pk - pn);
    if (!jfo) return q + FE[kr] - FE[kw] + SQ[kr];
    const double te = U >= 0.0 ? thr[kr] : thr[ke], tw = U >= 0.0 ? thr[kw] : thr[kr];
    return q + te * FE[kr] - tw * FE[kw] + thr[kr] * SQ[kr];
  }

  void update_pscale() {
    double pm = std::abs(pamb - pcav);
    for (int kr = 0; kr < n * m; ++kr) pm = std::max(pm, std::abs(pr[kr] - pcav));
    pscale = std::max(pm, std::numeric_limits<double>::min());
  }

  // ---- models ----------------------------------------------------------------------------------------------------

  bool solve_none() {
    for (int kr = 0; kr < n * m; ++kr) fr[kr] = !dirr[kr];
    if (!factor_free()) return fail("factorisation failed (matrix not positive definite)");
    solve_free([&](int, int, int kr) { return b0[kr]; });  // no cavitated nodes
    return true;
  }

  // Swift-Stieber conditions as the complementarity problem p >= p_cav, A p - b >= 0, (p - p_cav)(A p - b) = 0,
  // solved by the primal-dual active-set method (Hintermueller, Ito & Kunisch 2002), warm-started from the last
  // cavitated set.
  bool solve_gumbel() {
    const double tol = o.tolerance;
    const int nm = n * m;
    // Local pointers: the flag stores would otherwise make the compiler reload every array's data pointer (restrict
    // for the arrays nothing else writes during the call).
    const ByteFlag* __restrict dirr_ = dirr.data();
    ByteFlag* cr_ = cr.data();
    ByteFlag* fr_ = fr.data();
    double* pr_ = pr.data();
    const double* __restrict b0_ = b0.data();
    const double* __restrict cw_ = Cw.data();
    const double* __restrict ce_ = Ce.data();
    const double* __restrict cs_ = Cs.data();
    const double* __restrict cn_ = Cn.data();
    const double* __restrict fe_ = FE.data();
    const double* __restrict sq_ = SQ.data();
    const int* __restrict iwest_ = iwest.data();
    const int* __restrict ieast_ = ieast.data();
    for (int kr = 0; kr < nm; ++kr) {
      if (dirr_[kr]) cr_[kr] = 0;
      if (cr_[kr]) pr_[kr] = pcav;
    }
    for (int it = 0; it < o.max_iterations; ++it) {
      for (int kr = 0; kr < nm; ++kr) fr_[kr] = !dirr_[kr] && !cr_[kr];
      if (!factor_free()) return fail("factorisation failed (matrix not positive definite)");
      if (pcav == 0.0)
        solve_free([&](int, int, int kr) { return b0_[kr] + 0.0; });  // cavitated_couplings = 0
      else
        solve_free([&](int i, int j, int kr) { return b0_[kr] + cavitated_couplings(i, j, kr); });
      if (it == 0) update_pscale();
      int changed = 0;
      const double plim = pcav - tol * pscale, qlim = -tol * fscale;
      for (int i = 0; i < n; ++i) {
        const int kw0 = iwest_[i] * m, ke0 = ieast_[i] * m, kr0 = i * m;
        for (int j = 0; j < m; ++j) {
          const int kr = kr0 + j;
          if (dirr_[kr]) continue;
          if (!cr_[kr]) {
            if (pr_[kr] < plim) {
              cr_[kr] = 1;
              ++changed;
            }
            continue;
          }
          // outflow(i, j, false): the residual (A p - b) of the cavitated node, the same operations.
          const int kw = kw0 + j, ke = ke0 + j;
          const double pk = pr_[kr];
          const double ps = j > 0 ? pr_[kr - 1] : pamb;
          const double pn = j + 1 < m ? pr_[kr + 1] : pamb;
          const double q = cw_[kr] * (pk - pr_[kw]) + ce_[kr] * (pk - pr_[ke]) + cs_[kr] * (pk - ps) + cn_[kr] * (pk - pn);
          if (q + fe_[kr] - fe_[kw] + sq_[kr] < qlim) {
            cr_[kr] = 0;
            ++changed;
          }
        }
      }
      if (changed == 0) return true;
      for (int kr = 0; kr < nm; ++kr)
        if (cr_[kr]) pr_[kr] = pcav;
    }
    return fail("Swift-Stieber active set did not settle in " + std::to_string(o.max_iterations) + " sweeps");
  }

  // Film fraction of the cavitated nodes from the current pressures: in a cavitated control volume the pressure is
  // p_cav and the mass balance  theta_k (F_out + SQ_k) = theta_up F_in + pressure inflow  is marched downstream
  // from the last full node of each axial row (Elrod-Adams upwinding of the Couette flux). Nodes where no film
  // fraction can be found (den <= 0) are flagged with theta = +inf.
  void march_theta() {
    const bool fwd = U >= 0.0;
    const double inf = std::numeric_limits<double>::infinity();
    for (int j = 0; j < m; ++j) {
      auto node = [&](int i) { return ((i % n) + n) % n * m + j; };
      const int step = fwd ? 1 : -1;
      // Start at a cavitated node whose upstream neighbour is full (theta_up = 1).
      int start = -1;
      bool anyc = false;
      for (int i = 0; i < n; ++i) {
        anyc |= cr[i * m + j] == kCav;
        if (cr[i * m + j] == kCav && cr[node(i - step)] != kCav) {
          start = i;
          break;
        }
      }
      if (!anyc) continue;
      double up = 1.0;
      if (start < 0) {
        // The whole row is cavitated: theta_i = alpha_i theta_up + beta_i around the circle has the fixed point
        // theta_up = B / (1 - A) of the composed map.
        start = 0;
        double A = 1.0, B = 0.0;
        for (int s = 0; s < n; ++s) {
          double alpha, beta;
          theta_coefficients(node(start + step * s), alpha, beta);
          A = alpha * A;
          B = alpha * B + beta;
        }
        up = (std::isfinite(A) && std::isfinite(B) && 1.0 - A > 1e-12) ? B / (1.0 - A) : inf;
        if (!std::isfinite(up)) {
          // No steady film fraction on a closed cavitated ring: flag the row (it must carry pressure).
          for (int i = 0; i < n; ++i) thr[i * m + j] = inf;
          continue;
        }
      }
      for (int s = 0; s < n; ++s) {
        const int kr = node(start + step * s);
        if (cr[kr] != kCav) {
          up = 1.0;
          continue;
        }
        double alpha, beta;
        theta_coefficients(kr, alpha, beta);
        const double t = std::isfinite(alpha) ? alpha * up + beta : inf;
        thr[kr] = t;
        up = std::isfinite(t) ? t : 1.0;
      }
    }
  }

  // theta_kr = alpha * theta_upstream + beta in a cavitated node (alpha = +inf when no film fraction exists).
  void theta_coefficients(int kr, double& alpha, double& beta) const {
    const int i = kr / m, j = kr % m;
    const int kw = iwest[i] * m + j, ke = ieast[i] * m + j;
    const double ps = j > 0 ? pr[kr - 1] : pamb;
    const double pn = j + 1 < m ? pr[kr + 1] : pamb;
    const double inflow = Cw[kr] * (pr[kw] - pcav) + Ce[kr] * (pr[ke] - pcav) + Cs[kr] * (ps - pcav) +
                          Cn[kr] * (pn - pcav);
    double fin, fout;
    if (U >= 0.0) {
      fin = FE[kw];
      fout = FE[kr];
    } else {
      fin = -FE[kr];
      fout = -FE[kw];
    }
    const double den = fout + SQ[kr];
    if (!(den > 1e-14 * fscale)) {
      alpha = std::numeric_limits<double>::infinity();
      beta = 0.0;
      return;
    }
    alpha = fin / den;
    beta = inflow / den;
  }

  // Film fractions of the feeding nodes -> full-film pressures (one back-substitution) -> march -> new film
  // fractions of the feeding nodes: an affine map x -> phi(x) on the r cavitated nodes just upstream of a full node,
  // the only place where theta enters the pressure equations (Couette inflow at a reformation boundary).
  void jfo_phi(const double* x, double* out) {
    const bool fwd = U >= 0.0;
    for (int a = 0; a < nfeed; ++a) thr[feed[a]] = x[a];
    // Full-film source b0 corrected for the film fraction carried in from an upstream cavitated node.
    solve_free([&](int i, int j, int kr) {
      double b = b0[kr] + cavitated_couplings(i, j, kr);
      if (fwd) {
        const int kw = iwest[i] * m + j;
        if (cr[kw] == kCav) b += (thr[kw] - 1.0) * FE[kw];
      } else {
        const int ke = ieast[i] * m + j;
        if (cr[ke] == kCav) b -= (thr[ke] - 1.0) * FE[kr];
      }
      return b;
    });
    if (mk_generic)
      march_theta();
    else
      march_program();
    for (int a = 0; a < nfeed; ++a) out[a] = thr[feed[a]];
  }

  // The march of march_theta() for a fixed cavitated set, compiled once per active-set sweep: cavitated nodes in
  // marching order with their upstream link (-1: a full node, theta_up = 1), alpha, 1/den, the constant inflow from
  // the ends and the neighbour indices (index n m is a sentinel holding p_cav). Not used when a whole row is
  // cavitated (its cyclic fixed point needs the general march).
  void build_march_program() {
    mk_count = 0;
    mk_generic = false;
    const bool fwd = U >= 0.0;
    const int N = n * m;
    pr[N] = pcav;
    for (int j = 0; j < m; ++j) {
      int start = -1;
      bool anyc = false;
      for (int i = 0; i < n; ++i) {
        const int iu = fwd ? iwest[i] : ieast[i];
        anyc |= cr[i * m + j] == kCav;
        if (cr[i * m + j] == kCav && cr[iu * m + j] != kCav) {
          start = i;
          break;
        }
      }
      if (!anyc) continue;
      if (start < 0) {
        mk_generic = true;
        return;
      }
      int prev = -1, i = start;
      for (int s = 0; s < n; ++s, i = fwd ? ieast[i] : iwest[i]) {
        const int kr = i * m + j;
        if (cr[kr] != kCav) {
          prev = -1;
          continue;
        }
        const int t = mk_count++;
        double alpha, beta;
        theta_coefficients(kr, alpha, beta);  // for alpha and the denominator
        const int kw = iwest[i] * m + j, ke = ieast[i] * m + j;
        const double fout = fwd ? FE[kr] : -FE[kw];
        const double den = fout + SQ[kr];
        mk_node[t] = kr;
        mk_up[t] = prev;
        mk_alpha[t] = alpha;
        mk_invden[t] = std::isfinite(alpha) ? 1.0 / den : 0.0;
        mk_kw[t] = kw;
        mk_ke[t] = ke;
        mk_ks[t] = j > 0 ? kr - 1 : N;
        mk_kn[t] = j + 1 < m ? kr + 1 : N;
        double c = 0.0;
        if (j == 0) c += Cs[kr] * (pamb - pcav);
        if (j == m - 1 && !sym) c += Cn[kr] * (pamb - pcav);
        mk_const[t] = c;
        prev = t;
      }
    }
  }

  void march_program() {
    const double inf = std::numeric_limits<double>::infinity();
    for (int t = 0; t < mk_count; ++t) {
      const int kr = mk_node[t];
      if (!std::isfinite(mk_alpha[t])) {
        thr[kr] = inf;
        continue;
      }
      const double inflow = mk_const[t] + Cw[kr] * (pr[mk_kw[t]] - pcav) + Ce[kr] * (pr[mk_ke[t]] - pcav) +
                            Cs[kr] * (pr[mk_ks[t]] - pcav) + Cn[kr] * (pr[mk_kn[t]] - pcav);
      const int up = mk_up[t];
      double tu = up < 0 ? 1.0 : thr[mk_node[up]];
      if (!std::isfinite(tu)) tu = 1.0;
      thr[kr] = mk_alpha[t] * tu + inflow * mk_invden[t];
    }
  }

  // Solves x = phi(x) by GMRES on (I - G) x = phi(0) with G the linear part of phi (restarted after kmax steps).
  // Returns false if phi produced non-finite film fractions (the active set is inconsistent).
  bool jfo_inner(double tol) {
    const int r = nfeed;
    double* x = gm_x.data();
    double* f0 = gm_f.data();
    // Start from a full film at the feeding nodes rather than from the last call's film fractions: the result is
    // then a function of the state and the active set alone (repeated solves agree bit for bit), at a cost of
    // 5-10 % more back-substitutions in the whirl benchmark.
    std::fill(x, x + r, 1.0);
    const int kmax = std::min(r, kGmresRestart);
    for (int restart = 0; restart < o.max_iterations; ++restart) {
      jfo_phi(x, f0);
      double beta = 0.0;
      for (int a = 0; a < r; ++a) {
        if (!std::isfinite(f0[a])) return false;
        gm_v[a] = f0[a] - x[a];
        beta += gm_v[a] * gm_v[a];
      }
      beta = std::sqrt(beta);
      if (r == 0 || beta <= tol) {
        for (int kr = 0; kr < n * m; ++kr)
          if (cr[kr] == kCav && !std::isfinite(thr[kr])) return false;
        return true;
      }
      for (int a = 0; a < r; ++a) gm_v[a] /= beta;
      std::fill(gm_g.begin(), gm_g.begin() + kmax + 1, 0.0);
      gm_g[0] = beta;
      int k = 0;
      double res = beta;
      for (; k < kmax && res > tol; ++k) {
        double* vk = gm_v.data() + static_cast<std::ptrdiff_t>(k) * r;
        double* w = gm_v.data() + static_cast<std::ptrdiff_t>(k + 1) * r;
        for (int a = 0; a < r; ++a) gm_t[a] = x[a] + vk[a];
        jfo_phi(gm_t.data(), w);
        for (int a = 0; a < r; ++a) {
          if (!std::isfinite(w[a])) return false;
          w[a] = vk[a] - (w[a] - f0[a]);  // (I - G) v_k
        }
        double* hk = gm_h.data() + static_cast<std::ptrdiff_t>(k) * (kmax + 1);
        for (int l = 0; l <= k; ++l) {
          const double* vl = gm_v.data() + static_cast<std::ptrdiff_t>(l) * r;
          double d = 0.0;
          for (int a = 0; a < r; ++a) d += w[a] * vl[a];
          hk[l] = d;
          for (int a = 0; a < r; ++a) w[a] -= d * vl[a];
        }
        double nw = 0.0;
        for (int a = 0; a < r; ++a) nw += w[a] * w[a];
        nw = std::sqrt(nw);
        hk[k + 1] = nw;
        if (nw > 0.0)
          for (int a = 0; a < r; ++a) w[a] /= nw;
        for (int l = 0; l < k; ++l) {  // previous Givens rotations
          const double t = gm_cs[l] * hk[l] + gm_sn[l] * hk[l + 1];
          hk[l + 1] = -gm_sn[l] * hk[l] + gm_cs[l] * hk[l + 1];
          hk[l] = t;
        }
        const double den = std::hypot(hk[k], hk[k + 1]);
        gm_cs[k] = den > 0.0 ? hk[k] / den : 1.0;
        gm_sn[k] = den > 0.0 ? hk[k + 1] / den : 0.0;
        hk[k] = den;
        hk[k + 1] = 0.0;
        gm_g[k + 1] = -gm_sn[k] * gm_g[k];
        gm_g[k] = gm_cs[k] * gm_g[k];
        res = std::abs(gm_g[k + 1]);
        if (nw == 0.0) {
          ++k;
          break;
        }
      }
      // x += V y with H y = g (upper triangular, k x k)
      for (int l = k - 1; l >= 0; --l) {
        double s = gm_g[l];
        for (int q = l + 1; q < k; ++q) s -= gm_h[static_cast<std::ptrdiff_t>(q) * (kmax + 1) + l] * gm_y[q];
        gm_y[l] = s / gm_h[static_cast<std::ptrdiff_t>(l) * (kmax + 1) + l];
      }
      for (int l = 0; l < k; ++l) {
        const double* vl = gm_v.data() + static_cast<std::ptrdiff_t>(l) * r;
        for (int a = 0; a < r; ++a) x[a] += gm_y[l] * vl[a];
      }
    }
    return false;
  }

  // JFO (Jakobsson-Floberg-Olsson) mass-conserving cavitation in the Elrod-Adams form: in the full film p >= p_cav
  // and theta = 1, in the cavitated zone p = p_cav and 0 <= theta < 1; the Couette flux carries theta h
  // (upwinded). Active-set (semismooth Newton) iteration on (full, cavitated); for a fixed set the pressures of the
  // full nodes (SPD system, factorised once) and the film fractions (downstream march) are solved exactly through
  // the small fixed-point problem of jfo_inner().
  bool solve_jfo() {
    const double tol = o.tolerance;
    for (int kr = 0; kr < n * m; ++kr) {
      if (dirr[kr]) {
        cr[kr] = kFull;
        thr[kr] = 1.0;
        continue;
      }
      if (cr[kr] == kFallback) {  // keep the fallback only where a film fraction still cannot exist
        double alpha, beta;
        theta_coefficients(kr, alpha, beta);
        if (std::isfinite(alpha)) cr[kr] = kCav;
      }
      if (cr[kr] == kFull || cr[kr] == kFallback) thr[kr] = 1.0;
      if (cr[kr] != kFull) pr[kr] = pcav;
    }
    std::fill(switches.begin(), switches.end(), 0);
    const bool fwd = U >= 0.0;
    for (int it = 0; it < o.max_iterations; ++it) {
      for (int kr = 0; kr < n * m; ++kr) fr[kr] = !dirr[kr] && !cr[kr];
      if (!factor_free()) return fail("factorisation failed (matrix not positive definite)");
      nfeed = 0;
      if (U != 0.0)
        for (int kr = 0; kr < n * m; ++kr) {
          if (cr[kr] != kCav) continue;
          const int i = kr / m, j = kr % m;
          const int kd = (fwd ? (i + 1) % n : (i + n - 1) % n) * m + j;
          if (fr[kd]) feed[nfeed++] = kr;
        }
      build_march_program();
      const bool consistent = jfo_inner(tol);
      update_pscale();
      // Full -> cavitated where p < p_cav; cavitated -> full where theta > 1; cavitated -> fallback where no film
      // fraction exists (the gap closes faster than the Couette flow empties the cell: den <= 0); fallback -> full
      // where the Swift-Stieber multiplier asks for pressure. While theta is not finite somewhere (inconsistent
      // set), the pressures are not trusted and only the last two switches are made.
      // Anti-cycling: simultaneous switching is not monotone here (the Couette coupling of theta makes the system
      // no M-matrix), and sets can cycle in squeeze-dominated states; a cell that has switched kMaxSwitches times
      // in this call is frozen in the fallback state, which is always admissible.
      int changed = 0;
      const double qlim = -tol * fscale;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
          const int kr = i * m + j;
          if (dirr[kr] || switches[kr] > kMaxSwitches) continue;
          const int before = cr[kr];
          switch (cr[kr]) {
            case kFull:
              if (consistent && pr[kr] < pcav - tol * pscale) {
                cr[kr] = kCav;
                ++changed;
              }
              break;
            case kCav:
              if (!std::isfinite(thr[kr])) {
                cr[kr] = kFallback;
                ++changed;
              } else if (thr[kr] > 1.0 + tol) {
                cr[kr] = kFull;
                ++changed;
              }
              break;
            default:  // kFallback
              if (consistent && outflow(i, j, true) < qlim) {
                cr[kr] = kFull;
                ++changed;
              }
          }
          if (cr[kr] != before) {
            switches[kr] = switches[kr] + 1;
            if (switches[kr] > kMaxSwitches) cr[kr] = kFallback;
          }
        }
      if (changed == 0) {
        if (!consistent) return fail("mass-conserving iteration failed (no film fraction for the cavitated set)");
        for (int kr = 0; kr < n * m; ++kr)
          if (cr[kr] == kCav) thr[kr] = std::clamp(thr[kr], 0.0, 1.0);
        return true;
      }
      for (int kr = 0; kr < n * m; ++kr) {
        if (cr[kr] == kCav) {
          pr[kr] = pcav;
          if (!std::isfinite(thr[kr]) || thr[kr] > 1.0) thr[kr] = 1.0;
          if (thr[kr] < 0.0) thr[kr] = 0.0;
        } else {
          if (cr[kr] == kFallback) pr[kr] = pcav;
          thr[kr] = 1.0;
        }
      }
    }
    return fail("mass-conserving active set did not settle in " + std::to_string(o.max_iterations) + " sweeps");
  }

  bool fail(const std::string& msg) {
    err = msg;
    return false;
  }

  // ---- outputs ---------------------------------------------------------------------------------------------------

  // Net volume outflow of the control volume of full-grid node (i, j) with the full-grid fields: for a Dirichlet
  // node, the flow that the hole or groove feeds into the film there.
  double outflow_full(int i, int j, bool jfo) const {
    const int k = i * nz + j, iw = (i + n - 1) % n, ie = (i + 1) % n;
    const int kw = iw * nz + j;
    const double pk = pressure_at(i, j);
    const double ps = j > 0 ? pressure_at(i, j - 1) : pamb, pn = j + 1 < nz ? pressure_at(i, j + 1) : pamb;
    double q = aE[kw] * (pk - pressure_at(iw, j)) + aE[k] * (pk - pressure_at(ie, j)) + aF[i * nzf + j] * (pk - ps) +
               aF[i * nzf + j + 1] * (pk - pn);
    if (!jfo) return q + cE[k] - cE[kw] + sq[k];
    const double tk = theta_at(i, j);
    const double te = U >= 0.0 ? tk : theta_at(ie, j), tw = U >= 0.0 ? theta_at(iw, j) : tk;
    return q + te * cE[k] - tw * cE[kw] + tk * sq[k];
  }

  // The last solve's pressure and film content at full-grid node (i, j), read from the reduced solution: row j, or
  // its mirror image nz - 1 - j of a symmetric solve.
  int reduced_node(int i, int j) const { return i * m + (j < m ? j : nz - 1 - j); }
  double pressure_at(int i, int j) const { return pr[reduced_node(i, j)]; }
  double theta_at(int i, int j) const {
    return o.cavitation == Cavitation::MassConserving ? thr[reduced_node(i, j)] : 1.0;
  }

  // Expands the reduced solution (pr, thr, cr in the layout m, sym) to the full-grid fields p, theta, cav, ff,
  // unless they already hold it.
  void ensure_fields() {
    if (!fields_stale) return;
    fields_stale = false;
    const bool jfo = o.cavitation == Cavitation::MassConserving;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const int kr = i * m + j, k = i * nz + j;
        p[k] = pr[kr];
        theta[k] = jfo ? thr[kr] : 1.0;
        cav[k] = cr[kr];
        ff[k] = jfo ? thr[kr] : (cr[kr] != kFull ? 0.0 : 1.0);
      }
    if (sym) mirror_axially(m, p, theta, cav, ff);
  }

  void outputs(const FilmState& s, FilmResult& r) {
    if (forces_only)
      outputs_of<false>(s, r);
    else
      outputs_of<true>(s, r);
  }

  // Full: also the torques' sums (Couette and Poiseuille shear), the end and hole flows.
  template <bool Full>
  void outputs_of(const FilmState& s, FilmResult& r) {
    const bool jfo = o.cavitation == Cavitation::MassConserving;
    int ncav = 0, nfallback = 0;
    // The outputs read the reduced solution in place (pressure_at, theta_at): the same values, summed in the same
    // order, as from the full-grid fields, which are expanded only when something asks for them.
    fields_stale = true;
    for (int j = 0; j < m; ++j) {
      const int copies = sym && 2 * j != nz - 1 ? 2 : 1;
      for (int i = 0; i < n; ++i) {
        ncav += copies * (cr[i * m + j] != kFull);
        nfallback += copies * (cr[i * m + j] == kFallback);
      }
    }

    const double R = g.radius;
    double sc = 0, ss = 0, zc = 0, zs = 0, couette = 0, pois = 0, pmax = pamb;
    if (!Full && sym && seal_conductance == 0.0) {
      // Forces of a film symmetric about mid-width (open ends): the column sums over the m reduced rows, each row
      // but a mid-width one standing for itself and its mirror image; the moments vanish, and the end term's two
      // slopes are equal and opposite. The loop below in half the work, the same sums up to round-off.
      const double* __restrict pr_ = pr.data();
      const double* __restrict wz_ = wz.data();
      const double r1 = wz[1] / wz[0], end_factor = wz[0] / 12.0;  // hend^2 / 12 times twice slope_lo below
      for (int i = 0; i < n; ++i) {
        const double* pc = pr_ + i * m;
        double rp = 0;
        for (int j = 0; j < m; ++j) {
          const double pk = pc[j];
          rp += (2 * j != nz - 1 ? 2.0 : 1.0) * pk * wz_[j];
          pmax = std::max(pmax, pk);
        }
        if (plain_column[i]) rp += end_factor * (4.0 * (pc[0] - pamb) - r1 * (pressure_at(i, 1) - pamb));
        sc += rp * ct[i];
        ss += rp * st[i];
      }
    } else {
      for (int i = 0; i < n; ++i) {
        const int ie = (i + 1) % n;
        double rp = 0, rz = 0, rc = 0, rpz = 0;
        for (int j = 0; j < nz; ++j) {
          const int k = i * nz + j;
          const double pk = pressure_at(i, j), w = wz[j];
          rp += pk * w;
          rpz += pk * zn[j] * w;
          if constexpr (Full) {
            rc += theta_at(i, j) / hN[k] * wc[j];
            rz += hE[k] * (pressure_at(ie, j) - pk) * w;
          }
          pmax = std::max(pmax, pk);
        }
        if (seal_conductance > 0.0) {
          // Behind a seal the land's ends carry p_end = p_amb + (a / c_s) (p_node - p_amb) (flow continuity through
          // the end face a, in series, and the slot c_s); the end strips of width dz/2 between the first node's cell
          // and the land end, negligible at open ends, are integrated with p linear from p_end to the face.
          const double strip = zf[0] + 0.5 * g.length, zend = 0.5 * g.length - 0.5 * strip;
          const double p0 = pressure_at(i, 0), p1 = pressure_at(i, nz - 1);
          const double e0 = pamb + aF[i * nzf] / seal_conductance * (p0 - pamb);
          const double e1 = pamb + aF[i * nzf + nz] / seal_conductance * (p1 - pamb);
          const double s0 = (3.0 * e0 + p0) / 4.0 * strip, s1 = (3.0 * e1 + p1) / 4.0 * strip;  // strip integrals
          rp += s0 + s1;
          rpz += zend * (s1 - s0);
        } else {
          // Open ends (p = p_amb there): the cell sums are the trapezoidal rule of p - p_amb and (p - p_amb) z
          // along the column, whose error is dominated by the ends, where the profile is steepest. The
          // Euler-Maclaurin end term -dz^2/12 [f']_-L/2^L/2, with p' at the ends from second-order one-sided
          // differences, makes them converge faster in the axial step (docs/reynolds.md §2). The force's term only
          // in columns without hole or groove nodes, whose profile kinks at the hole's edge (there it made the
          // forces worse); the moment's in every column (a hole at mid-width hardly weighs in it).
          // On a graded grid the rule is the trapezoidal one in the mapped coordinate xi, for F = f dz/dxi: its end
          // slope F' = f' (dz/dxi)^2 (f = 0 there) from the same differences of F, with hend = dxi dz/dxi(end).
          const double pc0 = pressure_at(i, 0), pc1 = pressure_at(i, 1);
          const double pcl = pressure_at(i, nz - 1), pcm = pressure_at(i, nz - 2);
          const double r1 = wz[1] / wz[0];  // 1 on the uniform grid
          const double slope_lo = (4.0 * (pc0 - pamb) - r1 * (pc1 - pamb)) * wz[0] / (2.0 * hend * hend);
          const double slope_hi = -(4.0 * (pcl - pamb) - r1 * (pcm - pamb)) * wz[0] / (2.0 * hend * hend);
          if (plain_column[i]) rp -= hend * hend / 12.0 * (slope_hi - slope_lo);  // f = p - p_amb
          rpz -= hend * hend / 12.0 * 0.5 * g.length * (slope_hi + slope_lo);  // f = (p - p_amb) z
          end_slope_lo[i] = slope_lo;
          end_slope_hi[i] = slope_hi;
        }
        sc += rp * ct[i];
        ss += rp * st[i];
        zc += rpz * ct[i];
        zs += rpz * st[i];
        couette += rc;
        pois += rz;
      }
    }
    r.fx = -R * dth * sc;
    r.fy = -R * dth * ss;
    r.my = -R * dth * zc;  // sum of z dFx
    r.mx = R * dth * zs;   // -sum of z dFy
    if (sym) r.mx = r.my = 0.0;
    if constexpr (!Full) {
      constexpr double nan = std::numeric_limits<double>::quiet_NaN();
      r.torque_inner = r.torque_outer = r.flow_ends = nan;
      r.hole_flows.resize(g.holes.size());
      std::fill(r.hole_flows.begin(), r.hole_flows.end(), nan);
    } else {
      const double c = g.clearance, zl = -0.5 * g.length, zu = 0.5 * g.length;
      if (seal_conductance == 0.0) {
        // The Poiseuille shear's axial sums get the forces' end term, so that the film's torque balance
        // T_journal + T_bush = -(e x F)_z holds as closely as before: between two plain columns the integrand is
        // h_e (p_east - p) (zero at the ends), its end slope h_e(end) (p'_east(end) - p'(end)).
        for (int i = 0; i < n; ++i) {
          const int ie = (i + 1) % n;
          if (!plain_column[i] || !plain_column[ie]) continue;
          const double hl = c - (s.ex + zl * s.sx) * cte[i] - (s.ey + zl * s.sy) * ste[i];
          const double hu = c - (s.ex + zu * s.sx) * cte[i] - (s.ey + zu * s.sy) * ste[i];
          pois -= hend * hend / 12.0 * (hu * (end_slope_hi[ie] - end_slope_hi[i]) - hl * (end_slope_lo[ie] - end_slope_lo[i]));
        }
      }
      // Couette end strips with h at the end planes.
      double ends = 0.0;
      for (int i = 0; i < n; ++i) {
        const double hl = c - (s.ex + zl * s.sx) * ct[i] - (s.ey + zl * s.sy) * st[i];
        const double hu = c - (s.ex + zu * s.sx) * ct[i] - (s.ey + zu * s.sy) * st[i];
        ends += 0.5 * (theta_at(i, 0) / hl + theta_at(i, nz - 1) / hu);
      }
      couette += ends * 2.0 * (zf[0] + 0.5 * g.length);  // the end strips
      // A groove is deep against the clearance: no Couette shear across its width, which the rows' cells above
      // counted at the land's thickness (taken at the groove's centre line here).
      for (const Groove& gr : g.grooves)
        for (int i = 0; i < n; ++i)
          couette -= gr.width / (c - (s.ex + gr.z * s.sx) * ct[i] - (s.ey + gr.z * s.sy) * st[i]);
      const double tc = R * eta * R * (s.omega_outer - s.omega_inner) * couette * dx;
      const double tp = -R * 0.5 * pois;
      r.torque_inner = tc + tp;
      r.torque_outer = -tc + tp;
      double qe = 0.0;
      for (int i = 0; i < n; ++i)
        qe += aF[i * nzf] * (pressure_at(i, 0) - pamb) + aF[i * nzf + nz] * (pressure_at(i, nz - 1) - pamb);
      r.flow_ends = qe;
      r.hole_flows.resize(g.holes.size());
      std::fill(r.hole_flows.begin(), r.hole_flows.end(), 0.0);
      for (int k : dir_nodes)
        if (kind[k] >= 0) r.hole_flows[kind[k]] += outflow_full(k / nz, k % nz, jfo);
    }
    r.max_pressure = pmax;
    r.cavitated_fraction = static_cast<double>(ncav) / (n * nz);
    r.fallback_nodes = nfallback;
    r.iterations = iterations;
    r.linear_solves = solves;
    r.symmetric = sym;
  }

  // Per-call inputs shared by solve() and solve_same_matrix(): speeds, pressures, the Dirichlet values and whether
  // the mid-width symmetry applies.
  void set_inputs(const FilmState& s) {
    U = g.radius * (s.omega_inner + s.omega_outer);
    pcav = g.cavitation_pressure;
    pamb = g.ambient_pressure;
    for (int k : dir_nodes) {
      const int kd = kind[k];
      dval[k] = kd >= 0 ? (s.use_override ? s.hole_pressure_override[kd] : g.holes[kd].pressure)
                        : g.grooves[-2 - kd].pressure;
    }
  }
  bool symmetric_state(const FilmState& s) const {
    return o.use_symmetry && mask_symmetric && s.sx == 0.0 && s.sy == 0.0 && s.dsx == 0.0 && s.dsy == 0.0 &&
           symmetric_values();
  }

  // Film closure (min_film_thickness). Sets the error if the film closes.
  bool closes(const FilmState& s) {
    const double h = min_film_thickness(g, s);
    if (h > 0.0) return false;
    const double e = g.clearance - h;
    std::ostringstream os;
    os << "film closes: eccentricity " << e << " m >= clearance " << g.clearance << " m (eccentricity ratio "
       << e / g.clearance << ")";
    fail(os.str());
    return true;
  }

  // The checks of solve_same_matrix() and solve_linearised() (`what` names the caller in the messages), then the
  // state's speeds, pressures and Dirichlet values: a None or Gumbel factorisation exists, the state is finite,
  // the thickness is the factorisation's (same_thickness) or the film is open, and the mid-width symmetry is kept.
  bool can_reuse_factorisation(const FilmState& s, const char* what, bool same_thickness) {
    err.clear();
    auto refuse = [&](const char* why) { return fail(std::string(what) + ": " + why); };  // allocates on failure only
    if (o.cavitation == Cavitation::MassConserving)
      return refuse("not for the mass-conserving model (its film fractions are not linear)");
    if (!factored) return refuse("no factorisation of a previous solve to reuse");
    if (!finite_state(s)) return fail("state is not finite");
    if (same_thickness) {
      if (s.ex != factored_at[0] || s.ey != factored_at[1] || s.sx != factored_at[2] || s.sy != factored_at[3])
        return refuse("the film thickness differs from that of the last solve");
    } else if (closes(s)) {
      return false;
    }
    set_inputs(s);
    if (symmetric_state(s) != sym) return refuse("the state changes the mid-width symmetry");
    return true;
  }

  // One Newton step of the new state's system from the factorisation's solution p0, with the factorisation's
  // matrix A0 and its cavitated set: p = p0 + A0^-1 (b - A p0) on the free nodes. Exact in the right-hand side,
  // first order in the film thickness (the error is A0^-1 (A0 - A)(p - p0), second order in the change).
  bool solve_linearised(const FilmState& s, FilmResult& r) {
    if (!can_reuse_factorisation(s, "solve_linearised", false)) return false;
    thickness_current = false;
    geometry_arrays(s);
    reduced_system();  // new couplings, sources and hole values; Dirichlet nodes take their values in pr
    for (int kr = 0; kr < n * m; ++kr)
      if (cr[kr])
        pr[kr] = pcav;
      else if (fr[kr])
        pr[kr] = pr0[kr];
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const int kr = i * m + j;
        if (fr[kr]) res[kr] = -outflow(i, j, false);  // b - A p0 of the free node
      }
    iterations = 0;
    solves = 0;
    solve_free([&](int, int, int kr) { return res[kr]; });  // the correction, into pr
    for (int kr = 0; kr < n * m; ++kr)
      if (fr[kr]) pr[kr] += pr0[kr];
    outputs(s, r);
    return true;
  }

  bool solve_same_matrix(const FilmState& s, FilmResult& r) {
    if (!can_reuse_factorisation(s, "solve_same_matrix", true)) return false;
    // The same thickness: new squeeze and Couette terms, the same couplings, new sources and hole values.
    geometry_arrays(s, thickness_current);
    reduced_system(thickness_current);
    thickness_current = true;
    // The cavitated set (cr) and the free set (fr) of the factorisation are kept.
    for (int kr = 0; kr < n * m; ++kr)
      if (cr[kr]) pr[kr] = pcav;
    iterations = 0;
    solves = 0;
    solve_free([&](int i, int j, int kr) { return b0[kr] + cavitated_couplings(i, j, kr); });
    outputs(s, r);
    return true;
  }

  bool solve(const FilmState& s, FilmResult& r) {
    err.clear();
    factored = false;
    thickness_current = false;
    if (!finite_state(s)) return fail("state is not finite");
    if (closes(s)) return false;
    set_inputs(s);
    if (o.cavitation == Cavitation::MassConserving) {
      double supply = pamb;
      for (int k : dir_nodes) supply = std::max(supply, dval[k]);
      if (!(supply > pcav))
        return fail(
            "mass-conserving cavitation needs an oil supply: a hole or groove above the cavitation pressure, or "
            "ambient pressure above it (without one the steady film runs dry)");
    }
    const bool sym_new = symmetric_state(s);
    // The warm start is the last solve's solution, which the reduced fields still hold (an expansion to the full
    // grid only copies them): kept in place if the layout is the same (the values the full-grid copy below would
    // take), expanded first otherwise.
    const bool in_place = warm && sym_new == sym;
    if (warm && !in_place) ensure_fields();
    sym = sym_new;
    m = sym ? (nz + 1) / 2 : nz;
    w_last = (sym && nz % 2 == 1) ? 0.5 : 1.0;
    geometry_arrays(s);
    reduced_system();  // Dirichlet nodes take their values in pr
    // Warm start from the full-grid state of the last call.
    if (!in_place) {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
          const int kr = i * m + j, k = i * nz + j;
          cr[kr] = warm ? cav[k] : ByteFlag(0);
          thr[kr] = warm ? theta[k] : 1.0;
          pr[kr] = dirr[kr] ? dval[k] : (warm ? p[k] : pamb);
        }
    }
    iterations = 0;
    solves = 0;
    bool ok = false;
    switch (o.cavitation) {
      case Cavitation::None:
        for (int kr = 0; kr < n * m; ++kr) cr[kr] = 0;
        ok = solve_none();
        break;
      case Cavitation::Gumbel: ok = solve_gumbel(); break;
      case Cavitation::MassConserving: ok = solve_jfo(); break;
    }
    if (!ok) {
      warm = false;
      return false;
    }
    if (o.cavitation != Cavitation::MassConserving) std::copy(pr.begin(), pr.begin() + n * m, pr0.begin());
    outputs(s, r);
    warm = true;
    factored = o.cavitation != Cavitation::MassConserving;
    thickness_current = factored;
    factored_at[0] = s.ex;
    factored_at[1] = s.ey;
    factored_at[2] = s.sx;
    factored_at[3] = s.sy;
    return true;
  }
};

FilmSolver::FilmSolver(const FilmGeometry& g, double viscosity, const SolverOptions& o)
    : impl_(std::make_unique<Impl>(g, viscosity, o)) {}
FilmSolver::~FilmSolver() = default;
FilmSolver::FilmSolver(const FilmSolver& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
FilmSolver& FilmSolver::operator=(const FilmSolver& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
FilmSolver::FilmSolver(FilmSolver&&) noexcept = default;
FilmSolver& FilmSolver::operator=(FilmSolver&&) noexcept = default;

double min_film_thickness(const FilmGeometry& g, const FilmState& s) {
  const double hl = 0.5 * g.length;
  const double e1 = std::hypot(s.ex - hl * s.sx, s.ey - hl * s.sy);
  const double e2 = std::hypot(s.ex + hl * s.sx, s.ey + hl * s.sy);
  return g.clearance - std::max(e1, e2);
}

bool FilmSolver::solve(const FilmState& s, FilmResult& r) { return impl_->solve(s, r); }
bool FilmSolver::solve_same_matrix(const FilmState& s, FilmResult& r) { return impl_->solve_same_matrix(s, r); }
bool FilmSolver::solve_linearised(const FilmState& s, FilmResult& r) { return impl_->solve_linearised(s, r); }
const std::string& FilmSolver::last_error() const { return impl_->err; }
const std::vector<double>& FilmSolver::pressure() const {
  impl_->ensure_fields();
  return impl_->p;
}
const std::vector<double>& FilmSolver::film_fraction() const {
  impl_->ensure_fields();
  return impl_->ff;
}
double FilmSolver::node_pressure(int i, int j) const {
  const Impl& d = *impl_;
  return d.fields_stale ? d.pressure_at(i, j) : d.p[static_cast<std::size_t>(i) * d.nz + j];
}
std::vector<double> FilmSolver::theta_nodes() const { return impl_->th; }
std::vector<double> FilmSolver::z_nodes() const { return impl_->zn; }
std::vector<double> FilmSolver::z_widths() const { return impl_->wz; }
void FilmSolver::reset_warm_start() { impl_->warm = false; }
void FilmSolver::set_forces_only(bool forces_only) {
  Impl& d = *impl_;
  // The loads-only arrays lack the mirrored half of a symmetric solve's node arrays: a same-matrix solve after the
  // switch must not take them for the factorisation's.
  if (forces_only != d.forces_only) d.thickness_current = false;
  d.forces_only = forces_only;
}
bool FilmSolver::set_viscosity(double viscosity) {
  Impl& d = *impl_;
  if (!(viscosity > 0.0) || !std::isfinite(viscosity)) return false;
  if (viscosity == d.eta) return true;
  if (d.seal_conductance > 0.0) d.seal_conductance *= d.eta / viscosity;  // gap^3 / (12 eta length)
  d.eta = viscosity;
  d.factored = false;
  d.thickness_current = false;  // aE, aF depend on the viscosity
  return true;
}
const FilmGeometry& FilmSolver::geometry() const { return impl_->g; }
double FilmSolver::viscosity() const { return impl_->eta; }
const SolverOptions& FilmSolver::options() const { return impl_->o; }

void FilmSolver::assemble_full_film_system(const FilmState& s, Eigen::SparseMatrix<double>& A,
                                           Eigen::VectorXd& b) const {
  const Impl& d = *impl_;
  const int n = d.n, nz = d.nz, N = n * nz;
  const double c = d.g.clearance, U = d.g.radius * (s.omega_inner + s.omega_outer);
  auto h_at = [&](double cth, double sth, double z) {
    return c - (s.ex + z * s.sx) * cth - (s.ey + z * s.sy) * sth;
  };
  auto value = [&](int k) {
    const int kd = d.kind[k];
    return kd >= 0 ? (s.use_override ? s.hole_pressure_override[kd] : d.g.holes[kd].pressure)
                   : d.g.grooves[-2 - kd].pressure;
  };
  // The holes' fitted faces (SolverOptions::fitted_holes), as the solver scales them.
  std::vector<double> fit_e(N, 1.0), fit_a(n * d.nzf, 1.0);
  for (const auto& [k, f] : d.fit_east) fit_e[k] = f;
  for (const auto& [kf, f] : d.fit_axial) fit_a[kf] = f;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(5 * N);
  b.setZero(N);
  const double pamb = d.g.ambient_pressure;
  for (int i = 0; i < n; ++i) {
    const int iw = (i + n - 1) % n, ie = (i + 1) % n;
    for (int j = 0; j < nz; ++j) {
      const int k = i * nz + j;
      if (d.kind[k] != -1) {
        t.emplace_back(k, k, 1.0);
        b[k] = value(k);
        continue;
      }
      const double z = d.zn[j];
      const double he = h_at(d.cte[i], d.ste[i], z), hw = h_at(d.cte[iw], d.ste[iw], z);
      const double hs = h_at(d.ct[i], d.st[i], d.zf[j]), hn = h_at(d.ct[i], d.st[i], d.zf[j + 1]);
      const double kx = d.wz[j] / (12.0 * d.eta * d.dx), ks = d.dx / (12.0 * d.eta * d.dzf[j]),
                   kn = d.dx / (12.0 * d.eta * d.dzf[j + 1]);
      const double ae = kx * he * he * he * fit_e[k], aw = kx * hw * hw * hw * fit_e[iw * nz + j],
                   as = ks * hs * hs * hs * fit_a[i * d.nzf + j], an = kn * hn * hn * hn * fit_a[i * d.nzf + j + 1];
      const double hdot = -((s.vx + z * s.dsx) * d.ct[i] + (s.vy + z * s.dsy) * d.st[i]);
      double rhs = -0.5 * U * d.wz[j] * (he - hw) - hdot * d.dx * d.wz[j];
      t.emplace_back(k, k, ae + aw + as + an);
      auto couple = [&](int kn, double a) {
        if (d.kind[kn] != -1)
          rhs += a * value(kn);
        else
          t.emplace_back(k, kn, -a);
      };
      couple(ie * nz + j, ae);
      couple(iw * nz + j, aw);
      if (j > 0) couple(k - 1, as); else rhs += as * pamb;
      if (j + 1 < nz) couple(k + 1, an); else rhs += an * pamb;
      b[k] = rhs;
    }
  }
  A.resize(N, N);
  A.setFromTriplets(t.begin(), t.end());
}

}  // namespace turbodyn::reynolds

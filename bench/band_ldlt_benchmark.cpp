// Cost of the film's linear algebra alone (model/films/bordered_band_ldlt.h): one factorisation and one solve of the
// system of a film on the grids of the reference examples, 48 columns of m axial nodes (m = 10: a floating ring's
// film; m = 3: the half of the ball damper's 48 x 6 film that its mid-plane symmetry leaves), the wrap-around column
// as the border. The arguments are m, the border's size (na: how many of that column's nodes are free; 0 when the
// film has a fully cavitated column, where the cut goes; half-bandwidths 2 to 5 are then eliminated from both ends)
// and the share of fixed (cavitated or hole) nodes in per cent, laid out as a cavitated zone of whole columns'
// interiors, as the films produce them.
//
//   build/bench/band_ldlt_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "model/films/bordered_band_ldlt.h"

namespace {

using turbodyn::reynolds::BorderedBandLdlt;

constexpr int kColumns = 48;

// Fills the band (columns 0 .. kColumns - 2) and the border (column kColumns - 1) with a diagonally dominant
// five-point system; fixed nodes are identity rows.
void assemble(BorderedBandLdlt& s, int kM, int na, int fixed_percent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  const int nb = (kColumns - 1) * kM;
  // A cavitated zone of whole columns' interiors (the edge rows next to the ambient stay free) holding the share.
  // (The half film of m = 3 rows has its mid-plane row, not an edge row, at j = 2: it cavitates too.)
  const int per_column = kM > 3 ? kM - 2 : kM - 1, zone = fixed_percent * nb / 100 / per_column;
  auto fixed = [&](int r) {
    const int q = r / kM, j = r % kM;
    return q >= kColumns / 3 && q < kColumns / 3 + zone && j > 0 && (j < kM - 1 || kM <= 3);
  };
  s.reset(nb, kM, na);
  for (int r = 0; r < nb; ++r) {
    double* col = s.column(r);
    const bool f = fixed(r);
    s.set_fixed(r, f);
    if (f) {
      col[0] = 1.0;
      continue;
    }
    const int q = r / kM, j = r % kM;
    double sum = 1.0;
    if (j + 1 < kM && !fixed(r + 1)) sum += -(col[1] = -u(rng));
    if (q + 1 < kColumns - 1) {
      if (!fixed(r + kM)) sum += -(col[kM] = -u(rng));
    } else if (j < na) {
      sum += -(s.border(r, j) = -u(rng));
    }
    if (q == 0 && j < na) sum += -(s.border(r, j) += -u(rng));
    col[0] = 2.0 * sum + 4.0;
  }
  for (int a = 0; a < na; ++a) {
    s.corner(a, a) = 6.0;
    if (a + 1 < na) s.corner(a + 1, a) = -u(rng);
  }
}

void Factor(benchmark::State& st) {
  const int kM = static_cast<int>(st.range(0)), na = static_cast<int>(st.range(1)),
            fixed_percent = static_cast<int>(st.range(2));
  // A pool of assembled systems, refilled with the timer paused once per kPool factorisations: pausing the timer
  // costs about a microsecond, as much as the factorisation of a small film.
  constexpr int kPool = 64;
  std::vector<BorderedBandLdlt> pool(kPool);
  for (BorderedBandLdlt& s : pool) s.reserve(kColumns * kM, kM);
  int next = kPool;
  for (auto _ : st) {
    if (next == kPool) {
      st.PauseTiming();
      for (BorderedBandLdlt& s : pool) assemble(s, kM, na, fixed_percent, 7);
      next = 0;
      st.ResumeTiming();
    }
    if (!pool[next++].factor()) st.SkipWithError("not positive definite");
  }
}

void Solve(benchmark::State& st) {
  const int kM = static_cast<int>(st.range(0)), na = static_cast<int>(st.range(1)),
            fixed_percent = static_cast<int>(st.range(2));
  BorderedBandLdlt s;
  s.reserve(kColumns * kM, kM);
  assemble(s, kM, na, fixed_percent, 7);
  if (!s.factor()) st.SkipWithError("not positive definite");
  const int nb = (kColumns - 1) * kM;
  for (auto _ : st) {
    for (int r = 0; r < nb; ++r) s.rhs()[r] = 1e-3 * (r % 17);
    for (int a = 0; a < na; ++a) s.rhs_border()[a] = 1.0;
    s.solve();
    benchmark::DoNotOptimize(s.rhs()[nb / 2]);
  }
}

void Args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"m", "na", "fixed%"});
  for (int na : {0, 1, 3, 6, 10})
    for (int f : {0, 37}) b->Args({10, na, f});
  for (int na : {0, 1, 3})
    for (int f : {0, 37}) b->Args({3, na, f});
  for (int f : {0, 37}) b->Args({5, 0, f});
}

BENCHMARK(Factor)->Apply(Args)->Unit(benchmark::kMicrosecond);
BENCHMARK(Solve)->Apply(Args)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

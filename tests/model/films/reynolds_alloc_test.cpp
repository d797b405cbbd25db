// The film solver allocates nothing in steady use: this file links with tests/support/alloc_counter.cpp, which
// replaces the global operator new with a counting one.
#include "model/films/reynolds.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>
#include <Eigen/SparseLU>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/reynolds_fixtures.h"
#include "tests/support/alloc_counter.h"

namespace turbodyn::reynolds {
namespace {

using ::testing::HasSubstr;
using namespace turbodyn::reynolds::testing;

TEST(Allocation, NoHeapAllocationInSteadyUse) {
  FilmGeometry g = plain(0.7, 60, 12, 0.005, 15e-6);
  for (int k = 0; k < 4; ++k) g.holes.push_back(Hole{k * kPi / 2, 0.0, 0.002, 2e5});
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel, Cavitation::MassConserving}) {
    FilmSolver solver(g, 0.0108, with(cav));
    FilmResult r;
    FilmState s = journal(0.6, 0.0, 10000.0, 15e-6);
    ASSERT_TRUE(solver.solve(s, r));
    const long before = turbodyn::testing::allocation_count();
    for (int k = 0; k < 50; ++k) {
      s = journal(0.6, 0.01 * k, 10000.0, 15e-6);
      s.sx = k % 2 ? 2e-4 : 0.0;  // alternate symmetric and full solves
      solver.solve(s, r);
    }
    EXPECT_EQ(turbodyn::testing::allocation_count() - before, 0) << to_string(cav);
  }
}

}  // namespace
}  // namespace turbodyn::reynolds

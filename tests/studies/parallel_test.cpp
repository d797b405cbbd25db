#include "studies/parallel.h"

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace turbodyn::studies {
namespace {

TEST(Parallel, ThreadsComeFromTheCommandLineThenTheStudyThenAllCores) {
  EXPECT_EQ(run_threads(3, 5), 3);
  EXPECT_EQ(run_threads(0, 5), 5);
  EXPECT_EQ(run_threads(0, 0), static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

// Every index once, and the same results whatever the cap, also with a loop inside the loop.
TEST(Parallel, ResultsDoNotDependOnTheThreadCount) {
  auto run = [](int threads) {
    std::vector<double> out(40 * 3, NAN);
    parallel_runs(40, threads, [&](std::size_t i) {
      parallel_runs(3, 0, [&](std::size_t c) { out[3 * i + c] = std::sin(double(i)) * double(c + 1); });
    });
    return out;
  };
  const std::vector<double> one = run(1);
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], std::sin(double(k / 3)) * double(k % 3 + 1));
  EXPECT_EQ(run(2), one);
  EXPECT_EQ(run(4), one);
  EXPECT_EQ(run(0), one);
}

TEST(Parallel, TheCapHolds) {
  std::atomic<int> running{0}, most{0};
  parallel_runs(16, 2, [&](std::size_t) {
    const int now = ++running;
    for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    --running;
  });
  EXPECT_LE(most.load(), 2);
  EXPECT_GE(most.load(), 1);
}

TEST(Parallel, ABodysExceptionReachesTheCaller) {
  EXPECT_THROW(parallel_runs(8, 2,
                             [](std::size_t i) {
                               if (i == 5) throw std::runtime_error("run 5");
                             }),
               std::runtime_error);
  parallel_runs(0, 2, [](std::size_t) { FAIL() << "no runs: no calls"; });
}

}  // namespace
}  // namespace turbodyn::studies

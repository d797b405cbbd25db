// The element team: every task once, on its own thread, exceptions passed on; and a whole run-up gives the same
// numbers on one and on two threads.
#include "model/engine/element_team.h"

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "model/engine/integrator.h"
#include "model/engine/runup.h"
#include "model/io/model_file.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

struct Record {
  std::vector<std::atomic<int>> runs;
  std::vector<std::thread::id> thread;
  explicit Record(int n) : runs(n), thread(n) {}
};

TEST(ElementTeam, RunsEveryTaskOnceOnItsThreadAndPassesExceptionsOn) {
  ElementTeam team(3);
  EXPECT_EQ(team.threads(), 3);
  for (int round = 0; round < 100; ++round) {
    Record r(7);
    team.run(7, [](void* c, int k) {
      Record& rec = *static_cast<Record*>(c);
      ++rec.runs[k];
      rec.thread[k] = std::this_thread::get_id();
    }, &r);
    for (int k = 0; k < 7; ++k) EXPECT_EQ(r.runs[k].load(), 1);
    // Task k on thread k % 3: tasks 0, 3, 6 on the caller, 1 and 4 on one worker, 2 and 5 on the other.
    EXPECT_EQ(r.thread[0], std::this_thread::get_id());
    EXPECT_EQ(r.thread[3], r.thread[0]);
    EXPECT_EQ(r.thread[4], r.thread[1]);
    EXPECT_EQ(r.thread[5], r.thread[2]);
    EXPECT_NE(r.thread[1], r.thread[0]);
    EXPECT_NE(r.thread[1], r.thread[2]);
  }
  EXPECT_THROW(team.run(5, [](void*, int k) { if (k == 4) throw std::runtime_error("task 4"); }, nullptr),
               std::runtime_error);
  int ok = 0;
  team.run(1, [](void* c, int) { ++*static_cast<int*>(c); }, &ok);  // usable after an exception
  EXPECT_EQ(ok, 1);
  EXPECT_THROW(ElementTeam(1), std::invalid_argument);
}

TEST(ElementTeam, ARunUpGivesTheSameNumbersOnOneAndTwoThreads) {
  // Floating rings (two elements, each two Reynolds films), 0 -> 6,000 rpm in 0.05 s: every sample identical.
  const MachineSpec spec =
      load_model(testing::source_dir() + "/examples/reference_floating_ring.toml",
                 {{"speed.end", "6000 rpm"}, {"speed.duration", "0.05"}});
  const auto model = make_runup_model(spec);
  RunupOptions o = runup_options(spec);
  o.threads = 1;
  const RunupResult one = simulate_runup(*model, o);
  o.threads = 2;
  const RunupResult two = simulate_runup(*model, o);
  ASSERT_TRUE(one.complete);
  ASSERT_TRUE(two.complete);
  EXPECT_EQ(one.stats.steps, two.stats.steps);
  EXPECT_EQ(one.time, two.time);
  EXPECT_EQ(one.columns, two.columns);
}

}  // namespace
}  // namespace turbodyn

// A small team of threads that evaluates the force elements of one right-hand side (or Jacobian) side by side, for
// one long run on several cores. Task k always runs on thread k % threads() (thread 0 is the caller), and the
// caller adds the results up in element order afterwards, so the numbers do not depend on the thread count. The
// workers wait by spinning (then yielding) between calls: no allocation and no system call per call. Meant for a
// single run; a parameter study already puts one run on each core and keeps one thread per run.
#pragma once

#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace turbodyn {

class ElementTeam {
 public:
  /// threads >= 2: the caller and threads - 1 workers.
  explicit ElementTeam(int threads);
  ~ElementTeam();
  ElementTeam(const ElementTeam&) = delete;
  ElementTeam& operator=(const ElementTeam&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// Runs fn(context, k) for k = 0 .. n - 1, task k on thread k % threads(), and returns when all have finished.
  /// An exception thrown by a task is rethrown here (the first one, by task order of the threads).
  void run(int n, void (*fn)(void*, int), void* context);

 private:
  void work(int id);
  std::vector<std::thread> workers_;
  std::atomic<long> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<bool> stop_{false};
  int n_ = 0;
  void (*fn_)(void*, int) = nullptr;
  void* context_ = nullptr;
  std::vector<std::exception_ptr> errors_;  // one per thread
};

}  // namespace turbodyn

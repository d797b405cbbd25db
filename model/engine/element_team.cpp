#include "model/engine/element_team.h"

#include <stdexcept>

namespace turbodyn {

namespace {

// Waits until `ready()` holds: spins a while (the usual wait is a film solve, tens of microseconds), then yields.
template <class Ready>
void wait_until(Ready ready) {
  for (int i = 0; !ready(); ++i)
    if (i > 2000) std::this_thread::yield();
}

}  // namespace

ElementTeam::ElementTeam(int threads) : errors_(static_cast<std::size_t>(threads > 1 ? threads : 1)) {
  if (threads < 2) throw std::invalid_argument("ElementTeam: needs at least 2 threads");
  for (int id = 1; id < threads; ++id) workers_.emplace_back([this, id] { work(id); });
}

ElementTeam::~ElementTeam() {
  stop_.store(true, std::memory_order_release);
  generation_.fetch_add(1, std::memory_order_acq_rel);
  for (std::thread& t : workers_) t.join();
}

void ElementTeam::work(int id) {
  long seen = 0;
  for (;;) {
    wait_until([&] { return generation_.load(std::memory_order_acquire) != seen; });
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_acquire)) return;
    try {
      for (int k = id; k < n_; k += threads()) fn_(context_, k);
    } catch (...) {
      errors_[static_cast<std::size_t>(id)] = std::current_exception();
    }
    pending_.fetch_sub(1, std::memory_order_acq_rel);
  }
}

void ElementTeam::run(int n, void (*fn)(void*, int), void* context) {
  n_ = n;
  fn_ = fn;
  context_ = context;
  pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_acq_rel);  // publishes n_, fn_, context_ to the workers
  try {
    for (int k = 0; k < n; k += threads()) fn(context, k);
  } catch (...) {
    errors_[0] = std::current_exception();
  }
  wait_until([&] { return pending_.load(std::memory_order_acquire) == 0; });
  for (std::exception_ptr& e : errors_)
    if (e) {
      const std::exception_ptr first = e;
      for (std::exception_ptr& x : errors_) x = nullptr;
      std::rethrow_exception(first);
    }
}

}  // namespace turbodyn

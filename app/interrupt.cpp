#include "app/interrupt.h"

#include <csignal>
#include <iomanip>
#include <sstream>

namespace turbodyn::app {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_stop_signal(int) { g_interrupted.store(true); }

}  // namespace

InterruptGuard::InterruptGuard() {
  g_interrupted.store(false);
  previous_int_ = std::signal(SIGINT, on_stop_signal);
  previous_term_ = std::signal(SIGTERM, on_stop_signal);  // a scheduler's stop: the same orderly end as Ctrl-C
}

InterruptGuard::~InterruptGuard() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

const std::atomic<bool>* InterruptGuard::flag() { return &g_interrupted; }

std::string format_duration(double seconds) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << (seconds < 120 ? seconds : seconds / 60.0)
     << (seconds < 120 ? " s" : " min");
  return os.str();
}

}  // namespace turbodyn::app

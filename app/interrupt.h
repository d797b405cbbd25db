// What the commands share about stopping early and telling the time: Ctrl-C and SIGTERM as one flag that the
// engine and the study loops poll, the exit codes, and durations in progress lines.
#pragma once

#include <atomic>
#include <string>

namespace turbodyn::app {

inline constexpr int kExitIncomplete = 3;     ///< the integrator gave up (results so far written)
inline constexpr int kExitInterrupted = 130;  ///< SIGINT or SIGTERM (results so far written)

/// While alive, SIGINT and SIGTERM set flag() instead of ending the program (the previous handlers come back when
/// it goes, also when a command throws). One at a time: the commands do not nest.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// Set by the signal; cleared when a guard is made.
  static const std::atomic<bool>* flag();
  static bool interrupted() { return flag()->load(); }

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

/// "12.3 s" below two minutes, else "4.5 min".
std::string format_duration(double seconds);

}  // namespace turbodyn::app

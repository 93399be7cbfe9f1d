#pragma once

// Ctrl-C (SIGINT) or SIGTERM stops a tool that writes an output between two steps of its work, along
// the path an error takes, so that what it was writing under a temporary name (OutputInProgress,
// build_map's OUTPUT.part) is removed; the signals' default action would leave it behind. A second
// signal, of either kind, ends the tool at once.

#include <signal.h>

#include <csignal>
#include <stdexcept>
#include <string>

namespace mrs_vpr {
namespace tools {

/// Thrown by stopIfInterrupted(). runTool() exits with 128 + the signal's number, as shells report a
/// process a signal ended.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal_number)
      : std::runtime_error(std::string("interrupted by ") + (signal_number == SIGINT ? "SIGINT" : "SIGTERM")),
        signal_number_(signal_number) {}
  int signalNumber() const { return signal_number_; }

 private:
  int signal_number_;
};

namespace detail {
inline volatile std::sig_atomic_t g_interruption = 0;
/// Which of SIGINT and SIGTERM catchInterruptions() caught: set before any can arrive, then only read.
inline volatile std::sig_atomic_t g_caught_int = 0;
inline volatile std::sig_atomic_t g_caught_term = 0;
inline void noteInterruption(int signal_number) {
  g_interruption = signal_number;
  // Either signal from now on takes its default action (std::signal is async-signal-safe).
  if (g_caught_int != 0) std::signal(SIGINT, SIG_DFL);
  if (g_caught_term != 0) std::signal(SIGTERM, SIG_DFL);
}
}  // namespace detail

/// From now on a first SIGINT or SIGTERM is only noted, for stopIfInterrupted(); the handler then
/// gives way to the default action, so that a second signal, of either kind, ends the tool at once. A
/// signal the tool was started to ignore (nohup, a shell's background job) stays ignored.
inline void catchInterruptions() {
  struct sigaction action {};
  action.sa_handler = detail::noteInterruption;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);  // One handler at a time: the first signal is the one noted.
  sigaddset(&action.sa_mask, SIGTERM);
  // SA_RESTART: a read or write under way completes, and the tool stops after its step.
  action.sa_flags = SA_RESTART;
  for (const int signal_number : {SIGINT, SIGTERM}) {
    struct sigaction inherited {};
    sigaction(signal_number, nullptr, &inherited);
    if (inherited.sa_handler == SIG_IGN) continue;
    (signal_number == SIGINT ? detail::g_caught_int : detail::g_caught_term) = 1;
    sigaction(signal_number, &action, nullptr);
  }
}

/// Throws Interrupted when a signal caught by catchInterruptions() has come.
inline void stopIfInterrupted() {
  if (detail::g_interruption != 0) throw Interrupted(detail::g_interruption);
}

}  // namespace tools
}  // namespace mrs_vpr

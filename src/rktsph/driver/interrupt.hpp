// SIGINT (Ctrl-C) and SIGTERM during a run: the handler only notes the signal; the run stops
// between two steps (Simulation's stop check), writes its probes, last fields and summary
// (status "interrupted") and the program exits with 128 + the signal (130, 143).
#pragma once

#include <csignal>
#include <string>

namespace rktsph {

class InterruptHandler {
 public:
  /// Installs the handler for SIGINT and SIGTERM (unless the signal is ignored, as in a shell's
  /// background job); the previous handlers come back on destruction. The handler resets itself
  /// (SA_RESETHAND), so a second Ctrl-C ends the program at once, the usual way out of a run that
  /// does not stop.
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  /// The signal received since installation, or 0.
  static int received_signal();
  /// "SIGINT received" / "SIGTERM received", or "" if none: a StopCheck for the run.
  static std::string stop_reason();

 private:
  struct sigaction previous_interrupt_ {};
  struct sigaction previous_terminate_ {};
};

}  // namespace rktsph

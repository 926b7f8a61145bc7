#include "rktsph/driver/interrupt.hpp"

namespace rktsph {

namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void note_signal(int signal_number) {
  received = signal_number;  // all a handler may safely do; the run loop does the rest
}

// A signal the parent chose to ignore (a shell's background job ignores SIGINT) stays ignored.
void install(int signal_number, struct sigaction& previous) {
  sigaction(signal_number, nullptr, &previous);
  if (previous.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;  // restart interrupted writes of result files
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

InterruptHandler::InterruptHandler() {
  received = 0;
  install(SIGINT, previous_interrupt_);
  install(SIGTERM, previous_terminate_);
}

InterruptHandler::~InterruptHandler() {
  sigaction(SIGINT, &previous_interrupt_, nullptr);
  sigaction(SIGTERM, &previous_terminate_, nullptr);
}

int InterruptHandler::received_signal() {
  return received;
}

std::string InterruptHandler::stop_reason() {
  switch (received) {
    case 0:
      return {};
    case SIGINT:
      return "SIGINT received";
    case SIGTERM:
      return "SIGTERM received";
    default:
      return "signal received";
  }
}

}  // namespace rktsph

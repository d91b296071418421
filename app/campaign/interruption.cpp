#include "interruption.hpp"

#include <csignal>

namespace dtwire::app {
namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void record_signal(int signal) { received = signal; }

}  // namespace

InterruptionGuard::InterruptionGuard() {
  received = 0;
  previous_int_ = std::signal(SIGINT, record_signal);
  previous_term_ = std::signal(SIGTERM, record_signal);
}

InterruptionGuard::~InterruptionGuard() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

int interruption_signal() { return received; }

}  // namespace dtwire::app

#pragma once
// Interrupting a campaign (Ctrl-C, SIGINT or SIGTERM to the runner's pid alone, as a batch
// system sends it): each step runs in its own process group (step_process.hpp), so the signal
// reaches a step's whole tree (a gap run and its `dem run`s) only through the runner, which
// passes it on, lets the steps stop (a fit saves its checkpoint on SIGINT), and starts nothing
// new; the state keeps every finished step, so the same command resumes.
namespace dtwire::app {

// While it lives, SIGINT and SIGTERM are only recorded (interruption_signal()); its end restores
// the previous handlers.
class InterruptionGuard {
 public:
  InterruptionGuard();
  ~InterruptionGuard();
  InterruptionGuard(const InterruptionGuard&) = delete;
  InterruptionGuard& operator=(const InterruptionGuard&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

// The signal received since the guard was installed (SIGINT or SIGTERM), or 0.
int interruption_signal();

}  // namespace dtwire::app

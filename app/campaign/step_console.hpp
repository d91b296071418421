#pragma once
// The campaign's console (stderr): one line when a step ends, with its time; with several steps
// side by side (--jobs > 1) also one when a step starts, each naming the steps still running.
// On a terminal a status line, rewritten in place, shows every running step's time and progress.
// Thread safe: the steps' workers report through it.
#include <mutex>
#include <string>
#include <vector>

namespace dtwire::app {

class StepConsole {
 public:
  explicit StepConsole(bool side_by_side);
  // `label` is "[3/12] name"; `name` the step's name.
  void started(const std::string& label, const std::string& name);
  void progress(const std::string& label, double seconds, const std::string& progress);
  // A step that did not run (skipped, blocked...) is finished without being started.
  void finished(const std::string& label, const std::string& message);

  static std::string seconds_text(double seconds);

 private:
  struct Running {
    std::string label, name, status;
  };
  std::string running_names() const;
  void redraw();

  std::mutex mutex_;
  const bool live_;          // stderr is a terminal
  const bool side_by_side_;
  std::vector<Running> running_;
};

}  // namespace dtwire::app

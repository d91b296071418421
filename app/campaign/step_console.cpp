#include "step_console.hpp"

#include <unistd.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace dtwire::app {
namespace {

constexpr std::size_t kWidth = 118;

std::string clip(const std::string& line) {
  return line.size() > kWidth ? line.substr(0, kWidth - 3) + "..." : line;
}

}  // namespace

StepConsole::StepConsole(bool side_by_side) : live_(::isatty(2) == 1), side_by_side_(side_by_side) {}

std::string StepConsole::seconds_text(double seconds) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(seconds < 10 ? 1 : 0) << seconds << " s";
  return s.str();
}

std::string StepConsole::running_names() const {
  std::string names;
  for (const auto& r : running_) names += (names.empty() ? "" : ", ") + r.name;
  return names;
}

// The status line: the one running step as "label: running 12 s, progress", several as
// "running: a 12 s, progress | b 3.0 s".
void StepConsole::redraw() {
  if (!live_ || running_.empty()) return;
  std::string line;
  if (running_.size() == 1) {
    line = running_.front().label + ": running " + running_.front().status;
  } else {
    line = "running:";
    for (const auto& r : running_) line += (line.size() > 8 ? " | " : " ") + r.name + " " + r.status;
  }
  std::cerr << "\r\033[K" << clip(line) << std::flush;
}

void StepConsole::started(const std::string& label, const std::string& name) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (side_by_side_) {
    const std::string others = running_names();
    std::cerr << (live_ ? "\r\033[K" : "") << label << ": started"
              << (others.empty() ? "" : " (also running: " + others + ")") << "\n";
  }
  running_.push_back({label, name, seconds_text(0.0)});
  redraw();
}

void StepConsole::progress(const std::string& label, double seconds, const std::string& progress) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto& r : running_)
    if (r.label == label) r.status = seconds_text(seconds) + (progress.empty() ? "" : ", " + progress);
  redraw();
}

void StepConsole::finished(const std::string& label, const std::string& message) {
  const std::lock_guard<std::mutex> lock(mutex_);
  running_.erase(std::remove_if(running_.begin(), running_.end(), [&](const Running& r) { return r.label == label; }),
                 running_.end());
  const std::string others = side_by_side_ ? running_names() : std::string();
  std::cerr << (live_ ? "\r\033[K" : "") << label << ": " << message
            << (others.empty() ? "" : " (still running: " + others + ")") << "\n";
  redraw();
}

}  // namespace dtwire::app

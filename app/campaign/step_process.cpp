#include "step_process.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <chrono>
#include <cstring>
#include <fstream>
#include <optional>
#include <regex>
#include <thread>

#include "dtwire/core/error.hpp"
#include "interruption.hpp"

extern char** environ;

namespace dtwire::app {
namespace {

// How long an interrupted step may take to stop (a fit writes its checkpoint) before it is killed.
constexpr std::chrono::seconds kGraceAfterInterruption{30};

std::string tail(const std::filesystem::path& file, std::size_t bytes = 8192) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(in.tellg());
  in.seekg(static_cast<std::streamoff>(size > bytes ? size - bytes : 0));
  std::string text(std::min(size, bytes), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  return text;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  if (start < text.size()) lines.push_back(text.substr(start));
  return lines;
}

// The progress a line shows in the patterns of fem's run.log and calibrate's fitter, or "".
std::string progress_of(const std::string& line) {
  static const std::regex fe(R"(^step (\d+): t = \S+ -> (\S+))");
  static const std::regex fit(R"(^fit start (\d+/\d+) iteration (\d+))");
  static const std::regex fit_state(R"(^fit start (\d+/\d+) (\w+))");
  std::smatch m;
  if (std::regex_search(line, m, fe)) return "FE step " + m[1].str() + ", t = " + m[2].str();
  if (std::regex_search(line, m, fit)) return "fit start " + m[1].str() + ", iteration " + m[2].str();
  if (std::regex_search(line, m, fit_state)) return "fit start " + m[1].str() + " " + m[2].str();
  return {};
}

}  // namespace

std::string last_line(const std::filesystem::path& file) {
  const auto lines = lines_of(tail(file, 2048));
  for (auto line = lines.rbegin(); line != lines.rend(); ++line)
    if (line->find_first_not_of(" \t\r") != std::string::npos) return *line;
  return {};
}

std::string step_progress(const std::vector<std::filesystem::path>& logs) {
  for (const auto& log : logs) {
    const auto lines = lines_of(tail(log));
    for (auto line = lines.rbegin(); line != lines.rend(); ++line)
      if (auto progress = progress_of(*line); !progress.empty()) return progress;
  }
  std::string fallback = logs.empty() ? std::string() : last_line(logs.front());
  if (fallback.size() > 60) fallback = fallback.substr(0, 57) + "...";
  return fallback;
}

int run_step_process(const std::filesystem::path& executable, const std::vector<std::string>& args,
                     const std::filesystem::path& log, const std::function<void(double)>& tick,
                     const std::function<void(int, bool)>& track) {
  // Everything the child needs is prepared here: between fork and exec it makes only system
  // calls (the runner has other threads, whose locks a forked child must not touch).
  std::vector<std::string> argv_text{executable.string()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log_name = log.string();
  int report[2];  // the child's exec error, if any; closed by a successful exec
  if (::pipe2(report, O_CLOEXEC) != 0)
    throw ComputationError("cannot start " + executable.string() + ": pipe: " + std::strerror(errno));
  const pid_t runner = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(report[0]);
    ::close(report[1]);
    throw ComputationError("cannot start " + executable.string() + ": fork: " + std::strerror(error));
  }
  if (pid == 0) {
    // Its own process group: a signal meant for the runner alone reaches the step's whole tree
    // only when the runner passes it on (interruption.hpp), and then all of it.
    ::setpgid(0, 0);
    // The step dies with the runner (killed by a scheduler or a closed terminal): SIGTERM when
    // the runner's thread that started it ends, which it does only after the step has ended.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    int error = 0;
    if (::getppid() != runner) error = ESRCH;  // the runner died before prctl took effect
    const int in = error ? -1 : ::open("/dev/null", O_RDONLY);
    const int out = error ? -1 : ::open(log_name.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (!error && (in < 0 || out < 0)) error = errno;
    if (!error && (::dup2(in, STDIN_FILENO) < 0 || ::dup2(out, STDOUT_FILENO) < 0 || ::dup2(out, STDERR_FILENO) < 0))
      error = errno;
    if (in > STDERR_FILENO) ::close(in);
    if (out > STDERR_FILENO) ::close(out);
    if (!error) {
      ::execve(argv[0], argv.data(), environ);
      error = errno;
    }
    if (::write(report[1], &error, sizeof error) < 0) { /* the runner reports a silent failure */ }
    ::_exit(127);
  }
  ::close(report[1]);
  ::setpgid(pid, pid);  // also from this side, so the group exists before it is signalled
  int child_error = 0;
  ssize_t got;
  do got = ::read(report[0], &child_error, sizeof child_error);
  while (got < 0 && errno == EINTR);
  ::close(report[0]);
  if (got == static_cast<ssize_t>(sizeof child_error)) {
    ::waitpid(pid, nullptr, 0);
    throw ComputationError("cannot start " + executable.string() + ": " +
                           (child_error == ESRCH ? std::string("the campaign runner is ending") : std::strerror(child_error)));
  }
  if (track) track(pid, true);
  struct Untrack {
    const std::function<void(int, bool)>& track;
    pid_t pid;
    ~Untrack() {
      if (track) track(pid, false);
    }
  } untrack{track, pid};

  const auto start = std::chrono::steady_clock::now();
  auto next_tick = start + std::chrono::seconds(1);
  int status = 0;
  std::optional<std::chrono::steady_clock::time_point> passed_on;  // when the interruption was passed on
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) throw ComputationError(std::string("waitpid: ") + std::strerror(errno));
    if (const int signal = interruption_signal(); signal != 0 && !passed_on) {
      ::kill(-pid, signal);
      passed_on = std::chrono::steady_clock::now();
    } else if (passed_on && std::chrono::steady_clock::now() - *passed_on > kGraceAfterInterruption) {
      ::kill(-pid, SIGKILL);  // a step that ignores the signal does not hold the campaign
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (const auto now = std::chrono::steady_clock::now(); now >= next_tick) {
      tick(std::chrono::duration<double>(now - start).count());
      next_tick = now + std::chrono::seconds(1);
    }
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace dtwire::app

#include <csignal>
#include <string>
#include <vector>

#include "cli.hpp"

int main(int argc, char** argv) {
  // Under a file-size limit (ulimit -f) a write past it fails with EFBIG ("File too large"),
  // which the writer reports with the file's name and exit code 1, instead of the default
  // SIGXFSZ that kills the process (and a campaign's steps inherit this).
  std::signal(SIGXFSZ, SIG_IGN);
  return dtwire::app::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}

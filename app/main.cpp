#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"

int main(int argc, char** argv) {
  // Under a file-size limit (ulimit -f) a write past it fails with EFBIG ("File too large"),
  // which the writer reports with the file's name and exit code 1, instead of the default
  // SIGXFSZ that kills the process (and a campaign's steps inherit this).
  std::signal(SIGXFSZ, SIG_IGN);
  // The runs a fit or a propagation starts are this binary's, whatever name it was copied to
  // (calibrate::dtwire_executable takes a binary named dtwire itself, else this variable; for
  // a copy under another name a value the user set is kept).
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) setenv("DTWIRE_EXECUTABLE", self.c_str(), 0);
  const int code = dtwire::app::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
  // What a command printed is part of its result (`parameters > file.prm`): a write that failed
  // (a full disk, /dev/full) is a failed command.
  std::fflush(stdout);
  if (!(std::cout << std::flush) || std::ferror(stdout)) {
    std::cerr << "dtwire: failed: the standard output: cannot write (" << std::strerror(errno) << ")\n";
    return code == 0 ? 1 : code;
  }
  return code;
}

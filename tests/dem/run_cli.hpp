#pragma once
// Runs the dtwire executable with arguments and captures its exit code and console output
// (stdout and stderr), for the dem run input tests.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace dtwire::dem::test {

struct CliOutcome {
  int code = 0;
  std::string output;
};

inline CliOutcome run_dtwire(const std::string& arguments) {
  const std::string command = std::string(DTWIRE_EXECUTABLE) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WEXITSTATUS(status), output};
}

}  // namespace dtwire::dem::test

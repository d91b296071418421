#include <string>
#include <vector>

#include "cli.hpp"

int main(int argc, char** argv) {
  return dtwire::app::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}

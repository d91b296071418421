#pragma once
// A simulator that runs an external program, e.g. an FE virtual experiment through
// `dtwire run` (fits (1) and (2) with FE in the loop, without linking deal.II into calibrate):
// the input template gets every {name} replaced by the parameter's value, the program runs in
// its own directory per evaluation (so runs can go in parallel), and the result CSV is read
// back. A non-zero exit status or a missing/bad result is a failed simulation
// (ComputationError); that run's directory is kept for diagnosis, successful ones are removed.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/calibrate/simulator.hpp"
#include "dtwire/core/prm_document.hpp"

namespace dtwire::calibrate {

struct CommandSpecification {
  std::filesystem::path program;      // executable
  std::vector<std::string> arguments; // {input} -> input file, {output} -> run directory
  std::string input_template;         // text with {name} placeholders
  std::string input_name = "input.prm";
  std::string result = "curve.csv";   // path of the result CSV inside the run directory
  std::filesystem::path work_directory;
  ParameterValues fixed;              // further placeholders
};

class CommandSimulator final : public Simulator {
 public:
  explicit CommandSimulator(CommandSpecification specification);
  Curve simulate(const ParameterValues& parameters) const override;
  std::string identity() const override;
  // The {placeholders} of the input template.
  std::vector<std::string> parameter_names() const override;

  // The input text for these values; throws ComputationError naming a placeholder without a
  // value.
  std::string instantiate(const ParameterValues& parameters) const;

 private:
  CommandSpecification spec_;
};

// `dtwire` itself when running inside it (/proc/self/exe), else $DTWIRE_EXECUTABLE, else
// "dtwire" from PATH.
std::filesystem::path dtwire_executable();

// The entries of an FE experiment .prm with their defaults, as `program parameters` lists them
// (a dtwire built with the FE solver); nothing for another program or one that cannot list them.
// Asked once per program.
std::optional<PrmDocument> program_parameters(const std::filesystem::path& program);

}  // namespace dtwire::calibrate

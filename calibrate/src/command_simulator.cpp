#include "dtwire/calibrate/command_simulator.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sys/wait.h>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::calibrate {
namespace {

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

std::optional<PrmDocument> program_parameters(const std::filesystem::path& program) {
  if (program.filename() != "dtwire") return std::nullopt;
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::optional<PrmDocument>> asked;
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto hit = asked.find(program); hit != asked.end()) return hit->second;
  const std::string command = shell_quote(program.string()) + " parameters 2>/dev/null";
  std::string listing;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    std::array<char, 4096> buffer{};
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) listing.append(buffer.data(), n);
    if (::pclose(pipe) != 0) listing.clear();
  }
  std::optional<PrmDocument> declared;
  if (!listing.empty()) declared = PrmDocument::parse(listing, program.string() + " parameters");
  return asked[program] = declared;
}

std::filesystem::path dtwire_executable() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error && self.filename() == "dtwire") return self;
  if (const char* env = std::getenv("DTWIRE_EXECUTABLE")) return env;
  return "dtwire";
}

CommandSimulator::CommandSimulator(CommandSpecification specification) : spec_(std::move(specification)) {}

std::string CommandSimulator::instantiate(const ParameterValues& parameters) const {
  ParameterValues all = spec_.fixed;
  for (const auto& [name, value] : parameters) all[name] = value;
  std::string text = spec_.input_template;
  for (const auto& [name, value] : all) text = replace_all(text, "{" + name + "}", format_number(value));
  static const std::regex placeholder(R"(\{[A-Za-z_][A-Za-z0-9_]*\})");
  std::smatch left;
  if (std::regex_search(text, left, placeholder))
    throw ComputationError("input template: no value for placeholder " + left.str());
  return text;
}

std::vector<std::string> CommandSimulator::parameter_names() const {
  static const std::regex placeholder(R"(\{([A-Za-z_][A-Za-z0-9_]*)\})");
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(spec_.input_template.begin(), spec_.input_template.end(), placeholder);
       it != std::sregex_iterator(); ++it)
    if (std::find(names.begin(), names.end(), (*it)[1].str()) == names.end()) names.push_back((*it)[1].str());
  return names;
}

Curve CommandSimulator::simulate(const ParameterValues& parameters) const {
  const std::string input = instantiate(parameters);
  const auto run = spec_.work_directory / sha256_text(identity() + "\n" + input).substr(0, 24);
  std::filesystem::remove_all(run);
  std::filesystem::create_directories(run);
  const auto input_file = run / spec_.input_name;
  std::ofstream(input_file) << input;
  std::string command = shell_quote(spec_.program.string());
  for (const auto& argument : spec_.arguments)
    command += " " + shell_quote(replace_all(replace_all(argument, "{input}", input_file.string()),
                                             "{output}", run.string()));
  command += " > " + shell_quote((run / "command.log").string()) + " 2>&1";
  const int status = std::system(command.c_str());
  const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (exit_code != 0)
    throw ComputationError("command failed (exit " + std::to_string(exit_code) + "), see " +
                           (run / "command.log").string());
  Curve curve;
  try {
    curve = read_csv(run / spec_.result);
  } catch (const InputError& error) {
    throw ComputationError(std::string("no usable result: ") + error.what());
  }
  std::filesystem::remove_all(run);
  return curve;
}

std::string CommandSimulator::identity() const {
  std::string text = "command program=" + spec_.program.filename().string() + " args=";
  for (const auto& a : spec_.arguments) text += a + " ";
  text += "\nresult=" + spec_.result + "\ntemplate:\n" + spec_.input_template + "\nfixed:";
  for (const auto& [name, value] : spec_.fixed) text += " " + name + "=" + format_number(value);
  return text;
}

}  // namespace dtwire::calibrate

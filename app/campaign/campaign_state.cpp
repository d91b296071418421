#include "campaign_state.hpp"

#include <algorithm>
#include <fstream>
#include <iostream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {
namespace {

std::filesystem::path state_path(const std::filesystem::path& out) { return out / "campaign_state.json"; }

}  // namespace

nlohmann::json load_state(const std::filesystem::path& out) {
  const auto path = state_path(out);
  if (!std::filesystem::exists(path)) return nlohmann::json::object();
  std::ifstream in(path);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    std::cerr << "campaign: ignoring unreadable state " << path << " (" << e.what() << ")\n";
    return nlohmann::json::object();
  }
}

void save_state(const std::filesystem::path& out, const nlohmann::json& state) {
  write_file_atomically(state_path(out), [&](std::ostream& stream) { stream << state.dump(2) << "\n"; });
}

std::string step_fingerprint(const std::vector<std::string>& command, const std::vector<std::string>& inputs) {
  std::string text = std::string("dtwire ") + tool_version() + "\n";
  for (const auto& arg : command) text += arg + '\0';
  for (const auto& input : inputs) text += "\n" + input + " " + sha256_file(input);
  return sha256_text(text);
}

bool outputs_exist(const std::vector<std::string>& outputs) {
  return std::all_of(outputs.begin(), outputs.end(),
                     [](const std::string& o) { return std::filesystem::exists(o); });
}

bool is_within(const std::filesystem::path& path, const std::filesystem::path& folder) {
  const auto p = std::filesystem::absolute(path).lexically_normal().string();
  const auto f = std::filesystem::absolute(folder).lexically_normal().string();
  return p.compare(0, f.size(), f) == 0;
}

}  // namespace dtwire::app

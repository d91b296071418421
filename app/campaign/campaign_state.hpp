#pragma once
// What a campaign remembers between runs ({out}/campaign_state.json): per step its status,
// fingerprint (tool version, command, inputs' SHA-256), wall time, start offset and log, so that
// a resumed campaign skips the steps that are up to date.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace dtwire::app {

// {} if there is no state; an unreadable state is ignored with a note on stderr.
nlohmann::json load_state(const std::filesystem::path& out);
void save_state(const std::filesystem::path& out, const nlohmann::json& state);

// SHA-256 of the tool version, the expanded command and the inputs' contents.
std::string step_fingerprint(const std::vector<std::string>& command, const std::vector<std::string>& inputs);

bool outputs_exist(const std::vector<std::string>& outputs);

// True if `path` lies inside `folder` (both made absolute, lexically normalised).
bool is_within(const std::filesystem::path& path, const std::filesystem::path& folder);

}  // namespace dtwire::app

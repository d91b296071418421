#include "campaign_file.hpp"

#include <toml++/toml.h>

#include <set>

#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

[[noreturn]] void fail(const std::string& file, const toml::node* node, const std::string& message) {
  if (node) {
    const auto& where = node->source().begin;
    throw InputError(file, static_cast<int>(where.line), static_cast<int>(where.column), message);
  }
  throw InputError(file, message);
}

std::vector<std::string> string_list(const std::string& file, const toml::table& step,
                                     const std::string& key, bool required) {
  const toml::node* node = step.get(key);
  if (!node) {
    if (required) fail(file, &step, "step lacks '" + key + "', expected an array of strings");
    return {};
  }
  const toml::array* array = node->as_array();
  if (!array) fail(file, node, "'" + key + "' must be an array of strings");
  std::vector<std::string> out;
  for (const toml::node& element : *array) {
    const auto* text = element.as_string();
    if (!text) fail(file, &element, "'" + key + "' must contain only strings");
    out.push_back(text->get());
  }
  return out;
}

}  // namespace

Campaign read_campaign(const std::filesystem::path& file) {
  const std::string source = file.string();
  if (std::filesystem::is_directory(file))
    throw InputError(source, "is a directory, expected a campaign .toml file");
  if (!std::filesystem::exists(file)) throw InputError(source, "no such file");
  toml::table root;
  try {
    root = toml::parse_file(source);
  } catch (const toml::parse_error& e) {
    throw InputError(source, static_cast<int>(e.source().begin.line),
                     static_cast<int>(e.source().begin.column), std::string(e.description()));
  }
  Campaign campaign;
  campaign.file = file;
  campaign.name = root["name"].value_or(file.stem().string());
  campaign.title = root["title"].value_or(campaign.name);
  const toml::node* steps = root.get("step");
  if (!steps || !steps->is_array_of_tables())
    fail(source, steps, "expected one or more [[step]] tables");
  std::set<std::string> names;
  for (const toml::node& node : *steps->as_array()) {
    const toml::table& table = *node.as_table();
    CampaignStep step;
    const auto name = table["name"].value<std::string>();
    if (!name || name->empty()) fail(source, &table, "step lacks 'name', expected a string");
    for (char c : *name)
      if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
        fail(source, table.get("name"), "step name '" + *name + "' may use only a-z, 0-9 and _");
    if (!names.insert(*name).second)
      fail(source, table.get("name"), "duplicate step name '" + *name + "'");
    step.name = *name;
    step.description = table["description"].value_or(std::string());
    step.command = string_list(source, table, "command", true);
    if (step.command.empty()) fail(source, table.get("command"), "'command' must not be empty");
    step.inputs = string_list(source, table, "inputs", false);
    step.outputs = string_list(source, table, "outputs", false);
    step.report = string_list(source, table, "report", false);
    campaign.steps.push_back(std::move(step));
  }
  return campaign;
}

std::string expand(const std::string& text, const std::filesystem::path& out,
                   const std::filesystem::path& campaign_dir) {
  std::string result = text;
  const auto replace_all = [&](const std::string& key, const std::string& value) {
    for (auto pos = result.find(key); pos != std::string::npos; pos = result.find(key, pos + value.size()))
      result.replace(pos, key.size(), value);
  };
  replace_all("{out}", out.string());
  replace_all("{campaign}", campaign_dir.string());
  return result;
}

}  // namespace dtwire::app

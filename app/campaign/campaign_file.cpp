#include "campaign_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "campaign_graph.hpp"
#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {

// Throws InputError at the line of the step's `field` (or of the step).
[[noreturn]] void fail_at_step_field(const Campaign& campaign, const CampaignStep& step,
                                     const std::string& field, const std::string& message);

namespace {

const std::vector<std::string> kTopFields = {"name", "title", "include", "variables", "step"};
const std::vector<std::string> kStepFields = {"name",   "description", "command", "inputs",          "outputs",
                                              "report", "summary",     "threads", "expected_seconds"};
const std::vector<std::string> kBuiltInPlaceholders = {"out", "campaign"};

[[noreturn]] void fail(const std::string& file, const toml::node* node, const std::string& message) {
  if (node) {
    const auto& where = node->source().begin;
    throw InputError(file, static_cast<int>(where.line), static_cast<int>(where.column), message);
  }
  throw InputError(file, message);
}

std::string suggestion(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string close = closest_name(word, candidates);
  return close.empty() ? std::string() : " (did you mean '" + close + "'?)";
}

void refuse_unknown_fields(const std::string& file, const toml::table& table,
                           const std::vector<std::string>& known, const std::string& where) {
  for (const auto& [key, value] : table) {
    const std::string name(key.str());
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string expected;
    for (const auto& k : known) expected += (expected.empty() ? "" : ", ") + k;
    fail(file, &value, "unknown " + where + "field '" + name + "'" + suggestion(name, known) +
                           ", expected one of: " + expected);
  }
}

std::vector<std::string> string_list(const std::string& file, const toml::table& step, const std::string& key,
                                     bool required, const std::vector<std::string>& placeholders) {
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
    const std::string& value = text->get();
    // A {word} that is not a known placeholder is a typo, not a folder name.
    for (auto open = value.find('{'); open != std::string::npos; open = value.find('{', open + 1)) {
      const auto close = value.find('}', open);
      if (close == std::string::npos) break;
      const std::string word = value.substr(open + 1, close - open - 1);
      const bool identifier = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
      });
      if (identifier && std::find(placeholders.begin(), placeholders.end(), word) == placeholders.end()) {
        std::string expected;
        for (const auto& p : placeholders) expected += (expected.empty() ? "{" : ", {") + p + "}";
        fail(file, &element, "'" + key + "': unknown placeholder '{" + word + "}'" + suggestion(word, placeholders) +
                                 ", expected one of " + expected);
      }
    }
    out.push_back(value);
  }
  return out;
}

bool is_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
  });
}

// [variables]: name = "default value".
std::map<std::string, std::string> read_variables(const std::string& file, const toml::table& root) {
  std::map<std::string, std::string> variables;
  const toml::node* node = root.get("variables");
  if (!node) return variables;
  const toml::table* table = node->as_table();
  if (!table) fail(file, node, "'variables' must be a table of name = \"value\"");
  for (const auto& [key, value] : *table) {
    const std::string name(key.str());
    if (!is_name(name)) fail(file, &value, "variable name '" + name + "' may use only a-z, 0-9 and _");
    if (std::find(kBuiltInPlaceholders.begin(), kBuiltInPlaceholders.end(), name) != kBuiltInPlaceholders.end())
      fail(file, &value, "variable '" + name + "' would hide the built-in {" + name + "}");
    const auto* text = value.as_string();
    if (!text) fail(file, &value, "variable '" + name + "' must be a string (its default), e.g. \"false\"");
    variables[name] = text->get();
  }
  return variables;
}

// Every {out} input must be an output (or lie in an output folder) of an earlier step.
void check_graph(const Campaign& campaign) {
  for (auto step = campaign.steps.begin(); step != campaign.steps.end(); ++step)
    for (const std::string& input : step->inputs) {
      if (input.rfind("{out}", 0) != 0) continue;
      if (std::any_of(campaign.steps.begin(), step, [&](const CampaignStep& s) { return step_writes(s, input); }))
        continue;
      const auto later = std::find_if(step + 1, campaign.steps.end(),
                                      [&](const CampaignStep& s) { return step_writes(s, input); });
      fail_at_step_field(campaign, *step, "inputs",
                         "step '" + step->name + "': input '" + input + "' is written by no earlier step" +
                             (later != campaign.steps.end() ? " (step '" + later->name + "' writes it, after this one)"
                                                            : std::string()));
    }
}

}  // namespace

[[noreturn]] void fail_at_step_field(const Campaign& campaign, const CampaignStep& step,
                                     const std::string& field, const std::string& message) {
  const auto line = step.field_lines.find(field);
  const std::filesystem::path& file = step.file.empty() ? campaign.file : step.file;
  throw InputError(file.string(), line != step.field_lines.end() ? line->second : step.line, 0, message);
}

namespace {

Campaign read_campaign_file(const std::filesystem::path& file, std::vector<std::filesystem::path>& including);

// Resolves {campaign} in an included step's strings to its own file's folder.
void pin_campaign_folder(CampaignStep& step, const std::filesystem::path& folder) {
  const auto pin = [&](std::string& text) {
    const std::string key = "{campaign}";
    for (auto pos = text.find(key); pos != std::string::npos; pos = text.find(key, pos + folder.string().size()))
      text.replace(pos, key.size(), folder.string());
  };
  pin(step.description);
  for (auto* list : {&step.command, &step.inputs, &step.outputs, &step.report, &step.summary})
    for (auto& text : *list) pin(text);
}

// include = ["file.toml", ...]: the included campaigns' variables and steps, in order.
void read_includes(const std::string& source, const toml::table& root, Campaign& campaign,
                   std::vector<std::filesystem::path>& including) {
  const toml::node* node = root.get("include");
  if (!node) return;
  const toml::array* files = node->as_array();
  if (!files) fail(source, node, "'include' must be an array of campaign file paths (relative to this file)");
  for (const toml::node& element : *files) {
    const auto* text = element.as_string();
    if (!text) fail(source, &element, "'include' must contain only strings (campaign file paths)");
    const auto path = std::filesystem::absolute(campaign.file.parent_path() / text->get()).lexically_normal();
    if (std::find(including.begin(), including.end(), path) != including.end())
      fail(source, &element, "'include' of '" + text->get() + "' makes a cycle: that file includes this one");
    if (!std::filesystem::is_regular_file(path))
      fail(source, &element, "'include': no campaign file '" + path.string() + "'");
    Campaign included = read_campaign_file(path, including);
    for (CampaignStep& step : included.steps) {
      pin_campaign_folder(step, path.parent_path());
      campaign.steps.push_back(std::move(step));
    }
    for (const auto& [name, value] : included.variables) campaign.variables.emplace(name, value);
  }
}

Campaign read_campaign_file(const std::filesystem::path& file, std::vector<std::filesystem::path>& including) {
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
  refuse_unknown_fields(source, root, kTopFields, "");
  Campaign campaign;
  campaign.file = file;
  campaign.name = root["name"].value_or(file.stem().string());
  campaign.title = root["title"].value_or(campaign.name);
  including.push_back(std::filesystem::absolute(file).lexically_normal());
  read_includes(source, root, campaign, including);
  including.pop_back();
  for (const auto& [name, value] : read_variables(source, root)) {
    const auto known = campaign.variables.find(name);
    if (known != campaign.variables.end() && known->second != value)
      fail(source, root["variables"][name].node(), "variable '" + name + "' is declared by an included campaign with the default \"" +
                                              known->second + "\"; declare it once");
    campaign.variables[name] = value;
  }
  std::vector<std::string> placeholders = kBuiltInPlaceholders;
  for (const auto& [name, value] : campaign.variables) placeholders.push_back(name);
  const toml::node* steps = root.get("step");
  if (!steps || !steps->is_array_of_tables())
    fail(source, steps, "expected one or more [[step]] tables");
  std::set<std::string> names;
  for (const CampaignStep& step : campaign.steps) names.insert(step.name);
  for (const toml::node& node : *steps->as_array()) {
    const toml::table& table = *node.as_table();
    refuse_unknown_fields(source, table, kStepFields, "step ");
    CampaignStep step;
    const auto name = table["name"].value<std::string>();
    if (!name || name->empty()) fail(source, &table, "step lacks 'name', expected a string");
    if (!is_name(*name)) fail(source, table.get("name"), "step name '" + *name + "' may use only a-z, 0-9 and _");
    if (!names.insert(*name).second)
      fail(source, table.get("name"), "duplicate step name '" + *name + "'" +
                                          (std::any_of(campaign.steps.begin(), campaign.steps.end(),
                                                       [&](const CampaignStep& s) { return s.name == *name && s.file != file; })
                                               ? " (an included campaign has it)"
                                               : ""));
    step.name = *name;
    step.file = file;
    step.line = static_cast<int>(table.source().begin.line);
    for (const auto& [key, value] : table)
      step.field_lines[std::string(key.str())] = static_cast<int>(value.source().begin.line);
    step.description = table["description"].value_or(std::string());
    step.command = string_list(source, table, "command", true, placeholders);
    if (step.command.empty()) fail(source, table.get("command"), "'command' must not be empty");
    step.inputs = string_list(source, table, "inputs", false, placeholders);
    step.outputs = string_list(source, table, "outputs", false, placeholders);
    step.report = string_list(source, table, "report", false, placeholders);
    step.summary = string_list(source, table, "summary", false, placeholders);
    if (const toml::node* threads = table.get("threads")) {
      const auto count = threads->value<std::int64_t>();
      if (!threads->is_integer() || !count || *count < 1 || *count > 4096)
        fail(source, threads, "'threads' must be an integer from 1 to 4096 (the cores the step uses)");
      step.threads = static_cast<int>(*count);
    }
    if (const toml::node* expected = table.get("expected_seconds")) {
      const auto seconds = expected->value<double>();
      if (!(expected->is_integer() || expected->is_floating_point()) || !seconds || !std::isfinite(*seconds) ||
          *seconds <= 0.0)
        fail(source, expected, "'expected_seconds' must be a number of seconds > 0 (the step's wall time as measured)");
      step.expected_seconds = *seconds;
    }
    campaign.steps.push_back(std::move(step));
  }
  check_graph(campaign);
  return campaign;
}

}  // namespace

Campaign read_campaign(const std::filesystem::path& file) {
  std::vector<std::filesystem::path> including;
  return read_campaign_file(file, including);
}

void check_commands(const Campaign& campaign, const std::vector<std::string>& known_commands) {
  for (const CampaignStep& step : campaign.steps) {
    const std::string& command = step.command.front();
    if (std::find(known_commands.begin(), known_commands.end(), command) != known_commands.end()) continue;
    std::string expected;
    for (const auto& k : known_commands) expected += (expected.empty() ? "" : ", ") + k;
    fail_at_step_field(campaign, step, "command",
                       "step '" + step.name + "': unknown dtwire command '" + command + "'" +
                           suggestion(command, known_commands) + ", expected one of: " + expected);
  }
}

void apply_variables(Campaign& campaign, const std::vector<std::string>& settings) {
  std::vector<std::string> names;
  for (const auto& [name, value] : campaign.variables) names.push_back(name);
  for (const auto& setting : settings) {
    const auto equals = setting.find('=');
    if (equals == std::string::npos || equals == 0)
      throw InputError("--var", "'" + setting + "': expected NAME=VALUE");
    const std::string name = setting.substr(0, equals);
    if (!campaign.variables.count(name)) {
      std::string expected;
      for (const auto& n : names) expected += (expected.empty() ? "" : ", ") + n;
      throw InputError("--var", "'" + name + "' is not a variable of " + campaign.file.string() +
                                    suggestion(name, names) + (expected.empty() ? " (it declares none)" : ", expected one of: " + expected));
    }
    campaign.variables[name] = setting.substr(equals + 1);
    campaign.overridden.push_back(name);
  }
  const auto substitute = [&](std::string& text) {
    for (const auto& [name, value] : campaign.variables) {
      const std::string key = "{" + name + "}";
      for (auto pos = text.find(key); pos != std::string::npos; pos = text.find(key, pos + value.size()))
        text.replace(pos, key.size(), value);
    }
  };
  for (auto& step : campaign.steps) {
    substitute(step.description);
    for (auto* list : {&step.command, &step.inputs, &step.outputs, &step.report, &step.summary})
      for (auto& text : *list) substitute(text);
  }
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

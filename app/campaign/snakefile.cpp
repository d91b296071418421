#include "snakefile.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "campaign_graph.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {
namespace {

// Snakemake formats every rule string (wildcards in paths, {input} in shell): literal braces
// are doubled. Then the text goes into a Python string literal.
std::string python_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '{' || c == '}') out += std::string(2, c);
    else if (c == '"' || c == '\\') out += std::string("\\") + c;
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out + "\"";
}

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool strictly_within(const std::string& path, const std::string& folder) { return path.rfind(folder + "/", 0) == 0; }

std::string rule_name(const std::string& step) {
  const bool plain = std::isalpha(static_cast<unsigned char>(step.front())) && step.rfind("dtwire_", 0) != 0;
  return plain ? step : "step_" + step;
}

class Writer {
 public:
  Writer(const Campaign& campaign, const SnakefileOptions& options)
      : campaign_(campaign),
        options_(options),
        campaign_dir_(std::filesystem::absolute(campaign.file).parent_path()) {}

  std::string text() {
    const auto campaign_file = std::filesystem::absolute(campaign_.file).lexically_normal().string();
    std::string run = "dtwire campaign " + campaign_file + " -o " + options_.out.string();
    for (const auto& v : options_.variables) run += " --var " + v;
    text_ << "# The campaign '" << campaign_.name << "' (" << campaign_file << ") as a Snakemake workflow,\n"
          << "# written by " << "dtwire " << tool_version() << ": `snakemake -s THIS_FILE --cores N` writes into\n"
          << "# " << options_.out.string() << " what `" << run << "` would.\n"
          << "# Regenerate it (dtwire campaign ... --snakefile) rather than edit it.\n\n";
    text_ << "rule dtwire_all:\n    input: " << python_string(out("report.md")) << "\n\n";
    const auto waits = step_dependencies(campaign_);
    for (std::size_t i = 0; i < campaign_.steps.size(); ++i) step_rule(campaign_.steps[i], waits[i]);
    report_rule();
    return text_.str();
  }

 private:
  std::string out(const std::string& relative) const { return (options_.out / relative).string(); }
  std::string marker(const CampaignStep& step) const { return out("steps/" + step.name + "/command.txt"); }
  std::string expand_text(const std::string& text) const { return expand(text, options_.out, campaign_dir_); }

  // A folder output (Snakemake's directory()): another step reads inside it, or it has no
  // file extension.
  bool is_folder(const std::string& output) const {
    if (std::filesystem::path(output).extension().empty()) return true;
    return std::any_of(campaign_.steps.begin(), campaign_.steps.end(), [&](const CampaignStep& s) {
      return std::any_of(s.inputs.begin(), s.inputs.end(), [&](const std::string& in) { return strictly_within(in, output); });
    });
  }

  // A {out} input inside a folder output is read through that folder.
  std::string rule_input(const std::string& input, const std::vector<std::size_t>& waits) const {
    for (std::size_t j : waits)
      for (const auto& output : campaign_.steps[j].outputs)
        if (strictly_within(input, output)) return expand_text(output);
    return expand_text(input);
  }

  void list(const std::string& field, const std::vector<std::string>& items) {
    text_ << "    " << field << ":";
    for (std::size_t k = 0; k < items.size(); ++k) text_ << (k ? ",\n        " : "\n        ") << items[k];
    text_ << "\n";
  }

  void step_rule(const CampaignStep& step, const std::vector<std::size_t>& waits) {
    std::vector<std::string> inputs, outputs;
    for (const auto& input : step.inputs) {
      const std::string item = python_string(rule_input(input, waits));
      if (std::find(inputs.begin(), inputs.end(), item) == inputs.end()) inputs.push_back(item);
    }
    for (std::size_t j : waits) inputs.push_back(python_string(marker(campaign_.steps[j])));
    for (const auto& output : step.outputs)
      outputs.push_back(is_folder(output) ? "directory(" + python_string(expand_text(output)) + ")"
                                          : python_string(expand_text(output)));
    outputs.push_back(python_string(marker(step)));
    const std::string folder = out("steps/" + step.name);
    std::string command = "dtwire", shell = shell_quote(options_.executable.string());
    for (const auto& argument : step.command) {
      command += " " + expand_text(argument);
      shell += " " + shell_quote(expand_text(argument));
    }
    shell = "printf '%s\\n' " + shell_quote(command) + " > " + shell_quote(marker(step)) + " && " + shell + " > " +
            shell_quote(folder + "/output.log") + " 2>&1";
    text_ << "rule " << rule_name(step.name) << ":\n";
    if (!inputs.empty()) list("input", inputs);
    list("output", outputs);
    text_ << "    log: " << python_string(folder + "/output.log") << "\n"
          << "    benchmark: " << python_string(folder + "/benchmark.tsv") << "\n"
          << "    threads: " << step.threads << "\n"
          << "    shell: " << python_string(shell) << "\n\n";
  }

  void report_rule() {
    std::vector<std::string> inputs;
    for (const CampaignStep& step : campaign_.steps) inputs.push_back(python_string(marker(step)));
    std::string shell = shell_quote(options_.executable.string()) + " campaign " +
                        shell_quote(std::filesystem::absolute(campaign_.file).lexically_normal().string()) + " -o " +
                        shell_quote(options_.out.string()) + " --report-only";
    for (const auto& v : options_.variables) shell += " --var " + shell_quote(v);
    text_ << "rule dtwire_report:\n";
    list("input", inputs);
    list("output", {python_string(out("report.md")), python_string(out("report.html")),
                    python_string(out("provenance.json"))});
    text_ << "    shell: " << python_string(shell) << "\n";
  }

  const Campaign& campaign_;
  const SnakefileOptions& options_;
  const std::filesystem::path campaign_dir_;
  std::ostringstream text_;
};

}  // namespace

std::string snakefile_text(const Campaign& campaign, const SnakefileOptions& options) {
  return Writer(campaign, options).text();
}

}  // namespace dtwire::app

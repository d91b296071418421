#include "command_input.hpp"

#include <fstream>
#include <sstream>

#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/prm_document.hpp"

namespace dtwire::calibrate {
namespace {

CommandSpecification from_template(const Table& x, CommandSpecification spec,
                                   const std::filesystem::path& template_file) {
  std::ifstream in(template_file);
  if (!in) x.fail(x.get("input_template"), "input_template", "cannot open " + template_file.string());
  std::ostringstream text;
  text << in.rdbuf();
  // {template_dir}: the template's own folder, for inputs next to it (e.g. a mesh file),
  // since the instantiated copy runs in the work directory.
  std::string template_text = text.str();
  const std::string template_folder = std::filesystem::absolute(template_file).parent_path().string();
  for (auto at = template_text.find("{template_dir}"); at != std::string::npos;
       at = template_text.find("{template_dir}", at + template_folder.size()))
    template_text.replace(at, 14, template_folder);
  spec.input_template = template_text;
  spec.input_name = template_file.stem().string();  // "sw_tension.prm.in" -> "sw_tension.prm"
  if (spec.input_name.empty()) spec.input_name = "input";
  return spec;
}

CommandSpecification from_prm(const Table& x, CommandSpecification spec, const std::filesystem::path& prm_file) {
  if (!std::filesystem::is_regular_file(prm_file))
    x.fail(x.get("input_prm"), "input_prm", "cannot open " + prm_file.string());
  PrmDocument document = PrmDocument::read(prm_file);  // InputError with the .prm's own file:line
  const std::optional<PrmDocument> declared = program_parameters(spec.program);
  if (declared) check_declared(document, *declared);
  std::vector<std::string> declared_paths;
  if (declared)
    for (const auto& entry : declared->entries()) declared_paths.push_back(entry.path);

  const toml::node* set = x.get("prm_set");
  if (set && !set->is_table()) x.fail(set, "prm_set", "expected a table of \"Section/Entry\" = value");
  if (set)
    for (const auto& [key, node] : *set->as_table()) {
      const std::string path(key.str());
      if (declared && !declared->find(path))
        x.fail(&node, "prm_set." + path,
               "no such entry in `" + spec.program.filename().string() + " parameters`" +
                   did_you_mean(path, declared_paths));
      std::string value;
      if (node.is_string()) value = node.as_string()->get();
      else if (node.is_boolean()) value = node.as_boolean()->get() ? "true" : "false";
      else value = format_number(x.number_of(&node, "prm_set." + path));
      document.set(path, value);
    }
  // The copy runs in the work directory: its mesh is found from the .prm's folder.
  if (const auto mesh = document.get("Geometry/Mesh file");
      mesh && !mesh->empty() && mesh->find('{') == std::string::npos && std::filesystem::path(*mesh).is_relative())
    document.set("Geometry/Mesh file", (std::filesystem::absolute(prm_file).parent_path() / *mesh).string());
  spec.input_template = document.text();
  spec.input_name = prm_file.filename().string();
  return spec;
}

}  // namespace

CommandSpecification command_experiment(const Table& x, CommandSpecification base,
                                        const std::function<std::filesystem::path(const std::string&)>& resolve,
                                        std::vector<std::filesystem::path>& inputs) {
  if (x.has("input_template") == x.has("input_prm"))
    x.fail(nullptr, "input_prm", "give either input_prm (with prm_set) or input_template");
  if (x.has("prm_set") && !x.has("input_prm")) x.fail(x.get("prm_set"), "prm_set", "needs input_prm");
  const std::string key = x.has("input_prm") ? "input_prm" : "input_template";
  const std::filesystem::path file = resolve(x.text(key));
  inputs.push_back(file);
  return key == "input_prm" ? from_prm(x, std::move(base), file) : from_template(x, std::move(base), file);
}

}  // namespace dtwire::calibrate

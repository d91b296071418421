#include "prm_check.hpp"

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::fem {
namespace {

struct Section {
  std::vector<std::string> subsections, entries;
};

// deal.II's whitespace rule for names: tabs are spaces, runs of spaces count as one.
std::string normalise(const std::string& text) {
  std::string s = std::regex_replace(text, std::regex("[ \t]+"), " ");
  return std::regex_replace(s, std::regex("^ | $"), "");
}

std::string join(const std::vector<std::string>& path) {
  std::string s;
  for (const auto& p : path) s += p + "/";
  return s;
}

// The declared tree, from deal.II's own short listing ("subsection X", "set Y = Z", "end").
std::map<std::string, Section> declared_tree(const dealii::ParameterHandler& prm) {
  std::ostringstream listing;
  prm.print_parameters(listing, dealii::ParameterHandler::ShortPRM);
  std::map<std::string, Section> tree;
  std::vector<std::string> path;
  std::istringstream in(listing.str());
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    line = normalise(line);
    if (std::regex_match(line, m, std::regex("subsection (.*)"))) {
      tree[join(path)].subsections.push_back(m[1]);
      path.push_back(m[1]);
    } else if (line == "end" && !path.empty()) {
      path.pop_back();
    } else if (std::regex_match(line, m, std::regex("set (.*?) ?=.*"))) {
      tree[join(path)].entries.push_back(m[1]);
    }
  }
  return tree;
}

std::string where(const std::vector<std::string>& path) {
  return path.empty() ? "at the top level" : "in subsection '" + join(path).substr(0, join(path).size() - 1) + "'";
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

EntryLines check_prm_names(const dealii::ParameterHandler& declared, const std::string& file) {
  const auto tree = declared_tree(declared);
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open the parameter file");
  EntryLines lines;
  std::vector<std::string> path;
  std::smatch m;
  int number = 0;
  for (std::string raw; std::getline(in, raw);) {
    const int first = ++number;
    while (!raw.empty() && raw.back() == '\\') {  // deal.II's line continuation
      raw.pop_back();
      std::string next;
      if (!std::getline(in, next)) break;
      raw += next;
      ++number;
    }
    const std::string line = normalise(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    const Section& here = tree.count(join(path)) ? tree.at(join(path)) : Section{};
    if (std::regex_match(line, m, std::regex("subsection (.+)"))) {
      const std::string name = m[1];
      if (!contains(here.subsections, name))
        throw InputError(file, first, 0,
                         "unknown subsection '" + name + "' " + where(path) + did_you_mean(name, here.subsections));
      path.push_back(name);
    } else if (line == "end") {
      if (path.empty()) throw InputError(file, first, 0, "'end' without a subsection to close");
      path.pop_back();
    } else if (std::regex_match(line, m, std::regex("set (.+?) ?= ?(.*)"))) {
      const std::string name = m[1];
      if (!contains(here.entries, name))
        throw InputError(file, first, 0, "unknown entry '" + name + "' " + where(path) + did_you_mean(name, here.entries));
      lines[join(path) + name] = first;
    } else if (line.rfind("include ", 0) != 0) {
      throw InputError(file, first, 0, "expected 'set Entry = value', 'subsection Name' or 'end', found '" + line + "'");
    }
  }
  if (!path.empty()) throw InputError(file, number, 0, "subsection '" + path.back() + "' is not closed by 'end'");
  if (lines.empty())
    throw InputError(file, "no 'set' line: an empty parameter file would run on the defaults alone");
  return lines;
}

}  // namespace dtwire::fem

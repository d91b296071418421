#include "dtwire/core/prm_document.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire {
namespace {

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// deal.II's rule for names and values: blanks trimmed, runs of blanks inside count as one space.
std::string normalise(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (blank(c)) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string trim(const std::string& text) {
  const auto first = std::find_if_not(text.begin(), text.end(), blank);
  const auto last = std::find_if_not(text.rbegin(), text.rend(), blank).base();
  return first < last ? std::string(first, last) : std::string();
}

std::string join(const std::vector<std::string>& parts, std::size_t count) {
  std::string out;
  for (std::size_t i = 0; i < count; ++i) out += (i ? "/" : "") + parts[i];
  return out;
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  for (std::string part; std::getline(in, part, '/');) parts.push_back(part);
  return parts;
}

bool starts_with_word(const std::string& line, const std::string& word) {
  return line.rfind(word, 0) == 0 && (line.size() == word.size() || line[word.size()] == ' ');
}

}  // namespace

std::optional<double> parse_number(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(value)) return std::nullopt;
  return value;
}

PrmDocument PrmDocument::parse(const std::string& text, const std::string& source) {
  PrmDocument document;
  document.source_ = source;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) document.lines_.push_back(line);
  document.reparse();
  return document;
}

PrmDocument PrmDocument::read(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot read the parameter file");
  std::stringstream text;
  text << in.rdbuf();
  // deal.II's ParameterHandler reads the file itself and would take the mark for a name.
  if (text.str().compare(0, 3, "\xEF\xBB\xBF") == 0)
    throw InputError(file.string(), 1, 1,
                     "the file starts with a UTF-8 byte-order mark (an editor's 'UTF-8 with BOM'); save it as "
                     "plain UTF-8 without the mark");
  return parse(text.str(), file.string());
}

void PrmDocument::reparse() {
  entries_.clear();
  subsections_.clear();
  spans_.clear();
  blocks_.clear();
  std::vector<std::string> path;
  std::vector<std::size_t> opened;  // line index of each open `subsection`
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    const std::size_t first = i;
    std::string logical = lines_[i];
    while (!logical.empty() && logical.back() == '\\' && i + 1 < lines_.size()) {
      logical.pop_back();
      logical += lines_[++i];
    }
    const int line_number = static_cast<int>(first) + 1;
    const std::string line = normalise(logical.substr(0, logical.find('#')));
    if (line.empty() || starts_with_word(line, "include")) continue;
    if (starts_with_word(line, "subsection")) {
      const std::string name = normalise(line.substr(10));
      if (name.empty()) throw InputError(source_, line_number, 0, "'subsection' without a name");
      path.push_back(name);
      opened.push_back(first);
      subsections_.push_back({join(path, path.size()), line_number});
    } else if (line == "end") {
      if (path.empty()) throw InputError(source_, line_number, 0, "'end' without a subsection to close");
      blocks_.push_back({join(path, path.size()), first});
      path.pop_back();
      opened.pop_back();
    } else if (starts_with_word(line, "set") && line.find('=') != std::string::npos) {
      const auto equals = line.find('=');
      const std::string name = normalise(line.substr(4, equals - 4));
      if (name.empty()) throw InputError(source_, line_number, 0, "'set' without an entry name");
      const std::string entry_path = path.empty() ? name : join(path, path.size()) + "/" + name;
      entries_.push_back({entry_path, trim(line.substr(equals + 1)), line_number});
      spans_.push_back({first, i});
    } else {
      throw InputError(source_, line_number, 0,
                       "expected 'set Entry = value', 'subsection Name' or 'end', found '" + line + "'");
    }
  }
  if (!path.empty())
    throw InputError(source_, static_cast<int>(opened.back()) + 1, 0,
                     "subsection '" + path.back() + "' is not closed by 'end'");
}

const PrmDocument::Entry* PrmDocument::find(const std::string& path) const {
  const std::string wanted = normalise(path);
  for (auto e = entries_.rbegin(); e != entries_.rend(); ++e)
    if (e->path == wanted) return &*e;
  return nullptr;
}

std::optional<std::string> PrmDocument::get(const std::string& path) const {
  if (const Entry* e = find(path)) return e->value;
  return std::nullopt;
}

std::string PrmDocument::value(const std::string& path, const PrmDocument* defaults) const {
  if (const Entry* e = find(path)) return e->value;
  if (defaults)
    if (const Entry* e = defaults->find(path)) return e->value;
  throw InputError(source_, "no entry '" + path + "' (and no default for it)");
}

double PrmDocument::number(const std::string& path, const PrmDocument* defaults) const {
  const Entry* e = find(path);
  const PrmDocument& owner = e || !defaults ? *this : *defaults;
  if (!e && defaults) e = defaults->find(path);
  if (!e) throw InputError(source_, "no entry '" + path + "' (and no default for it)");
  if (const auto number = parse_number(e->value)) return *number;
  throw InputError(owner.source_, e->line, 0, "'" + path + "': expected a number, found '" + e->value + "'");
}

std::size_t PrmDocument::end_of_section(const std::vector<std::string>& section) {
  if (section.empty()) return lines_.size();
  const std::string wanted = join(section, section.size());
  for (auto b = blocks_.rbegin(); b != blocks_.rend(); ++b)
    if (b->path == wanted) return b->end_index;
  // Missing: open it at the end of its parent, then look again.
  const std::vector<std::string> parent(section.begin(), section.end() - 1);
  const std::size_t at = end_of_section(parent);
  const std::string indent(2 * parent.size(), ' ');
  lines_.insert(lines_.begin() + static_cast<std::ptrdiff_t>(at),
                {indent + "subsection " + section.back(), indent + "end"});
  reparse();
  return at + 1;
}

void PrmDocument::set(const std::string& path, const std::string& value) {
  std::vector<std::string> parts = split_path(normalise(path));
  for (auto& part : parts) part = normalise(part);
  const std::string wanted = join(parts, parts.size());
  bool replaced = false;
  for (std::size_t k = entries_.size(); k-- > 0;) {  // from the back: erasing lines keeps earlier spans valid
    if (entries_[k].path != wanted) continue;
    const auto [first, last] = spans_[k];
    std::string logical;
    for (std::size_t i = first; i <= last; ++i) {
      std::string piece = lines_[i];
      if (i < last && !piece.empty() && piece.back() == '\\') piece.pop_back();
      logical += piece;
    }
    const auto comment = logical.find('#');
    std::string tail = comment == std::string::npos ? std::string() : logical.substr(comment);
    if (!tail.empty()) {  // keep the blanks before the comment
      std::size_t start = comment;
      while (start > 0 && blank(logical[start - 1])) --start;
      tail = logical.substr(start);
    }
    const std::string& head = lines_[first];
    std::size_t value_start = head.find('=') + 1;
    while (value_start < head.size() && blank(head[value_start])) ++value_start;
    lines_[first] = head.substr(0, value_start) + value + tail;
    lines_.erase(lines_.begin() + static_cast<std::ptrdiff_t>(first) + 1,
                 lines_.begin() + static_cast<std::ptrdiff_t>(last) + 1);
    replaced = true;
  }
  if (!replaced) {
    const std::vector<std::string> section(parts.begin(), parts.end() - 1);
    const std::size_t at = end_of_section(section);
    lines_.insert(lines_.begin() + static_cast<std::ptrdiff_t>(at),
                  std::string(2 * section.size(), ' ') + "set " + parts.back() + " = " + value);
  }
  reparse();
}

std::string PrmDocument::text() const {
  std::string out;
  for (const auto& line : lines_) out += line + "\n";
  return out;
}

void PrmDocument::write(const std::filesystem::path& file) const {
  write_file_atomically(file, [&](std::ostream& out) { out << text(); });
}

void check_declared(const PrmDocument& document, const PrmDocument& declared) {
  const auto where = [](const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? std::string("at the top level")
                                      : "in subsection '" + path.substr(0, slash) + "'";
  };
  const auto parent = [](const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash);
  };
  const auto leaf = [](const std::string& path) { return path.substr(path.rfind('/') + 1); };
  // The names declared directly under `section`.
  const auto declared_under = [&](const std::string& section, bool want_subsections) {
    std::vector<std::string> names;
    if (want_subsections) {
      for (const auto& s : declared.subsections())
        if (parent(s.path) == section) names.push_back(leaf(s.path));
    } else {
      for (const auto& e : declared.entries())
        if (parent(e.path) == section) names.push_back(leaf(e.path));
    }
    return names;
  };
  const auto known = [](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  // The first unknown name in file order.
  int line = 0;
  std::string message;
  const auto report = [&](int at, const std::string& what) {
    if (line == 0 || at < line) line = at, message = what;
  };
  for (const auto& s : document.subsections()) {
    const auto names = declared_under(parent(s.path), true);
    if (!known(names, leaf(s.path)))
      report(s.line, "unknown subsection '" + leaf(s.path) + "' " + where(s.path) + did_you_mean(leaf(s.path), names));
  }
  for (const auto& e : document.entries()) {
    const auto names = declared_under(parent(e.path), false);
    if (!known(names, leaf(e.path)))
      report(e.line, "unknown entry '" + leaf(e.path) + "' " + where(e.path) + did_you_mean(leaf(e.path), names));
  }
  if (line > 0) throw InputError(document.source(), line, 0, message);
}

}  // namespace dtwire

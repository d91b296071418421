#pragma once
// An experiment .prm file (deal.II ParameterHandler syntax: `subsection Name`, `set Entry =
// value  # comment`, `end`, `include`, trailing `\` continues a line) as a typed document:
// entries addressed as "Section/Sub/Entry", values read as text or checked numbers, edits that
// keep every other line and comment, and errors that name file:line. One reader for the FE
// solver's name check, `dtwire gap --model`'s effect edits and anything else that reads or
// writes an experiment. Names follow deal.II's rule: runs of blanks count as one space.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dtwire {

class PrmDocument {
 public:
  struct Entry {
    std::string path;   // "Section/Sub/Entry"
    std::string value;  // without comment and surrounding blanks
    int line = 0;       // 1-based first line of its `set`
  };
  struct Subsection {
    std::string path;  // "Section/Sub"
    int line = 0;      // its `subsection` line
  };

  // Throws InputError(source, line, ...) for a line that is none of set/subsection/end/include,
  // an `end` without a subsection, or a subsection left open.
  static PrmDocument parse(const std::string& text, const std::string& source);
  // InputError naming the file when it cannot be read.
  static PrmDocument read(const std::filesystem::path& file);

  const std::string& source() const { return source_; }
  const std::vector<Entry>& entries() const { return entries_; }
  const std::vector<Subsection>& subsections() const { return subsections_; }

  // The last `set` of `path` (deal.II: the last one wins), or nothing.
  const Entry* find(const std::string& path) const;
  std::optional<std::string> get(const std::string& path) const;
  // The value, else `defaults`' value (e.g. the solver's declarations), else an InputError.
  std::string value(const std::string& path, const PrmDocument* defaults = nullptr) const;
  // A finite number, else an InputError naming file:line, the entry and the text found.
  double number(const std::string& path, const PrmDocument* defaults = nullptr) const;

  // Replaces every `set` of `path` (keeping its comment), or adds one at the end of its
  // subsection, opening the subsections that are missing.
  void set(const std::string& path, const std::string& value);

  std::string text() const;
  // Written under a temporary name, then renamed into place.
  void write(const std::filesystem::path& file) const;

 private:
  void reparse();
  std::size_t end_of_section(const std::vector<std::string>& section);

  std::string source_;
  std::vector<std::string> lines_;
  std::vector<Entry> entries_;
  std::vector<Subsection> subsections_;
  std::vector<std::pair<std::size_t, std::size_t>> spans_;  // per entry: first and last line index
  struct Block {
    std::string path;
    std::size_t end_index;  // line index of its `end`
  };
  std::vector<Block> blocks_;
};

// Checks every subsection and entry of `document` against `declared` (a listing of the known
// names with their defaults, e.g. deal.II's ShortPRM output): InputError at the first unknown
// name with its file:line and the closest declared name.
void check_declared(const PrmDocument& document, const PrmDocument& declared);

// "1.5" -> 1.5; nothing for text that is not one finite number.
std::optional<double> parse_number(const std::string& text);

}  // namespace dtwire

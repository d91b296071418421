#include "dtwire/core/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire {
namespace {

struct Cell {
  std::string_view text;  // trimmed
  int column;             // 1-based character column of the cell start
};

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<Cell> split_cells(std::string_view line) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    const auto raw = line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    const auto lead = raw.find_first_not_of(" \t");
    cells.push_back({trim(raw), static_cast<int>(start + (lead == raw.npos ? 0 : lead)) + 1});
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

bool looks_numeric(std::string_view s) {
  double value = 0;
  const auto result = std::from_chars(s.data(), s.data() + s.size(), value);
  return result.ec == std::errc() && result.ptr == s.data() + s.size();
}

double parse_number(const Cell& cell, const std::string& source, int line) {
  if (cell.text.empty()) throw InputError(source, line, cell.column, "empty cell, expected a number");
  std::string_view text = cell.text;
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec == std::errc::result_out_of_range)
    throw InputError(source, line, cell.column,
                     "number '" + std::string(cell.text) + "' is out of range");
  if (result.ec != std::errc() || result.ptr != text.data() + text.size())
    throw InputError(source, line, cell.column,
                     "expected a number, found '" + std::string(cell.text) + "'");
  if (!std::isfinite(value))
    throw InputError(source, line, cell.column,
                     "non-finite value '" + std::string(cell.text) + "', expected a finite number");
  return value;
}

}  // namespace

Curve parse_csv(const std::string& text, const std::string& source) {
  Curve curve;
  std::vector<std::string> names;
  std::vector<Unit> units;
  std::vector<std::vector<double>> columns;
  bool header_seen = false;
  bool any_content = false;
  int line_number = 0;
  int last_line = 0;

  // A UTF-8 byte-order mark (spreadsheets' "CSV UTF-8") is not part of the first column's name.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  std::istringstream lines(text.compare(0, kByteOrderMark.size(), kByteOrderMark) == 0 ? text.substr(kByteOrderMark.size())
                                                                                         : text);
  std::string line_text;
  while (std::getline(lines, line_text)) {
    ++line_number;
    const std::string_view line = trim(line_text);
    if (line.empty()) continue;
    any_content = true;
    if (line.front() == '#') {
      if (header_seen) continue;  // comments after the header are allowed, metadata is not
      const std::string_view body = trim(line.substr(1));
      const auto colon = body.find(':');
      if (colon != std::string_view::npos && colon > 0)
        curve.set_metadata(std::string(trim(body.substr(0, colon))),
                           std::string(trim(body.substr(colon + 1))));
      continue;
    }
    const auto cells = split_cells(line);
    if (!header_seen) {
      header_seen = true;
      for (const Cell& cell : cells) {
        if (cell.text.empty())
          throw InputError(source, line_number, cell.column,
                           "empty column name in header, expected <quantity>_<unit>");
        if (looks_numeric(cell.text))
          throw InputError(source, line_number, cell.column,
                           "no header row: found the number '" + std::string(cell.text) +
                               "', expected column names such as displacement_mm,force_N");
        ColumnName column;
        try {
          column = parse_column_name(cell.text);
        } catch (const std::invalid_argument& e) {
          throw InputError(source, line_number, cell.column, e.what());
        }
        for (const auto& existing : names)
          if (existing == column.quantity)
            throw InputError(source, line_number, cell.column,
                             "duplicate quantity '" + column.quantity + "' in header");
        names.push_back(column.quantity);
        units.push_back(column.unit);
      }
      columns.resize(names.size());
      continue;
    }
    if (cells.size() != names.size())
      throw InputError(source, line_number, cells.back().column,
                       "ragged row: expected " + std::to_string(names.size()) + " cells, found " +
                           std::to_string(cells.size()));
    for (std::size_t c = 0; c < cells.size(); ++c)
      columns[c].push_back(parse_number(cells[c], source, line_number));
    last_line = line_number;
  }

  if (!any_content)
    throw InputError(source, 1, 1, "empty file, expected '# key: value' lines, a header row "
                                   "such as displacement_mm,force_N, and at least 3 data rows");
  if (!header_seen)
    throw InputError(source, line_number, 1,
                     "no header row, expected column names such as displacement_mm,force_N");
  const std::size_t rows = columns.front().size();
  if (rows < kMinimumCurvePoints)
    throw InputError(source, last_line > 0 ? last_line : line_number, 1,
                     "only " + std::to_string(rows) + " data row(s), expected at least " +
                         std::to_string(kMinimumCurvePoints));
  for (std::size_t c = 0; c < names.size(); ++c)
    curve.add_channel(names[c], units[c], std::move(columns[c]));
  return curve;
}

Curve read_csv(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError(source, "is a directory, expected a CSV file");
  if (!std::filesystem::exists(path, error)) throw InputError(source, "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(source, "cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_csv(buffer.str(), source);
}

std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string format_csv(const Curve& curve) {
  std::string out;
  for (const auto& [key, value] : curve.metadata_entries()) out += "# " + key + ": " + value + "\n";
  const auto& channels = curve.channels();
  for (std::size_t c = 0; c < channels.size(); ++c)
    out += (c ? "," : "") + channels[c].column_name();
  out += "\n";
  for (std::size_t i = 0; i < curve.size(); ++i) {
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const double v = channels[c].values[i];
      if (!std::isfinite(v))
        throw std::runtime_error("refusing to write non-finite value in channel '" +
                                 channels[c].column_name() + "' row " + std::to_string(i + 1));
      out += (c ? "," : "") + format_number(v);
    }
    out += "\n";
  }
  return out;
}

void write_csv(const Curve& curve, const std::filesystem::path& path) {
  const std::string text = format_csv(curve);  // validate fully before touching the disk
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace dtwire

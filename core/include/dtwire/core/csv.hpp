#pragma once
// Curve CSV files:
//   # key: value          (any number of metadata lines; '#' lines without ':' are comments)
//   displacement_mm,force_N
//   0,0
//   ...
// Column names are <quantity>_<unit> (units: see units.hpp). At least 3 data rows.
#include <filesystem>
#include <string>

#include "dtwire/core/curve.hpp"

namespace dtwire {

inline constexpr std::size_t kMinimumCurvePoints = 3;

// Throws InputError naming file:line:column and what was expected.
Curve read_csv(const std::filesystem::path& path);
// Parses CSV text; `source` names it in errors.
Curve parse_csv(const std::string& text, const std::string& source);

// Writes atomically (temporary file, then rename). Values in shortest round-trip form.
void write_csv(const Curve& curve, const std::filesystem::path& path);
std::string format_csv(const Curve& curve);

// Shortest text that reads back as exactly `value`.
std::string format_number(double value);

}  // namespace dtwire

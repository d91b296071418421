#pragma once
// Units understood in file columns (`<quantity>_<unit>`) and their factors to SI.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dtwire {

enum class Dimension { Length, Force, Stress, Time, Angle, Energy, Moment, Dimensionless, Velocity, ForcePerLength };

std::string_view dimension_name(Dimension dimension);

struct Unit {
  std::string symbol;   // as written in a column name, e.g. "mm"
  Dimension dimension;
  double to_si;         // value_si = value * to_si

  bool operator==(const Unit& other) const { return symbol == other.symbol; }
};

// The unit with this symbol, or nothing.
std::optional<Unit> find_unit(std::string_view symbol);
// The SI unit of a dimension (m, N, Pa, s, rad, J, N_m is written "Nm", 1).
Unit si_unit(Dimension dimension);
// Every known symbol, comma separated, for error messages.
std::string known_unit_symbols();
// value in `from` expressed in `to`; throws std::invalid_argument if the dimensions differ.
double convert(double value, const Unit& from, const Unit& to);

// A column name split at its last underscore: "displacement_mm" -> {"displacement", mm}.
struct ColumnName {
  std::string quantity;
  Unit unit;
  std::string text() const { return quantity + "_" + unit.symbol; }
};

// Throws std::invalid_argument with a message saying what was expected.
ColumnName parse_column_name(std::string_view name);

}  // namespace dtwire

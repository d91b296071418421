#include "dtwire/core/units.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace dtwire {
namespace {
constexpr double kPi = 3.14159265358979323846;

const std::vector<Unit>& unit_table() {
  static const std::vector<Unit> units = {
      {"m", Dimension::Length, 1.0},         {"mm", Dimension::Length, 1e-3},
      {"um", Dimension::Length, 1e-6},       {"N", Dimension::Force, 1.0},
      {"kN", Dimension::Force, 1e3},         {"Pa", Dimension::Stress, 1.0},
      {"MPa", Dimension::Stress, 1e6},       {"GPa", Dimension::Stress, 1e9},
      {"s", Dimension::Time, 1.0},           {"min", Dimension::Time, 60.0},
      {"rad", Dimension::Angle, 1.0},        {"deg", Dimension::Angle, kPi / 180.0},
      {"J", Dimension::Energy, 1.0},         {"mJ", Dimension::Energy, 1e-3},
      {"Nm", Dimension::Moment, 1.0},        {"Nmm", Dimension::Moment, 1e-3},
      {"1", Dimension::Dimensionless, 1.0},  {"pct", Dimension::Dimensionless, 1e-2},
      {"mps", Dimension::Velocity, 1.0},     {"mmps", Dimension::Velocity, 1e-3},  // m/s, mm/s
      // Force per unit width of a mesh strip, N/m and kN/m (no '_': a column splits at its last one).
      {"Npm", Dimension::ForcePerLength, 1.0}, {"kNpm", Dimension::ForcePerLength, 1e3},
  };
  return units;
}
}  // namespace

std::string_view dimension_name(Dimension dimension) {
  switch (dimension) {
    case Dimension::Length: return "length";
    case Dimension::Force: return "force";
    case Dimension::Stress: return "stress";
    case Dimension::Time: return "time";
    case Dimension::Angle: return "angle";
    case Dimension::Energy: return "energy";
    case Dimension::Moment: return "moment";
    case Dimension::Dimensionless: return "dimensionless";
    case Dimension::Velocity: return "velocity";
    case Dimension::ForcePerLength: return "force per length";
  }
  return "unknown";
}

std::optional<Unit> find_unit(std::string_view symbol) {
  for (const Unit& unit : unit_table())
    if (unit.symbol == symbol) return unit;
  return std::nullopt;
}

Unit si_unit(Dimension dimension) {
  for (const Unit& unit : unit_table())
    if (unit.dimension == dimension && unit.to_si == 1.0) return unit;
  throw std::logic_error("no SI unit for dimension");
}

std::string known_unit_symbols() {
  std::string list;
  for (const Unit& unit : unit_table()) list += (list.empty() ? "" : ", ") + unit.symbol;
  return list;
}

double convert(double value, const Unit& from, const Unit& to) {
  if (from.dimension != to.dimension)
    throw std::invalid_argument("cannot convert " + from.symbol + " (" +
                                std::string(dimension_name(from.dimension)) + ") to " + to.symbol +
                                " (" + std::string(dimension_name(to.dimension)) + ")");
  if (from.symbol == to.symbol) return value;
  return value * from.to_si / to.to_si;
}

ColumnName parse_column_name(std::string_view name) {
  const auto split = name.rfind('_');
  if (split == std::string_view::npos || split == 0 || split + 1 == name.size())
    throw std::invalid_argument("column name '" + std::string(name) +
                                "' is not of the form <quantity>_<unit> (e.g. displacement_mm)");
  const std::string_view symbol = name.substr(split + 1);
  const auto unit = find_unit(symbol);
  if (!unit)
    throw std::invalid_argument("unknown unit '" + std::string(symbol) + "' in column '" +
                                std::string(name) + "'; expected one of " + known_unit_symbols());
  return {std::string(name.substr(0, split)), *unit};
}

}  // namespace dtwire

#include "dtwire/calibrate/column_map.hpp"

#include <cmath>
#include <stdexcept>

#include "dtwire/core/csv.hpp"

namespace dtwire::calibrate {
namespace {

const ColumnMapping* mapping_for(const std::vector<ColumnMapping>& mapping, const std::string& quantity) {
  for (const auto& m : mapping)
    if (m.quantity == quantity) return &m;
  return nullptr;
}

std::string columns_of(const Curve& curve) {
  std::string list;
  for (const Channel& c : curve.channels()) list += (list.empty() ? "" : ", ") + c.column_name();
  return list;
}

void check(const std::vector<ColumnMapping>& mapping) {
  for (std::size_t i = 0; i < mapping.size(); ++i) {
    const ColumnMapping& m = mapping[i];
    if (!std::isfinite(m.factor) || m.factor == 0.0)
      throw std::invalid_argument("'" + m.quantity + "': the factor must be a finite number other than 0");
    for (std::size_t j = 0; j < i; ++j)
      if (mapping[j].quantity == m.quantity) throw std::invalid_argument("'" + m.quantity + "' is mapped twice");
  }
}

std::vector<double> scaled(std::vector<double> values, double factor) {
  for (double& v : values) v *= factor;
  return values;
}

}  // namespace

Curve map_columns(const Curve& target, const std::vector<ColumnMapping>& mapping) {
  check(mapping);
  Curve out;
  for (const Channel& c : target.channels())
    if (!mapping_for(mapping, c.quantity)) out.add_channel(c.quantity, c.unit, c.values);
  std::string note;
  for (const auto& m : mapping) {
    const Channel* source = target.find(m.column);
    if (!source)
      throw std::invalid_argument("'" + m.quantity + "': the target has no column '" + m.column +
                                  "_<unit>' (columns: " + columns_of(target) + ")");
    out.add_channel(m.quantity, source->unit, scaled(source->values, m.factor));
    note += (note.empty() ? "" : ", ") + m.quantity + " = " + source->column_name() +
            (m.factor == 1.0 ? "" : " x " + format_number(m.factor));
  }
  for (const auto& [key, value] : target.metadata_entries()) out.set_metadata(key, value);
  if (!note.empty()) out.set_metadata("columns", note);
  return out;
}

Curve unmap_columns(const Curve& simulated, const std::vector<ColumnMapping>& mapping) {
  check(mapping);
  for (std::size_t i = 0; i < mapping.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (mapping[j].column == mapping[i].column)
        throw std::invalid_argument("'" + mapping[i].quantity + "' and '" + mapping[j].quantity +
                                    "' are both read from column '" + mapping[i].column +
                                    "': the mapping cannot be inverted");
  Curve out;
  for (const Channel& c : simulated.channels()) {
    const ColumnMapping* m = mapping_for(mapping, c.quantity);
    const std::string name = m ? m->column : c.quantity;
    if (out.has(name))
      throw std::invalid_argument("column '" + name + "' would be written twice when inverting the mapping");
    out.add_channel(name, c.unit, m ? scaled(c.values, 1.0 / m->factor) : c.values);
  }
  for (const auto& [key, value] : simulated.metadata_entries()) out.set_metadata(key, value);
  return out;
}

}  // namespace dtwire::calibrate

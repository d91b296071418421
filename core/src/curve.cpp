#include "dtwire/core/curve.hpp"

#include <stdexcept>

namespace dtwire {

std::vector<double> Channel::si() const {
  std::vector<double> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i] * unit.to_si;
  return out;
}

std::vector<double> Channel::in(const Unit& target) const {
  std::vector<double> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = convert(values[i], unit, target);
  return out;
}

void Curve::add_channel(std::string quantity, const Unit& unit, std::vector<double> values) {
  if (!channels_.empty() && values.size() != size())
    throw std::invalid_argument("channel '" + quantity + "' has " + std::to_string(values.size()) +
                                " values, the curve has " + std::to_string(size()));
  if (has(quantity)) throw std::invalid_argument("duplicate channel '" + quantity + "'");
  channels_.push_back({std::move(quantity), unit, std::move(values)});
}

void Curve::add_channel_si(std::string quantity, Dimension dimension,
                           const std::vector<double>& si_values, const Unit& display_unit) {
  if (display_unit.dimension != dimension)
    throw std::invalid_argument("channel '" + quantity + "': unit " + display_unit.symbol +
                                " is not a " + std::string(dimension_name(dimension)));
  std::vector<double> values(si_values.size());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = si_values[i] / display_unit.to_si;
  add_channel(std::move(quantity), display_unit, std::move(values));
}

const Channel* Curve::find(std::string_view quantity) const {
  for (const Channel& c : channels_)
    if (c.quantity == quantity) return &c;
  return nullptr;
}

const Channel& Curve::channel(std::string_view quantity) const {
  if (const Channel* c = find(quantity)) return *c;
  std::string present;
  for (const Channel& c : channels_) present += (present.empty() ? "" : ", ") + c.column_name();
  throw std::invalid_argument("no channel '" + std::string(quantity) + "' (channels: " +
                              (present.empty() ? "none" : present) + ")");
}

void Curve::set_metadata(const std::string& key, const std::string& value) {
  for (auto& entry : metadata_)
    if (entry.first == key) {
      entry.second = value;
      return;
    }
  metadata_.emplace_back(key, value);
}

std::string Curve::metadata(std::string_view key) const {
  for (const auto& entry : metadata_)
    if (entry.first == key) return entry.second;
  return {};
}

bool Curve::operator==(const Curve& other) const {
  if (metadata_ != other.metadata_ || channels_.size() != other.channels_.size()) return false;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const Channel& a = channels_[i];
    const Channel& b = other.channels_[i];
    if (a.quantity != b.quantity || !(a.unit == b.unit) || a.values != b.values) return false;
  }
  return true;
}

}  // namespace dtwire

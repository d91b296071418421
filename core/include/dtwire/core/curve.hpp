#pragma once
// A curve: named channels (quantity + unit) of equal length, plus `key: value` metadata.
// Values are stored as written, in the channel's unit, so that files round-trip exactly;
// `si()` gives them in SI.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dtwire/core/units.hpp"

namespace dtwire {

struct Channel {
  std::string quantity;
  Unit unit;
  std::vector<double> values;

  std::string column_name() const { return quantity + "_" + unit.symbol; }
  std::vector<double> si() const;
  std::vector<double> in(const Unit& target) const;
};

class Curve {
 public:
  // Throws std::invalid_argument on a length mismatch or a duplicate quantity.
  void add_channel(std::string quantity, const Unit& unit, std::vector<double> values);
  void add_channel_si(std::string quantity, Dimension dimension, const std::vector<double>& si_values,
                      const Unit& display_unit);

  bool has(std::string_view quantity) const { return find(quantity) != nullptr; }
  const Channel* find(std::string_view quantity) const;
  // Throws std::invalid_argument naming the missing quantity and the ones present.
  const Channel& channel(std::string_view quantity) const;
  std::vector<double> si(std::string_view quantity) const { return channel(quantity).si(); }

  const std::vector<Channel>& channels() const { return channels_; }
  std::size_t size() const { return channels_.empty() ? 0 : channels_.front().values.size(); }

  void set_metadata(const std::string& key, const std::string& value);
  // Empty string if absent.
  std::string metadata(std::string_view key) const;
  const std::vector<std::pair<std::string, std::string>>& metadata_entries() const {
    return metadata_;
  }

  bool operator==(const Curve& other) const;

 private:
  std::vector<Channel> channels_;
  std::vector<std::pair<std::string, std::string>> metadata_;
};

}  // namespace dtwire

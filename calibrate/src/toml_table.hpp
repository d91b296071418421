#pragma once
// Reading the fields of one TOML table of a fit file, with errors at the field's file:line:column.
// Internal to calibrate/.
#include <toml++/toml.h>

#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {

// Reads fields of one TOML table and reports errors at the right place.
class Table {
 public:
  Table(const toml::table& table, std::string path, const std::string& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& what) const {
    const auto& where = node ? node->source() : table_.source();
    throw InputError(file_, static_cast<int>(where.begin.line), static_cast<int>(where.begin.column),
                     "field '" + field(key) + "': " + what);
  }
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const toml::node* get(const std::string& key) const { return table_.get(key); }
  bool has(const std::string& key) const { return table_.contains(key); }

  std::string text(const std::string& key, std::optional<std::string> fallback = std::nullopt) const {
    const toml::node* node = get(key);
    if (!node) {
      if (fallback) return *fallback;
      fail(nullptr, key, "missing (expected a string)");
    }
    if (!node->is_string()) fail(node, key, "expected a string");
    return node->as_string()->get();
  }
  double number(const std::string& key, std::optional<double> fallback = std::nullopt) const {
    const toml::node* node = get(key);
    if (!node) {
      if (fallback) return *fallback;
      fail(nullptr, key, "missing (expected a number)");
    }
    return number_of(node, key);
  }
  double number_of(const toml::node* node, const std::string& key) const {
    double value = 0;
    if (node->is_integer()) value = static_cast<double>(node->as_integer()->get());
    else if (node->is_floating_point()) value = node->as_floating_point()->get();
    else fail(node, key, "expected a number");
    if (!std::isfinite(value)) fail(node, key, "expected a finite number");
    return value;
  }
  long long integer(const std::string& key, long long fallback, long long minimum,
                    long long maximum = std::numeric_limits<long long>::max()) const {
    const toml::node* node = get(key);
    if (!node) return fallback;
    if (!node->is_integer()) fail(node, key, "expected an integer");
    const long long value = node->as_integer()->get();
    if (value < minimum) fail(node, key, "expected an integer >= " + std::to_string(minimum));
    if (value > maximum) fail(node, key, "expected an integer <= " + std::to_string(maximum));
    return value;
  }
  bool boolean(const std::string& key, bool fallback) const {
    const toml::node* node = get(key);
    if (!node) return fallback;
    if (!node->is_boolean()) fail(node, key, "expected true or false");
    return node->as_boolean()->get();
  }
  std::vector<double> numbers(const std::string& key) const {
    const toml::node* node = get(key);
    if (!node || !node->is_array()) fail(node, key, "expected an array of numbers");
    std::vector<double> out;
    for (const toml::node& item : *node->as_array()) out.push_back(number_of(&item, key));
    return out;
  }
  // Rejects keys outside `known` (typos must not be ignored silently).
  void only(const std::set<std::string>& known, const std::string& prefix_allowed = "") const {
    for (const auto& [key, node] : table_) {
      const std::string name(key.str());
      const bool prefixed = !prefix_allowed.empty() && name.rfind(prefix_allowed, 0) == 0;
      if (!known.count(name) && !prefixed) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        fail(&node, name, "unknown field (expected one of: " + list + ")");
      }
    }
  }

 private:
  const toml::table& table_;
  std::string path_;
  std::string file_;
};

}  // namespace dtwire::calibrate

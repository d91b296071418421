#pragma once
// Parameter files read by `dtwire dem driver` and `dtwire export` (formats in
// docs/dem_driver_export.md):
//   thesis:    {"single_wire": {name: number, ...}, "double_twist": {...}, ...}  (one set per
//              object; top-level strings such as "source" are ignored)
//   flat:      {"law": "wirepm", "wire_type": "sw", "parameters": {name: number, ...},
//               "backbone": {"strain_1": [...], "stress_Pa": [...]}}   (law, wire_type, backbone
//              optional)
//   calibrate: {"law": ..., "wire_type": ..., "parameters": [{"name", "value", "unit", "sigma"}]}
// Names carry their unit as a suffix ("N0_N"); a calibrate entry whose name lacks the suffix of
// a column unit symbol (units.hpp, not "1") gets it appended ("N0" + "N" -> "N0_N").
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"
#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

struct ParameterEntry {
  std::string name;
  double value = 0.0;
  std::string unit;  // SI symbol, "1" if dimensionless
  std::optional<double> sigma;
};

struct ParameterSet {
  std::string wire_type;  // "single_wire", "double_twist", or the file's wire_type ("default")
  std::string law;        // empty if the file does not say
  std::vector<ParameterEntry> entries;

  ParameterMap map() const;
  bool has(const std::string& name) const;
  // Replaces or appends.
  void set(const std::string& name, double value, const std::string& unit = "");
};

// Throws InputError naming the file and the JSON field for anything malformed.
std::vector<ParameterSet> read_parameter_file(const std::filesystem::path& file);
// The set named `wire_type`, or the only set if `wire_type` is empty; InputError otherwise.
ParameterSet select_wire_type(const std::vector<ParameterSet>& sets, const std::string& wire_type,
                              const std::filesystem::path& file);

// Refuses a name that `law` does not read (law_schema.hpp): InputError naming the file, the
// line where the name first appears in it, the wire type and the closest name the law reads.
void check_parameter_names(const ParameterSet& set, const std::string& law, const std::filesystem::path& file);

// A backbone CSV: a dimensionless strain column and a stress column (any stress unit), e.g.
// strain_1,stress_Pa. Throws InputError.
Curve read_backbone_csv(const std::filesystem::path& file);
// Adds backbone_<i>_strain_1 / backbone_<i>_stress_Pa entries (replacing any present).
void add_backbone(ParameterSet& set, const Curve& backbone);

// The unit of a parameter from its name suffix ("EA_N" -> "N"); "1" if none is recognised.
std::string parameter_unit(const std::string& name);

}  // namespace dtwire::dem

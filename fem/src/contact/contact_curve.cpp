#include "contact_curve.hpp"

#include <functional>
#include <string>

#include "dtwire/core/units.hpp"

namespace dtwire::fem::contact {

void add_contact_channels(Curve& curve, const std::vector<ContactRecord>& records) {
  const auto channel = [&](const std::string& name, Dimension dimension, const char* unit,
                           const std::function<double(const ContactRecord&)>& value) {
    std::vector<double> v;
    for (const auto& r : records) v.push_back(value(r));
    curve.add_channel_si(name, dimension, v, *find_unit(unit));
  };
  channel("contact_normal_force", Dimension::Force, "N", [](const ContactRecord& r) { return r.normal_force; });
  channel("contact_friction_force", Dimension::Force, "N", [](const ContactRecord& r) { return r.friction_force; });
  const char* axes[] = {"x", "y", "z"};
  for (std::size_t tool = 0; tool < records.front().tool_forces.size(); ++tool)
    for (unsigned k = 0; k < 3; ++k) {
      channel("tool" + std::to_string(tool + 1) + "_displacement_" + axes[k], Dimension::Length, "mm",
              [tool, k](const ContactRecord& r) { return r.tool_displacements[tool][k]; });
      channel("tool" + std::to_string(tool + 1) + "_force_" + axes[k], Dimension::Force, "N",
              [tool, k](const ContactRecord& r) { return r.tool_forces[tool][k]; });
    }
  channel("friction_dissipation", Dimension::Energy, "J", [](const ContactRecord& r) { return r.friction_dissipation; });
  channel("contact_energy", Dimension::Energy, "J", [](const ContactRecord& r) { return r.contact_energy; });
  channel("contact_max_pressure", Dimension::Stress, "MPa", [](const ContactRecord& r) { return r.max_pressure; });
  channel("contact_max_slip", Dimension::Length, "mm", [](const ContactRecord& r) { return r.max_slip; });
  channel("contact_max_penetration", Dimension::Length, "mm",
          [](const ContactRecord& r) { return r.max_penetration; });
}

void add_wire_contact_channels(Curve& curve, const std::vector<WireContactRecord>& records) {
  using R = WireContactRecord;
  const auto channel = [&](const std::string& name, Dimension dimension, const char* unit,
                           const std::function<double(const R&)>& value) {
    std::vector<double> v;
    for (const auto& r : records) v.push_back(value(r));
    curve.add_channel_si(name, dimension, v, *find_unit(unit));
  };
  channel("wire_contact_normal_force", Dimension::Force, "N", [](const R& r) { return r.normal_force; });
  channel("wire_contact_friction_force", Dimension::Force, "N", [](const R& r) { return r.friction_force; });
  channel("wire_friction_dissipation", Dimension::Energy, "J", [](const R& r) { return r.friction_dissipation; });
  channel("wire_contact_energy", Dimension::Energy, "J", [](const R& r) { return r.contact_energy; });
  channel("wire_contact_points", Dimension::Dimensionless, "1", [](const R& r) { return r.active_points; });
  channel("wire_contact_slipping_points", Dimension::Dimensionless, "1", [](const R& r) { return r.slipping_points; });
  channel("wire_contact_max_pressure", Dimension::Stress, "MPa", [](const R& r) { return r.max_pressure; });
  channel("wire_contact_max_slip", Dimension::Length, "mm", [](const R& r) { return r.max_slip; });
  channel("wire_contact_max_penetration", Dimension::Length, "mm", [](const R& r) { return r.max_penetration; });
}

void add_grip_channels(Curve& curve, const std::vector<GripRecord>& records) {
  const auto channel = [&](const std::string& name, Dimension dimension, const char* unit,
                           const std::function<double(const GripRecord&)>& value) {
    std::vector<double> v;
    for (const auto& r : records) v.push_back(value(r));
    curve.add_channel_si(name, dimension, v, *find_unit(unit));
  };
  channel("grip_bond_energy", Dimension::Energy, "J", [](const GripRecord& r) { return r.bond_energy; });
  channel("grip_slip_dissipation", Dimension::Energy, "J", [](const GripRecord& r) { return r.slip_dissipation; });
  channel("grip_max_slip", Dimension::Length, "mm", [](const GripRecord& r) { return r.max_slip; });
  channel("grip_slipping_fraction", Dimension::Dimensionless, "1",
          [](const GripRecord& r) { return r.slipping_fraction; });
}

}  // namespace dtwire::fem::contact

#pragma once
// Contact channels of the run's curve CSV / HDF5 (one row per converged step).
#include <vector>

#include "contact_record.hpp"
#include "dtwire/core/curve.hpp"

namespace dtwire::fem::contact {

// contact_normal_force_N, contact_friction_force_N, tool<k>_displacement_{x,y,z}_mm,
// tool<k>_force_{x,y,z}_N (force of the wire on tool k),
// friction_dissipation_J, contact_energy_J, contact_max_pressure_MPa, contact_max_slip_mm,
// contact_max_penetration_mm.
void add_contact_channels(Curve& curve, const std::vector<ContactRecord>& records);

// wire_contact_normal_force_N, wire_contact_friction_force_N (sum of |t_T| dA),
// wire_friction_dissipation_J, wire_contact_energy_J, wire_contact_points_1 (active slave Gauss
// points), wire_contact_slipping_points_1, wire_contact_max_pressure_MPa, wire_contact_max_slip_mm,
// wire_contact_max_penetration_mm.
void add_wire_contact_channels(Curve& curve, const std::vector<WireContactRecord>& records);

// Bonded grips: grip_bond_energy_J, grip_slip_dissipation_J, grip_max_slip_mm,
// grip_slipping_fraction_1 (share of the top grips' area slipping in the step).
void add_grip_channels(Curve& curve, const std::vector<GripRecord>& records);

}  // namespace dtwire::fem::contact

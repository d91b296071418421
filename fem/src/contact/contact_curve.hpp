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

}  // namespace dtwire::fem::contact

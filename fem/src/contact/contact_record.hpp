#pragma once
// Contact results of a converged load step (part of the solver's StepRecord). Light header:
// deal.II tensors only. Each record serialises itself (checkpoints, boost::serialization).
#include <array>
#include <vector>

#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

// One active contact point (this rank's points only), for tests and field output.
struct ContactSample {
  unsigned tool = 0;
  Vector3 reference_position, position;  // m
  double weight = 0.0;                    // reference area (m^2)
  double pressure = 0.0;                  // Pa
  double gap = 0.0;                       // m
  double slip = 0.0;                      // m, accumulated
  bool slipping = false;

  template <class Archive>
  void serialize(Archive& ar, const unsigned /*version*/) {
    ar& tool & reference_position & position & weight & pressure & gap & slip & slipping;
  }
};

// Contact results of a converged step. Totals are summed over MPI ranks and multiplied by the
// symmetry multipliers of the model (so that they refer to the whole wire, like StepRecord).
struct ContactRecord {
  bool enabled = false;
  double normal_force = 0.0;           // N, sum of p dA over all tools
  double friction_force = 0.0;         // N, |sum of t_T dA|
  std::vector<std::array<double, 3>> tool_displacements;  // m, prescribed, at the step's end
  std::vector<std::array<double, 3>> tool_forces;  // N, force of the wire on each tool (modelled part x multiplier)
  double friction_dissipation = 0.0;   // J, accumulated
  // J, energy stored in the penalty springs: normal -g (p + lambda_N) / 2 (= p^2 / (2 eps_N) without
  // augmentation) plus tangential |t_T|^2 / (2 eps_T). External work = elastic + plastic +
  // friction + this.
  double contact_energy = 0.0;
  double active_area = 0.0;            // m^2, reference area with p > 0
  double max_pressure = 0.0;           // Pa
  double max_slip = 0.0;               // m, accumulated, largest over the points
  double max_penetration = 0.0;        // m
  unsigned augmentations = 0;          // Uzawa updates in this step
  std::array<double, 3> bottom_reaction{}, top_reaction{};  // N, all components at the wire ends
  std::vector<ContactSample> samples;  // filled when keep_samples is set

  template <class Archive>
  void serialize(Archive& ar, const unsigned /*version*/) {
    ar& enabled & normal_force & friction_force & tool_displacements & tool_forces & friction_dissipation & contact_energy & active_area & max_pressure & max_slip & max_penetration & augmentations & bottom_reaction & top_reaction & samples;
  }
};

// Wire-wire contact results of a converged step (totals over ranks, symmetry multipliers applied).
struct WireContactRecord {
  bool enabled = false;
  double normal_force = 0.0;          // N, sum of p dA
  double friction_force = 0.0;        // N, sum of |t_T| dA (the tangential tractions point many ways)
  double friction_dissipation = 0.0;  // J, accumulated
  double contact_energy = 0.0;        // J, in the penalty springs (as ContactRecord)
  double active_area = 0.0;           // m^2, slave reference area with p > 0
  unsigned active_points = 0;         // slave Gauss points in contact
  unsigned slipping_points = 0;
  unsigned candidate_pairs = 0;       // slave face x master face pairs searched
  unsigned frozen_points = 0;         // chattering guard engaged in this step
  double max_pressure = 0.0, max_slip = 0.0, max_penetration = 0.0;  // Pa, m, m
  unsigned augmentations = 0;
  std::vector<ContactSample> samples;  // filled when keep_samples is set (tool = 0)

  template <class Archive>
  void serialize(Archive& ar, const unsigned /*version*/) {
    ar& enabled & normal_force & friction_force & friction_dissipation & contact_energy & active_area & active_points & slipping_points & candidate_pairs & frozen_points & max_pressure & max_slip & max_penetration & augmentations & samples;
  }
};

// Bonded grips (contact/bonded_grip.hpp) at a converged step: totals over ranks, symmetry
// multipliers applied.
struct GripRecord {
  bool enabled = false;
  double bond_energy = 0.0;        // J, elastic energy in the bond springs (both grips)
  double slip_dissipation = 0.0;   // J, accumulated tau_b x slip x area (top grips)
  double max_slip = 0.0;           // m, accumulated, largest over the top grips' points
  double slipping_fraction = 0.0;  // share of the top grips' bonded area that slipped in this step
  double top_area = 0.0;           // m^2, bonded area of the top grips (whole specimen)

  template <class Archive>
  void serialize(Archive& ar, const unsigned /*version*/) {
    ar& enabled & bond_energy & slip_dissipation & max_slip & slipping_fraction & top_area;
  }
};

}  // namespace dtwire::fem::contact

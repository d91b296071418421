#pragma once
// The record of one converged load step (what curve.csv and results.h5 hold), shared by the
// solver and the contact parts that fill their own columns.
#include <array>
#include <vector>

#include "contact/contact_record.hpp"

namespace dtwire::fem {

// One converged load step, in SI units and for the whole wire (symmetry multipliers applied).
struct StepRecord {
  unsigned step = 0;
  double time = 0.0;
  double displacement = 0.0;  // m, elongation of the whole specimen
  double force = 0.0;         // N, axial reaction
  double plastic_dissipation = 0.0;  // J
  double elastic_energy = 0.0;       // J
  double neck_radius = 0.0;          // m, smallest deformed radius in the imperfection plane
  unsigned iterations = 0;
  // Ductile failure indicator: its largest value and, at that point, triaxiality, Lode
  // parameter, height z and distance from the axis (reference configuration, m).
  double damage = 0.0, damage_triaxiality = 0.0, damage_lode = 0.0, damage_z = 0.0, damage_r = 0.0;
  contact::ContactRecord contact;  // contact (issue 5): enabled only with tools in the .prm
  contact::WireContactRecord wire_contact;  // enabled with `subsection Wire contact`
  contact::GripRecord grip;                 // enabled with Grip interface = bonded
  // Generalised results at the top end (whole model): force and moment of the specimen on the
  // top end's constraint, the moment about the end centre; translation of that centre and the
  // prescribed rotation (rad); external work of the end and the tools (J, trapezoidal rule).
  std::array<double, 3> end_force{}, end_moment{}, end_translation{};
  std::array<double, 3> end_centre{};  // m, current position of the centre the moment is about
  std::vector<std::array<double, 3>> probe_displacements;  // m, one per Output/Probe points entry
  double end_rotation = 0.0, external_work = 0.0;

  // Every field, so that a checkpoint cannot drop one (boost::serialization).
  template <class Archive>
  void serialize(Archive& ar, const unsigned /*version*/) {
    ar& step & time & displacement & force & plastic_dissipation & elastic_energy & neck_radius & iterations;
    ar& damage & damage_triaxiality & damage_lode & damage_z & damage_r;
    ar& contact & wire_contact & grip;
    ar& end_force & end_moment & end_translation & end_centre & probe_displacements & end_rotation & external_work;
  }
};

}  // namespace dtwire::fem

#pragma once
// Where a laboratory record ends: in a fracture (the force's terminal drop) or otherwise (a test
// stopped, a record cut short). A damage law runs on each fractured record's own clock to that
// record's end (docs/gap.md, "ductile_damage"); a record that did not break keeps the law's own
// clock.
#include <cstddef>
#include <vector>

#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {

// A fracture's drop: within the last kFractureWindow of the record's displacement range the
// force falls below kFractureRemainder of the largest force there, the displacement not going
// back. A neck does not lose three quarters of its force over 1 % of the travel (it thins
// gradually: the Voce model's neck takes a tenth of its travel to fall to 0.4 of the peak),
// and an unloading takes the displacement back; a broken specimen carries only the load cell's
// noise and zero drift (judgment: 25 % leaves room for such a remainder).
inline constexpr double kFractureWindow = 0.01;
inline constexpr double kFractureRemainder = 0.25;

struct RecordEnd {
  bool fracture = false;
  // Points up to the fracture (the whole record when it did not break): the last one at or
  // above half the largest force of the window, where the drop starts.
  std::size_t intact_points = 0;
  double end_m = 0.0;  // displacement of the last intact point
};

RecordEnd record_end(const ForceCurve& lab);

// The record up to its fracture (the drop's points left out: no effect of the catalogue models
// the fracture itself, only the curve up to it).
ForceCurve intact_part(const ForceCurve& lab, const RecordEnd& end);

// Each comparison's damage clock from the fracture displacements (`fracture_m`, 0 for a record
// that did not break): the largest fracture displacement u_ref over fracture_m for a fractured
// record, 1 for the others (and for all when none broke).
void set_damage_clocks(std::vector<Comparison>& labs);

}  // namespace dtwire::gap

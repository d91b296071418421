#pragma once
// Reading a target curve under the simulator's names. An FE or laboratory curve may call a
// quantity differently from the simulator (an FE run's axial_force_N for the law's force_N) or
// use another convention (a half model's end rotation is half the relative rotation), so a fit
// definition can map a target column onto a simulated quantity, with a factor.
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"

namespace dtwire::calibrate {

struct ColumnMapping {
  std::string quantity;  // the simulator's name (an experiment's abscissa or channel)
  std::string column;    // the target quantity it is read from
  double factor = 1.0;   // compared value = target value x factor, in the column's unit
};

// The target with each mapped quantity read from its column (times the factor). A target
// column named like a mapped quantity is replaced by it; the other columns are kept. Throws
// std::invalid_argument naming a missing column (and the columns present), a factor that is
// zero or not finite, or a quantity mapped twice.
Curve map_columns(const Curve& target, const std::vector<ColumnMapping>& mapping);

// The inverse: a curve in the simulator's names written under the target's column names
// (values / factor), so that synthetic targets read back through the same mapping. Throws
// std::invalid_argument if the mapping cannot be inverted (two quantities from one column) or
// a renamed channel would collide with a channel already present.
Curve unmap_columns(const Curve& simulated, const std::vector<ColumnMapping>& mapping);

}  // namespace dtwire::calibrate

#pragma once
// The fit file's cross-field checks, run once the file is read: every name a simulator must
// know, every offset's base and order, every compared channel. Each error names its field at
// file:line:column. Internal to calibrate/ (fit_file.cpp).
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "dtwire/calibrate/fit_file.hpp"
#include "toml_table.hpp"

namespace dtwire::calibrate {

// law_replay: the law must exist and read every fixed name (a typo would leave the law's
// default in place without a word).
void check_fixed_law_parameters(const FitDefinition& def, const Table& sim);

// dem_specimen: the law must be thesis or macro3d, every fixed name sw.<name> or dt.<name> with
// <name> in the law's schema, and both sets need their reference length.
void check_fixed_specimen_parameters(const FitDefinition& def, const Table& sim);

// Every fitted parameter must be read by at least one experiment's simulator, where the
// simulators say what they read. `tables` are the [[parameter]] tables, in order.
void check_parameters_are_read(const FitDefinition& def, const std::vector<Table>& tables);

// offset_from (parameter.hpp): names another fitted parameter, closes no cycle; an offset's
// reference lies within its bounds and needs its base's reference.
void check_offsets(const std::vector<ParameterDefinition>& parameters, const std::vector<Table>& tables);

// One evaluation of an experiment holds its whole path: the samples, the driver's history and the
// simulated curve, about 48 numbers per increment (law_replay.cpp, dem_export's driver.cpp). A path
// of `increments` rows that the available memory cannot hold is refused at `increments_per_leg`
// here, not by the allocator in the middle of the fit.
void check_path_memory(const Table& experiment, double increments);

// A quantity an experiment compares, and the field that names it (for error positions).
struct Compared {
  std::string quantity;
  std::string key;
  const toml::node* node;
};

// The compared quantities exist in the simulated curve and have the target's dimension, when
// the simulator declares its channels (a mapping to the wrong column is caught here).
void check_simulated_channels(const Experiment& e, const std::vector<Compared>& compared, const std::string& kind,
                              const Table& x);

}  // namespace dtwire::calibrate

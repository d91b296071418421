#pragma once
// Starting a fit from an earlier one (`dtwire fit --initial FILE`): the fitted parameters take
// their initial values from a parameters.json that `dtwire fit` wrote (its "parameters" list of
// {name, value}), e.g. a level-1 fit started at the level-0 optimum. Parameters the file does not
// name keep the fit file's initial value. The values are the parameters' own: an offset parameter
// (parameter.hpp) starts at its value minus its base's (the file's, else the base's initial).
#include <filesystem>
#include <vector>

#include "dtwire/calibrate/parameter.hpp"

namespace dtwire::calibrate {

// Returns how many parameters were set. Throws InputError naming the file (and the parameter)
// if it cannot be read, has no "parameters" list, names none of the fitted parameters, or gives
// a value outside a parameter's bounds or not finite.
std::size_t apply_initial_values(std::vector<ParameterDefinition>& parameters, const std::filesystem::path& file);

}  // namespace dtwire::calibrate

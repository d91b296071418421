#pragma once
// The campaign's steps as a graph: which earlier steps a step must wait for. A step waits for
// every earlier step that writes one of its {out} inputs (the file or a folder holding it) or
// a {out} path its command names (an input the file forgot to declare), and for every earlier
// step whose outputs overlap its own, so that two steps never write the same file or folder at
// once.
#include <cstddef>
#include <string>
#include <vector>

#include "campaign_file.hpp"

namespace dtwire::app {

// True if `path` is one of the step's outputs or lies inside an output folder (unexpanded
// strings, e.g. "{out}/fit/parameters.json").
bool step_writes(const CampaignStep& step, const std::string& path);

// For each step, the indices of the earlier steps it waits for (ascending).
std::vector<std::vector<std::size_t>> step_dependencies(const Campaign& campaign);

}  // namespace dtwire::app

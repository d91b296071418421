#pragma once
// Where and how a wire fails: the place along a double twist where the ductile failure
// indicator first reached 1, and the stress state that drove it. The laboratory's DT specimens
// fail at the junction, where the single wire leaves the twist, by combined tension and shear
// (thesis ch. 4, Figures 4.13-4.14; experiments/data/wire_2.7mm_literature.md); a model that
// fails by necking inside the twist misses that (issue 50).
#include <array>
#include <string>

namespace dtwire::fem {

enum class FailurePlace { twist, junction, arm };

// z (m) of the point against the twist's ends (m): the junction is the band of one wire diameter
// on either side of an end (the last contact with the partner wire and the start of the bend
// that leads the wire away, bend radius 2 d in the default mesh), the twist lies between the two
// bands, the arms outside them.
FailurePlace failure_place(double z, double diameter, const std::array<double, 2>& twist_ends);
const char* to_string(FailurePlace place);

// Necking-driven when the stress state is axisymmetric tension raised by a neck (Lode parameter
// > 0.5, triaxiality > 0.38), shear-driven when the Lode parameter is near 0 (|xi| < 0.5: shear or
// plane strain), otherwise uniform tension (or compression).
std::string failure_mode(double triaxiality, double lode_parameter);

}  // namespace dtwire::fem

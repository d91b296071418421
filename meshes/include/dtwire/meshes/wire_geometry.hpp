#pragma once
// Builds the hexahedral meshes of a single wire (SW) and of a double twist (DT).
//
// SW: axis along z from 0 to length, grips of grip-length at both ends.
// DT: twist axis along z from 0 to L_dt; wire A's axis is the helix
//   (R cos(k z), R sin(k z), z), wire B's the same turned by pi, R = (d + 2 t + gap) / 2,
//   k = n pi / L_dt, so the surfaces are gap apart along the whole twist. At both ends each wire
//   bends (bend-radius) into a straight arm in the mesh plane (x, z) at arm-angle to the twist
//   axis, away from the other wire; arms end in grips. Arm length is the axis length from the
//   twist end to the arm end.
// Segment: one SW segment as the hexagonal mesh has it between two twists (the DT's own axes):
//   wire A leaves the upper end of a twist along its helix tangent, bends (bend-radius) into a
//   straight part in the mesh plane at arm-angle to the twist axis, and bends into the lower end
//   of the next twist, the segment being symmetric under the half turn about its midpoint.
//   `length` is the axis length between the two twist ends (the mesh's SW segment, 60 mm for
//   8x10); a grip of grip-length continues straight along the helix tangent into each twist, where
//   the twist holds the wire. The chord from twist end to twist end lies along +z from the origin
//   (the direction a DEM link between the two nodes measures), the straight part in (x, z).
#include "dtwire/meshes/parameters.hpp"
#include "dtwire/meshes/wire_axis.hpp"
#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {

// The axis pieces of wire 0 or 1 (throws InputError at `locations` for arms too short).
std::vector<AxisPiece> double_twist_axis(const MeshParameters& parameters, int wire,
                                         const FieldLocations& locations = {});
double helix_lay_angle(const MeshParameters& parameters);
// The axis pieces of a segment (throws InputError at `length` when the bends leave no straight part).
std::vector<AxisPiece> segment_axis(const MeshParameters& parameters, const FieldLocations& locations = {});

// Validates (parameters.hpp) and checks that no arm comes closer to the other wire, or to its
// own twist, than the wires' outer diameter (InputError at arm-angle otherwise).
WireMesh build_wire_mesh(const MeshParameters& parameters, const FieldLocations& locations = {});

}  // namespace dtwire::meshes

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
#include "dtwire/meshes/parameters.hpp"
#include "dtwire/meshes/wire_axis.hpp"
#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {

// The axis pieces of wire 0 or 1 (throws InputError at `locations` for arms too short).
std::vector<AxisPiece> double_twist_axis(const MeshParameters& parameters, int wire,
                                         const FieldLocations& locations = {});
double helix_lay_angle(const MeshParameters& parameters);

// Validates (parameters.hpp) and checks that no arm comes closer to the other wire, or to its
// own twist, than the wires' outer diameter (InputError at arm-angle otherwise).
WireMesh build_wire_mesh(const MeshParameters& parameters, const FieldLocations& locations = {});

}  // namespace dtwire::meshes

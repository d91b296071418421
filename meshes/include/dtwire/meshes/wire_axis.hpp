#pragma once
// The axis of one wire as a chain of pieces (straight, circular bend, helix), each with a
// frame that the cross-section is swept along, and its sampling into mesh stations.
#include <functional>
#include <vector>

#include "dtwire/meshes/cross_section.hpp"
#include "dtwire/meshes/vec3.hpp"
#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {

// A point of the axis with the unit tangent and the unit section direction u (normal to the
// tangent); the section direction v is tangent x u.
struct Station {
  Vec3 point;
  Vec3 tangent;
  Vec3 normal;
};

struct AxisPiece {
  std::function<Station(double)> at;  // arc length 0..length from the piece start
  double length;
  WirePart part;
  int min_layers = 1;  // e.g. to bound the section turn per layer along a helix
};

Station flipped(const Station& station);  // same frame, tangent reversed, v kept right-handed
// The piece run backwards (for the arm built outwards from the start of the twist).
AxisPiece reversed(const AxisPiece& piece);

AxisPiece straight_piece(const Station& start, double length, WirePart part);
// Circular bend of the given radius turning the start tangent towards `direction` by `angle`;
// the frame is rotation-minimising (turned about the bend's binormal).
AxisPiece bend_piece(const Station& start, const Vec3& direction, double radius, double angle);

// The piece moved rigidly: `origin` goes to 0, then everything turns about the unit `axis` by
// `angle` (points, tangents and section directions alike).
AxisPiece rigidly_moved(const AxisPiece& piece, const Vec3& origin, const Vec3& axis, double angle);

struct SampledAxis {
  std::vector<Station> stations;
  // Curvature vector d(tangent)/ds at each station (1/m, towards the centre of curvature),
  // from the piece the station lies in: what bending a straight wire into this axis takes.
  std::vector<Vec3> curvature;
  std::vector<double> arc_length;  // m from the first station
  std::vector<WirePart> layer_part;  // part of the cell layer between station k and k + 1
  double length = 0;                 // exact axis length
};
// Each piece gets max(ceil(length / cell_length), min_layers) equal layers.
SampledAxis sample_axis(const std::vector<AxisPiece>& pieces, double cell_length);

std::vector<AxisSample> axis_samples(const SampledAxis& axis);

// Sweeps the section along the axis and appends hexes, end faces and lateral faces of wire
// `wire` (0 or 1) with the region ids of wire_mesh.hpp.
void sweep_wire(HexMesh& mesh, const CrossSection& section, const SampledAxis& axis, int wire,
                bool double_twist);

}  // namespace dtwire::meshes

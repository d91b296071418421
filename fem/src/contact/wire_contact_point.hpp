#pragma once
// One slave Gauss point of the wire-wire contact against one bilinear master face: its nodal
// forces on the 24 dofs (12 of the slave face, 12 of the master face) and their exact derivative,
// the consistent tangent. The closest-point parameters, the master normal and the anchor of the
// friction predictor all move with the 24 dofs; forward automatic differentiation (Sacado
// SFad, 24 directions) differentiates through them, the closest-point parameters by the implicit
// function theorem (one Newton correction in AD arithmetic from the converged projection).
// This is the full linearisation of the Gauss-point-to-surface penalty contact with Coulomb
// friction (Wriggers 2006, sec. 4.1 and 10.5.2; Laursen 2002, sec. 5.3): normal, curvature and
// projection-variation terms included, which the frozen-normal tangent drops.
//
// Smoothed normal (optional, `vertex_corners` given): the master normal is interpolated with the
// bilinear shape functions from vertex normals, each the normalised sum of the corner normals
// x_xi x x_eta of the master faces around that vertex (averaged nodal normals, Puso & Laursen
// 2004, CMAME 193, sec. 3; Wriggers 2006, sec. 9.1.2). The normal then turns continuously as
// a point slides over a facet edge, where the faceted normal jumps by the facet angle. Vertex
// normals depend on the faces around the master face, so the point's force and tangent extend
// over those neighbour vertices' dofs (AD with up to kMaxDofs directions).
#include <array>
#include <vector>

#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

// One corner of a master face around a vertex: the face's four vertices as patch indices (0-3 the
// master face's own vertices, 4 and up the neighbours, in deal.II's face vertex order), the
// corner (0-3) at the vertex and the face's outward sign.
struct NormalCorner {
  std::array<unsigned, 4> face{};
  unsigned corner = 0;
  double sign = 1.0;
};

constexpr unsigned kMaxNeighbourVertices = 28;  // a vertex of valence 6 on every corner of the face

struct WireContactPointInput {
  std::array<Vector3, 4> slave_reference, master_reference;  // face vertices, reference positions
  std::array<double, 12> slave_displacement{}, master_displacement{};  // vertex v, component c at 3 v + c
  std::array<double, 12> master_committed_displacement{};             // at the last converged step
  double master_sign = 1.0;                   // +1 if x_xi x x_eta points out of the master body
  double slave_xi = 0.0, slave_eta = 0.0;     // the Gauss point on the slave face
  double weight = 0.0;                        // reference area of the point
  double master_xi = 0.5, master_eta = 0.5;   // converged closest point (clamped to the face)
  Vector3 committed_slave_position;           // x_s at the last converged step
  double gap_offset = 0.0;                    // m, added to the gap
  ContactHistory history;                     // committed tangential traction; current multiplier
  FrictionStatus forced = FrictionStatus::free;
  // Smoothed normal: per vertex of the master face, the corners around it (empty: faceted normal);
  // the neighbour vertices' reference positions and displacements (component c at 3 k + c).
  std::array<std::vector<NormalCorner>, 4> vertex_corners;
  std::vector<Vector3> neighbour_reference;
  std::vector<double> neighbour_displacement;
};

// Dofs in this order: slave face (12), master face (12), neighbour vertices (3 each).
struct WireContactPointOutput {
  ContactResponse response;      // traction, pressure, gap, slip as the kernel reports them
  std::vector<double> force;     // internal force on the dofs (slave +N t, master -N t, times -weight)
  std::vector<double> stiffness; // d force / d u, row-major n x n; empty without the tangent
  double tangent(unsigned i, unsigned j) const { return stiffness[i * force.size() + j]; }
};

// With `with_tangent` false only the response and the force are computed (plain doubles).
// Throws std::invalid_argument for more than kMaxNeighbourVertices neighbours or a corner
// naming a vertex outside the patch.
WireContactPointOutput evaluate_wire_contact_point(const WireContactPointInput& input, const ContactLaw& law,
                                                   bool with_tangent);

}  // namespace dtwire::fem::contact

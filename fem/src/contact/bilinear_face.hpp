#pragma once
// Geometry of a bilinear quadrilateral face (the boundary face of a Q1 hexahedron) in its current
// position: shape functions, tangents, outward normal and the closest-point projection of a
// point onto it. Vertex order as deal.II's face vertices: (0,0), (1,0), (0,1), (1,1) in (xi, eta).
#include <array>

#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

struct BilinearFace {
  std::array<Vector3, 4> vertex;  // current positions
  double normal_sign = 1.0;       // +1 if x_xi x x_eta points out of the cell, -1 otherwise

  static std::array<double, 4> shape(double xi, double eta) {
    return {{(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta, xi * eta}};
  }
  Vector3 position(double xi, double eta) const;
  Vector3 tangent_xi(double eta) const { return (1 - eta) * (vertex[1] - vertex[0]) + eta * (vertex[3] - vertex[2]); }
  Vector3 tangent_eta(double xi) const { return (1 - xi) * (vertex[2] - vertex[0]) + xi * (vertex[3] - vertex[1]); }
  Vector3 outward_normal(double xi, double eta) const;  // unit
  double area_element(double xi, double eta) const;     // |x_xi x x_eta|
};

struct FaceProjection {
  double xi = 0.0, eta = 0.0;
  double distance = 0.0;  // |x - x_face(xi, eta)|
  bool inside = false;    // the unconstrained minimiser lies in the face (with a small tolerance)
};

// Closest point of the face to x: Newton on |x - x(xi, eta)|^2 / 2 with the parameters kept in
// [0, 1]^2 by an active set (a clamped parameter stays on its edge and the other is minimised
// there) (Wriggers 2006, sec. 4.1, closest-point projection).
FaceProjection project_onto_face(const BilinearFace& face, const Vector3& x);

}  // namespace dtwire::fem::contact

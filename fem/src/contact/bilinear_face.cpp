#include "bilinear_face.hpp"

#include <algorithm>
#include <cmath>

namespace dtwire::fem::contact {

Vector3 BilinearFace::position(double xi, double eta) const {
  const auto N = shape(xi, eta);
  return N[0] * vertex[0] + N[1] * vertex[1] + N[2] * vertex[2] + N[3] * vertex[3];
}

Vector3 BilinearFace::outward_normal(double xi, double eta) const {
  const Vector3 n = normal_sign * dealii::cross_product_3d(tangent_xi(eta), tangent_eta(xi));
  return n / n.norm();
}

double BilinearFace::area_element(double xi, double eta) const {
  return dealii::cross_product_3d(tangent_xi(eta), tangent_eta(xi)).norm();
}

FaceProjection project_onto_face(const BilinearFace& face, const Vector3& x) {
  constexpr double kInsideTolerance = 1e-3;
  const Vector3 twist = face.vertex[0] - face.vertex[1] - face.vertex[2] + face.vertex[3];  // x_xi_eta
  double xi = 0.5, eta = 0.5;
  bool inside = true;
  for (unsigned it = 0; it < 30; ++it) {
    const Vector3 r = x - face.position(xi, eta);
    const Vector3 a = face.tangent_xi(eta), b = face.tangent_eta(xi);
    // Newton on f = |r|^2 / 2: gradient -(r.a, r.b), Hessian [[a.a, a.b - r.c], [., b.b]] with
    // c the twist x_xi_eta; Gauss-Newton (c dropped) where that Hessian is not positive definite.
    const double aa = a * a, bb = b * b, ra = r * a, rb = r * b;
    double ab = a * b - r * twist;
    if (aa * bb - ab * ab <= 1e-12 * aa * bb) ab = a * b;
    const double det = aa * bb - ab * ab;
    if (!(det > 0.0)) break;
    double dxi = (bb * ra - ab * rb) / det, deta = (aa * rb - ab * ra) / det;
    const bool xi_out = xi + dxi < 0.0 || xi + dxi > 1.0;
    const bool eta_out = eta + deta < 0.0 || eta + deta > 1.0;
    inside = xi + dxi > -kInsideTolerance && xi + dxi < 1 + kInsideTolerance && eta + deta > -kInsideTolerance &&
             eta + deta < 1 + kInsideTolerance;
    // Active set: a parameter that leaves the face is held on its edge and the other one is
    // minimised alone there, so that a clamped projection is stationary in the free parameter.
    if (xi_out && !eta_out) {
      const double xi_edge = std::clamp(xi + dxi, 0.0, 1.0);
      const Vector3 b_edge = face.tangent_eta(xi_edge);
      dxi = xi_edge - xi;
      deta = ((x - face.position(xi_edge, eta)) * b_edge) / (b_edge * b_edge);
    } else if (eta_out && !xi_out) {
      const double eta_edge = std::clamp(eta + deta, 0.0, 1.0);
      const Vector3 a_edge = face.tangent_xi(eta_edge);
      deta = eta_edge - eta;
      dxi = ((x - face.position(xi, eta_edge)) * a_edge) / (a_edge * a_edge);
    }
    const double new_xi = std::clamp(xi + dxi, 0.0, 1.0), new_eta = std::clamp(eta + deta, 0.0, 1.0);
    const double moved = std::abs(new_xi - xi) + std::abs(new_eta - eta);
    xi = new_xi;
    eta = new_eta;
    if (moved < 1e-13) break;
  }
  FaceProjection p;
  p.xi = xi;
  p.eta = eta;
  p.inside = inside;
  p.distance = (x - face.position(xi, eta)).norm();
  return p;
}

}  // namespace dtwire::fem::contact

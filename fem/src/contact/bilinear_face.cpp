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
  double xi = 0.5, eta = 0.5;
  bool inside = true;
  for (unsigned it = 0; it < 12; ++it) {
    const Vector3 r = x - face.position(xi, eta);
    const Vector3 a = face.tangent_xi(eta), b = face.tangent_eta(xi);
    // Normal equations of the Gauss-Newton step (the bilinear twist term x_xi_eta is dropped:
    // it only slows convergence on warped faces, the fixed point is the same).
    const double aa = a * a, ab = a * b, bb = b * b, ra = r * a, rb = r * b;
    const double det = aa * bb - ab * ab;
    if (!(det > 0.0)) break;
    const double dxi = (bb * ra - ab * rb) / det, deta = (aa * rb - ab * ra) / det;
    const double new_xi = xi + dxi, new_eta = eta + deta;
    inside = new_xi > -kInsideTolerance && new_xi < 1 + kInsideTolerance && new_eta > -kInsideTolerance &&
             new_eta < 1 + kInsideTolerance;
    xi = std::clamp(new_xi, 0.0, 1.0);
    eta = std::clamp(new_eta, 0.0, 1.0);
    if (std::abs(dxi) + std::abs(deta) < 1e-12) break;
  }
  FaceProjection p;
  p.xi = xi;
  p.eta = eta;
  p.inside = inside;
  p.distance = (x - face.position(xi, eta)).norm();
  return p;
}

}  // namespace dtwire::fem::contact

// Element kernel (plain and F-bar total-Lagrangian hexahedron): the element tangent is the exact
// derivative of the element residual (finite differences), in elastic and plastic states.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "fbar_element.hpp"

namespace dtwire::fem {
namespace {

// Trilinear hexahedron, nodes in deal.II lexicographic order, corners of a distorted brick (m).
ElementGeometry distorted_hex() {
  const double h = 1e-3;
  std::array<dealii::Tensor<1, 3>, 8> x;
  for (unsigned v = 0; v < 8; ++v) {
    x[v][0] = h * (v & 1);
    x[v][1] = h * ((v >> 1) & 1);
    x[v][2] = h * ((v >> 2) & 1);
  }
  x[7][0] += 0.3 * h;
  x[3][1] += 0.2 * h;
  x[5][2] -= 0.25 * h;
  x[0][0] += 0.1 * h;
  auto shape_grad_ref = [](unsigned v, const std::array<double, 3>& xi) {
    dealii::Tensor<1, 3> g;
    for (unsigned d = 0; d < 3; ++d) {
      double p = 1.0;
      for (unsigned e = 0; e < 3; ++e) {
        const bool one = (v >> e) & 1;
        if (e == d) p *= one ? 1.0 : -1.0;
        else p *= one ? xi[e] : 1.0 - xi[e];
      }
      g[d] = p;
    }
    return g;
  };
  auto gradients = [&](const std::array<double, 3>& xi, double& detJ) {
    Tensor2 jac;  // dx/dxi
    for (unsigned v = 0; v < 8; ++v) jac += dealii::outer_product(x[v], shape_grad_ref(v, xi));
    detJ = dealii::determinant(jac);
    const Tensor2 inv = dealii::invert(jac);
    std::vector<dealii::Tensor<1, 3>> g(24);
    for (unsigned v = 0; v < 8; ++v)
      for (unsigned c = 0; c < 3; ++c) g[3 * v + c] = shape_grad_ref(v, xi) * inv;
    return g;
  };
  ElementGeometry geo;
  for (unsigned i = 0; i < 24; ++i) geo.component.push_back(i % 3);
  const double gp[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (unsigned q = 0; q < 8; ++q) {
    double detJ = 0;
    geo.shape_grad.push_back(gradients({{gp[q & 1], gp[(q >> 1) & 1], gp[(q >> 2) & 1]}}, detJ));
    geo.weight.push_back(detJ / 8.0);
  }
  return geo;
}

J2LogPlasticity steel() {
  HardeningParameters p;
  p.law = HardeningLaw::voce;
  p.yield_stress = 450e6;
  p.saturation_stress = 715e6;
  p.saturation_rate = 16.93;
  p.linear_modulus = 129.24e6;
  return J2LogPlasticity(ElasticParameters{206.9e9, 0.29}, IsotropicHardening(p));
}

std::vector<double> displacement(double scale) {
  std::vector<double> u(24);
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = scale * 1e-3 * std::sin(1.7 * i + 0.3);
  return u;
}

double tangent_error(bool fbar, double scale, bool plastic_history) {
  const J2LogPlasticity m = steel();
  const ElementGeometry geo = distorted_hex();
  std::vector<PlasticState> history(8);
  ElementResult r;
  if (plastic_history) {  // a previous plastic step as the committed state
    evaluate_element(m, geo, displacement(0.6 * scale), history, fbar, false, r);
    for (unsigned q = 0; q < 8; ++q) history[q] = r.points[q].state;
  }
  const auto u = displacement(scale);
  evaluate_element(m, geo, u, history, fbar, true, r);
  bool plastic = false;
  for (const auto& p : r.points) plastic = plastic || p.plastic_increment > 0;
  EXPECT_EQ(plastic, scale > 0.01) << "expected plastic points only for the large displacement";
  const double h = 1e-10;  // m, vs element size 1e-3
  double err2 = 0, ref2 = 0;
  ElementResult rp, rm;
  for (std::size_t j = 0; j < 24; ++j) {
    auto up = u, um = u;
    up[j] += h;
    um[j] -= h;
    evaluate_element(m, geo, up, history, fbar, false, rp);
    evaluate_element(m, geo, um, history, fbar, false, rm);
    for (std::size_t i = 0; i < 24; ++i) {
      const double fd = (rp.residual[i] - rm.residual[i]) / (2 * h);
      err2 += std::pow(fd - r.tangent[i * 24 + j], 2);
      ref2 += std::pow(r.tangent[i * 24 + j], 2);
    }
  }
  return std::sqrt(err2 / ref2);
}

// Tolerance 1e-6 relative (central differences, h = 1e-7 of the element size).
TEST(ElementTangent, PlainElasticMatchesFiniteDifferences) { EXPECT_LT(tangent_error(false, 0.001, false), 1e-6); }
TEST(ElementTangent, PlainPlasticMatchesFiniteDifferences) { EXPECT_LT(tangent_error(false, 0.08, true), 1e-6); }
TEST(ElementTangent, FbarElasticMatchesFiniteDifferences) { EXPECT_LT(tangent_error(true, 0.001, false), 1e-6); }
TEST(ElementTangent, FbarPlasticMatchesFiniteDifferences) { EXPECT_LT(tangent_error(true, 0.08, true), 1e-6); }

TEST(ElementFbar, HomogeneousDeformationGivesThePlainResidual) {
  const J2LogPlasticity m = steel();
  const ElementGeometry geo = distorted_hex();
  // Linear displacement field u = H X: F-bar changes nothing (J = J0 everywhere).
  Tensor2 H;
  H[0][0] = 0.03;
  H[0][1] = 0.01;
  H[2][1] = -0.02;
  H[1][1] = -0.012;
  std::vector<double> u(24);
  const double h = 1e-3;
  std::array<dealii::Tensor<1, 3>, 8> x;
  // The node coordinates of distorted_hex().
  for (unsigned v = 0; v < 8; ++v) {
    x[v][0] = h * (v & 1);
    x[v][1] = h * ((v >> 1) & 1);
    x[v][2] = h * ((v >> 2) & 1);
  }
  x[7][0] += 0.3 * h;
  x[3][1] += 0.2 * h;
  x[5][2] -= 0.25 * h;
  x[0][0] += 0.1 * h;
  for (unsigned v = 0; v < 8; ++v)
    for (unsigned c = 0; c < 3; ++c) u[3 * v + c] = (H * x[v])[c];
  std::vector<PlasticState> history(8);
  ElementResult plain, fbar;
  evaluate_element(m, geo, u, history, false, false, plain);
  evaluate_element(m, geo, u, history, true, false, fbar);
  double scale = 0;
  for (double v : plain.residual) scale = std::max(scale, std::abs(v));
  // Tolerance: round-off (1e-12 of the largest nodal force).
  for (std::size_t i = 0; i < 24; ++i) EXPECT_NEAR(fbar.residual[i], plain.residual[i], 1e-12 * scale);
  // Equilibrium of a homogeneous stress: the element forces sum to zero per component.
  for (unsigned c = 0; c < 3; ++c) {
    double sum = 0;
    for (unsigned v = 0; v < 8; ++v) sum += plain.residual[3 * v + c];
    EXPECT_NEAR(sum, 0.0, 1e-12 * scale);
  }
}

}  // namespace
}  // namespace dtwire::fem

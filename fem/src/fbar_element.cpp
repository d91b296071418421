#include "fbar_element.hpp"

#include <cmath>
#include <stdexcept>

namespace dtwire::fem {
namespace {

double trace_of_product(const Tensor2& a, const Tensor2& b) {  // tr(a b)
  double s = 0.0;
  for (unsigned k = 0; k < 3; ++k)
    for (unsigned l = 0; l < 3; ++l) s += a[k][l] * b[l][k];
  return s;
}

}  // namespace

void evaluate_element(const J2LogPlasticity& material, const ElementGeometry& geometry,
                      const std::vector<double>& u, const std::vector<PlasticState>& history,
                      bool fbar, bool with_tangent, ElementResult& result) {
  const std::size_t n = u.size();
  const std::size_t n_q = geometry.weight.size();
  result.residual.assign(n, 0.0);
  if (with_tangent) result.tangent.assign(n * n, 0.0);
  result.points.resize(n_q);
  result.jacobian.resize(n_q);

  // Pass 1: F, J, M_i = F^-1 G_i and b_i = tr M_i = F^-T : G_i at every quadrature point.
  std::vector<Tensor2> F(n_q);
  std::vector<std::vector<Tensor2>> M(n_q, std::vector<Tensor2>(fbar ? n : 0));
  std::vector<std::vector<double>> b(n_q, std::vector<double>(fbar ? n : 0));
  double volume = 0.0, J0 = 0.0;
  for (std::size_t q = 0; q < n_q; ++q) {
    F[q] = dealii::unit_symmetric_tensor<3>();
    for (std::size_t i = 0; i < n; ++i) F[q] += u[i] * geometry.grad[q][i];
    const double J = dealii::determinant(F[q]);
    if (!(J > 0.0) || !std::isfinite(J)) throw std::domain_error("det F <= 0 at a quadrature point");
    result.jacobian[q] = J;
    volume += geometry.weight[q];
    J0 += geometry.weight[q] * J;
    if (!fbar) continue;
    const Tensor2 F_inv = dealii::invert(F[q]);
    for (std::size_t i = 0; i < n; ++i) {
      M[q][i] = F_inv * geometry.grad[q][i];
      b[q][i] = dealii::trace(M[q][i]);
    }
  }
  J0 /= volume;

  // a_i = (dJ0/du_i) / J0 and its derivative da_ij = d a_i / d u_j.
  std::vector<double> a(fbar ? n : 0, 0.0);
  std::vector<double> da(fbar && with_tangent ? n * n : 0, 0.0);
  if (fbar) {
    for (std::size_t q = 0; q < n_q; ++q) {
      const double c = geometry.weight[q] * result.jacobian[q] / (volume * J0);
      for (std::size_t i = 0; i < n; ++i) a[i] += c * b[q][i];
      if (!with_tangent) continue;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          da[i * n + j] += c * (b[q][i] * b[q][j] - trace_of_product(M[q][i], M[q][j]));
    }
    for (std::size_t i = 0; i < da.size(); ++i) da[i] -= a[i / n] * a[i % n];
  }

  // Pass 2: stress update at Fbar, residual and tangent.
  std::vector<Tensor2> dFbar(n), AdF(n);
  std::vector<double> r_q(n, 0.0), PG(n, 0.0);
  for (std::size_t q = 0; q < n_q; ++q) {
    const auto& G = geometry.grad[q];
    const double alpha = fbar ? std::cbrt(J0 / result.jacobian[q]) : 1.0;
    const StressUpdate& s = result.points[q] = material.update(alpha * F[q], history[q], with_tangent);
    const double w = geometry.weight[q];
    for (std::size_t i = 0; i < n; ++i) {
      dFbar[i] = fbar ? alpha * (G[i] + (a[i] - b[q][i]) / 3.0 * F[q]) : G[i];
      r_q[i] = dealii::scalar_product(s.first_piola, dFbar[i]);
      result.residual[i] += r_q[i] * w;
    }
    if (!with_tangent) continue;

    for (std::size_t j = 0; j < n; ++j) AdF[j] = dealii::double_contract<2, 0, 3, 1>(s.tangent, dFbar[j]);
    const double PF = dealii::scalar_product(s.first_piola, F[q]);
    if (fbar)
      for (std::size_t j = 0; j < n; ++j) PG[j] = dealii::scalar_product(s.first_piola, G[j]);
    for (std::size_t i = 0; i < n; ++i) {
      double* row = &result.tangent[i * n];
      for (std::size_t j = 0; j < n; ++j) {
        double k = dealii::scalar_product(dFbar[i], AdF[j]);
        if (fbar) {
          // P : (second variation of Fbar)[i, j]; d b_i / d u_j = -tr(M_i M_j).
          const double db = -trace_of_product(M[q][i], M[q][j]);
          k += (a[j] - b[q][j]) / 3.0 * r_q[i] +
               alpha / 3.0 * ((da[i * n + j] - db) * PF + (a[i] - b[q][i]) * PG[j]);
        }
        row[j] += k * w;
      }
    }
  }
}

}  // namespace dtwire::fem

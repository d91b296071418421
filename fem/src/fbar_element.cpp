#include "fbar_element.hpp"

#include <cmath>
#include <stdexcept>

namespace dtwire::fem {

// With Grad phi_i = e_c (x) g_i every contraction below is a few multiplications:
//   P : Grad phi_i = (P g_i)_c,  F^-T : Grad phi_i = s_i[c] with s_i = F^-T g_i,
//   tr(F^-1 Grad phi_i F^-1 Grad phi_j) = s_i[c_j] s_j[c_i].
void evaluate_element(const J2LogPlasticity& material, const ElementGeometry& geometry,
                      const std::vector<double>& u, const std::vector<PlasticState>& history,
                      bool fbar, bool with_tangent, ElementResult& result) {
  using Vector3 = dealii::Tensor<1, 3>;
  const std::size_t n = u.size();
  const std::size_t n_q = geometry.weight.size();
  const auto& c = geometry.component;
  result.residual.assign(n, 0.0);
  if (with_tangent) result.tangent.assign(n * n, 0.0);
  result.points.resize(n_q);
  result.jacobian.resize(n_q);

  // Pass 1: F, J and s_i = F^-T g_i at every quadrature point.
  std::vector<Tensor2> F(n_q);
  std::vector<std::vector<Vector3>> s(n_q, std::vector<Vector3>(fbar ? n : 0));
  double volume = 0.0, J0 = 0.0;
  for (std::size_t q = 0; q < n_q; ++q) {
    F[q] = dealii::unit_symmetric_tensor<3>();
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned d = 0; d < 3; ++d) F[q][c[i]][d] += u[i] * geometry.shape_grad[q][i][d];
    const double J = dealii::determinant(F[q]);
    if (!(J > 0.0) || !std::isfinite(J)) throw std::domain_error("det F <= 0 at a quadrature point");
    result.jacobian[q] = J;
    volume += geometry.weight[q];
    J0 += geometry.weight[q] * J;
    if (!fbar) continue;
    const Tensor2 F_inv_T = dealii::transpose(dealii::invert(F[q]));
    for (std::size_t i = 0; i < n; ++i) s[q][i] = F_inv_T * geometry.shape_grad[q][i];
  }
  J0 /= volume;

  // F-bar: a_i = (dJ0/du_i) / J0 and da_ij = d a_i / d u_j.
  std::vector<double> a(fbar ? n : 0, 0.0);
  std::vector<double> da(fbar && with_tangent ? n * n : 0, 0.0);
  if (fbar) {
    for (std::size_t q = 0; q < n_q; ++q) {
      const double w = geometry.weight[q] * result.jacobian[q] / (volume * J0);
      const auto& sq = s[q];
      for (std::size_t i = 0; i < n; ++i) a[i] += w * sq[i][c[i]];
      if (!with_tangent) continue;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          da[i * n + j] += w * (sq[i][c[i]] * sq[j][c[j]] - sq[i][c[j]] * sq[j][c[i]]);
    }
    for (std::size_t i = 0; i < da.size(); ++i) da[i] -= a[i / n] * a[i % n];
  }

  // Pass 2: stress at Fbar = alpha F; dFbar_i = alpha (Grad phi_i + k_i F), k_i = (a_i - b_i) / 3.
  std::vector<double> k(n, 0.0), r_q(n, 0.0), PG(n, 0.0), FAdF(n, 0.0);
  std::vector<Tensor2> AG(n);  // A : Grad phi_j
  for (std::size_t q = 0; q < n_q; ++q) {
    const auto& g = geometry.shape_grad[q];
    const double alpha = fbar ? std::cbrt(J0 / result.jacobian[q]) : 1.0;
    const StressUpdate& su = result.points[q] = material.update(alpha * F[q], history[q], with_tangent);
    const Tensor2& P = su.first_piola;
    const double w = geometry.weight[q];
    const double PF = dealii::scalar_product(P, F[q]);
    for (std::size_t i = 0; i < n; ++i) {
      PG[i] = P[c[i]] * g[i];
      k[i] = fbar ? (a[i] - s[q][i][c[i]]) / 3.0 : 0.0;
      r_q[i] = alpha * (PG[i] + k[i] * PF);
      result.residual[i] += r_q[i] * w;
    }
    if (!with_tangent) continue;

    const Tensor4& A = su.tangent;
    Tensor2 AF, FA;  // A : F and F : A
    double FAF = 0.0;
    if (fbar) {
      AF = dealii::double_contract<2, 0, 3, 1>(A, F[q]);
      FA = dealii::double_contract<0, 0, 1, 1>(F[q], A);
      FAF = dealii::scalar_product(F[q], AF);
    }
    for (std::size_t j = 0; j < n; ++j) {
      for (unsigned i1 = 0; i1 < 3; ++i1)
        for (unsigned i2 = 0; i2 < 3; ++i2) AG[j][i1][i2] = A[i1][i2][c[j]] * g[j];
      if (fbar) FAdF[j] = FA[c[j]] * g[j];  // F : A : Grad phi_j
    }
    const double a2 = alpha * alpha;
    for (std::size_t i = 0; i < n; ++i) {
      double* row = &result.tangent[i * n];
      for (std::size_t j = 0; j < n; ++j) {
        // dFbar_i : A : dFbar_j
        double kij = AG[j][c[i]] * g[i];
        if (fbar) {
          kij += k[j] * (AF[c[i]] * g[i]) + k[i] * FAdF[j] + k[i] * k[j] * FAF;
          kij *= a2;
          // P : (second variation of Fbar)[i, j]; d b_i / d u_j = -s_i[c_j] s_j[c_i].
          const double db = -s[q][i][c[j]] * s[q][j][c[i]];
          kij += k[j] * r_q[i] + alpha / 3.0 * ((da[i * n + j] - db) * PF + 3.0 * k[i] * PG[j]);
        }
        row[j] += kij * w;
      }
    }
  }
}

}  // namespace dtwire::fem

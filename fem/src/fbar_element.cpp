#include "fbar_element.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace dtwire::fem {

// With Grad phi_i = e_c (x) g_i every contraction below is a few multiplications:
//   P : Grad phi_i = (P g_i)_c,  F^-T : Grad phi_i = s_i[c] with s_i = F^-T g_i,
//   tr(F^-1 Grad phi_i F^-1 Grad phi_j) = s_i[c_j] s_j[c_i] =: T_ij.
//
// The tangent, the exact derivative of r_i = sum_q w alpha (P:G_i + k_i P:F), k_i = (a_i - b_i)/3,
// b_i = s_i[c_i], a_i = sum_q w' b_i (w' = w J / (V J0)), is gathered as
//   K_ij = sum_q [ w alpha^2 G_i:A:G_j + w k_j U_i + w k_i V_j + (w beta - B w') T_ij + B w' b_i b_j ]
//          - B a_i a_j,
//   U_i = alpha^2 (A:F):G_i + r_i,  V_j = alpha^2 (F:A:G_j + k_j F:A:F) + alpha P:G_j,
//   beta = alpha P:F / 3,  B = sum_q w beta,
// where B (...) is the element-level second variation of J0 (da_ij = d a_i / d u_j summed once
// instead of per point). Every (i, j) entry is then seven multiply-adds over contiguous rows:
// the assembly of the level-1 DT mesh spends most of its time here.
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

  // Pass 1: F, J and s_i = F^-T g_i at every quadrature point (s stored point by point).
  std::vector<Tensor2> F(n_q);
  std::vector<Vector3> s(fbar ? n_q * n : 0);
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
    for (std::size_t i = 0; i < n; ++i) s[q * n + i] = F_inv_T * geometry.shape_grad[q][i];
  }
  J0 /= volume;

  // F-bar: a_i = (dJ0/du_i) / J0; w'_q = w J / (V J0).
  std::vector<double> a(fbar ? n : 0, 0.0), w_bar(n_q, 0.0), alpha(n_q, 1.0), PF(n_q, 0.0);
  if (fbar)
    for (std::size_t q = 0; q < n_q; ++q) {
      w_bar[q] = geometry.weight[q] * result.jacobian[q] / (volume * J0);
      alpha[q] = std::cbrt(J0 / result.jacobian[q]);
      for (std::size_t i = 0; i < n; ++i) a[i] += w_bar[q] * s[q * n + i][c[i]];
    }

  // Stress at Fbar = alpha F at every point first: B needs all of them. The cell's size (cube
  // root of its reference volume) is the crack band of the softening.
  double B = 0.0;
  const double cell_size = std::cbrt(volume);
  for (std::size_t q = 0; q < n_q; ++q) {
    result.points[q] = material.update(alpha[q] * F[q], history[q], with_tangent, cell_size);
    PF[q] = dealii::scalar_product(result.points[q].first_piola, F[q]);
    if (fbar) B += geometry.weight[q] * alpha[q] * PF[q] / 3.0;
  }

  // Pass 2: residual and tangent point by point; dFbar_i = alpha (Grad phi_i + k_i F).
  std::vector<double> k(n, 0.0), b(n, 0.0), r_q(n, 0.0), PG(n, 0.0), U(n, 0.0), V(n, 0.0), kw(n, 0.0);
  std::array<std::vector<double>, 3> s_component;  // s_component[d][j] = s_j[d]
  for (auto& column : s_component) column.assign(n, 0.0);
  std::vector<std::array<std::array<double, 4>, 3>> H(n);  // per i and c2: (w a^2 A[c_i][.][c2][.] g_i, t s_i[c2])
  for (std::size_t q = 0; q < n_q; ++q) {
    const auto& g = geometry.shape_grad[q];
    const double w = geometry.weight[q];
    const StressUpdate& su = result.points[q];
    const Tensor2& P = su.first_piola;
    for (std::size_t i = 0; i < n; ++i) {
      PG[i] = P[c[i]] * g[i];
      if (fbar) {
        b[i] = s[q * n + i][c[i]];
        k[i] = (a[i] - b[i]) / 3.0;
      }
      r_q[i] = alpha[q] * (PG[i] + k[i] * PF[q]);
      result.residual[i] += r_q[i] * w;
    }
    if (!with_tangent) continue;

    const Tensor4& A = su.tangent;
    const double a2 = alpha[q] * alpha[q];
    const double wa2 = w * a2;
    const double t = fbar ? w * alpha[q] * PF[q] / 3.0 - B * w_bar[q] : 0.0;  // coefficient of T_ij
    const double bb = B * w_bar[q];                                        // coefficient of b_i b_j
    Tensor2 AF, FA;  // A : F and F : A
    double FAF = 0.0;
    if (fbar) {
      AF = dealii::double_contract<2, 0, 3, 1>(A, F[q]);
      FA = dealii::double_contract<0, 0, 1, 1>(F[q], A);
      FAF = dealii::scalar_product(F[q], AF);
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (unsigned c2 = 0; c2 < 3; ++c2) {
        for (unsigned e = 0; e < 3; ++e) {
          double h = 0.0;
          for (unsigned d = 0; d < 3; ++d) h += A[c[i]][d][c2][e] * g[i][d];
          H[i][c2][e] = wa2 * h;
        }
        H[i][c2][3] = fbar ? t * s[q * n + i][c2] : 0.0;
        if (fbar) s_component[c2][i] = s[q * n + i][c2];
      }
      U[i] = fbar ? a2 * (AF[c[i]] * g[i]) + r_q[i] : 0.0;
      V[i] = fbar ? a2 * (FA[c[i]] * g[i] + k[i] * FAF) + alpha[q] * PG[i] : 0.0;
      kw[i] = w * k[i];
    }
    for (std::size_t i = 0; i < n; ++i) {
      double* row = &result.tangent[i * n];
      const double* s_ci = s_component[c[i]].data();
      const double U_i = U[i], kw_i = kw[i], bb_i = bb * b[i];
      for (std::size_t j = 0; j < n; ++j) {
        const auto& h = H[i][c[j]];
        row[j] += h[0] * g[j][0] + h[1] * g[j][1] + h[2] * g[j][2] + h[3] * s_ci[j] + kw[j] * U_i + kw_i * V[j] +
                  bb_i * b[j];
      }
    }
  }
  if (fbar && with_tangent)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) result.tangent[i * n + j] -= B * a[i] * a[j];
}

}  // namespace dtwire::fem

#pragma once
// Element kernel of the total-Lagrangian displacement element, plain or F-bar (de Souza Neto,
// Peric, Dunne & Owen 1996, IJSS 33; de Souza Neto et al. 2008, sec. 15.2): the isochoric part
// of F from the quadrature point, the volume change from the element,
//   Fbar = (J0 / J)^(1/3) F,   J0 = (1/V) int J dV  (mean dilatation, Nagtegaal et al. 1974),
// in its variational form: residual r_i = int P(Fbar) : dFbar/du_i dV, whose exact derivative
// (with the second variation of Fbar) is the element tangent. With the element-mean J0 (rather
// than J at the centre) a homogeneous deformation gives exactly the plain residual, so the patch
// test holds on distorted meshes. Independent of deal.II FE classes so that it is tested alone
// against finite differences.
#include <vector>

#include "j2_log_plasticity.hpp"

namespace dtwire::fem {

struct ElementGeometry {
  // Vector-valued Lagrange elements: shape function i has one nonzero component,
  // component[i], and Grad phi_i = e_c (x) shape_grad[q][i] (reference configuration).
  std::vector<unsigned> component;
  std::vector<std::vector<dealii::Tensor<1, 3>>> shape_grad;
  std::vector<double> weight;  // JxW at each quadrature point
};

struct ElementResult {
  std::vector<double> residual;  // internal force, n_dofs
  std::vector<double> tangent;   // n_dofs x n_dofs, row-major: d residual_i / d u_j
  std::vector<StressUpdate> points;
  std::vector<double> jacobian;  // det F (not F-bar) at each quadrature point
};

// Throws std::domain_error if a quadrature point has det F <= 0.
void evaluate_element(const J2LogPlasticity& material, const ElementGeometry& geometry,
                      const std::vector<double>& displacement, const std::vector<PlasticState>& history,
                      bool fbar, bool with_tangent, ElementResult& result);

}  // namespace dtwire::fem

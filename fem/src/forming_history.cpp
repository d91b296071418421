#include "forming_history.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dtwire/core/error.hpp"

namespace dtwire::fem {

using namespace dealii;

PlasticState formed_state(const J2LogPlasticity& material, const Tensor<1, 3>& tangent, double axial_log_strain,
                          unsigned increments) {
  // The path in the fibre's frame (axis e_0), F = diag(la, ll, ll); ll from P_11 = 0 by Newton.
  PlasticState state;
  Tensor2 F = unit_symmetric_tensor<3>();
  double lateral = 1.0;
  for (unsigned k = 1; k <= increments; ++k) {
    F[0][0] = std::exp(axial_log_strain * k / increments);
    StressUpdate u;
    for (unsigned it = 0;; ++it) {
      F[1][1] = F[2][2] = lateral;
      u = material.update(F, state, true);
      const double slope = u.tangent[1][1][1][1] + u.tangent[1][1][2][2];
      const double change = -u.first_piola[1][1] / slope;
      lateral += change;
      if (std::abs(change) < 1e-13) break;
      if (it == 50) throw ComputationError("forming history: no uniaxial stress state at strain " +
                                           std::to_string(axial_log_strain));
    }
    state = u.state;
  }
  // b_e = F Cp^-1 F^T and the backstress are diagonal with equal lateral entries: rotate them
  // onto the tangent as a I + (b - a) t (x) t.
  const SymTensor2 t_t = symmetrize(outer_product(tangent, tangent));
  const auto onto_tangent = [&](double axial, double lateral_value) {
    return lateral_value * unit_symmetric_tensor<3>() + (axial - lateral_value) * t_t;
  };
  PlasticState formed = state;
  const double ba = F[0][0] * F[0][0] * state.plastic_metric_inverse[0][0];
  const double bl = F[1][1] * F[1][1] * state.plastic_metric_inverse[1][1];
  formed.plastic_metric_inverse = onto_tangent(ba, bl);
  formed.backstress = onto_tangent(state.backstress[0][0], state.backstress[1][1]);
  return formed;
}

WireAxes::WireAxes(const std::vector<std::vector<AxisStation>>& wires) {
  for (const auto& wire : wires) {
    auto& stations = stations_.emplace_back();
    for (const AxisStation& a : wire) {
      Station st;
      st.arc_length = a.arc_length;
      for (unsigned c = 0; c < 3; ++c) {
        st.point[c] = a.point[c];
        st.tangent[c] = a.tangent[c];
        st.curvature[c] = a.curvature[c];
      }
      stations.push_back(st);
    }
  }
  if (stations_.empty()) throw InputError("As made/Axis file", "no stations");
}

AxisLocation WireAxes::locate(unsigned wire, const Point<3>& x) const {
  if (wire >= stations_.size())
    throw InputError("As made/Axis file", "the mesh has wire " + std::to_string(wire) + " but the axis file " +
                                              std::to_string(stations_.size()) + " wire(s)");
  const auto& w = stations_[wire];
  std::size_t k = 0;
  double best = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < w.size(); ++i)
    if (const double d = (x - w[i].point).norm_square(); d < best) best = d, k = i;
  // The neighbour on the side of x's foot point, and the fraction of the way to it.
  const double along = (x - w[k].point) * w[k].tangent;
  const std::size_t j = along >= 0 ? std::min(k + 1, w.size() - 1) : (k == 0 ? 0 : k - 1);
  double f = 0.0;
  if (j != k) f = std::clamp(std::abs(along) / (w[j].point - w[k].point).norm(), 0.0, 1.0);
  const Point<3> p = w[k].point + f * (w[j].point - w[k].point);
  Tensor<1, 3> t = (1 - f) * w[k].tangent + f * w[j].tangent;
  t /= t.norm();
  const Tensor<1, 3> kappa = (1 - f) * w[k].curvature + f * w[j].curvature;
  Tensor<1, 3> y = x - p;
  y -= (y * t) * t;
  AxisLocation location;
  location.point = p;
  location.tangent = t;
  const double stretch = 1.0 - kappa * y;
  if (!(stretch > 0.0))
    throw ComputationError("forming history: the point (" + std::to_string(1e3 * x[0]) + ", " +
                           std::to_string(1e3 * x[1]) + ", " + std::to_string(1e3 * x[2]) + ") mm of wire " +
                           std::to_string(wire) + " lies beyond the centre of curvature of its axis (offset " +
                           std::to_string(1e3 * y.norm()) + " mm, radius of curvature " +
                           std::to_string(1e3 / kappa.norm()) + " mm): is the axis file that of the mesh?");
  location.bending_strain = std::log(stretch);
  location.arc_length = (1 - f) * w[k].arc_length + f * w[j].arc_length;
  location.station = static_cast<unsigned>(f < 0.5 ? k : j);
  return location;
}

}  // namespace dtwire::fem

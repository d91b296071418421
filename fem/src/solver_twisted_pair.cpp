// The twisted pair's state (issue 19): written at the end of a twisting run with Release after
// path, mapped onto a DT mesh's twist by As made/Twisted pair state (twisted_pair_state.hpp).
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dtwire/core/region_ids.hpp"
#include "forming_history.hpp"
#include "plastic_state_pack.hpp"
#include "solver_impl.hpp"
#include "twisted_pair_state.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {
bool is_free_part(types::material_id id) {
  return (id - 1) % 10 == static_cast<int>(regions::WirePart::Free);
}
constexpr unsigned kPackedPoint = 1 + 1 + 3 + kPackedPlasticStateSize;  // wire, station, position, state (b_e, ...)
}  // namespace

void WireSolver::Impl::write_twisted_pair_state(const std::filesystem::path& file) {
  const WireAxes axes(prm.forming.axes);
  refresh_relevant_values();
  FEValues<3> values(fe, quadrature, update_quadrature_points | update_gradients | update_values | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  const unsigned n_q = quadrature.size();
  std::vector<Tensor<2, 3>> gradients(n_q);
  std::vector<Tensor<1, 3>> u(n_q);
  // Per point: wire, station, deformed position, b_e = Fbar Cp^-1 Fbar^T and the rest of the state.
  std::vector<double> packed;
  std::vector<unsigned> first(axes.wires() + 1, 0);
  for (unsigned w = 0; w < axes.wires(); ++w) first[w + 1] = first[w] + axes.stations(w);
  std::vector<double> weight(first.back()), reference_z(first.back()), centroid(3 * first.back());
  double z0 = std::numeric_limits<double>::max(), z1 = -z0;
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned() || is_coating(cell->material_id())) continue;
    if (is_free_part(cell->material_id()))
      for (const unsigned v : cell->vertex_indices()) z0 = std::min(z0, cell->vertex(v)[2]), z1 = std::max(z1, cell->vertex(v)[2]);
    values.reinit(cell);
    values[displacement].get_function_gradients(ghosted, gradients);
    values[displacement].get_function_values(ghosted, u);
    const unsigned wire = prm.geometry.double_twist ? static_cast<unsigned>(regions::wire_of_id(cell->material_id())) : 0;
    double volume = 0.0, deformed_volume = 0.0;  // F-bar's element-mean J (fbar_element.hpp)
    for (unsigned q = 0; q < n_q; ++q) {
      Tensor<2, 3> F = gradients[q];
      for (unsigned c = 0; c < 3; ++c) F[c][c] += 1.0;
      volume += values.JxW(q);
      deformed_volume += determinant(F) * values.JxW(q);
    }
    for (unsigned q = 0; q < n_q; ++q) {
      const Point<3>& X = values.quadrature_point(q);
      const AxisLocation at = axes.locate(wire, X);
      Tensor<2, 3> F = gradients[q];
      for (unsigned c = 0; c < 3; ++c) F[c][c] += 1.0;
      if (prm.formulation.fbar) F *= std::cbrt(deformed_volume / volume / determinant(F));
      PlasticState state = points[cell->active_cell_index() * n_q + q].committed;
      state.plastic_metric_inverse = symmetrize(Tensor<2, 3>(F * Tensor<2, 3>(state.plastic_metric_inverse) * transpose(F)));
      const unsigned k = first[wire] + at.station;
      const Point<3> x = X + u[q];
      weight[k] += values.JxW(q);
      reference_z[k] += X[2] * values.JxW(q);
      for (unsigned c = 0; c < 3; ++c) centroid[3 * k + c] += x[c] * values.JxW(q);
      packed.insert(packed.end(), {double(wire), double(k), x[0], x[1], x[2]});
      pack_plastic_state(state, packed);
    }
  }
  Utilities::MPI::sum(weight, comm, weight);
  Utilities::MPI::sum(reference_z, comm, reference_z);
  Utilities::MPI::sum(centroid, comm, centroid);
  z0 = Utilities::MPI::min(z0, comm);
  z1 = Utilities::MPI::max(z1, comm);
  const auto gathered = Utilities::MPI::gather(comm, packed, 0);
  if (Utilities::MPI::this_mpi_process(comm) != 0) return;
  std::vector<TwistedPairPoint> rows;
  for (const auto& part : gathered)
    for (std::size_t i = 0; i + kPackedPoint <= part.size(); i += kPackedPoint) {
      TwistedPairPoint p;
      p.wire = static_cast<unsigned>(part[i]);
      const auto k = static_cast<std::size_t>(part[i + 1]);
      p.station_z_ref = reference_z[k] / weight[k];
      for (unsigned c = 0; c < 3; ++c) p.axis[c] = centroid[3 * k + c] / weight[k], p.position[c] = part[i + 2 + c];
      const double* in = part.data() + i + 5;
      p.state = unpack_plastic_state(in);
      rows.push_back(p);
    }
  write_twisted_pair_csv(file, z0, z1, rows);
  log << "twisted pair state: " << rows.size() << " points, twisted between z = " << z0 * 1e3 << " and " << z1 * 1e3
      << " mm, written to " << file.filename().string() << "\n";
}

void WireSolver::Impl::apply_twisted_pair_state(const std::filesystem::path& file) {
  Timer timer;
  const TwistedPairState pair(file, prm.forming.axes);
  const WireAxes axes(prm.forming.axes);
  auto& f = stats.forming;
  FEValues<3> values(fe, quadrature, update_quadrature_points);
  const unsigned n_q = quadrature.size();
  std::size_t mapped = 0, steel = 0;
  double largest = 0.0;
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned() || is_coating(cell->material_id())) continue;
    values.reinit(cell);
    const unsigned wire = static_cast<unsigned>(regions::wire_of_id(cell->material_id()));
    for (unsigned q = 0; q < n_q; ++q) {
      const Point<3>& X = values.quadrature_point(q);
      const TransferredState t = pair.at(wire, X, axes.locate(wire, X).point);
      ++steel;
      if (!t.inside) continue;
      ++mapped;
      largest = std::max(largest, t.distance);
      auto& point = points[cell->active_cell_index() * n_q + q];
      point.committed = point.trial = t.state;
    }
  }
  f.mapped_points = Utilities::MPI::sum(mapped, comm);
  f.steel_points = Utilities::MPI::sum(steel, comm);
  f.largest_mapping_distance = Utilities::MPI::max(largest, comm);
  log << "as made: the twist (z = " << pair.twist_bottom() * 1e3 << " to " << pair.twist_top() * 1e3
      << " mm) takes the state of " << file.filename().string() << ": " << f.mapped_points << " of " << f.steel_points
      << " steel points, farthest " << f.largest_mapping_distance * 1e3 << " mm from the pair point they took ("
      << timer.wall_time() << " s)\n";
}

}  // namespace dtwire::fem

// The non-local crack initiation (j2_log_plasticity.hpp, FailureParameters::nonlocal_radius):
// after each converged step, the average of the committed failure indicator D over a ball of
// radius R around every steel quadrature point, within its own wire (nonlocal_average.hpp). Every
// rank gathers the steel points of all ranks once (reference positions, J x W, wire) and their D
// after each step: a few 10^4 points on the DT meshes, so a plain all-gather costs little against
// a step's factorisations. The coating's points (and a run without a radius) keep their own D.
#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>

#include <sstream>

#include "dtwire/core/error.hpp"
#include "dtwire/core/region_ids.hpp"
#include "dtwire/core/resources.hpp"
#include "nonlocal_average.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {

template <typename T>
std::vector<T> concatenated(const std::vector<std::vector<T>>& parts) {
  std::vector<T> all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace

void WireSolver::Impl::make_nonlocal_average() {
  FEValues<3> values(fe, quadrature, update_quadrature_points | update_JxW_values);
  const unsigned n_q = quadrature.size();
  std::vector<std::array<double, 3>> positions;
  std::vector<double> volumes;
  std::vector<int> groups;
  nonlocal_points.clear();
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned() || is_coating(cell->material_id())) continue;
    values.reinit(cell);
    const int wire = prm.geometry.double_twist ? regions::wire_of_id(cell->material_id()) : 0;
    for (unsigned q = 0; q < n_q; ++q) {
      const Point<3>& x = values.quadrature_point(q);
      positions.push_back({{x[0], x[1], x[2]}});
      volumes.push_back(values.JxW(q));
      groups.push_back(wire);
      nonlocal_points.push_back(cell->active_cell_index() * n_q + q);
    }
  }
  const auto rank_positions = Utilities::MPI::all_gather(comm, positions);
  std::size_t first = 0;
  for (unsigned r = 0; r < Utilities::MPI::this_mpi_process(comm); ++r) first += rank_positions[r].size();
  std::vector<std::size_t> own(positions.size());
  for (std::size_t i = 0; i < own.size(); ++i) own[i] = first + i;
  const std::vector<std::array<double, 3>> all_positions = concatenated(rank_positions);
  const std::vector<int> all_groups = concatenated(Utilities::MPI::all_gather(comm, groups));
  const double radius = prm.material.failure.nonlocal_radius;
  // The weights take 8 bytes a pair (an index and a weight) on the rank that averages: counted
  // first, against the memory the first rank reads, so that every rank refuses alike.
  const double bytes =
      Utilities::MPI::sum(8.0 * static_cast<double>(NonlocalAverage::count_pairs(all_positions, all_groups, radius, own)), comm);
  const auto available = Utilities::MPI::broadcast(comm, available_memory().value_or(0), 0);
  if (available > 0 && bytes > 0.5 * static_cast<double>(available)) {
    std::ostringstream message;
    message << "'Nonlocal radius (mm)' = " << radius * 1e3 << " puts so many points in each ball that its weights take "
            << format_bytes(bytes) << ", more than half of the " << format_bytes(static_cast<double>(available))
            << " of memory available; expected a radius of a few cells (the largest ball holds every point of a wire)";
    throw InputError("subsection Material", message.str());
  }
  nonlocal = std::make_unique<NonlocalAverage>(all_positions, concatenated(Utilities::MPI::all_gather(comm, volumes)),
                                               all_groups, radius, std::move(own));
  std::size_t fewest = std::numeric_limits<std::size_t>::max(), most = 0;
  for (std::size_t i = 0; i < nonlocal->size(); ++i) {
    fewest = std::min(fewest, nonlocal->neighbours(i));
    most = std::max(most, nonlocal->neighbours(i));
  }
  fewest = Utilities::MPI::min(fewest, comm);
  most = Utilities::MPI::max(most, comm);
  log << "non-local crack initiation: radius " << prm.material.failure.nonlocal_radius * 1e3 << " mm, "
      << Utilities::MPI::sum(nonlocal->size(), comm) << " steel points, " << fewest << " to " << most
      << " points in a ball\n";
}

void WireSolver::Impl::update_nonlocal_indicator() {
  if (!prm.material.failure.nonlocal()) return;
  if (!nonlocal) make_nonlocal_average();
  std::vector<double> damage(nonlocal_points.size());
  for (std::size_t i = 0; i < damage.size(); ++i) damage[i] = points[nonlocal_points[i]].committed.damage;
  const std::vector<double> average = nonlocal->apply(concatenated(Utilities::MPI::all_gather(comm, damage)));
  for (auto& p : points) p.committed.nonlocal_damage = p.trial.nonlocal_damage = p.committed.damage;  // the coating
  for (std::size_t i = 0; i < average.size(); ++i) {
    auto& p = points[nonlocal_points[i]];
    p.committed.nonlocal_damage = p.trial.nonlocal_damage = average[i];
  }
}

}  // namespace dtwire::fem

// The as-made state file (As made/State file): the springback's result written once and read by
// later runs instead of forming and releasing again. Rank-independent: one block per active cell,
// in the order of cell_order_key (the mesh file's order of coarse cells, then the children of a
// junction refinement, junction_refinement.hpp), holding the cell's centre (to
// recognise the mesh), its displacement dof values and the committed material state of its
// quadrature points; written by rank 0 from what every rank gathered, read whole by every rank.
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <deal.II/base/timer.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "forming_history.hpp"
#include "junction_refinement.hpp"
#include "plastic_state_pack.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {

constexpr char kStateMagic[16] = "dtwire-asmade-2";  // 2: the softening in each point's state

// The material's answer to three uniaxial forming paths (compression, moderate and large
// tension): a state formed with other hardening, backstress or failure parameters differs.
std::vector<double> material_fingerprint(const J2LogPlasticity& material, const Parameters& prm) {
  std::vector<double> values{prm.material.young, prm.material.poisson};
  Tensor<1, 3> axis;
  axis[2] = 1.0;
  for (const double strain : {-0.1, 0.05, 0.2}) {
    const PlasticState s = formed_state(material, axis, strain, 20);
    values.insert(values.end(), {s.equivalent_plastic_strain, s.backstress[2][2], s.damage});
  }
  return values;
}

bool same_material(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::abs(a[k] - b[k]) > 1e-9 * std::max({std::abs(a[k]), std::abs(b[k]), 1e-12})) return false;
  return true;
}

std::vector<double> pack_summary(const FormingSummary& f) {
  return {static_cast<double>(f.steps), static_cast<double>(f.newton_iterations), static_cast<double>(f.cutbacks),
          f.seconds, f.initial_elastic_energy, f.elastic_energy, f.plastic_work, f.friction_work, f.holding_work,
          f.energy_balance, f.largest_displacement, static_cast<double>(f.clearance_points),
          static_cast<double>(f.points_in_contact), f.clearance_mean, f.clearance_largest};
}

void unpack_summary(const std::vector<double>& v, FormingSummary& f) {
  f.steps = static_cast<unsigned>(v[0]);
  f.newton_iterations = static_cast<unsigned>(v[1]);
  f.cutbacks = static_cast<unsigned>(v[2]);
  f.seconds = v[3];
  f.initial_elastic_energy = v[4];
  f.elastic_energy = v[5];
  f.plastic_work = v[6];
  f.friction_work = v[7];
  f.holding_work = v[8];
  f.energy_balance = v[9];
  f.largest_displacement = v[10];
  f.clearance_points = static_cast<unsigned>(v[11]);
  f.points_in_contact = static_cast<unsigned>(v[12]);
  f.clearance_mean = v[13];
  f.clearance_largest = v[14];
}
constexpr std::size_t kSummarySize = 15;

// Every active cell's order key, from all ranks, sorted: a cell's block is at its key's position.
std::vector<double> sorted_cell_keys(const parallel::distributed::Triangulation<3>& tria, MPI_Comm comm) {
  std::vector<double> owned;
  for (const auto& cell : tria.active_cell_iterators())
    if (cell->is_locally_owned()) owned.push_back(cell_order_key(cell->id()));
  std::vector<double> keys;
  for (const auto& block : Utilities::MPI::all_gather(comm, owned)) keys.insert(keys.end(), block.begin(), block.end());
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::size_t cell_position(const std::vector<double>& keys, const CellId& id) {
  return static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), cell_order_key(id)) - keys.begin());
}

}  // namespace

// Header: cells, DoFs, degree, quadrature points per cell, dof values per cell, forming scale.
std::vector<double> WireSolver::Impl::as_made_header() const {
  return {static_cast<double>(triangulation.n_global_active_cells()), static_cast<double>(dof_handler.n_dofs()),
          static_cast<double>(prm.formulation.degree), static_cast<double>(quadrature.size()),
          static_cast<double>(fe.n_dofs_per_cell()), prm.forming.scale};
}

void WireSolver::Impl::write_as_made_state(const std::filesystem::path& file) {
  refresh_relevant_values();
  const unsigned n_q = quadrature.size(), per_cell = 3 + fe.n_dofs_per_cell() + kPackedPlasticStateSize * n_q;
  const std::vector<double> keys = sorted_cell_keys(triangulation, comm);
  std::vector<double> blocks;  // per owned cell: its position in the file, then its values
  Vector<double> cell_values(fe.n_dofs_per_cell());
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    blocks.push_back(static_cast<double>(cell_position(keys, cell->id())));
    const Point<3> centre = cell->center();
    blocks.insert(blocks.end(), {centre[0], centre[1], centre[2]});
    cell->get_dof_values(ghosted, cell_values);
    blocks.insert(blocks.end(), cell_values.begin(), cell_values.end());
    for (unsigned q = 0; q < n_q; ++q) pack_plastic_state(points[cell->active_cell_index() * n_q + q].committed, blocks);
  }
  const auto gathered = Utilities::MPI::gather(comm, blocks, 0);
  if (Utilities::MPI::this_mpi_process(comm) == 0) {
    const std::size_t n_cells = triangulation.n_global_active_cells();
    std::vector<double> cells(n_cells * per_cell);
    for (const auto& rank_blocks : gathered)
      for (std::size_t at = 0; at < rank_blocks.size(); at += 1 + per_cell) {
        const auto id = static_cast<std::size_t>(rank_blocks[at]);
        std::copy_n(rank_blocks.begin() + static_cast<long>(at) + 1, per_cell, cells.begin() + static_cast<long>(id * per_cell));
      }
    const auto temporary = file.string() + ".tmp";
    {
      std::ofstream out(temporary, std::ios::binary);
      out.write(kStateMagic, sizeof kStateMagic);
      boost::archive::binary_oarchive archive(out);
      const std::string version = std::string(tool_version()) + " (" + git_hash() + ")";
      const std::string mesh = prm.geometry.mesh_file.filename().string();
      const std::string axis = prm.forming.axis_file.filename().string();
      archive << version << mesh << axis << as_made_header() << material_fingerprint(material, prm)
              << pack_summary(stats.forming) << cells;
      if (!out) throw ComputationError("cannot write the as-made state " + temporary);
    }
    std::filesystem::rename(temporary, file);
  }
  MPI_Barrier(comm);
  log << "as made: state written to " << file.string() << "\n";
}

// Reads the state, then lets the contact parts start from that configuration without friction
// history, and re-balances it in one settling solve (what the friction held at rest is lost).
void WireSolver::Impl::read_as_made_state(const std::filesystem::path& file) {
  Timer timer;
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  char magic[sizeof kStateMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::string(magic) != kStateMagic)
    throw InputError(name, "not a dtwire as-made state (written by a run with As made/Forming history = true)");
  std::string version, mesh, axis;
  std::vector<double> header, fingerprint, summary, cells;
  try {
    boost::archive::binary_iarchive archive(in);
    archive >> version >> mesh >> axis >> header >> fingerprint >> summary >> cells;
  } catch (const std::exception& e) {
    throw InputError(name, std::string("unreadable as-made state: ") + e.what());
  }
  const auto expected = as_made_header();
  if (header.size() != expected.size() || summary.size() != kSummarySize)
    throw InputError(name, "an as-made state of another format");
  if (!std::equal(expected.begin(), expected.end() - 1, header.begin()))
    throw InputError(name, "formed on another mesh or element (" + mesh + ": " + std::to_string(std::lround(header[0])) +
                               " cells, " + std::to_string(std::lround(header[1])) + " DoFs, degree " +
                               std::to_string(std::lround(header[2])) + "; this run: " +
                               std::to_string(std::lround(expected[0])) + " cells, " +
                               std::to_string(std::lround(expected[1])) + " DoFs, degree " +
                               std::to_string(std::lround(expected[2])) + ")");
  if (header.back() != expected.back())
    throw InputError(name, "formed with Forming scale " + std::to_string(header.back()) + ", this run asks for " +
                               std::to_string(expected.back()));
  if (!same_material(fingerprint, material_fingerprint(material, prm)))
    throw InputError(name, "formed with another material (elasticity, hardening, backstress or failure parameters "
                           "differ from this run's Material section)");
  const unsigned n_q = quadrature.size(), per_cell = 3 + fe.n_dofs_per_cell() + kPackedPlasticStateSize * n_q;
  if (cells.size() != expected[0] * per_cell) throw InputError(name, "truncated as-made state");

  // The same cell count on another geometry (say, longer arms): the cell centres tell.
  const std::vector<double> keys = sorted_cell_keys(triangulation, comm);
  double misplaced = 0.0;
  for (const auto& cell : triangulation.active_cell_iterators())
    if (cell->is_locally_owned()) {
      const double* centre = cells.data() + cell_position(keys, cell->id()) * per_cell;
      misplaced = std::max(misplaced, cell->center().distance(Point<3>(centre[0], centre[1], centre[2])));
    }
  misplaced = Utilities::MPI::max(misplaced, comm);
  if (misplaced > 1e-9)
    throw InputError(name, "formed on another mesh (" + mesh + "): a cell centre lies " +
                               std::to_string(misplaced * 1e3) + " mm from this mesh's");
  std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    const double* values = cells.data() + cell_position(keys, cell->id()) * per_cell + 3;
    cell->get_dof_indices(dofs);
    for (unsigned i = 0; i < dofs.size(); ++i)
      if (owned.is_element(dofs[i])) solution[dofs[i]] = values[i];
    values += dofs.size();
    for (unsigned q = 0; q < n_q; ++q) {
      auto& point = points[cell->active_cell_index() * n_q + q];
      point.trial = point.committed = unpack_plastic_state(values);
    }
  }
  solution.compress(VectorOperation::insert);
  unpack_summary(summary, stats.forming);

  assemble(false, homogeneous);  // current positions for the contact parts
  for (const auto& part : contact_parts)
    if (!part->restart_here())
      throw InputError(name, "the " + part->name() + " cannot start from a saved state (use Grip interface = clamped)");
  const PETScWrappers::MPI::Vector loaded = solution;
  unsigned iterations = 0;
  std::string reason;
  if (!solve_contact_step(0.0, 0.0, nullptr, loaded, iterations, reason))
    throw ComputationError("the as-made state of " + name + " does not settle in this run's fixtures (" + reason + ")");
  commit();
  PETScWrappers::MPI::Vector change = solution;
  change -= loaded;
  assemble(false, homogeneous);
  record_forming_profile();
  StepRecord reset;  // the top end's work counts from here
  record_end(reset);
  end_work = tool_work = 0.0;
  stats.forming.done = true;
  stats.forming.state_file = file;
  log << "as made: state read from " << name << " (formed on " << mesh << " with " << axis << " by dtwire " << version
      << "; springback there: " << stats.forming.steps << " steps, balance " << 100.0 * stats.forming.energy_balance
      << " %); settled in " << iterations << " Newton iterations, largest displacement "
      << change.linfty_norm() * 1e3 << " mm, " << timer.wall_time() << " s\n";
}

}  // namespace dtwire::fem

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <cstdio>
#include <fstream>

#include "contact/packed_state.hpp"
#include "dtwire/core/error.hpp"
#include "plastic_state_pack.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

std::filesystem::path WireSolver::Impl::checkpoint_file(unsigned step) const {
  char name[32];
  std::snprintf(name, sizeof name, "step_%05u", step);
  return checkpoint_directory / name / ("rank_" + std::to_string(Utilities::MPI::this_mpi_process(comm)) + ".bin");
}

namespace {
constexpr char kCheckpointMagic[16] = "dtwire-ckpt-6";  // 6: 16 doubles per point (softening)
}  // namespace

// Layout: magic, then one boost binary archive: the header (ranks, DoFs, cells, quadrature
// points), the stepping state, the statistics, the step records (each serialises every field),
// this rank's solution and last step values, the committed material state of its points, the
// names of the contact parts and the state of each part (part_states).
void WireSolver::Impl::write_checkpoint(const SteppingState& state, const PETScWrappers::MPI::Vector& last_step) {
  const auto file = checkpoint_file(state.step);
  std::filesystem::create_directories(file.parent_path());
  std::vector<double> header = {static_cast<double>(stats.ranks), static_cast<double>(stats.dofs),
                                static_cast<double>(triangulation.n_active_cells()), static_cast<double>(quadrature.size())};
  std::vector<double> stepping = {static_cast<double>(state.step), state.t, state.dt, state.last_dt, state.last_knot,
                                  static_cast<double>(stats.steps), static_cast<double>(stats.newton_iterations),
                                  static_cast<double>(stats.cutbacks)};
  std::vector<double> values;
  for (const auto i : owned) values.push_back(solution[i]);
  for (const auto i : owned) values.push_back(last_step[i]);
  for (const auto& p : points) pack_plastic_state(p.committed, values);
  const auto temporary = file.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(kCheckpointMagic, sizeof kCheckpointMagic);
    boost::archive::binary_oarchive archive(out);
    archive << header << stepping << history << values << part_names() << part_states();
    if (!out) throw ComputationError("cannot write checkpoint " + temporary);
  }
  std::filesystem::rename(temporary, file);
  log << "  checkpoint written: " << file.parent_path().string() << "\n";
}

void WireSolver::Impl::read_checkpoint(unsigned step, SteppingState& state, PETScWrappers::MPI::Vector& last_step) {
  const auto file = checkpoint_file(step);
  std::ifstream in(file, std::ios::binary);
  char magic[sizeof kCheckpointMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::string(magic) != kCheckpointMagic)
    throw InputError(file.string(), "not a dtwire checkpoint of this version (or missing)");
  std::vector<double> header, stepping, values;
  std::vector<std::string> names;
  std::vector<std::vector<double>> parts;
  try {
    boost::archive::binary_iarchive archive(in);
    archive >> header >> stepping >> history >> values >> names >> parts;
  } catch (const std::exception& e) {
    throw InputError(file.string(), std::string("unreadable checkpoint: ") + e.what());
  }
  const std::vector<double> expected = {static_cast<double>(stats.ranks), static_cast<double>(stats.dofs),
                                        static_cast<double>(triangulation.n_active_cells()), static_cast<double>(quadrature.size())};
  if (header != expected)
    throw InputError(file.string(), "checkpoint from another mesh, element or number of MPI ranks");
  const std::size_t n_values = 2 * owned.n_elements() + kPackedPlasticStateSize * points.size();
  if (stepping.size() != 8 || values.size() != n_values)
    throw InputError(file.string(), "checkpoint of another size than this run's state");
  state.step = static_cast<unsigned>(stepping[0]);
  state.t = stepping[1];
  state.dt = stepping[2];
  state.last_dt = stepping[3];
  state.last_knot = stepping[4];
  stats.steps = static_cast<std::size_t>(stepping[5]);
  stats.newton_iterations = static_cast<std::size_t>(stepping[6]);
  stats.cutbacks = static_cast<std::size_t>(stepping[7]);
  std::size_t k = 0;
  for (const auto i : owned) solution[i] = values[k++];
  for (const auto i : owned) last_step[i] = values[k++];
  solution.compress(VectorOperation::insert);
  last_step.compress(VectorOperation::insert);
  const double* packed = values.data() + k;
  for (auto& p : points) p.trial = p.committed = unpack_plastic_state(packed);
  restore_part_states(names, parts, file.string());
}

std::vector<std::string> WireSolver::Impl::part_names() const {
  std::vector<std::string> names;
  for (const auto& part : contact_parts) names.push_back(part->name());
  return names;
}

// One list per contact part, then the external-work sums.
std::vector<std::vector<double>> WireSolver::Impl::part_states() const {
  std::vector<std::vector<double>> states;
  for (const auto& part : contact_parts) states.push_back(part->saved_state());
  contact::StateWriter work;
  work.put(end_work);
  work.put(tool_work);
  for (std::size_t k = 0; k < top_end_dofs.size(); ++k) {
    work.put(previous_end_force[k]);
    work.put(previous_end_displacement[k]);
  }
  work.put(previous_tool_force.size());
  for (std::size_t k = 0; k < previous_tool_force.size(); ++k)
    for (unsigned c = 0; c < 3; ++c) {
      work.put(previous_tool_force[k][c]);
      work.put(previous_tool_displacement[k][c]);
    }
  states.push_back(work.take());
  return states;
}

void WireSolver::Impl::restore_part_states(const std::vector<std::string>& names,
                                           const std::vector<std::vector<double>>& parts, const std::string& file) {
  if (names != part_names()) {
    const auto list = [](const std::vector<std::string>& n) {
      std::string text;
      for (const auto& name : n) text += (text.empty() ? "" : ", ") + name;
      return text.empty() ? std::string("no contact parts") : text;
    };
    throw InputError(file, "checkpoint of a run with " + list(names) + ", unlike this one (" + list(part_names()) + ")");
  }
  if (parts.size() != contact_parts.size() + 1) throw InputError(file, "checkpoint without the state of the contact parts");
  try {
    for (std::size_t k = 0; k < contact_parts.size(); ++k) contact_parts[k]->restore_state(parts[k]);
    contact::StateReader work(parts.back(), "external work");
    end_work = work.get();
    tool_work = work.get();
    for (std::size_t k = 0; k < top_end_dofs.size(); ++k) {
      previous_end_force[k] = work.get();
      previous_end_displacement[k] = work.get();
    }
    const long tools = static_cast<long>(prm.contact.tools.size());
    previous_tool_force.resize(static_cast<std::size_t>(work.get_whole(0, tools)));
    previous_tool_displacement.resize(previous_tool_force.size());
    for (std::size_t k = 0; k < previous_tool_force.size(); ++k)
      for (unsigned c = 0; c < 3; ++c) {
        previous_tool_force[k][c] = work.get();
        previous_tool_displacement[k][c] = work.get();
      }
    work.finish();
  } catch (const std::invalid_argument& e) {
    throw InputError(file, std::string("checkpoint does not fit this run: ") + e.what());
  }
  if (wire_contact) make_matrix();  // the restored pattern holds every pair met so far
}

void WireSolver::set_checkpoints(const std::filesystem::path& directory, unsigned interval, int restart_step) {
  impl_->checkpoint_directory = directory;
  impl_->checkpoint_interval = interval;
  impl_->restart_step = restart_step;
}

}  // namespace dtwire::fem

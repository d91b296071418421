#pragma once
// The parts of the FE model that act on the wire's surface and keep state of their own between
// load steps (rigid tools, wire-wire contact, bonded grips) behind one interface. The solver holds
// them in a list, in the order they assemble, and calls each at the same points of the data path:
// begin a step, assemble (every Newton iteration), augment (Uzawa, after a converged solve),
// commit (after an accepted step), record, cell fields, save and restore (checkpoints).
#include <deal.II/base/index_set.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "../step_record.hpp"
#include "rigid_motion.hpp"

namespace dtwire::fem::contact {

// What a part may need when a load step begins.
struct StepStart {
  double t_old = 0.0, t_new = 0.0;              // load-path parameter
  const std::vector<double>* relevant_values = nullptr;  // committed displacements of the locally relevant dofs
  RigidMotion top_motion;                       // prescribed motion of the top end at t_new
  bool extrapolated = false;                    // the predictor extrapolates the previous increment
};

// Where a part adds its contributions (constrained like the cells').
struct AssemblyTarget {
  const dealii::IndexSet& relevant;
  const std::vector<double>& relevant_values;
  bool with_matrix;
  const dealii::AffineConstraints<double>& constraints;
  dealii::PETScWrappers::MPI::SparseMatrix& matrix;
  dealii::PETScWrappers::MPI::Vector& rhs;
  dealii::PETScWrappers::MPI::Vector& internal_force;
};

// Model -> whole specimen (symmetry multipliers): forces and energies.
struct RecordScales {
  const dealii::PETScWrappers::MPI::Vector& internal_force;
  double force = 1.0, energy = 1.0;
};

class ContactPart {
 public:
  virtual ~ContactPart() = default;
  // Names the part in logs and checkpoints ("contact tools", "wire contact", "bonded grips").
  virtual std::string name() const = 0;
  // Extra couplings of the matrix pattern (candidate pairs); none by default.
  virtual void add_sparsity(dealii::DynamicSparsityPattern&, const dealii::AffineConstraints<double>&) const {}
  // Returns true when the matrix pattern must be rebuilt (new candidate pairs).
  virtual bool begin_step(const StepStart& step) = 0;
  // false: a state the part cannot handle; the step is cut back.
  virtual bool assemble(const AssemblyTarget& target) = 0;
  // Uzawa update after a converged solve: true when the step is to be solved again.
  virtual bool augment() { return false; }
  virtual unsigned augmentations() const { return 0; }
  virtual void commit() = 0;
  // Fills the part's own columns of `record`; `log` (when given) gets a line about the step.
  virtual void record(const RecordScales& scales, StepRecord& record, std::ostream* log) const = 0;
  // Per-cell output (name with unit, values over the active cells).
  virtual std::vector<std::pair<std::string, dealii::Vector<float>>> cell_fields(unsigned n_cells) const {
    (void)n_cells;
    return {};
  }
  virtual std::vector<double> saved_state() const = 0;
  // Throws std::invalid_argument when `values` do not fit this part.
  virtual void restore_state(const std::vector<double>& values) = 0;
  // Called after an assembly at a configuration carried in from another run (the as-made state
  // file): that configuration becomes the committed one, with no friction history (tractions,
  // slip, multipliers, dissipation). false: the part cannot start this way.
  virtual bool restart_here() { return false; }
};

}  // namespace dtwire::fem::contact

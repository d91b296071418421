#pragma once
// Frictional contact of the wire with rigid analytic tools, assembled at the Gauss points of
// the wire's contact boundary faces (segment-to-analytic-surface; Wriggers 2006, sec. 9.1).
// Each (face quadrature point, tool) pair carries its own history (tangential traction, slip,
// augmented multiplier), committed only when a load step has converged. The solver calls:
// begin_step() before each step, assemble() inside every residual/tangent assembly (adds to
// the element contributions before compress), augment() after a converged Newton solve (Uzawa:
// true means "multipliers updated, solve the step again"), commit() with the material history.
#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <set>
#include <vector>

#include "contact_kernel.hpp"
#include "contact_part.hpp"
#include "contact_parameters.hpp"
#include "contact_record.hpp"

namespace dtwire::fem::contact {

class RigidToolContact final : public ContactPart {
 public:
  // `young` and the smallest contact face size set the penalties (epsilon = factor E / h).
  RigidToolContact(const ContactParameters& parameters, double young, const dealii::DoFHandler<3>& dof_handler,
                   const std::set<dealii::types::boundary_id>& bottom_ids,
                   const std::set<dealii::types::boundary_id>& top_ids, MPI_Comm comm);

  std::string name() const override { return "contact tools"; }
  bool begin_step(const StepStart& step) override;
  // Returns false if a point cannot be evaluated (on a cylinder axis).
  bool assemble(const AssemblyTarget& target) override;
  bool augment() override;
  void commit() override;
  void record(const RecordScales& scales, StepRecord& record, std::ostream* log) const override;
  // Largest contact pressure (Pa) and accumulated slip (m) over each cell's contact points.
  std::vector<std::pair<std::string, dealii::Vector<float>>> cell_fields(unsigned n_cells) const override;

  const ContactLaw& law() const { return law_; }
  unsigned augmentations() const override { return augmentations_; }
  // The committed state for checkpoints (packed_state.hpp): point positions, each pair's
  // friction history, the dissipation.
  std::vector<double> saved_state() const override;
  void restore_state(const std::vector<double>& values) override;
  bool restart_here() override;

 private:
  ContactRecord totals(const dealii::PETScWrappers::MPI::Vector& internal_force, double force_scale,
                       double contact_scale) const;
  struct Face {
    std::vector<dealii::types::global_dof_index> dofs;
    unsigned first_point = 0, n_points = 0;
    unsigned cell = 0;  // active cell index
  };
  struct Point {
    Vector3 reference;            // X
    Vector3 committed_position;   // x at the last converged step
    Vector3 position;             // x at the last assembly
    double weight = 0.0;          // reference area
    std::vector<double> shape;    // cell shape values at this point (dofs_per_cell)
  };
  struct PairState {  // one (point, tool) pair
    ContactHistory committed;
    double multiplier = 0.0;  // trial augmented multiplier of this step
    ContactResponse last;     // response at the last assembly
    double slip = 0.0;        // accumulated, including the last assembly
  };

  ContactParameters parameters_;
  ContactLaw law_;
  MPI_Comm comm_;
  std::vector<unsigned> component_;  // component of each cell dof
  std::vector<Face> faces_;
  std::vector<Point> points_;
  std::vector<PairState> pairs_;     // points x tools
  std::vector<ToolGeometry> tools_;  // at the end of the current step
  std::vector<Vector3> tool_increment_;
  double time_ = 0.0;  // pseudo-time at the end of the current step
  std::array<dealii::IndexSet, 3> bottom_dofs_, top_dofs_;
  double dissipation_ = 0.0;  // committed, this rank, modelled part
  unsigned augmentations_ = 0;
};

}  // namespace dtwire::fem::contact

#pragma once
// Bonded grips (`Grip interface = bonded`): instead of Dirichlet clamps, every Gauss point of a
// grip face (the Bottom / Top boundary ids) is tied by the bond law (bond_law.hpp) to its anchor
// on the rigid grip, X + u_grip(X, t): u_grip = 0 for the bottom grips, the top end's rigid motion
// for the top grips. The top grips' bond slides at |t_T| = tau_b (the steel core sliding in a
// sheath held by the grips); the bottom grips' bond is elastic only: two rate-independent sliding
// grips in series on one wire would leave its axial position undetermined (zero tangent
// stiffness once both slide), and the curve is the same whichever grip slides.
// History (plastic slip per point) is committed only after a converged step. The solver calls
// begin_step() before each step, assemble() in every assembly, commit() with the material.
#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <set>
#include <vector>

#include "parameters.hpp"
#include "bond_law.hpp"
#include "contact_part.hpp"
#include "contact_record.hpp"
#include "rigid_motion.hpp"

namespace dtwire::fem::contact {

class BondedGrip final : public ContactPart {
 public:
  std::string name() const override { return "bonded grips"; }
  // Penalty k = stiffness_factor E / h, h the smallest grip face edge (all ranks).
  BondedGrip(const GripParameters& parameters, double young, const dealii::DoFHandler<3>& dof_handler,
             const std::set<dealii::types::boundary_id>& bottom_ids,
             const std::set<dealii::types::boundary_id>& top_ids, MPI_Comm comm);

  // Takes the top grips' motion at the end of the coming step. A step started without an
  // extrapolated increment (the solver's linearised predictor) has a stuck predictor: its first
  // assembly treats the bond as stuck, so that the grip drags the wire along as the clamps'
  // predictor does; the return map starts from there. Started from the committed state instead,
  // the return map sees the whole grip increment as slip (the elastic range tau_b / k is far
  // below a step), whose tangent has no stiffness along the slip: after a load reversal Newton
  // swung the wire between forward and reversed slip (15 iterations and 6 cut-backs per reversal).
  bool begin_step(const StepStart& step) override;
  // Adds the bond's residual (-int N t dA) and tangent to the system.
  bool assemble(const AssemblyTarget& target) override;
  void commit() override;

  // The pull of the top grips on the wire (this rank, modelled part, last assembly): the sum of
  // the bond tractions times their areas, and its moment about `centre` (current positions).
  void top_resultants(const Vector3& centre, Vector3& force, Vector3& moment) const;
  // Work of the top grips on the wire (this rank, modelled part): per point
  // (t_old + t_new) / 2 . (anchor_new - anchor_old), accumulated over the converged steps.
  double external_work() const { return work_; }
  // Totals over the ranks: areas times the force scale, energies times the energy scale.
  void record(const RecordScales& scales, StepRecord& record, std::ostream* log) const override;

  // The committed state for checkpoints (packed_state.hpp): per point the bond's slip history,
  // traction and anchor; the work and dissipation.
  std::vector<double> saved_state() const override;
  void restore_state(const std::vector<double>& values) override;

  double stiffness() const { return law_.stiffness; }
  double top_area() const { return top_area_; }        // m^2, all ranks, modelled part
  double bottom_area() const { return bottom_area_; }  // m^2, all ranks, modelled part

 private:
  GripRecord totals(double area_scale, double energy_scale) const;
  struct Point {
    Vector3 reference, normal;  // X and the outward normal of the reference face
    double weight = 0.0;        // reference area
    std::vector<double> shape;  // cell shape values at this point
    bool top = false;
    BondHistory committed;
    Vector3 committed_traction, committed_anchor;  // current frame, at the last converged step
    BondResponse last;                             // at the last assembly (grip frame)
    Vector3 traction, anchor, position;            // current frame, at the last assembly
  };
  struct Face {
    std::vector<dealii::types::global_dof_index> dofs;
    unsigned first_point = 0, n_points = 0;
  };

  MPI_Comm comm_;
  BondLaw top_law_, law_;  // law_: the bottom grips' (elastic); top_law_ slides
  std::vector<unsigned> component_;
  std::vector<Face> faces_;
  std::vector<Point> points_;
  RigidMotion top_;
  bool predictor_ = false;                // the next assembly is the stuck predictor
  double work_ = 0.0, dissipation_ = 0.0;  // this rank, modelled part, committed
  double top_area_ = 0.0, bottom_area_ = 0.0;
};

}  // namespace dtwire::fem::contact

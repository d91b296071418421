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
#include "contact_record.hpp"

namespace dtwire::fem::contact {

// A rigid motion X -> X + translation + (R - I)(X - centre).
struct RigidMotion {
  Matrix3 rotation;
  Vector3 translation, centre;
  Vector3 displacement(const Vector3& X) const { return translation + rotation * (X - centre) - (X - centre); }
};
RigidMotion identity_motion();

// The top end's rigid motion at pseudo-time t: the load path along `direction` and the rotation
// path about the rotation axis through `centre` (Rodrigues), as the clamped top end moves.
RigidMotion top_end_motion(const LoadParameters& load, const Vector3& direction, const Vector3& centre, double t);

class BondedGrip {
 public:
  // Penalty k = stiffness_factor E / h, h the smallest grip face edge (all ranks).
  BondedGrip(const GripParameters& parameters, double young, const dealii::DoFHandler<3>& dof_handler,
             const std::set<dealii::types::boundary_id>& bottom_ids,
             const std::set<dealii::types::boundary_id>& top_ids, MPI_Comm comm);

  // The top grips' motion at the end of the coming step. With `stuck_predictor` (a step started
  // without an extrapolated increment: the solver's linearised predictor) the step's first
  // assembly treats the bond as stuck, so that the grip drags the wire along as the clamps'
  // predictor does; the return map starts from there. Started from the committed state instead,
  // the return map sees the whole grip increment as slip (the elastic range tau_b / k is far
  // below a step), whose tangent has no stiffness along the slip: after a load reversal Newton
  // swung the wire between forward and reversed slip (15 iterations and 6 cut-backs per reversal).
  void begin_step(const RigidMotion& top, bool stuck_predictor);
  // Adds the bond's residual (-int N t dA) and tangent to the system.
  void assemble(const dealii::IndexSet& relevant, const std::vector<double>& relevant_values, bool with_matrix,
                const dealii::AffineConstraints<double>& constraints, dealii::PETScWrappers::MPI::SparseMatrix& matrix,
                dealii::PETScWrappers::MPI::Vector& rhs);
  void commit();

  // The pull of the top grips on the wire (this rank, modelled part, last assembly): the sum of
  // the bond tractions times their areas, and its moment about `centre` (current positions).
  void top_resultants(const Vector3& centre, Vector3& force, Vector3& moment) const;
  // Work of the top grips on the wire (this rank, modelled part): per point
  // (t_old + t_new) / 2 . (anchor_new - anchor_old), accumulated over the converged steps.
  double external_work() const { return work_; }
  // Totals over the ranks: areas times area_scale, energies times energy_scale.
  GripRecord record(double area_scale, double energy_scale) const;

  // The committed state for checkpoints (packed_state.hpp): per point the bond's slip history,
  // traction and anchor; the work and dissipation.
  std::vector<double> saved_state() const;
  void restore_state(const std::vector<double>& values);

  double stiffness() const { return law_.stiffness; }
  double top_area() const { return top_area_; }        // m^2, all ranks, modelled part
  double bottom_area() const { return bottom_area_; }  // m^2, all ranks, modelled part

 private:
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

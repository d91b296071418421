#pragma once
// Frictional contact between two deformable wires with finite sliding: Gauss points of the slave
// surface (wire A) projected onto the bilinear faces of the master surface (wire B), penalty
// normal law with optional Uzawa augmentation and Coulomb friction by the same return map as the
// rigid-tool kernel (Wriggers 2006, sec. 4.1 closest-point projection, 5.2 penalty, 10.5
// friction; Laursen 2002, ch. 5). The search keeps, per slave face, the master faces whose
// bounding boxes (inflated by the search distance) meet its own, found with an R-tree at the
// start of every step; the matrix pattern holds these couplings and grows when sliding brings
// new faces near. Chattering guards: a point whose stick/slip status or master face changed
// `flip_limit` times within a step keeps them for the rest of the step.
//
// Smoothed normals (optional): the master normal at a point is interpolated from averaged vertex
// normals (wire_contact_point.hpp), so each point couples to the vertices of the master faces
// around its face as well (the matrix pattern grows accordingly).
//
// Linearisation: consistent (wire_contact_point.hpp): the variations of the master normal, of the
// closest-point parameters and of the friction anchor are differentiated exactly (forward AD), so
// Newton converges quadratically once the stick/slip status and the master faces settle. Every
// rank holds the master surface (gathered once), so contact works across MPI
// partitions; contributions to constrained dofs this rank does not know are dropped (their rows
// are replaced by the constraint anyway; reactions still include the contact forces).
#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <vector>

#include "bilinear_face.hpp"
#include "contact_part.hpp"
#include "contact_parameters.hpp"
#include "contact_record.hpp"
#include "wire_contact_point.hpp"

namespace dtwire::fem::contact {

class WireWireContact final : public ContactPart {
 public:
  WireWireContact(const WireContactParameters& parameters, double young, double diameter,
                  const dealii::DoFHandler<3>& dof_handler, MPI_Comm comm);

  // Every master-surface dof: the solver adds them to its locally relevant set.
  const dealii::IndexSet& needed_dofs() const { return needed_; }
  // Once the relevant set and the constraints are final.
  void initialise(const dealii::IndexSet& relevant, const dealii::AffineConstraints<double>& constraints,
                  const dealii::IndexSet& owned);
  // Couplings of the current candidate pairs (slave face x master face).
  void add_sparsity(dealii::DynamicSparsityPattern& pattern,
                    const dealii::AffineConstraints<double>& constraints) const override;
  // Before each step, with the committed displacement: new candidate pairs from the R-tree.
  // Returns true (on every rank) if a pair is new to the matrix pattern: rebuild it.
  std::string name() const override { return "wire contact"; }
  bool begin_step(const StepStart& step) override;
  bool assemble(const AssemblyTarget& target) override;
  bool augment() override;
  void commit() override;
  void record(const RecordScales& scales, StepRecord& record, std::ostream* log) const override;
  // Largest pressure (Pa) and accumulated slip (m) over each slave cell's points.
  std::vector<std::pair<std::string, dealii::Vector<float>>> cell_fields(unsigned n_cells) const override;
  unsigned augmentations() const override { return augmentations_; }
  // The normal gap between the wires at the slave points that project onto wire B (last
  // assembly), over all ranks: the clearance a springback leaves (m).
  struct Clearance {
    unsigned points = 0, in_contact = 0;
    double mean = 0.0, largest = 0.0;  // of max(gap, 0)
  };
  Clearance clearance() const;
  // The committed state for checkpoints (packed_state.hpp): per point the friction history,
  // pressure, position and master face; per slave face the matrix pattern; the master
  // displacements; the dissipation. After restore_state the caller rebuilds the matrix.
  std::vector<double> saved_state() const override;
  void restore_state(const std::vector<double>& values) override;
  bool restart_here() override;

 private:
  WireContactRecord totals(double contact_scale) const;
  struct MasterFace {  // gathered on every rank
    std::array<dealii::types::global_dof_index, 12> dofs;  // vertex v, component c at 3 v + c
    std::array<Vector3, 4> reference;
    double normal_sign = 1.0;
    std::array<unsigned, 12> value_index{};  // positions in the relevant values
    // Smoothed normals only: the vertices of the faces around this one (indices in vertices_)
    // and, per own vertex, the corners whose normals are averaged there.
    std::vector<unsigned> neighbours;
    std::array<std::vector<NormalCorner>, 4> corners;
  };
  struct MasterVertex {
    std::array<dealii::types::global_dof_index, 3> dofs;
    Vector3 reference;
    std::array<unsigned, 3> value_index{};
  };
  struct SlaveFace {  // this rank's
    std::array<dealii::types::global_dof_index, 12> dofs;
    std::array<Vector3, 4> reference;
    double normal_sign = 1.0;
    std::array<unsigned, 12> value_index{};
    unsigned cell = 0;
    unsigned first_point = 0;
    std::vector<unsigned> candidates;         // master faces searched at the last begin_step
    std::vector<unsigned> pattern;            // master faces in the matrix pattern (sorted)
  };
  struct SlavePoint {
    double xi = 0.0, eta = 0.0, weight = 0.0;  // on the slave face; reference area
    ContactHistory committed;
    double committed_pressure = 0.0;          // at the last converged step
    Vector3 committed_position, position;
    double multiplier = 0.0;
    ContactResponse last;
    int master = -1, committed_master = -1;   // master face at the last assembly / step
    double master_xi = 0.0, master_eta = 0.0;
    unsigned flips = 0;
    FrictionStatus frozen = FrictionStatus::free;
    bool master_frozen = false;
    int status = 0;  // 0 open, 1 stick, 2 slip (last assembly with a matrix)
  };

  void build_normal_patches();
  std::vector<dealii::types::global_dof_index> point_dofs(const SlaveFace& slave, const MasterFace& master) const;
  BilinearFace current_face(const std::array<Vector3, 4>& reference, const std::array<unsigned, 12>& index,
                            double sign, const std::vector<double>& values) const;

  WireContactParameters parameters_;
  ContactLaw law_;
  MPI_Comm comm_;
  double search_distance_ = 0.0;
  double keep_margin_ = 0.0;  // m: how much nearer another master face must be to replace the current one
  std::vector<MasterFace> masters_;
  std::vector<MasterVertex> vertices_;  // of the master surface; smoothed normals only
  std::vector<SlaveFace> slaves_;
  std::vector<SlavePoint> points_;
  std::vector<double> committed_master_values_;  // 12 per master face, displacement at the last step
  std::vector<double> master_values_;            // at the last assembly
  dealii::IndexSet needed_, constrained_;        // constrained_: every constrained contact dof (all ranks)
  double dissipation_ = 0.0;
  unsigned augmentations_ = 0;
};

}  // namespace dtwire::fem::contact

#pragma once
// Local refinement at the junctions of a double twist (issue 50): where each wire leaves the
// helix into its bend (the planes z = 0 and z = L_dt of a `dtwire mesh dt` file), a level-0
// mesh has one element through the contact zone. `Junction refinement cycles` times, every
// active cell whose centre lies within the half-width of a junction plane is split into eight
// (both wires, both ends); p4est keeps neighbouring cells within one level (2:1 balance).
//
// No manifold is attached: a child of a faceted (trilinear) cell is the image of a sub-cube
// under the parent's trilinear map, so the refined mesh has exactly the level-0 geometry
// (the facets and their 0.04 mm clearance at level 0 stay): the refinement resolves the
// fields (stress, plastic strain, contact pressure) at the junction, not the surface.
//
// The fine cells' vertices on a coarse neighbour's face or edge are hanging nodes: their
// values follow the coarse face (make_hanging_node_constraints), so the surface stays closed.
// The wire contact's Gauss points may press on a hanging node of another rank's part of the
// master surface: every rank then needs that node's constraint line, which the owner's part
// alone makes; the lines of the `shared` dofs are exchanged (all ranks hold all of them).
#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <mpi.h>

#include "parameters.hpp"

namespace dtwire::fem {

// Whether x lies within the refinement half-width of one of the junction planes (none given:
// false). The planes may be given without refinement: the run then logs the junction's state.
bool near_junction(const GeometryParameters& g, const dealii::Point<3>& x);

// Refines `tria` (serial or parallel::distributed) g.junction_cycles times near the junctions.
void refine_junctions(const GeometryParameters& g, dealii::Triangulation<3>& tria);

// The hanging-node constraints (closed) of the locally relevant dofs plus those of the `shared`
// dofs, gathered from the ranks that make them; stored for the dofs of `relevant`.
void make_shared_hanging_node_constraints(const dealii::DoFHandler<3>& dof_handler, const dealii::IndexSet& relevant,
                                          const dealii::IndexSet& shared, MPI_Comm comm,
                                          dealii::AffineConstraints<double>& hanging);

// A key that orders the active cells of any refinement of one coarse mesh the same way on any
// number of ranks: the coarse cell first, then the child indices (at most kMaxKeyLevels levels).
// On an unrefined mesh it orders by coarse cell, as the files written before refinement did.
constexpr unsigned kMaxKeyLevels = 6;
double cell_order_key(const dealii::CellId& id);

}  // namespace dtwire::fem

#include <deal.II/base/function.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <map>

#include "solver_impl.hpp"
#include "wire_mesh.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {

// Prescribed motion increment of the top end between two pseudo-times: translation a(t) d plus a
// rigid rotation R(theta(t)) about the axis through the centre c (Rodrigues' formula).
class TopEndIncrement : public Function<3> {
 public:
  TopEndIncrement(const LoadParameters& load, const Tensor<1, 3>& direction, const Point<3>& centre, double t_old,
                  double t_new)
      : Function<3>(3), load_(load), direction_(direction), centre_(centre), t_old_(t_old), t_new_(t_new) {}
  void vector_value(const Point<3>& X, Vector<double>& values) const override {
    const Tensor<1, 3> u = motion(X, t_new_) - motion(X, t_old_);
    for (unsigned c = 0; c < 3; ++c) values[c] = u[c];
  }

 private:
  Tensor<1, 3> motion(const Point<3>& X, double t) const {
    Tensor<1, 3> u = path_displacement(load_, t) * direction_;
    const double angle = path_rotation(load_, t);
    if (angle != 0.0) {
      Tensor<1, 3> k;
      for (unsigned c = 0; c < 3; ++c) k[c] = load_.rotation_axis[c];
      const Tensor<1, 3> r = X - centre_;
      const Tensor<1, 3> rotated =
          r * std::cos(angle) + cross_product_3d(k, r) * std::sin(angle) + k * (k * r) * (1.0 - std::cos(angle));
      u += rotated - r;
    }
    return u;
  }
  const LoadParameters& load_;
  Tensor<1, 3> direction_;
  Point<3> centre_;
  double t_old_, t_new_;
};

}  // namespace

void WireSolver::Impl::make_constraints(AffineConstraints<double>& c, double t_old, double t_new) const {
  c.clear();
  c.reinit(relevant);
  // Hanging nodes first: a Dirichlet value is then not set on a hanging node (it follows its
  // face), and close() resolves a hanging node whose masters are prescribed.
  for (const auto& line : hanging.get_lines()) {
    c.add_line(line.index);
    c.add_entries(line.index, line.entries);
  }
  const FEValuesExtractors::Scalar ux(0), uy(1), uz(2);
  const ComponentMask all(3, true), z_only = fe.component_mask(uz);
  const auto zero = Functions::ZeroFunction<3>(3);
  const TopEndIncrement top(prm.load, load_direction, rotation_centre, t_old, t_new);
  std::map<types::boundary_id, const Function<3>*> top_map, bottom_map;
  if (!prm.load.grip.bonded) {  // bonded grips are held by the bond (contact/bonded_grip.hpp) instead
    if (!top_released)
      for (const auto id : top_ids) top_map[id] = &top;
    for (const auto id : bottom_ids) bottom_map[id] = &zero;
  }
  if (top_released) {
    // springback of the as-made wires: the top end follows the wires (solver_forming.cpp)
  } else if (prm.load.force_control) {
    // The top face translates as one along z (all u_z equal to force_dof's); clamped also
    // holds u_x, u_y.
    if (prm.load.top == EndCondition::clamped) {
      std::map<types::boundary_id, const Function<3>*> fixed;
      for (const auto id : top_ids) fixed[id] = &zero;
      VectorTools::interpolate_boundary_values(dof_handler, fixed, c, ComponentMask(std::vector<bool>{true, true, false}));
    }
    for (const auto i : top_loaded_dofs)
      if (i != force_dof && relevant.is_element(i) && !c.is_constrained(i)) {
        c.add_line(i);
        c.add_entry(i, force_dof, 1.0);
      }
  } else if (prm.load.top != EndCondition::free)
    VectorTools::interpolate_boundary_values(dof_handler, top_map, c,
                                             prm.load.top == EndCondition::clamped ? all
                                                                                   : fe.component_mask(loaded_component()));
  const ComponentMask x_and_z(std::vector<bool>{true, false, true});
  VectorTools::interpolate_boundary_values(dof_handler, bottom_map, c,
                                           prm.load.bottom == EndCondition::clamped  ? all
                                           : prm.load.bottom == EndCondition::guided ? x_and_z
                                                                                     : z_only);
  if (prm.geometry.quarter) {
    VectorTools::interpolate_boundary_values(dof_handler, kSymmetryX, zero, c, fe.component_mask(ux));
    VectorTools::interpolate_boundary_values(dof_handler, kSymmetryY, zero, c, fe.component_mask(uy));
  }
  c.close();
}

}  // namespace dtwire::fem

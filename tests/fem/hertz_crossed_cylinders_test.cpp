// Hertz contact of crossed cylinders in 3D through the whole solver (label verification): an
// elastic wire (radius R) pressed by a rigid frictionless cylinder of the same radius whose axis
// crosses the wire axis at 90 degrees. One eighth is modelled (quarter section, symmetry planes
// x = 0, y = 0, mid-plane z = 0), so the wire is squeezed between two crossed rigid cylinders and
// the contact centre (0, R, 0) lies on the planes x = 0 and z = 0. The mesh is graded towards
// that point and read by the solver as a quarter-section .msh (wire_mesh.cpp).
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_out.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "parameters.hpp"
#include "solver.hpp"

namespace dtwire::fem {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Exponential grading of [0, 1] towards 0: g(0) = 0, g(1) = 1, g'(0) = beta / (e^beta - 1).
double graded(double t, double beta) { return beta > 0.0 ? std::expm1(beta * t) / std::expm1(beta) : t; }

// Quarter of a round wire (x >= 0, y >= 0, 0 <= z <= length; metres), refined towards the
// surface point (0, R, 0): the disc of deal.II's quarter_hyper_ball refined `section_refinements`
// times (2^(r+1) arcs on the quarter circle), extruded into `axial_cells` layers, then mapped in
// polar coordinates (theta from the y axis): depth R - r and theta graded towards 0 (the theta
// grading blended in by (r/R)^2 so that the centre is untouched), z graded towards 0. Hull vertices
// stay on the circle of radius R. Boundary ids as the solver's: 1 z = 0, 2 z = length; the
// faces on x = 0 and y = 0 are recognised by the solver as symmetry planes, the rest is hull (0).
struct GradedQuarterWire {
  double radius = 1.35e-3, length = 4.05e-3;
  unsigned section_refinements = 2, axial_cells = 12;  // level 2 of the test
  double depth_grading = 2.4, angle_grading = 3.0, axial_grading = 3.4;  // betas of graded()
};

void write_graded_quarter_wire(const GradedQuarterWire& m, const std::filesystem::path& file) {
  using namespace dealii;
  const double R = m.radius;
  Triangulation<2> disc;
  GridGenerator::quarter_hyper_ball(disc, Point<2>(), R);
  disc.reset_all_manifolds();
  disc.set_all_manifold_ids(1);
  for (const auto& cell : disc.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary() && std::abs(cell->face(f)->vertex(0).norm() - R) < 1e-9 * R &&
          std::abs(cell->face(f)->vertex(1).norm() - R) < 1e-9 * R)
        cell->face(f)->set_manifold_id(0);
  disc.set_manifold(0, SphericalManifold<2>(Point<2>()));
  TransfiniteInterpolationManifold<2> interior;
  interior.initialize(disc);
  disc.set_manifold(1, interior);
  disc.refine_global(m.section_refinements);
  Triangulation<2> flat;
  GridGenerator::flatten_triangulation(disc, flat);
  Triangulation<3> wire;
  GridGenerator::extrude_triangulation(flat, m.axial_cells + 1, 1.0, wire);
  GridTools::transform(
      [&](const Point<3>& p) {
        const double r = std::hypot(p[0], p[1]);
        const double theta = std::atan2(p[0], p[1]);  // from the y axis
        const double depth = R * graded(std::max(0.0, R - r) / R, m.depth_grading);
        const double blend = (r / R) * (r / R);
        const double theta_graded = 0.5 * kPi * graded(theta / (0.5 * kPi), m.angle_grading);
        const double t = theta + blend * (theta_graded - theta);
        const double rho = R - depth;
        return Point<3>(rho * std::sin(t), rho * std::cos(t), m.length * graded(p[2], m.axial_grading));
      },
      wire);
  const double tol = 1e-9 * R;
  for (const auto& cell : wire.active_cell_iterators())
    for (const auto f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary()) continue;
      const double z = cell->face(f)->center()[2];
      cell->face(f)->set_boundary_id(std::abs(z) < tol ? 1 : std::abs(z - m.length) < tol ? 2 : 0);
    }
  std::ofstream out(file);
  out.precision(15);
  GridOut grid_out;
  grid_out.set_flags(GridOutFlags::Msh(true, false));
  grid_out.write_msh(wire, out);
}

// The experiment (also experiments/verification/contact_hertz_crossed.prm, with the level-2
// mesh): E = 200 GPa, nu = 0.3, elastic; rigid frictionless cylinder of the wire's radius, axis
// along x through (0, 2R, 0) (touching the top vertex (0, R, 0) at zero travel), moved down by
// `travel_mm` in `steps` equal steps. Q2 displacement elements (Q1 needs about 8 x the elements
// for the same accuracy here). Pure penalty (factor 10): the Gauss-point pressures of the
// tightly augmented constraint oscillate by +-100 % between neighbouring points, the penalty
// ones follow the Hertz profile; its penetration is taken out of the approach.
std::string crossed_cylinder_prm(const std::string& mesh_file, double R_mm, double travel_mm, unsigned steps) {
  std::ostringstream prm;
  prm.precision(15);
  prm << "subsection Geometry\n  set Cross section = full\n  set Mesh file = " << mesh_file << "\nend\n"
      << "subsection Material\n  set Young modulus (MPa) = 200000\n  set Poisson ratio = 0.3\n"
         "  set Hardening law = linear\n  set Yield stress (MPa) = 1e9\nend\n"
         "subsection Formulation\n  set Element = displacement\n  set Polynomial degree = 2\nend\n"
         "subsection Boundary conditions\n  set Bottom end = symmetry\n  set Top end = clamped\n"
         "  set Load path (mm) = 0:0, 1:0\nend\n"
         "subsection Load stepping\n  set Initial step = "
      << 1.0 / steps << "\n  set Maximum step = " << 1.0 / steps
      << "\n  set Minimum step = 1e-4\nend\n"
         "subsection Newton\n  set Relative tolerance = 1e-9\n  set Maximum iterations = 25\nend\n"
         "subsection Output\n  set Fields = false\nend\n"
         "subsection Contact\n  set Friction coefficient = 0\n  set Normal penalty factor = 10\n"
         "  set Augmentations = 0\n  subsection Tool 1\n    set Shape = cylinder\n    set Point (mm) = 0 "
      << 2.0 * R_mm << " 0\n    set Direction = 1 0 0\n    set Radius (mm) = " << R_mm
      << "\n    set Path (mm) = 0: 0 0 0, 1: 0 " << -travel_mm << " 0\n  end\nend\n";
  return prm.str();
}

struct LoadLevel {
  double force = 0.0;     // N, on one tool (its whole contact patch)
  double approach = 0.0;  // m, tool travel minus the penetration at the contact centre
  double radius = 0.0;    // m, from the pressure's second moment
  double sum_p_dA = 0.0;  // N, 4 x sum of p dA over the modelled quarter patch
};

struct HertzRun {
  std::vector<LoadLevel> levels;
  std::size_t dofs = 0, cells = 0;
  double seconds = 0.0;
};

HertzRun run_crossed_cylinders(const std::string& name, const GradedQuarterWire& mesh, double travel_mm,
                               unsigned steps) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_hertz_crossed_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  write_graded_quarter_wire(mesh, dir / "wire.msh");
  std::ofstream(dir / "hertz.prm") << crossed_cylinder_prm("wire.msh", mesh.radius * 1e3, travel_mm, steps);
  Parameters p = read_parameters(dir / "hertz.prm");
  p.contact.keep_samples = true;
  std::ofstream log(dir / "run.log");
  const auto start = std::chrono::steady_clock::now();
  WireSolver solver(p, log, {});
  HertzRun run;
  solver.run([&](const StepRecord& r) {
    const auto& c = r.contact;
    if (c.samples.empty()) return;
    double m0 = 0.0, m2 = 0.0, centre = std::numeric_limits<double>::max(), centre_gap = 0.0;
    for (const auto& s : c.samples) {
      const double rho2 = s.position[0] * s.position[0] + s.position[2] * s.position[2];
      m0 += s.pressure * s.weight;
      m2 += s.pressure * s.weight * rho2;
      if (rho2 < centre) centre = rho2, centre_gap = s.gap;
    }
    LoadLevel l;
    // The record refers to the whole mirrored specimen, which has two tools (mirror y = 0):
    // one tool carries half of it.
    l.force = 0.5 * c.tool_forces[0][1];
    l.sum_p_dA = 4.0 * m0;
    // Hertz circle p0 sqrt(1 - rho^2/a^2): int p rho^2 dA / int p dA = 2 a^2 / 5.
    l.radius = std::sqrt(2.5 * m2 / m0);
    l.approach = -c.tool_displacements[0][1] + centre_gap;
    run.levels.push_back(l);
  });
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.dofs = solver.statistics().dofs;
  run.cells = solver.statistics().cells;
  return run;
}

struct HertzErrors {
  double worst_radius = 0.0;  // largest |a_FE / a_Hertz - 1| over the load levels
  double approach = 0.0;      // k_FE / k_Hertz - 1
  double far_field = 0.0;     // C F / (k_Hertz F^(2/3)) at the last level
};

// Hertz, crossed cylinders of equal radius R, one rigid (Johnson 1985, Contact Mechanics,
// sec. 4.2): circular contact, a = (3 F R / (4 E*))^(1/3), approach delta = a^2 / R =
// k F^(2/3) with k = (9 / (16 E*^2 R))^(1/3), E* = E / (1 - nu^2).
// The approach is the tool travel relative to the wire's centre plane y = 0 (fixed by
// symmetry) minus the penetration; Hertz's refers to distant points of two half-spaces. The
// difference (the compliance of the finite wire between its centre and the contact region,
// less the half-space far field) is regular in F, i.e. linear: delta_FE = k F^(2/3) + C F. k
// and C are fitted by least squares over the load levels and k is compared with Hertz.
HertzErrors hertz_errors(const std::string& name, const HertzRun& run, double R, double E_star) {
  const double k_hertz = std::cbrt(9.0 / (16.0 * E_star * E_star * R));
  double s11 = 0, s12 = 0, s22 = 0, b1 = 0, b2 = 0;
  HertzErrors e;
  std::cout << "[hertz crossed " << name << "] " << run.cells << " cells, " << run.dofs << " dofs, " << run.seconds
            << " s\n";
  for (const auto& l : run.levels) {
    const double f = std::cbrt(l.force * l.force);  // F^(2/3)
    s11 += f * f, s12 += f * l.force, s22 += l.force * l.force, b1 += f * l.approach, b2 += l.force * l.approach;
    const double a_hertz = std::cbrt(3.0 * l.force * R / (4.0 * E_star));
    e.worst_radius = std::max(e.worst_radius, std::abs(l.radius / a_hertz - 1.0));
    std::cout << "  F = " << l.force << " N (sum p dA " << l.sum_p_dA << " N), a/R = " << a_hertz / R
              << ", a_FE/a_Hertz - 1 = " << l.radius / a_hertz - 1.0
              << ", approach/(a_Hertz^2/R) = " << l.approach / (k_hertz * f) << "\n";
    EXPECT_NEAR(l.sum_p_dA / l.force, 1.0, 0.01);  // normal and vertical force agree (a << R)
  }
  const double det = s11 * s22 - s12 * s12;
  const double k = (b1 * s22 - b2 * s12) / det, C = (s11 * b2 - s12 * b1) / det;
  const double F = run.levels.back().force;
  e.approach = k / k_hertz - 1.0;
  e.far_field = C * F / (k_hertz * std::cbrt(F * F));
  std::cout << "  fit delta = k F^(2/3) + C F: k/k_Hertz - 1 = " << e.approach << ", C F/delta_Hertz at the last level "
            << e.far_field << "; worst |a_FE/a_Hertz - 1| = " << e.worst_radius << "\n";
  return e;
}

// Two mesh levels (the section refinement and the axial cells doubled, same grading). Each load
// level has 0.04 < a/R < 0.11; the level-2 mesh has 3-6 elements across the contact radius.
TEST(HertzCrossedCylinders, ApproachAndContactRadius) {
  const double E = 200e9, nu = 0.3, E_star = E / (1.0 - nu * nu);
  GradedQuarterWire level1, level2;  // level 2: the mesh of contact_hertz_crossed.prm
  level1.section_refinements = 1, level1.axial_cells = 6;
  const double R = level2.radius;
  const HertzErrors coarse = hertz_errors("level 1", run_crossed_cylinders("level1", level1, 0.016, 8), R, E_star);
  const HertzErrors fine = hertz_errors("level 2", run_crossed_cylinders("level2", level2, 0.016, 8), R, E_star);
  std::cout << "[hertz crossed] contact radius worst error " << coarse.worst_radius << " -> " << fine.worst_radius
            << ", approach error " << coarse.approach << " -> " << fine.approach << "\n";
  EXPECT_LT(fine.worst_radius, 0.05);         // contact radius within 5 % at every load level
  EXPECT_LT(std::abs(fine.approach), 0.05);   // approach coefficient within 5 %
  EXPECT_LT(std::abs(fine.far_field), 0.15);  // the fitted finite-body term stays a correction
  EXPECT_LT(fine.worst_radius, coarse.worst_radius);                // both converge with the mesh
  EXPECT_LT(std::abs(fine.approach), std::abs(coarse.approach));
}

}  // namespace
}  // namespace dtwire::fem

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

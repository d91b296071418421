// Frictional contact with rigid tools through the whole solver (label verification):
// Coulomb sliding block, capstan over a rigid cylinder, plane-strain Hertz contact of a
// cylinder on a rigid plane. Small meshes; each case well under a minute on one core.
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/fem/run.hpp"
#include "parameters.hpp"
#include "solver.hpp"

namespace dtwire::fem {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Also under mpirun (rank 0 writes the files; samples are then this rank's points only).
std::vector<StepRecord> run_case(const std::string& name, const std::string& prm_text) {
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_contact_test_" + name);
  const auto file = dir / (name + ".prm");
  if (root) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(file) << prm_text;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  Parameters p = read_parameters(file);
  p.contact.keep_samples = true;
  std::ofstream log(root ? dir / "run.log" : std::filesystem::path("/dev/null"));
  WireSolver solver(p, log, {});
  std::vector<StepRecord> records;
  solver.run([&](const StepRecord& r) { records.push_back(r); });
  return records;
}

std::string elastic_material(double young_MPa, double poisson) {
  std::ostringstream s;
  s << "subsection Material\n  set Young modulus (MPa) = " << young_MPa << "\n  set Poisson ratio = " << poisson
    << "\n  set Hardening law = linear\n  set Yield stress (MPa) = 1e9\nend\n";
  return s.str();
}

// (a) An elastic 10 x 10 x 10 mm block squeezed between two rigid planes (top one pressed by
// 0.01 mm, then dragged 0.05 mm along z; bottom one fixed), ends held axially.
TEST(ContactVerification, CoulombSlidingBlock) {
  const double mu = 0.3;
  const double R = 5.0 / (std::sqrt(kPi) / 2.0);  // square half side 5 mm
  std::ostringstream prm;
  prm << "subsection Geometry\n  set Diameter (mm) = " << 2 * R
      << "\n  set Length (mm) = 10\n  set Cross section = full\n  set Radial refinements = 0\n"
         "  set Axial cells = 4\nend\n"
      << elastic_material(200000, 0.3)
      << "subsection Boundary conditions\n  set Bottom end = clamped\n  set Top end = axial\n"
         "  set Load path (mm) = 0:0, 1:0, 2:0\nend\n"
         "subsection Load stepping\n  set Initial step = 0.02\n  set Maximum step = 0.02\n"
         "  set Minimum step = 1e-5\nend\n"
         "subsection Newton\n  set Relative tolerance = 1e-9\n  set Maximum iterations = 25\nend\n"
         "subsection Output\n  set Fields = false\nend\n"
         "subsection Contact\n  set Friction coefficient = "
      << mu
      << "\n  subsection Tool 1\n    set Shape = plane\n    set Point (mm) = 0 5 0\n    set Direction = 0 -1 0\n"
         "    set Path (mm) = 0: 0 0 0, 1: 0 -0.01 0, 2: 0 -0.01 0.05\n  end\n"
         "  subsection Tool 2\n    set Shape = plane\n    set Point (mm) = 0 -5 0\n    set Direction = 0 1 0\n"
         "  end\nend\n";
  const auto records = run_case("sliding_block", prm.str());
  ASSERT_GT(records.size(), 60u);
  bool saw_stick = false;
  const StepRecord* first_slip = nullptr;
  for (const auto& r : records) {
    if (r.time <= 1.0 + 1e-9) continue;
    const double N = r.contact.tool_forces[0][1], T = -r.contact.tool_forces[0][2];
    ASSERT_GT(N, 0.0);
    EXPECT_LE(T, mu * N * 1.01) << "Coulomb bound exceeded at t = " << r.time;  // 1 %
    if (T > 0.0 && T < 0.95 * mu * N) saw_stick = true;  // stick below mu N while the drag builds up
    if (!first_slip && T > 0.999 * mu * N) first_slip = &r;
  }
  EXPECT_TRUE(saw_stick);
  ASSERT_NE(first_slip, nullptr);
  const StepRecord& last = records.back();
  const double N = last.contact.tool_forces[0][1], T = -last.contact.tool_forces[0][2];
  EXPECT_NEAR(T / (mu * N), 1.0, 0.01);  // tangential reaction at slip = mu N within 1 %
  // The drag is carried by the held ends: reactions balance the tool forces (converged Newton).
  for (unsigned c = 0; c < 3; ++c)
    EXPECT_NEAR(last.contact.bottom_reaction[c] + last.contact.top_reaction[c],
                last.contact.tool_forces[0][c] + last.contact.tool_forces[1][c], 1e-6 * N);
  // Dissipation over the steady sliding from the first fully slipping step on: mu N s within 2 %.
  const double tool_travel = 0.05e-3 * (last.time - first_slip->time);
  const double mean_N = 0.5 * (N + first_slip->contact.tool_forces[0][1]);
  const double dissipated = last.contact.friction_dissipation - first_slip->contact.friction_dissipation;
  ASSERT_GT(tool_travel, 0.02e-3);
  EXPECT_NEAR(dissipated / (mu * mean_N * tool_travel), 1.0, 0.02);
  // Energy balance: work of the tools on the block (trapezoidal over the steps; the held ends do
  // no work) = elastic energy + friction dissipation + penalty-spring energy, within 1 %.
  double work = 0.0;
  for (std::size_t i = 1; i < records.size(); ++i)
    for (std::size_t k = 0; k < 2; ++k)
      for (unsigned c = 0; c < 3; ++c)
        work -= 0.5 * (records[i].contact.tool_forces[k][c] + records[i - 1].contact.tool_forces[k][c]) *
                (records[i].contact.tool_displacements[k][c] - records[i - 1].contact.tool_displacements[k][c]);
  const double stored = last.elastic_energy + last.plastic_dissipation + last.contact.friction_dissipation +
                        last.contact.contact_energy;
  EXPECT_NEAR(stored / work, 1.0, 0.01);  // balance error < 1 % of the external work
  std::cout << "[sliding block] N = " << N << " N, T/(mu N) = " << T / (mu * N)
            << ", energy: work " << work << " J, elastic " << last.elastic_energy << " J, friction "
            << last.contact.friction_dissipation << " J, penalty " << last.contact.contact_energy
            << " J, balance error " << stored / work - 1.0
            << ", dissipation / (mu N s) = " << dissipated / (mu * mean_N * tool_travel)
            << ", first full slip at tool travel " << (first_slip->time - 1.0) * 0.05 << " mm\n";
}

// `dtwire run` on the sliding-block .prm (with fields): the curve CSV carries the contact
// channels, finite, with the friction force at mu times the normal force at the end; the VTU
// fields carry the contact pressure and slip.
TEST(ContactVerification, RunWritesContactChannels) {
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_contact_test_run";
  const auto prm = dir / "sliding_block.prm";
  if (root) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ifstream in(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/verification/contact_sliding_block.prm");
    std::stringstream text;
    text << in.rdbuf();
    const std::string fields_off = "set Fields = false";
    std::string s = text.str();
    ASSERT_NE(s.find(fields_off), std::string::npos);
    s.replace(s.find(fields_off), fields_off.size(), "set Fields = true");
    std::ofstream(prm) << s;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  RunOptions options;
  options.parameter_file = prm;
  options.output_directory = dir / "out";
  options.command_line = "test contact run";
  options.echo = false;
  const RunSummary summary = run_experiment(options);
  if (!summary.root) return;  // rank 0 wrote the files
  const Curve curve = read_csv(summary.curve_csv);
  for (const char* name : {"contact_normal_force", "contact_friction_force", "tool1_displacement_z", "tool1_force_y", "tool1_force_z",
                           "tool2_force_y", "friction_dissipation", "contact_max_pressure", "contact_max_slip",
                           "contact_max_penetration"}) {
    ASSERT_TRUE(curve.has(name)) << name;
    for (const double v : curve.si(name)) ASSERT_TRUE(std::isfinite(v)) << name;
  }
  const double N = curve.si("tool1_force_y").back(), T = -curve.si("tool1_force_z").back();
  EXPECT_NEAR(T / (0.3 * N), 1.0, 0.01);  // mu = 0.3 in the .prm, within 1 %
  EXPECT_GT(curve.si("friction_dissipation").back(), 0.0);
  bool has_pressure_field = false;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "out" / "fields")) {
    if (entry.path().extension() != ".vtu") continue;
    std::ifstream vtu(entry.path());
    const std::string content((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
    has_pressure_field = has_pressure_field || (content.find("contact_pressure_Pa") != std::string::npos &&
                                                content.find("contact_slip_m") != std::string::npos);
  }
  EXPECT_TRUE(has_pressure_field);
}

// A tool path knot that the load path does not have is an input error naming the entry.
TEST(ContactVerification, ToolKnotOutsideLoadPathIsRejected) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_contact_test_knot";
  std::filesystem::create_directories(dir);
  const auto file = dir / "knot.prm";
  std::ofstream(file) << "subsection Boundary conditions\n  set Load path (mm) = 0:0, 1:0\nend\n"
                         "subsection Contact\n  subsection Tool 1\n    set Shape = plane\n"
                         "    set Path (mm) = 0: 0 0 0, 0.5: 0 -0.1 0, 1: 0 0 0\n  end\nend\n";
  try {
    read_parameters(file);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Tool 1/Path (mm)"), std::string::npos) << e.what();
  }
}

// (b) Capstan: a 1 x 1 mm strip, 120 mm long, clamped at both ends, lifted over a rigid
// cylinder (radius 30 mm, axis x) at mid-length, then pulled at the top end so that it slides
// over the cylinder. The wrap angle is the angle between the end forces (those carry the belt
// tension into the wrap; the small bending shear of the strip is included in them).
// Returns (T_out/T_in) / exp(mu theta) at the end of the pull.
double capstan_ratio(double mu, double pull_mm) {
  const double Rc = 30.0;
  const double R = 0.5 / (std::sqrt(kPi) / 2.0);  // strip half side 0.5 mm
  std::ostringstream prm;
  prm << "subsection Geometry\n  set Diameter (mm) = " << 2 * R
      << "\n  set Length (mm) = 120\n  set Cross section = full\n  set Radial refinements = 0\n"
         "  set Axial cells = 120\nend\n"
      << elastic_material(200000, 0.3)
      << "subsection Boundary conditions\n  set Bottom end = clamped\n  set Top end = clamped\n"
         "  set Load path (mm) = 0:0, 1:0, 2:"
      << pull_mm << "\nend\n"
         "subsection Load stepping\n  set Initial step = 0.01\n  set Maximum step = 0.04\n"
         "  set Minimum step = 1e-6\nend\n"
         "subsection Newton\n  set Relative tolerance = 1e-9\n  set Maximum iterations = 25\nend\n"
         "subsection Output\n  set Fields = false\nend\n"
         "subsection Contact\n  set Friction coefficient = "
      << mu << "\n  subsection Tool 1\n    set Shape = cylinder\n    set Point (mm) = 0 " << -(0.5 + Rc + 0.01)
      << " 60\n    set Direction = 1 0 0\n    set Radius (mm) = " << Rc
      << "\n    set Path (mm) = 0: 0 0 0, 1: 0 17.6 0\n  end\nend\n";
  const auto records = run_case("capstan_" + std::to_string(mu), prm.str());
  const auto& c = records.back().contact;
  const auto norm = [](const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); };
  const double T_out = norm(c.top_reaction), T_in = norm(c.bottom_reaction);
  const double cosine = (c.top_reaction[0] * c.bottom_reaction[0] + c.top_reaction[1] * c.bottom_reaction[1] +
                         c.top_reaction[2] * c.bottom_reaction[2]) /
                        (T_out * T_in);
  const double theta = kPi - std::acos(cosine);
  EXPECT_GT(theta, 0.3);
  unsigned slipping = 0;
  for (const auto& s : c.samples) slipping += s.slipping ? 1 : 0;
  EXPECT_GT(slipping, 0.9 * c.samples.size());  // the strip slides over the whole wrap
  std::cout << "[capstan] mu = " << mu << ", theta = " << theta << " rad, T_out/T_in = " << T_out / T_in
            << ", exp(mu theta) = " << std::exp(mu * theta) << " (ratio " << (T_out / T_in) / std::exp(mu * theta)
            << "), slipping points " << slipping << "/" << c.samples.size() << "\n";
  return (T_out / T_in) / std::exp(mu * theta);
}

TEST(ContactVerification, CapstanOverRigidCylinder) {
  EXPECT_NEAR(capstan_ratio(0.3, 1.5), 1.0, 0.03);  // T_out/T_in = exp(mu theta) within 3 %
  EXPECT_NEAR(capstan_ratio(0.6, 3.0), 1.0, 0.03);
}

// (c) Hertz, plane strain: an elastic cylinder (R = 10 mm) pressed by a rigid frictionless
// plane (quarter model, so it is squeezed between two plates). Half-width a^2 = 4 P' R /
// (pi E*), peak pressure p0 = 2 P' / (pi a), P' the force per unit length (Johnson 1985,
// sec. 4.2). The half-width comes from the pressure's second moment: for the Hertz
// distribution int p x^2 / int p = a^2 / 4. The plate's approach to the cylinder centre is half
// the diametral compression of a cylinder between two plates,
//   Delta = 2 P' (1 - nu^2) / (pi E) (2 ln(4R/a) - 1)   (Johnson 1985, ch. 5).
struct HertzErrors {
  double half_width = 0.0, approach = 0.0, peak = 0.0;  // FE / closed form - 1
};

HertzErrors hertz_errors(unsigned refinements, double press = 0.17) {
  const double R = 10.0, L = 0.25, E = 200000.0, nu = 0.3;
  const double sides = 8.0 * std::pow(2.0, refinements);  // plane touches the top vertex at zero travel
  const double vertex_radius = R * std::sqrt(2.0 * kPi / (sides * std::sin(2.0 * kPi / sides)));
  std::ostringstream prm;
  prm.precision(12);
  prm << "subsection Geometry\n  set Diameter (mm) = " << 2 * R << "\n  set Length (mm) = " << L
      << "\n  set Cross section = quarter\n  set Radial refinements = " << refinements
      << "\n  set Axial cells = 1\nend\n"
      << elastic_material(E, nu)
      << "subsection Boundary conditions\n  set Bottom end = axial\n  set Top end = axial\n"
         "  set Load path (mm) = 0:0, 1:0\nend\n"
         "subsection Load stepping\n  set Initial step = 0.25\n  set Maximum step = 0.25\n"
         "  set Minimum step = 1e-4\nend\n"
         "subsection Newton\n  set Relative tolerance = 1e-9\nend\n"
         "subsection Output\n  set Fields = false\nend\n"
         "subsection Contact\n  set Augmentations = 5\n  set Gap tolerance (mm) = 1e-4\n"
         "  subsection Tool 1\n    set Shape = plane\n    set Point (mm) = 0 "
      << vertex_radius << " 0\n    set Direction = 0 -1 0\n    set Path (mm) = 0: 0 0 0, 1: 0 " << -press
      << " 0\n  end\nend\n";
  const auto records = run_case("hertz_" + std::to_string(refinements), prm.str());
  const auto& c = records.back().contact;
  double m0 = 0.0, m2 = 0.0;
  for (const auto& s : c.samples) {
    m0 += s.pressure * s.weight;
    m2 += s.pressure * s.weight * s.position[0] * s.position[0];
  }
  m0 = dealii::Utilities::MPI::sum(m0, MPI_COMM_WORLD);  // samples are per rank
  m2 = dealii::Utilities::MPI::sum(m2, MPI_COMM_WORLD);
  const double a_fe = 2.0 * std::sqrt(m2 / m0) * 1e3;                  // mm
  const double P = c.normal_force / (2.0 * L * 1e-3) * 1e-3;            // N/mm per contact (quarter x 4 = 2 contacts)
  const double E_star = E / (1.0 - nu * nu);                            // MPa, rigid plane
  const double a_hertz = std::sqrt(4.0 * P * R / (kPi * E_star));      // mm
  const double p0 = 2.0 * P / (kPi * a_hertz);                         // MPa
  const double johnson = P / (kPi * E_star) * (2.0 * std::log(4.0 * R / a_hertz) - 1.0);  // mm, one plate
  const double approach = press - c.max_penetration * 1e3;  // first touch at zero tool travel
  HertzErrors e;
  e.half_width = a_fe / a_hertz - 1.0;
  e.approach = approach / johnson - 1.0;
  e.peak = c.max_pressure * 1e-6 / p0 - 1.0;
  std::cout << "[hertz r" << refinements << "] " << records.back().contact.samples.size() << " contact points, P' = " << P
            << " N/mm, a_FE = " << a_fe << " mm, a_Hertz = " << a_hertz << " mm (a/R = " << a_hertz / R
            << "), approach " << approach << " mm vs " << johnson << " mm, p_max/p0 = " << 1.0 + e.peak
            << ", penetration " << c.max_penetration * 1e3 << " mm\n";
  return e;
}

// Two meshes (arc segment 0.49 and 0.25 mm; a ~ 1 mm): the finer one is asserted, the trend is
// printed. The peak pressure is sampled at Gauss points and only printed.
TEST(ContactVerification, HertzCylinderOnPlanePlaneStrain) {
  const HertzErrors coarse = hertz_errors(4);
  const HertzErrors fine = hertz_errors(5);
  std::cout << "[hertz] half-width error " << coarse.half_width << " -> " << fine.half_width << ", approach error "
            << coarse.approach << " -> " << fine.approach << "\n";
  EXPECT_LT(std::abs(fine.half_width), 0.05);  // half-width within 5 %
  EXPECT_LT(std::abs(fine.approach), 0.05);    // approach within 5 %
}

// (d) A round wire (D = 2 mm, 16-gon section) squeezed between two grooved clamp plates
// (groove radius 1.03 mm along the wire, 0.02 mm press), then both plates dragged 1 mm along
// the wire whose ends are held. At full slip the axial tool force is mu times the summed normal
// contact force, which exceeds the clamping force: the groove walls wedge the wire.
TEST(ContactVerification, GroovedClampPlatesSliding) {
  const double mu = 0.2, groove = 1.03;
  const double vertex = std::sqrt(2.0 * kPi / (16.0 * std::sin(2.0 * kPi / 16.0)));  // 16-gon, mm
  const double plate = vertex - groove + 0.002;  // 2 um between the top vertex and the groove bottom
  std::ostringstream prm;
  prm << "subsection Geometry\n  set Diameter (mm) = 2\n  set Length (mm) = 10\n  set Cross section = full\n"
         "  set Radial refinements = 2\n  set Axial cells = 10\nend\n"
      << elastic_material(200000, 0.3)
      << "subsection Boundary conditions\n  set Bottom end = clamped\n  set Top end = axial\n"
         "  set Load path (mm) = 0:0, 1:0, 2:0\nend\n"
         "subsection Load stepping\n  set Initial step = 0.02\n  set Maximum step = 0.02\n"
         "  set Minimum step = 1e-5\nend\n"
         "subsection Newton\n  set Relative tolerance = 1e-9\n  set Maximum iterations = 25\nend\n"
         "subsection Output\n  set Fields = false\nend\n"
         "subsection Contact\n  set Friction coefficient = "
      << mu << "\n";
  for (const int side : {1, -1})
    prm << "  subsection Tool " << (side > 0 ? 1 : 2) << "\n    set Shape = grooved plate\n    set Point (mm) = 0 "
        << side * plate << " 0\n    set Direction = 0 " << -side << " 0\n    set Groove axis = 0 0 1\n"
        << "    set Radius (mm) = " << groove << "\n    set Path (mm) = 0: 0 0 0, 1: 0 " << -side * 0.02
        << " 0, 2: 0 " << -side * 0.02 << " 1.0\n  end\n";
  prm << "end\n";
  const auto records = run_case("grooved_plates", prm.str());
  const auto& c = records.back().contact;
  const double axial = -(c.tool_forces[0][2] + c.tool_forces[1][2]);
  const double clamp = c.tool_forces[0][1];
  unsigned slipping = 0;
  for (const auto& s : c.samples) slipping += s.slipping ? 1 : 0;
  EXPECT_EQ(slipping, c.samples.size());
  EXPECT_NEAR(axial / (mu * c.normal_force), 1.0, 0.01);  // Coulomb at slip within 1 %
  EXPECT_GT(c.normal_force, 2.0 * clamp);                  // inclined groove-wall normals: sum p dA > clamping
  std::cout << "[grooved plates] clamp " << clamp << " N per plate, sum p dA " << c.normal_force
            << " N, axial/(mu sum p dA) = " << axial / (mu * c.normal_force) << ", " << c.samples.size()
            << " contact points\n";
}


// (e) Three-point bending on rigid rollers, elastic and slender (d = 1 mm, span 40 mm, L/d = 40;
// support roller radius 20 mm as in the SW bending experiment, frictionless). Half model: the
// midspan cross-section z = 0 is clamped (the symmetry plane of the bent beam, which also holds
// the midspan deflection), the roller at z = 20 mm pushes the wire by w, the overhanging end is
// free. In this frame w is the midspan deflection relative to the supports and the roller force
// is P/2. The roller presses on a flat facet of the 8-gon section (outward normal at 157.5 deg;
// the bending stiffness of a regular polygon is the same about every axis), so that its line
// contact meets the face quadrature points. The support line is where the roller reaction
// acts: the pressure-weighted z of the contact points (a fraction of an element from 20 mm), so
// the span compared with the closed form is 2 z_c. Timoshenko beam:
// w = P L^3/(48 E I) + P L/(4 kappa G A), kappa = 6(1 + nu)/(7 + 6 nu) (circular section);
// I of the 8-gon section (area exact). The secant stiffness between w = 2 and 4 um removes the
// contact onset.
TEST(ContactVerification, ThreePointBendingOnRollersMatchesBeamTheory) {
  const double E = 200e9, nu = 0.3, d = 1e-3, a_nominal = 20e-3, Rc = 20.0;
  const double rho = 0.5 * std::sqrt(2.0 * kPi / (8.0 * std::sin(2.0 * kPi / 8.0)));  // 8-gon vertex, mm
  const double apothem = rho * std::cos(kPi / 8.0), theta = 7.0 * kPi / 8.0;        // facet normal 157.5 deg
  const double nx = std::cos(theta), ny = std::sin(theta);
  std::ostringstream prm;
  prm.precision(15);
  prm << "subsection Geometry\n  set Diameter (mm) = 1\n  set Length (mm) = 24\n  set Cross section = full\n"
         "  set Radial refinements = 1\n  set Axial cells = 16\nend\n"
      << elastic_material(200000, nu)
      << "subsection Formulation\n  set Element = displacement\n  set Polynomial degree = 2\nend\n"
         "subsection Boundary conditions\n  set Bottom end = clamped\n  set Top end = free\n"
         "  set Load path (mm) = 0:0, 1:0, 2:0\nend\n"
         "subsection Load stepping\n  set Initial step = 0.5\n  set Maximum step = 0.5\nend\n"
         "subsection Newton\n  set Relative tolerance = 1e-7\nend\n"
         "subsection Output\n  set Fields = false\nend\n"
         "subsection Contact\n  set Friction coefficient = 0\n  set Augmentations = 10\n"
         "  set Gap tolerance (mm) = 1e-7\n  subsection Tool 1\n    set Shape = cylinder\n    set Point (mm) = "
      << (apothem + Rc) * nx << " " << (apothem + Rc) * ny << " 20\n    set Direction = " << -ny << " " << nx
      << " 0\n    set Radius (mm) = " << Rc << "\n    set Path (mm) = 0: 0 0 0, 1: " << -0.002 * nx << " "
      << -0.002 * ny << " 0, 2: " << -0.004 * nx << " " << -0.004 * ny << " 0\n  end\nend\n";
  const auto records = run_case("three_point_bending", prm.str());
  ASSERT_GE(records.size(), 3u);
  const auto& c1 = records[records.size() - 2].contact;
  const auto& c2 = records.back().contact;
  ASSERT_FALSE(c2.samples.empty());
  double pw = 0.0, pwz = 0.0;
  for (const auto& s : c2.samples) {
    pw += s.pressure * s.weight;
    pwz += s.pressure * s.weight * s.position[2];
  }
  pw = dealii::Utilities::MPI::sum(pw, MPI_COMM_WORLD);
  pwz = dealii::Utilities::MPI::sum(pwz, MPI_COMM_WORLD);
  const double a = pwz / pw;  // support line, half span
  const auto along = [&](const std::array<double, 3>& v) { return -(v[0] * nx + v[1] * ny); };  // push direction
  const double half_load = -(along(c2.tool_forces[0]) - along(c1.tool_forces[0]));
  const double dw = along(c2.tool_displacements[0]) - along(c1.tool_displacements[0]);
  const double I = [&] {
    const double r = rho * 1e-3;
    double sum = 0.0;  // second moment of the 8-gon about a diameter (vertices at pi/4 + k pi/4)
    for (int k = 0; k < 8; ++k) {
      const double a0 = kPi / 4 * (k + 1), a1 = kPi / 4 * (k + 2);
      const double x0 = r * std::cos(a0), y0 = r * std::sin(a0), x1 = r * std::cos(a1), y1 = r * std::sin(a1);
      sum += (x0 * y1 - x1 * y0) * (x0 * x0 + x0 * x1 + x1 * x1) / 12.0;
    }
    return sum;
  }();
  const double A = kPi * d * d / 4, G = E / (2 * (1 + nu)), kappa = 6 * (1 + nu) / (7 + 6 * nu);
  const double span = 2 * a, P = 2 * half_load;
  const double compliance = span * span * span / (48 * E * I) + span / (4 * kappa * G * A);
  const double k_fe = P / dw, k_beam = 1.0 / compliance;
  std::cout << "[three-point bending] support line z_c = " << a * 1e3 << " mm (roller axis 20 mm), P = "
            << 2 * -along(c2.tool_forces[0]) << " N at w = " << along(c2.tool_displacements[0]) * 1e3
            << " mm, secant k_FE = " << k_fe << " N/m, k_Timoshenko = " << k_beam << " N/m (Euler-Bernoulli "
            << 48 * E * I / (span * span * span) << ", nominal span " << 48 * E * I / std::pow(2 * a_nominal, 3)
            << "), error " << (k_fe / k_beam - 1) * 100 << " %, max penetration " << c2.max_penetration * 1e3
            << " mm, " << c2.samples.size() << " contact points\n";
  EXPECT_NEAR(a, a_nominal, 1e-3);                 // the reaction acts at the roller (within 1 mm)
  EXPECT_LT(c2.max_penetration, 1e-3 * dw);        // rigid roller: w is the tool travel to 0.1 %
  EXPECT_NEAR(k_fe / k_beam, 1.0, 0.01);           // midspan stiffness within 1 % of Timoshenko
}

}  // namespace
}  // namespace dtwire::fem

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

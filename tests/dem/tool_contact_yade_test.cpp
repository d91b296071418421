// One node on the hemispherical platter in our engine and in YADE 2023.02a, both undamped: the
// closed case for the node-platter friction of the punch cross-check. The node (r = 5.4 mm,
// 1 kg, I = 0.4 m r^2) is held in x and y, pressed down with 1 kN and free to rotate; the 0.5 m
// platter, kn = 1e9 N/m, ks = 1e8 N/m, mu = 0.2 as in punch_yade_check.toml, moves at
// (0.03, 0.02, 0) m/s under it, so the contact normal turns, the node rolls and slips and the
// stored shear force is carried over 1e5 steps. YADE runs Law2_ScGeom_FrictPhys_CundallStrack on
// Ig2_Sphere_Sphere_ScGeom, once with avoidGranularRatcheting=False (the shear increment from the
// velocities at the contact point, ScGeom::getIncidentVel, the model of Cundall and Strack 1979
// that our tools use) and once with YADE's default True (translation scaled by
// (R1 + R2) / (R1 + R2 - penetration), spins levered by the full radii R1, R2 while the torque
// uses R - penetration/2). Ours must match the first to round-off: 1e-4 of the largest force (the
// two codes order their arithmetic differently; measured 2.5e-6), and the second departs from it
// by more than that, which is why the punch export sets the flag (docs/dem_engine.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "dtwire/dem/engine.hpp"

namespace dtwire::dem {
namespace {

constexpr double kRadius = 0.0054, kMass = 1.0, kPlatter = 0.5, kKn = 1e9, kKs = 1e8, kMu = 0.2;
constexpr double kLoad = 1000.0, kPolar = 0.1, kStep = 1e-5;
constexpr int kSteps = 100000, kEvery = 500;

// Force on the platter (x, y, z) every kEvery steps.
using Rows = std::vector<Vector3>;

// Ours; `friction` gets the largest tangential part of the contact force.
Rows ours(double& friction) {
  NetNode node;
  node.mass = kMass;
  node.radius = kRadius;
  node.rotational_inertia = 0.4 * kMass * kRadius * kRadius;
  const double d = kPlatter + kRadius - 1e-6;
  node.position = Vector3(d * std::sin(kPolar), 0.0, d * std::cos(kPolar));
  EngineOptions options;
  options.local_damping = 0.0;
  options.gravity = Vector3(0.0, 0.0, -kLoad / kMass);
  options.time_step = kStep;
  Engine engine({node}, {}, options);
  auto platter = std::make_unique<SemiSpheroidPlatter>(kPlatter, kPlatter);
  platter->contact = {kKn, kKs, kMu};
  platter->velocity = Vector3(0.03, 0.02, 0.0);
  engine.add_tool(std::move(platter));
  engine.set_support(0, {true, true, false}, false);
  Rows rows;
  for (int k = 1; k <= kSteps; ++k) {
    engine.step();
    if (k % kEvery == 0) {
      const Vector3 f = engine.tool_force(0), normal = (engine.position(0) - engine.tool(0).position).normalized();
      friction = std::max(friction, (f - f.dot(normal) * normal).norm());
      rows.push_back(f);
    }
  }
  return rows;
}

Rows yade(bool avoid_granular_ratcheting) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_tool_contact_yade";
  std::filesystem::create_directories(dir);
  const auto script = dir / "one_node.py", out = dir / (avoid_granular_ratcheting ? "agr1.txt" : "agr0.txt");
  // Materials through Ip2_FrictMat_FrictMat_FrictPhys as the punch export sets them: the node's
  // E r = 3 kn / 4 with nu = 0.3, the platter's E R = 3 kn / 2 and the Poisson ratio giving ks.
  std::ostringstream s;
  s.precision(17);
  s << "import sys, math\nfrom yade import *\n"
    << "r, m, R, kn, ks, mu, load, th = " << kRadius << ", " << kMass << ", " << kPlatter << ", " << kKn << ", " << kKs
    << ", " << kMu << ", " << kLoad << ", " << kPolar << "\n"
    << "a = 0.75 * kn * 0.3; b = ks * a / (2 * a - ks)\n"
       "node_mat = O.materials.append(FrictMat(young=0.75 * kn / r, poisson=0.3, frictionAngle=math.atan(mu)))\n"
       "plate_mat = O.materials.append(FrictMat(young=1.5 * kn / R, poisson=b / (1.5 * kn), frictionAngle=math.atan(mu)))\n"
       "d = R + r - 1e-6\n"
       "n = O.bodies.append(sphere((d * math.sin(th), 0, d * math.cos(th)), r, material=node_mat))\n"
       "O.bodies[n].state.blockedDOFs = 'xy'; O.bodies[n].state.mass = m\n"
       "O.bodies[n].state.inertia = Vector3(1, 1, 1) * 0.4 * m * r * r\n"
       "p = O.bodies.append(sphere((0, 0, 0), R, material=plate_mat, fixed=True))\n"
       "O.bodies[p].state.blockedDOFs = 'xyzXYZ'; O.bodies[p].state.vel = Vector3(0.03, 0.02, 0.0)\n"
    << "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),\n"
       "  InteractionLoop([Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting="
    << (avoid_granular_ratcheting ? "True" : "False")
    << ")], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
       "  NewtonIntegrator(damping=0.0, gravity=(0, 0, 0))]\n"
    << "O.dt = " << kStep << "\nO.forces.setPermF(n, Vector3(0, 0, -load))\n"
    << "with open(sys.argv[1], 'w') as f:\n"
       "    for k in range(1, "
    << kSteps + 1 << "):\n"
       "        O.step()\n"
       "        if k % "
    << kEvery << " == 0:\n"
       "            g = O.forces.f(p); f.write('%r %r %r\\n' % (g[0], g[1], g[2]))\n";
  std::ofstream(script) << s.str();
  const std::string command = "yade -j1 -n -x " + script.string() + " " + out.string() + " > " + (dir / "yade.log").string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "yade.log").string();
  Rows rows;
  std::ifstream in(out);
  for (double x, y, z; in >> x >> y >> z;) rows.emplace_back(x, y, z);
  return rows;
}

TEST(DemToolContactYade, NodeOnAMovingSphereMatchesCundallStrackAtTheContactPoint) {
  if (std::system("command -v yade > /dev/null 2>&1") != 0) GTEST_SKIP() << "yade is not installed";
  double friction = 0.0;
  const Rows a = ours(friction), contact_point = yade(false), full_radii = yade(true);
  ASSERT_EQ(contact_point.size(), a.size());
  ASSERT_EQ(full_radii.size(), a.size());
  double largest = 0.0, off_contact_point = 0.0, off_full_radii = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    largest = std::max(largest, a[i].norm());
    off_contact_point = std::max(off_contact_point, (contact_point[i] - a[i]).norm());
    off_full_radii = std::max(off_full_radii, (full_radii[i] - a[i]).norm());
  }
  std::cout << "largest force " << largest << " N (friction up to " << friction
            << " N); YADE at the contact point departs by " << off_contact_point / largest
            << ", YADE's default (avoidGranularRatcheting) by " << off_full_radii / largest << " of it\n";
  EXPECT_GT(friction, 0.05 * largest);  // the friction is exercised, not just the normal spring
  EXPECT_LE(off_contact_point, 1e-4 * largest);
  EXPECT_GT(off_full_radii, 1e-4 * largest);
}

}  // namespace
}  // namespace dtwire::dem

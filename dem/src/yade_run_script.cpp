// The punch run as a YADE script (WireMat / Ip2_WireMat_WireMat_WirePhys /
// Law2_ScGeom_WirePhys_WirePM for the net, FrictMat facets for the platter), so that the same
// run can be repeated in YADE unchanged. Choices that make YADE do what our engine does are
// commented in the generated script; docs/dem_engine.md lists them.
#include <cmath>
#include <sstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/dem/run.hpp"
#include "dtwire/dem/wirepm.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::dem {
namespace {

double value_or(const ParameterMap& p, const std::string& name, double fallback) {
  const auto found = p.find(name);
  return found == p.end() ? fallback : found->second;
}

std::vector<std::pair<double, double>> backbone_points(const ParameterMap& p) {
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0;; ++i) {
    const auto strain = p.find("backbone_" + std::to_string(i) + "_strain_1");
    if (strain == p.end()) break;
    const double stress = p.at("backbone_" + std::to_string(i) + "_stress_Pa");
    if (strain->second == 0.0 && stress == 0.0) continue;
    points.emplace_back(strain->second, stress);
  }
  return points;
}

}  // namespace

std::string yade_run_script(const RunInput& in, const YadeScriptOptions& export_options) {
  const std::string file = in.file.string();
  if (in.tool != "platter") throw InputError(file, "tool.kind: the YADE export covers the platter punch only");
  const bool hemisphere = std::abs(in.platter_height - in.platter_base_radius) <= 1e-12 * in.platter_base_radius;
  if (export_options.platter == YadePlatter::Sphere && !hemisphere)
    throw InputError(file, "tool.height_m: the sphere platter in YADE needs a hemisphere (height_m = base_radius_m = " +
                               format_number(in.platter_base_radius) + "); found " + format_number(in.platter_height));
  // The exact surface whenever YADE has it: the facets' reaction departs from it near the peak.
  const bool sphere = export_options.platter == YadePlatter::Sphere ||
                      (export_options.platter == YadePlatter::Automatic && hemisphere);
  if (!in.force_levels.empty()) throw InputError(file, "tool.force_levels_N: the YADE export covers the monotonic punch only");
  if (in.settle_rest_ratio > 0.0)
    throw InputError(file, "dynamics.settle_rest_ratio: the YADE export settles for dynamics.settle_s steps; set the ratio to 0");
  // YADE's WirePM links carry axial force only, so a middle node would be a hinge there, and its
  // net material finds double twists by consecutive ids, which a split twist no longer has.
  if (in.mesh.nodes_per_wire != 2)
    throw InputError(file, "mesh.nodes_per_wire: the YADE export needs 2 (one WirePM link per wire); found " +
                               std::to_string(in.mesh.nodes_per_wire));
  if (in.mesh.selvedge) throw InputError(file, "mesh.selvedge: YADE's WirePM would take selvedge links between consecutive ids for double twists");
  const LinkSetInput& sw = in.link_sets.at(LinkTag::SingleWire);
  const LinkSetInput& dt = in.link_sets.at(LinkTag::DoubleTwist);
  if (sw.law != "wirepm" || dt.law != "wirepm") throw InputError(file, "links: the YADE export needs WirePM sets for sw and dt");
  const auto curve = backbone_points(sw.parameters);
  // YADE's types: 0 Bertrand double twist (no shift), 1 the double twist's own curve on twice the
  // wire area, 2 as 1 plus the Thoeni distortion (type, lambdau, seed, lambdaF on WireMat).
  const bool own_dt_curve = value_or(dt.parameters, "double_twist_model", 0.0) == 1.0;
  const bool distorted = sw.distortion.mode != DistortionMode::None;
  if (!own_dt_curve && curve != backbone_points(dt.parameters))
    throw InputError(file, "links.dt.backbone: YADE's Bertrand net material has one backbone for both link types");
  if (value_or(sw.parameters, "double_twist", 0.0) != 0.0 || value_or(dt.parameters, "double_twist", 0.0) != 1.0)
    throw InputError(file, "links: the YADE export needs a single-wire sw set and a double-twist dt set");
  for (const LinkSetInput* set : {&sw, &dt})
    if (value_or(set->parameters, "lambda_u", 0.0) != 0.0)
      throw InputError(file, "links: the YADE export takes the distortion from links.*.distortion, not from lambda_u in the parameter file");
  if (sw.distortion.mode != dt.distortion.mode || sw.distortion.lambda_u != dt.distortion.lambda_u ||
      sw.distortion.seed != dt.distortion.seed || value_or(sw.parameters, "lambda_F", 1.0) != value_or(dt.parameters, "lambda_F", 1.0))
    throw InputError(file, "links.dt.distortion: YADE's net material has one distortion (type, lambdau, seed, lambdaF) for sw and dt");
  if (!distorted && value_or(sw.parameters, "lambda_F", 1.0) != 1.0)
    throw InputError(file, "links: lambda_F acts only with a distortion");
  if (distorted && !own_dt_curve)
    throw InputError(file, "links.dt.params: YADE's distortion (type 2) needs the double twist's own curve (double_twist_model 1); its Bertrand type 0 has no shift");
  const int yade_type = distorted ? 2 : (own_dt_curve ? 1 : 0);
  if (value_or(sw.parameters, "diameter_m", 0.0) != value_or(dt.parameters, "diameter_m", -1.0))
    throw InputError(file, "links.dt.params: sw and dt sets must have the same wire diameter");

  BuiltNet built = build_net(in);
  std::vector<double> slacks;  // dL of each link as our engine has it
  for (const EngineLink& link : built.links) slacks.push_back(dynamic_cast<const WirePmLaw&>(*link.law).backbone().shift);
  const std::vector<Vector3> stretched = pretensioned_positions(in, built.mesh);
  // The critical step as our engine computes it, with the platter.
  EngineOptions options = in.engine;
  options.threads = 1;
  Engine engine(built.mesh.net.nodes, std::move(built.links), options);
  auto platter = std::make_unique<SemiSpheroidPlatter>(in.platter_base_radius, in.platter_height);
  platter->contact = in.contact;
  engine.add_tool(std::move(platter));
  const double dt_step = engine.time_step();

  const double r = in.mesh.node_radius;
  const double kn = in.contact.normal_stiffness, ks = in.contact.shear_stiffness;
  const double nu = value_or(dt.parameters, "poisson_1", 0.3);
  // Ip2_FrictMat_FrictMat_FrictPhys on a facet-sphere ScGeom (radius1 = 2r, radius2 = r):
  // kn = 2 (2r E_f)(r E_n)/(2r E_f + r E_n), ks the same with E V. Equal moduli E = 3 kn/(4r)
  // give kn; the node's V must stay the Bertrand Poisson ratio nu, so the facet's V_f gives ks.
  const double young = 3.0 * kn / (4.0 * r);
  const double beta = ks / (r * young);
  const double facet_poisson = nu * beta / (2.0 * (2.0 * nu - beta));
  // The sphere platter (radius1 = R, radius2 = r), same Ip2: E_p R = 3 kn / 2 gives kn with the
  // nodes' E r = 3 kn / 4, and its Poisson ratio gives ks with the nodes' nu.
  const double R = in.platter_base_radius;
  const double sphere_young = 1.5 * kn / R;
  const double node_shear = 0.75 * kn * nu;  // E r nu of the nodes
  if (sphere && !(2.0 * node_shear > ks))
    throw InputError(file, "tool.ks_N_per_m: the YADE sphere platter reaches ks < 1.5 nu kn = " +
                               format_number(2.0 * node_shear) + " N/m only");
  const double sphere_poisson = sphere ? ks * node_shear / (2.0 * node_shear - ks) / (sphere_young * R) : 0.0;
  const double links_expected = static_cast<double>(built.mesh.net.links.size());
  const double detection = 0.5 * (0.05 + 0.08);  // between the longest link and the nearest unlinked pair
  const double settle_steps = std::round(in.settle_time / dt_step);

  std::ostringstream s;
  s << "# Punch test '" << in.title << "' exported by dtwire " << tool_version() << " (" << git_hash() << ") from "
    << in.file.filename().string() << ".\n"
       "# Run headless:  yade -n -x <this file> OUT.csv\n"
       "# The same net (node positions, masses, pinned nodes, WirePM links), pre-tension, gravity, local\n"
       "# damping, mass scale, time step and semi-spheroid platter (as facets) as `dtwire dem run`.\n"
       "import sys, math\nfrom yade import *\n\n"
    << "output = sys.argv[1] if len(sys.argv) > 1 else 'yade_punch.csv'\n"
    << "radius = " << format_number(r) << "\n"
    << "time_step = " << format_number(dt_step) << "  # s, dtwire's safety x critical step\n"
    << "settle_steps = " << static_cast<long>(settle_steps) << "\n"
    << "damping = " << format_number(in.engine.local_damping) << "\n"
    << "gap = " << format_number(in.start_gap) << "\nspeed = " << format_number(in.speed)
    << "\ntravel = " << format_number(in.travel) << "\noutput_interval = " << format_number(in.output_interval) << "\n"
    << "base_radius = " << format_number(in.platter_base_radius) << "\nheight = " << format_number(in.platter_height)
    << "\n\n# Nodes: x, y, z (before pre-tension), x, y after pre-tension, inertial mass, inertia, weight, pinned.\n"
       "nodes = [\n";
  for (std::size_t i = 0; i < built.mesh.net.nodes.size(); ++i) {
    const NetNode& node = built.mesh.net.nodes[i];
    s << "(" << format_number(node.position.x()) << "," << format_number(node.position.y()) << ","
      << format_number(node.position.z()) << "," << format_number(stretched[i].x()) << "," << format_number(stretched[i].y())
      << "," << format_number(node.mass * in.engine.mass_scale) << ","
      << format_number(node.rotational_inertia * in.engine.mass_scale * in.engine.rotational_inertia_scale) << ","
      << format_number(node.mass * in.engine.gravity.z()) << "," << (node.fixity == NodeFixity::Pinned ? 1 : 0) << "),\n";
  }
  s << "]\nstrain_stress = [";
  for (const auto& [e, sigma] : curve) s << "(" << format_number(e) << "," << format_number(sigma) << "),";
  s << "]\n";
  if (own_dt_curve) {
    s << "strain_stress_dt = [";
    for (const auto& [e, sigma] : backbone_points(dt.parameters)) s << "(" << format_number(e) << "," << format_number(sigma) << "),";
    s << "]\n";
  }
  if (distorted) {
    // Our links in our order, and the slack dL our engine gives each (distortion.hpp).
    s << "# Links (node ids) in dtwire's order and the slack dL [m] dtwire gives each: YADE draws one\n"
         "# variate per interaction in creation order, so the links are created in this order.\n"
         "link_pairs = [";
    for (std::size_t l = 0; l < built.mesh.net.links.size(); ++l)
      s << "(" << built.mesh.net.links[l].a << "," << built.mesh.net.links[l].b << "),";
    s << "]\nexpected_slack = [";
    for (double slack : slacks) s << format_number(slack) << ",";
    s << "]\n";
  }
  s << "\n"
    << "# One material for the net: YADE finds double twists as links between consecutive ids.\n"
    << "# young/poisson also set the node-facet stiffness (see below); poisson is the Bertrand nu.\n"
    << "wire = O.materials.append(WireMat(young=" << format_number(young) << ", poisson=" << format_number(nu)
    << ", frictionAngle=math.atan(" << format_number(in.contact.friction) << "), density=7850.0, diameter="
    << format_number(value_or(sw.parameters, "diameter_m", 0.0027)) << ",\n    strainStressValues=strain_stress, isDoubleTwist=True, lambdak="
    << format_number(value_or(dt.parameters, "lambda_k", 0.73)) << ", lambdaEps="
    << format_number(value_or(dt.parameters, "lambda_eps", 0.47)) << ", type=" << yade_type
    << (own_dt_curve ? ", strainStressValuesDT=strain_stress_dt" : "");
  if (distorted)
    s << ",\n    lambdau=" << format_number(sw.distortion.lambda_u)
      << ", seed=" << (sw.distortion.mode == DistortionMode::Random ? sw.distortion.seed : -1)
      << ", lambdaF=" << format_number(value_or(sw.parameters, "lambda_F", 1.0));
  s << "))\n";
  if (sphere)
    s << "# The platter: one sphere, the exact hemisphere (node-sphere kn = " << format_number(kn) << " N/m, ks = "
      << format_number(ks) << " N/m).\n"
      << "plate = O.materials.append(FrictMat(young=" << format_number(sphere_young) << ", poisson="
      << format_number(sphere_poisson);
  else
    s << "# The platter: " << export_options.facet_segments << " x " << export_options.facet_rings
      << " facets inscribed in the semi-spheroid (node-facet kn = " << format_number(kn) << " N/m, ks = " << format_number(ks)
      << " N/m); near the peak their reaction departs from the exact platter's by several percent.\n"
      << "plate = O.materials.append(FrictMat(young=" << format_number(young) << ", poisson=" << format_number(facet_poisson);
  s << ", frictionAngle=math.atan(" << format_number(in.contact.friction) << "), density=7850.0))\n\n"
    << "ids = O.bodies.append([sphere((n[0], n[1], n[2]), radius, material=wire, fixed=bool(n[8])) for n in nodes])\n"
       "for i, n in zip(ids, nodes):\n"
       "    O.bodies[i].state.mass = n[5]\n"
       "    O.bodies[i].state.inertia = Vector3(n[6], n[6], n[6])\n\n"
    << "reach = " << format_number(detection) << " / (2.0 * radius)  # links for node pairs closer than this\n"
       "O.engines = [\n"
       "    ForceResetter(),\n"
       "    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=reach, label='aabb'), Bo1_Facet_Aabb()]),\n"
       "    # avoidGranularRatcheting=False: the shear increment from the velocities at the contact point\n"
       "    # (Cundall and Strack 1979), as dtwire; YADE's default levers the spins by the full radii.\n"
       "    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=reach, avoidGranularRatcheting=False, label='ig2'),\n"
       "                     Ig2_Facet_Sphere_ScGeom()],\n"
       "                    [Ip2_WireMat_WireMat_WirePhys(linkThresholdIteration=1), Ip2_FrictMat_FrictMat_FrictPhys()],\n"
       "                    [Law2_ScGeom_WirePhys_WirePM(), Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
       "    NewtonIntegrator(damping=damping, gravity=(0, 0, 0), label='newton'),\n"
       "]\n"
       "O.dt = time_step\n";
  if (distorted)
    s << "for a, b in link_pairs:\n"
         "    createInteraction(a, b)\n"
         "worst = max(abs(O.interactions[a, b].phys.dL - e) for (a, b), e in zip(link_pairs, expected_slack))\n"
         "if worst > 1e-12:\n"
         "    raise SystemExit('YADE drew other slacks than dtwire: largest difference %g m' % worst)\n"
         "print('slack of every link as dtwire drew it; largest difference', worst, 'm')\n";
  s << "O.step()  # creates the links at zero force (no load acts yet)\n"
       "aabb.aabbEnlargeFactor = -1\nig2.interactionDetectionFactor = -1\n"
       "links = sum(1 for i in O.interactions if i.isReal and hasattr(i.phys, 'isLinked') and i.phys.isLinked)\n"
    << "if links != " << static_cast<long>(links_expected) << ":\n"
    << "    raise SystemExit('expected " << static_cast<long>(links_expected) << " links, YADE made %d' % links)\n"
       "# Pre-tension (imposed stretch) and gravity on the real mass (the inertia is scaled).\n"
       "for i, n in zip(ids, nodes):\n"
       "    O.bodies[i].state.pos = Vector3(n[3], n[4], n[2])\n"
       "    O.forces.setPermF(i, Vector3(0, 0, n[7]))\n"
       "O.run(settle_steps, True)\n"
       "lowest = min(O.bodies[i].state.pos[2] for i in ids)\n"
       "sag = -lowest\n"
       "cx = 0.5 * (min(n[0] for n in nodes) + max(n[0] for n in nodes)); cy = 0.5 * (min(n[1] for n in nodes) + max(n[1] for n in nodes))\n"
       "base_z = lowest - radius - gap - height\n";
  if (sphere)
    s << "platter = [O.bodies.append(sphere((cx, cy, base_z), base_radius, material=plate, fixed=True))]\n";
  else
    s << "segments, rings = " << export_options.facet_segments << ", " << export_options.facet_rings << "\n"
      << "def dome(k, j):\n"
         "    theta = 0.5 * math.pi * k / rings; phi = 2.0 * math.pi * j / segments\n"
         "    return Vector3(cx + base_radius * math.sin(theta) * math.cos(phi), cy + base_radius * math.sin(theta) * math.sin(phi),\n"
         "                   base_z + height * math.cos(theta))\n"
         "facets = []\n"
         "for k in range(rings):\n"
         "    for j in range(segments):\n"
         "        a, b = dome(k, j), dome(k, j + 1); c, d = dome(k + 1, j), dome(k + 1, j + 1)\n"
         "        if k > 0: facets.append(facet([a, d, b], material=plate, fixed=True))\n"
         "        facets.append(facet([a, c, d], material=plate, fixed=True))\n"
         "platter = O.bodies.append(facets)\n";
  s << "for i in platter:\n"
       "    O.bodies[i].state.blockedDOFs = 'xyzXYZ'\n"
       "    O.bodies[i].state.vel = Vector3(0, 0, speed)\n"
       "start = O.bodies[platter[0]].state.pos[2]\n"
       "chunk = max(1, int(round(output_interval / time_step)))\n"
       "def platter_force():\n"
       "    f = Vector3(0, 0, 0)\n"
       "    for i in platter: f += O.forces.f(i)\n"
       "    return -f if all(math.isfinite(c) for c in f) else Vector3(0, 0, 0)\n";
  if (sphere)  // the mean over every step of the interval, as ours: one body, so it costs little
    s << "def interval_mean():\n"
         "    mean = Vector3(0, 0, 0)\n"
         "    for k in range(chunk):\n"
         "        O.step()\n"
         "        mean += platter_force() / chunk\n"
         "    return mean\n";
  else  // summing thousands of facets every step would cost more than the run: 25 samples
    s << "samples = 25\nsub = max(1, chunk // samples)\n"
         "def interval_mean():\n"
         "    mean = Vector3(0, 0, 0)\n"
         "    for k in range(samples):\n"
         "        O.run(sub, True)\n"
         "        mean += platter_force() / samples\n"
         "    return mean\n";
  s << "rows = [(0.0, 0.0, 0.0, 0.0, 0)]\n"
       "t0 = O.time\n"
       "while True:\n"
       "    mean = interval_mean()\n"
       "    d = O.bodies[platter[0]].state.pos[2] - start\n"
       "    linked = sum(1 for i in O.interactions if i.isReal and hasattr(i.phys, 'isLinked') and i.phys.isLinked)\n"
       "    rows.append((O.time - t0, d * 1000.0, mean.norm(), mean[2], links - linked))\n"
       "    if d >= travel: break\n"
       "with open(output, 'w') as out:\n"
       "    out.write('# source: YADE WirePM punch (exported by dtwire)\\n')\n"
       "    out.write('# sag_after_settling_mm: %r\\n' % (sag * 1000.0))\n"
       "    out.write('time_s,tool_displacement_mm,tool_force_N,tool_force_z_N,broken_links_1\\n')\n"
       "    for row in rows: out.write('%r,%r,%r,%r,%r\\n' % row)\n"
       "print('wrote', output, len(rows), 'rows; sag', sag)\n";
  return s.str();
}

}  // namespace dtwire::dem

// Timed comparison (not a test): the WirePM punch in our engine vs YADE on the same mesh, in one
// run, and link updates per second per core of the engine (the whole step: kinematics, law,
// gather, integration) for wirepm and macro3d links.
//   build/bench/bench_dem_punch [INPUT.toml]   (default experiments/dem/punch_yade_check.toml)
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "dtwire/dem/run.hpp"

using namespace dtwire::dem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Steps of the punch net with every link on `law`, the platter pushing up at 0.5 m/s; returns
// link updates per second on one thread.
double link_updates_per_second(RunInput input, const std::string& law, const std::string& file, long steps) {
  for (auto& [tag, set] : input.link_sets) {
    if (law == "wirepm") continue;
    set.law = law;
    const std::string wire_type = tag == LinkTag::DoubleTwist ? "double_twist" : "single_wire";
    set.parameters.clear();
    // The thesis calibrations, converted to macro3d by the factory (thesis keys).
    const std::map<std::string, ParameterMap> sets = {
        {"single_wire", {{"D_m", 0.0027}, {"EA_N", 1.6e7}, {"EI_Nm2_per_deg_convention", 0.122}, {"N0_N", 2750},
                         {"Nult_N", 3200}, {"Nc_N", 1650}, {"m_f", 0.0285}, {"beta_f", 0.195}, {"k_F", 2.39e4},
                         {"k_M", 1.12e3}, {"m_g", 4.78}, {"alpha_g", 0.5}, {"beta_g", 0.0358}, {"W1_J", 9.21},
                         {"W2_J", 140.01}, {"alpha_d", 2.7}, {"slide_a", 0.0}, {"slide_b", 0.0}}},
        {"double_twist", {{"D_m", 0.0027}, {"EA_N", 1.71e6}, {"EI_Nm2_per_deg_convention", 0.257}, {"N0_N", 2800},
                          {"Nult_N", 5000}, {"Nc_N", 1650}, {"m_f", 0.0354}, {"beta_f", 0.0642}, {"k_F", 4.08e3},
                          {"k_M", 0.112}, {"m_g", 6.32e-4}, {"alpha_g", 0.5}, {"beta_g", 3.24}, {"W1_J", 10.5},
                          {"W2_J", 202.278}, {"alpha_d", 2.75}, {"slide_a", 0.0}, {"slide_b", 0.0}}}};
    set.parameters = sets.at(wire_type);
  }
  input.engine.threads = 1;
  BuiltNet built = build_net(input);
  Engine engine(built.mesh.net.nodes, std::move(built.links), input.engine);
  auto platter = std::make_unique<SemiSpheroidPlatter>(input.platter_base_radius, input.platter_height);
  platter->position = Vector3(0.5 * input.mesh.width, 0.5 * input.mesh.height, -input.platter_height - 0.006);
  platter->velocity = Vector3(0.0, 0.0, 0.5);
  platter->contact = input.contact;
  engine.add_tool(std::move(platter));
  const auto start = Clock::now();
  for (long k = 0; k < steps; ++k) engine.step();
  return static_cast<double>(engine.link_count()) * static_cast<double>(steps) / seconds_since(start);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : std::string(DTWIRE_SOURCE_DIR) + "/experiments/dem/punch_yade_check.toml";
  const RunInput input = read_run_input(file);
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_bench_dem_punch";
  std::filesystem::create_directories(dir);

  RunOptions options;
  options.out = dir / "ours";
  options.quiet = true;
  options.write_frames = false;
  options.threads = 1;
  const RunSummary ours = run_simulation(input, options);
  std::cout << "ours (1 thread): " << ours.wall_seconds << " s wall, " << ours.steps << " steps, " << ours.links
            << " links, peak " << ours.peak_force << " N\n";
  options.threads = 2;
  options.out = dir / "ours2";
  const RunSummary ours2 = run_simulation(input, options);
  std::cout << "ours (2 threads): " << ours2.wall_seconds << " s wall\n";

  if (std::system("command -v yade > /dev/null 2>&1") == 0) {
    std::ofstream(dir / "punch.py") << yade_run_script(input);
    const auto start = Clock::now();
    const std::string command = "cd " + dir.string() + " && yade -n -j1 -x punch.py yade.csv > yade.log 2>&1";
    const int code = std::system(command.c_str());
    const double yade_seconds = seconds_since(start);
    std::cout << "YADE (1 thread): " << yade_seconds << " s wall" << (code ? " (FAILED, see yade.log)" : "") << "\n"
              << "ratio ours / YADE (1 thread each): " << ours.wall_seconds / yade_seconds << " (goal <= 0.5)\n";
  } else {
    std::cout << "YADE not installed: no comparison\n";
  }
  for (const std::string law : {"wirepm", "macro3d"})
    std::cout << law << ": " << link_updates_per_second(input, law, file, 2000) / 1e6
              << " M link updates per second per core (whole engine step)\n";
  return 0;
}

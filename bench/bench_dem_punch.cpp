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
double link_updates_per_second(RunInput input, const std::string& law, long steps) {
  if (law != "wirepm") {
    // The thesis calibrations (PFC7 example), run by the macro3d law (it reads thesis keys).
    const std::filesystem::path thesis = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/macroelement_thesis_params.json";
    for (auto& [tag, set] : input.link_sets) set.law = law;  // the thesis file names no law
    for (const std::string tag : {"sw", "dt"}) override_link_set(input, tag, thesis, "bench");
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
            << " links, peak " << ours.peak_force << " N" << std::endl;
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
    std::cout << law << ": " << link_updates_per_second(input, law, 2000) / 1e6
              << " M link updates per second per core (whole engine step)\n";
  return 0;
}

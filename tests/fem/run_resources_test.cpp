// The FE run's memory and disk estimate (issue 37): mesh sizes counted without building the mesh,
// the estimate against the peak memory measured on this project's machine (it must not fall
// below a measured run, nor exceed it by more than the stated margin), and the refusal of a run
// far beyond the machine, naming the count and the way round it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dtwire/core/error.hpp"
#include "run_resources.hpp"

namespace dtwire::fem {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_run_resources_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

GeometryParameters sw(unsigned radial_refinements, unsigned axial_cells, bool quarter = true) {
  GeometryParameters g;
  g.quarter = quarter;
  g.radial_refinements = radial_refinements;
  g.axial_cells = axial_cells;
  return g;
}

TEST(RunResources, GeneratedMeshCountsTheSectionTimesTheLayers) {
  EXPECT_EQ(generated_mesh_size(sw(1, 30)).cells, 360u);  // the default SW tension: 12 a section
  EXPECT_EQ(generated_mesh_size(sw(1, 30)).section_cells, 12u);
  EXPECT_EQ(generated_mesh_size(sw(2, 750)).cells, 36000u);
  EXPECT_EQ(generated_mesh_size(sw(0, 10, false)).cells, 50u);  // hyper_ball: 5 cells
  EXPECT_EQ(generated_mesh_size(sw(1, 10000000)).cells, 120000000u);
}

// The gmsh formats and their errors are tested with meshes::count_msh_volume_cells
// (tests/meshes/msh_reader_test.cpp); here the bundled double twist, whose size the FE run takes.
TEST(RunResources, MshFileCountsItsVolumeCells) {
  const MeshSize dt = msh_file_size(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/dt/dt_level0.msh");
  EXPECT_EQ(dt.cells, 1488u);  // `dtwire mesh dt --level 0 --check`: 1488 hexahedra
  EXPECT_EQ(dt.section_cells, 0u);
}

// Peak resident memory measured with `/usr/bin/time -f %M dtwire run` (KiB; docs/fem.md, Memory).
struct Measured {
  MeshSize mesh;
  unsigned degree;
  double peak_kib;
};

TEST(RunResources, EstimateCoversEveryMeasuredRunWithinItsMargin) {
  const MeshSize dt0{1488, 0}, dt1{11712, 0}, dt2{78720, 0};
  const std::vector<Measured> runs = {
      {generated_mesh_size(sw(1, 30)), 1, 197504},    {generated_mesh_size(sw(1, 3000)), 1, 953548},
      {generated_mesh_size(sw(2, 30)), 1, 237360},    {generated_mesh_size(sw(2, 750)), 1, 1221788},
      {generated_mesh_size(sw(1, 30)), 2, 311512},    {generated_mesh_size(sw(1, 300)), 2, 1379132},
      {dt0, 1, 247464},                               {dt1, 1, 878768},
      {dt2, 1, 5080100}};  // level 2: peak of its first 17 load steps (the factorisation's size is set at the first)
  for (const Measured& run : runs) {
    const double estimate = run_memory_estimate(run.mesh, run.degree, 1);
    const double measured = run.peak_kib * 1024.0;
    EXPECT_GE(estimate, 0.98 * measured) << run.mesh.cells << " cells, Q" << run.degree;
    EXPECT_LE(estimate, 1.35 * measured) << run.mesh.cells << " cells, Q" << run.degree;
  }
}

Parameters sw_tension(unsigned axial_cells) {
  Parameters p;
  p.geometry = sw(1, axial_cells);
  p.load.path = {{0.0, 0.0}, {1.0, 13e-3}};
  p.stepping.maximum_step = 0.02;
  p.output.fields = true;
  p.output.field_interval = 10;
  return p;
}

TEST(RunResources, FramesCountTheFewestStepsOfTheLoadPath) {
  // 1 / 0.02 = 50 steps at the least: frames at 0, 10, ..., 50 (the last is always written).
  const double frame = 360 * 128.0;
  EXPECT_DOUBLE_EQ(field_output_estimate(generated_mesh_size(sw(1, 30)), 1, sw_tension(30)), 6 * frame);
  Parameters quiet = sw_tension(30);
  quiet.output.fields = false;
  EXPECT_EQ(field_output_estimate(generated_mesh_size(sw(1, 30)), 1, quiet), 0.0);
}

TEST(RunResources, TenMillionAxialCellsAreRefusedByName) {
  const std::uint64_t gib = 1ull << 30;
  const auto out = scratch("out");
  EXPECT_NO_THROW(check_run_resources(sw_tension(30), 1, std::nullopt, 24 * gib, 100 * gib, "sw.prm", out));
  try {
    check_run_resources(sw_tension(10000000), 1, std::nullopt, 24 * gib, 100 * gib, "sw.prm", out);
    FAIL() << "120 million cells were accepted on 24 GiB";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.source(), "sw.prm");
    EXPECT_NE(message.find("120000000 cells"), std::string::npos) << message;
    EXPECT_NE(message.find("--max-memory"), std::string::npos) << message;
  }
  // --max-memory is the limit when given, above or below the machine's.
  EXPECT_THROW(check_run_resources(sw_tension(30), 1, 100ull << 20, 24 * gib, 100 * gib, "sw.prm", out), InputError);
  // The frames of 3 million cells every step do not fit 1 GiB of disk.
  Parameters frames = sw_tension(250000);
  frames.output.field_interval = 1;
  EXPECT_THROW(check_run_resources(frames, 1, 1000 * gib, 24 * gib, gib, "sw.prm", out), InputError);
}

}  // namespace
}  // namespace dtwire::fem

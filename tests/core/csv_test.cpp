#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire {
namespace {

TEST(Csv, ParsesMetadataHeaderAndValuesKeepingUnits) {
  const Curve curve = parse_csv(
      "# specimen: SW-01\n# comment line without colon\n"
      "displacement_mm,force_kN\n0,0\n0.5,1.25\n1.0,2.5\n",
      "inline");
  EXPECT_EQ(curve.metadata("specimen"), "SW-01");
  ASSERT_EQ(curve.size(), 3u);
  EXPECT_EQ(curve.channel("force").unit.symbol, "kN");
  EXPECT_DOUBLE_EQ(curve.channel("force").values[2], 2.5);
  EXPECT_DOUBLE_EQ(curve.si("force")[2], 2500.0);        // kN -> N
  EXPECT_DOUBLE_EQ(curve.si("displacement")[1], 0.5e-3);  // mm -> m
}

// Spreadsheets save "CSV UTF-8" with a byte-order mark before the header: it is no part of the
// first column's name.
TEST(Csv, AByteOrderMarkBeforeTheHeaderIsSkipped) {
  const Curve curve = parse_csv("\xEF\xBB\xBF# specimen: SW-02\ndisplacement_mm,force_N\n0,0\n1,10\n2,20\n", "bom.csv");
  EXPECT_EQ(curve.metadata("specimen"), "SW-02");
  ASSERT_TRUE(curve.has("displacement"));
  EXPECT_DOUBLE_EQ(curve.si("displacement")[2], 2e-3);
}

TEST(Csv, WriteThenReadIsExactForAwkwardNumbers) {
  Curve curve;
  curve.set_metadata("source", "test");
  curve.add_channel("strain", *find_unit("1"), {0.0, 0.1 + 0.2, 1.0 / 3.0, 6.02214076e23});
  curve.add_channel("stress", *find_unit("MPa"), {0.0, -1e-300, 5.12190000000001e2, 4.9e-324});
  const Curve back = parse_csv(format_csv(curve), "roundtrip");
  EXPECT_EQ(back, curve);
}

TEST(Csv, WriteIsAtomicAndLeavesNoTemporaryFiles) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_csv_atomic";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  Curve curve;
  curve.add_channel("displacement", *find_unit("mm"), {0, 1, 2});
  curve.add_channel("force", *find_unit("N"), {0, 10, 20});
  write_csv(curve, dir / "out.csv");
  EXPECT_EQ(read_csv(dir / "out.csv"), curve);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
  std::filesystem::remove_all(dir);
}

TEST(Csv, RefusesToWriteNonFiniteValuesAndLeavesNothing) {
  const auto path = std::filesystem::temp_directory_path() / "dtwire_nan.csv";
  std::filesystem::remove(path);
  Curve curve;
  curve.add_channel("displacement", *find_unit("mm"), {0, 1, 2});
  curve.add_channel("force", *find_unit("N"), {0, std::nan(""), 20});
  EXPECT_THROW(write_csv(curve, path), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(Csv, ReadsTheSharedDemBackboneOnceRenamed) {
  // The bundled copy of the DEM backbone (experiments/data) uses unit-named columns.
  const Curve curve =
      read_csv(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/data/sw_2.7mm_dem_backbone.csv");
  EXPECT_EQ(curve.size(), 8u);
  EXPECT_NEAR(curve.si("stress").back(), 5.6585e8, 1.0);
}

}  // namespace
}  // namespace dtwire

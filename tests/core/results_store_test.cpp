#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/results_store.hpp"

namespace dtwire {
namespace {

std::filesystem::path temp(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("dtwire_test_" + name);
}

TEST(ResultsStore, CsvToHdf5ToCsvRoundTripIsExact) {
  const std::string text =
      "# specimen: SW-07\n# rate: 2 mm/min\n"
      "displacement_mm,force_N,time_s\n"
      "0,0,0\n0.0123456789012345,12.3456789,0.37\n1e-9,3.24e3,1.5\n0.30000000000000004,-0.5,2\n";
  const Curve original = parse_csv(text, "inline");
  Results results;
  results.curves.emplace_back("sw_tension", original);
  results.parameters.push_back({"E", 1.6e11, "Pa", 2.1e9});
  results.parameters.push_back({"m_f", 0.0285, "1", std::nullopt});
  results.fields.emplace_back("vtu", "fields/step_0010.pvtu");
  results.provenance = make_provenance("dtwire test");
  const auto h5 = temp("roundtrip.h5");
  write_results(results, h5);
  const Results back = read_results(h5);
  ASSERT_EQ(back.curves.size(), 1u);
  EXPECT_EQ(back.curves[0].first, "sw_tension");
  EXPECT_EQ(back.curves[0].second, original);
  EXPECT_EQ(format_csv(back.curves[0].second), format_csv(original));
  EXPECT_EQ(format_csv(back.curves[0].second), format_csv(parse_csv(format_csv(original), "again")));
  ASSERT_EQ(back.parameters.size(), 2u);
  EXPECT_EQ(back.parameters[0].value, 1.6e11);
  EXPECT_EQ(back.parameters[0].sigma.value_or(0), 2.1e9);
  EXPECT_FALSE(back.parameters[1].sigma.has_value());
  EXPECT_EQ(back.parameters[1].unit, "1");
  EXPECT_EQ(back.fields, results.fields);
  EXPECT_EQ(back.provenance.git_hash, results.provenance.git_hash);
  EXPECT_EQ(back.provenance.command, "dtwire test");
  std::filesystem::remove(h5);
}

TEST(ResultsStore, ProvenanceRecordsInputHashes) {
  const auto csv = temp("input.csv");
  Curve c;
  c.add_channel("displacement", *find_unit("mm"), {0, 1, 2});
  write_csv(c, csv);
  Results results;
  results.provenance = make_provenance("dtwire test", {csv});
  const auto h5 = temp("provenance.h5");
  write_results(results, h5);
  const Results back = read_results(h5);
  ASSERT_EQ(back.provenance.input_sha256.size(), 1u);
  EXPECT_EQ(back.provenance.input_sha256[0].second, sha256_file(csv));
  EXPECT_EQ(back.provenance.input_sha256[0].second.size(), 64u);
  EXPECT_EQ(back.provenance.run_id, results.provenance.run_id);
  EXPECT_FALSE(back.provenance.run_id.empty());
  std::filesystem::remove(h5);
  std::filesystem::remove(csv);
}

TEST(ResultsStore, KnownSha256) {
  EXPECT_EQ(sha256_text("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(ResultsStore, RefusesNonFiniteParametersAndLeavesNoFile) {
  Results results;
  results.parameters.push_back({"E", std::nan(""), "Pa", std::nullopt});
  const auto h5 = temp("nan.h5");
  std::filesystem::remove(h5);
  EXPECT_THROW(write_results(results, h5), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(h5));
}

TEST(ResultsStore, ReadingANonHdf5FileIsAnInputError) {
  const auto path = temp("not.h5");
  Curve c;
  c.add_channel("displacement", *find_unit("mm"), {0, 1, 2});
  write_csv(c, path);
  EXPECT_THROW(read_results(path), InputError);
  EXPECT_THROW(read_results(std::filesystem::temp_directory_path()), InputError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace dtwire

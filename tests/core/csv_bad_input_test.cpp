// One test per bad-input case: each must give an InputError naming file:line:column and what
// was expected.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire {
namespace {

struct Failure {
  int line;
  int column;
  std::string message;
};

Failure parse_failure(const std::string& text) {
  try {
    parse_csv(text, "bad.csv");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "bad.csv");
    return {e.line(), e.column(), e.what()};
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return {};
}

TEST(CsvBadInput, EmptyFile) {
  const Failure f = parse_failure("");
  EXPECT_EQ(f.line, 1);
  EXPECT_NE(f.message.find("empty file"), std::string::npos) << f.message;
}

TEST(CsvBadInput, OnlyMetadataIsEmptyOfData) {
  const Failure f = parse_failure("# a: b\n\n");
  EXPECT_NE(f.message.find("no header row"), std::string::npos) << f.message;
}

TEST(CsvBadInput, NoHeaderRow) {
  const Failure f = parse_failure("0,0\n1,2\n2,4\n3,6\n");
  EXPECT_EQ(f.line, 1);
  EXPECT_EQ(f.column, 1);
  EXPECT_NE(f.message.find("no header row"), std::string::npos) << f.message;
}

TEST(CsvBadInput, UnknownUnit) {
  const Failure f = parse_failure("displacement_mm,force_lbf\n0,0\n1,1\n2,2\n");
  EXPECT_EQ(f.line, 1);
  EXPECT_EQ(f.column, 17);
  EXPECT_NE(f.message.find("unknown unit 'lbf'"), std::string::npos) << f.message;
  EXPECT_NE(f.message.find("expected one of"), std::string::npos) << f.message;
}

TEST(CsvBadInput, ColumnWithoutUnit) {
  const Failure f = parse_failure("strain,stress_Pa\n0,0\n1,1\n2,2\n");
  EXPECT_EQ(f.column, 1);
  EXPECT_NE(f.message.find("<quantity>_<unit>"), std::string::npos) << f.message;
}

TEST(CsvBadInput, NonNumericCell) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1,abc\n2,2\n");
  EXPECT_EQ(f.line, 3);
  EXPECT_EQ(f.column, 3);
  EXPECT_NE(f.message.find("expected a number, found 'abc'"), std::string::npos) << f.message;
}

TEST(CsvBadInput, NaN) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1,nan\n2,2\n");
  EXPECT_EQ(f.line, 3);
  EXPECT_NE(f.message.find("non-finite"), std::string::npos) << f.message;
}

TEST(CsvBadInput, Infinity) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1,2\n-inf,2\n");
  EXPECT_EQ(f.line, 4);
  EXPECT_EQ(f.column, 1);
  EXPECT_NE(f.message.find("non-finite"), std::string::npos) << f.message;
}

TEST(CsvBadInput, FewerThanThreePoints) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1,2\n");
  EXPECT_EQ(f.line, 3);
  EXPECT_NE(f.message.find("at least 3"), std::string::npos) << f.message;
}

TEST(CsvBadInput, RaggedRow) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1,2,3\n2,2\n");
  EXPECT_EQ(f.line, 3);
  EXPECT_NE(f.message.find("expected 2 cells, found 3"), std::string::npos) << f.message;
}

TEST(CsvBadInput, ShortRow) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1\n2,2\n");
  EXPECT_EQ(f.line, 3);
  EXPECT_NE(f.message.find("expected 2 cells, found 1"), std::string::npos) << f.message;
}

TEST(CsvBadInput, EmptyCell) {
  const Failure f = parse_failure("displacement_mm,force_N\n0,0\n1,\n2,2\n");
  EXPECT_EQ(f.line, 3);
  EXPECT_EQ(f.column, 3);
  EXPECT_NE(f.message.find("empty cell"), std::string::npos) << f.message;
}

TEST(CsvBadInput, DirectoryInsteadOfFile) {
  const auto dir = std::filesystem::temp_directory_path();
  try {
    read_csv(dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), dir.string());
    EXPECT_NE(std::string(e.what()).find("is a directory, expected a CSV file"), std::string::npos);
  }
}

TEST(CsvBadInput, MissingFile) {
  EXPECT_THROW(read_csv("/nonexistent/dtwire/curve.csv"), InputError);
}

TEST(CsvBadInput, ErrorMessageStartsWithFileLineColumn) {
  try {
    parse_csv("displacement_mm,force_N\n0,0\n1,x\n2,2\n", "lab/sw01.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("lab/sw01.csv:3:3: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace dtwire

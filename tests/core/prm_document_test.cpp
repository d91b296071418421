// The typed experiment document: reading entries by path, edits that keep the rest of the file,
// defaults behind the file, checked numbers and names, errors naming file:line.
#include <gtest/gtest.h>

#include "dtwire/core/error.hpp"
#include "dtwire/core/prm_document.hpp"

namespace dtwire {
namespace {

const char* kText =
    "# a comment line\n"
    "subsection Material\n"
    "  set Yield stress (MPa)   = 250   # nominal\n"
    "  set Hardening table = 0:250, \\\n"
    "                        0.1:350\n"
    "end\n"
    "subsection Contact\n"
    "  subsection Tool 1\n"
    "    set Shape = plane\n"
    "  end\n"
    "end\n";

const char* kDeclared =
    "subsection Material\n  set Yield stress (MPa) = 200\n  set Hardening table =\n  set Poisson ratio = 0.3\nend\n"
    "subsection Contact\n  subsection Tool 1\n    set Shape = none\n  end\nend\n"
    "subsection Output\n  set Fields = true\nend\n";

int line_of_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.line();
  }
  return -1;
}

TEST(PrmDocument, ReadsEntriesByPathWithTheirLines) {
  const PrmDocument d = PrmDocument::parse(kText, "test.prm");
  EXPECT_EQ(d.get("Material/Yield stress (MPa)").value(), "250");
  EXPECT_EQ(d.find("Material/Yield stress (MPa)")->line, 3);
  EXPECT_EQ(d.get("Material/Hardening table").value(), "0:250, 0.1:350");  // continued line joined
  EXPECT_EQ(d.get("Contact/Tool 1/Shape").value(), "plane");
  EXPECT_EQ(d.find("Contact/Tool 1/Shape")->line, 9);
  EXPECT_FALSE(d.get("Material/Poisson ratio"));
  EXPECT_DOUBLE_EQ(d.number("Material/Yield stress (MPa)"), 250.0);
}

TEST(PrmDocument, DefaultsStandBehindTheFile) {
  const PrmDocument d = PrmDocument::parse(kText, "test.prm");
  const PrmDocument declared = PrmDocument::parse(kDeclared, "declared");
  EXPECT_DOUBLE_EQ(d.number("Material/Poisson ratio", &declared), 0.3);
  EXPECT_DOUBLE_EQ(d.number("Material/Yield stress (MPa)", &declared), 250.0);  // the file wins
  EXPECT_THROW(d.value("Material/Density"), InputError);
}

TEST(PrmDocument, EditsKeepEveryOtherLineAndComment) {
  PrmDocument d = PrmDocument::parse(kText, "test.prm");
  d.set("Material/Yield stress (MPa)", "270");
  d.set("Material/Hardening table", "0:290, 0.06:350");
  d.set("Output/Fields", "false");                  // a missing subsection is opened
  d.set("Contact/Tool 1/Radius (mm)", "15");        // a missing entry goes to the end of its subsection
  EXPECT_EQ(d.text(),
            "# a comment line\n"
            "subsection Material\n"
            "  set Yield stress (MPa)   = 270   # nominal\n"
            "  set Hardening table = 0:290, 0.06:350\n"
            "end\n"
            "subsection Contact\n"
            "  subsection Tool 1\n"
            "    set Shape = plane\n"
            "    set Radius (mm) = 15\n"
            "  end\n"
            "end\n"
            "subsection Output\n"
            "  set Fields = false\n"
            "end\n");
  const PrmDocument again = PrmDocument::parse(d.text(), "again");
  EXPECT_EQ(again.get("Contact/Tool 1/Radius (mm)").value(), "15");
  EXPECT_EQ(again.get("Output/Fields").value(), "false");
}

TEST(PrmDocument, TheLastSetWinsAndEveryCopyIsEdited) {
  PrmDocument d = PrmDocument::parse("set A = 1\nset A = 2\n", "t");
  EXPECT_EQ(d.get("A").value(), "2");
  d.set("A", "3");
  EXPECT_EQ(d.text(), "set A = 3\nset A = 3\n");
}

TEST(PrmDocument, BadTextIsAnErrorNamingTheLine) {
  EXPECT_EQ(line_of_error([] { PrmDocument::parse("subsection A\n  set B = 1\n  bogus line\nend\n", "t"); }), 3);
  EXPECT_EQ(line_of_error([] { PrmDocument::parse("set B = 1\nend\n", "t"); }), 2);
  EXPECT_EQ(line_of_error([] { PrmDocument::parse("set B = 1\nsubsection A\n  set C = 2\n", "t"); }), 2);
  const PrmDocument d = PrmDocument::parse("subsection M\n  set E = 2e5\n  set nu = 0.3x\n  set inf = inf\nend\n", "m.prm");
  EXPECT_EQ(line_of_error([&] { d.number("M/nu"); }), 3);
  EXPECT_EQ(line_of_error([&] { d.number("M/inf"); }), 4);  // non-finite refused
  try {
    d.number("M/nu");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "m.prm");
    EXPECT_NE(std::string(e.what()).find("0.3x"), std::string::npos) << e.what();
  }
}

TEST(PrmDocument, UnknownNamesAreNamedWithTheClosestDeclaredOne) {
  const PrmDocument declared = PrmDocument::parse(kDeclared, "declared");
  EXPECT_NO_THROW(check_declared(PrmDocument::parse(kText, "ok.prm"), declared));
  const PrmDocument typo = PrmDocument::parse("subsection Material\n  set Poison ratio = 0.3\nend\n", "typo.prm");
  try {
    check_declared(typo, declared);
    ADD_FAILURE() << "an unknown entry passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("Poisson ratio"), std::string::npos) << e.what();
  }
  const PrmDocument section = PrmDocument::parse("set X = 1\nsubsection Outptu\n  set Fields = false\nend\n", "s.prm");
  EXPECT_EQ(line_of_error([&] { check_declared(section, declared); }), 1);  // the first unknown name in the file
}

TEST(PrmDocument, NumbersAreWholeTokens) {
  EXPECT_EQ(parse_number(" 1.5e3 ").value(), 1500.0);
  EXPECT_FALSE(parse_number("1.5 mm"));
  EXPECT_FALSE(parse_number(""));
  EXPECT_FALSE(parse_number("nan"));
}

}  // namespace
}  // namespace dtwire

// Target column mapping: renaming and scaling a target column onto a simulated quantity, and
// the inverse used to write synthetic targets that read back through the same mapping.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dtwire/calibrate/column_map.hpp"

namespace dtwire::calibrate {
namespace {

// A curve like an FE run with an end rotation (force_N is the reaction along z, axial_force_N
// the generalised axial force; here they differ so that the test sees which one is read).
Curve fe_like() {
  Curve c;
  c.add_channel("displacement", *find_unit("mm"), {0.0, 0.1, 0.2});
  c.add_channel("force", *find_unit("N"), {0.0, 1.0, 2.0});
  c.add_channel("axial_force", *find_unit("kN"), {0.0, 0.5, 0.75});
  c.add_channel("rotation", *find_unit("rad"), {0.0, 0.01, 0.02});
  c.set_metadata("source", "test");
  return c;
}

std::string message_of(const Curve& curve, const std::vector<ColumnMapping>& mapping) {
  try {
    map_columns(curve, mapping);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(ColumnMap, RenamesReplacesAndScales) {
  const Curve mapped = map_columns(fe_like(), {{"force", "axial_force", 1.0}, {"rotation", "rotation", 2.0}});
  // force now reads axial_force (kept in its unit, kN), the old force_N column is gone.
  EXPECT_EQ(mapped.channel("force").unit.symbol, "kN");
  EXPECT_EQ(mapped.si("force"), (std::vector<double>{0.0, 500.0, 750.0}));
  EXPECT_EQ(mapped.si("rotation"), (std::vector<double>{0.0, 0.02, 0.04}));
  EXPECT_TRUE(mapped.has("axial_force"));  // unmapped columns are kept
  EXPECT_EQ(mapped.si("displacement"), fe_like().si("displacement"));
  EXPECT_EQ(mapped.metadata("source"), "test");
  EXPECT_NE(mapped.metadata("columns").find("force = axial_force_kN"), std::string::npos);
}

TEST(ColumnMap, MappingsReadTheOriginalColumns) {
  // A swap: each mapping reads the unmapped target, not the result of another mapping.
  const Curve mapped = map_columns(fe_like(), {{"force", "axial_force", 1.0}, {"axial_force", "force", 1.0}});
  EXPECT_EQ(mapped.si("force").back(), 750.0);
  EXPECT_EQ(mapped.si("axial_force").back(), 2.0);
}

TEST(ColumnMap, NoMappingIsTheIdentity) { EXPECT_EQ(map_columns(fe_like(), {}), fe_like()); }

TEST(ColumnMap, BadMappingsNameTheProblem) {
  const std::string missing = message_of(fe_like(), {{"moment", "moment", 1.0}});
  EXPECT_NE(missing.find("no column 'moment_<unit>'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("axial_force_kN"), std::string::npos) << missing;  // lists the columns
  EXPECT_NE(message_of(fe_like(), {{"force", "axial_force", 0.0}}).find("factor"), std::string::npos);
  EXPECT_NE(message_of(fe_like(), {{"force", "axial_force", std::nan("")}}).find("factor"), std::string::npos);
  EXPECT_NE(message_of(fe_like(), {{"force", "axial_force", 1.0}, {"force", "force", 1.0}}).find("mapped twice"),
            std::string::npos);
}

TEST(ColumnMap, InverseReadsBackExactly) {
  Curve simulated;
  simulated.add_channel("rotation", *find_unit("rad"), {0.0, 0.02, 0.04});
  simulated.add_channel("force", *find_unit("N"), {0.0, 10.0, 20.0});
  const std::vector<ColumnMapping> mapping{{"force", "axial_force", 1.0}, {"rotation", "rotation", 2.0}};
  const Curve written = unmap_columns(simulated, mapping);
  EXPECT_TRUE(written.has("axial_force"));
  EXPECT_FALSE(written.has("force"));
  EXPECT_EQ(written.si("rotation"), (std::vector<double>{0.0, 0.01, 0.02}));
  const Curve read = map_columns(written, mapping);
  EXPECT_EQ(read.si("force"), simulated.si("force"));
  EXPECT_EQ(read.si("rotation"), simulated.si("rotation"));
}

TEST(ColumnMap, InverseRefusesAmbiguousMappings) {
  Curve simulated;
  simulated.add_channel("force", *find_unit("N"), {0.0, 1.0, 2.0});
  simulated.add_channel("moment", *find_unit("Nm"), {0.0, 1.0, 2.0});
  EXPECT_THROW(unmap_columns(simulated, {{"force", "x", 1.0}, {"moment", "x", 1.0}}), std::invalid_argument);
  // force -> moment would collide with the simulated moment.
  EXPECT_THROW(unmap_columns(simulated, {{"force", "moment", 1.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::calibrate

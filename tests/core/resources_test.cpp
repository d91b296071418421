// The machine checks a command makes before it runs: byte sizes, and the warning for threads that
// would share their cores with other work.
#include <gtest/gtest.h>

#include "dtwire/core/error.hpp"
#include "dtwire/core/resources.hpp"

namespace dtwire {
namespace {

TEST(Resources, ByteSizesReadWithTheirUnitsAndBadOnesNameTheOption) {
  EXPECT_EQ(parse_byte_size("512M", "--max-memory"), 512ull << 20);
  EXPECT_EQ(parse_byte_size("1.5G", "--max-memory"), 3ull << 29);
  EXPECT_EQ(parse_byte_size("4096", "--max-memory"), 4096u);
  try {
    parse_byte_size("lots", "--max-memory");
    FAIL() << "accepted 'lots'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

TEST(Resources, ThreadsThatWouldShareBusyCoresAreWarnedOf) {
  EXPECT_EQ(oversubscription_warning(2, 0.1, 2), "");  // an idle machine
  EXPECT_EQ(oversubscription_warning(1, 7.0, 2), "");  // one thread waits for nobody
  EXPECT_EQ(oversubscription_warning(2, 2.4, 4), "");  // 4.4 of 4 cores: within the half-core margin
  const std::string busy = oversubscription_warning(2, 2.0, 2);  // the measured case: 2 busy jobs
  EXPECT_NE(busy.find("2 threads on 2 cores"), std::string::npos) << busy;
  EXPECT_NE(busy.find("--threads 1"), std::string::npos) << busy;
  EXPECT_NE(oversubscription_warning(8, 1.0, 8), "");
}

}  // namespace
}  // namespace dtwire

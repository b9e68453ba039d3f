#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/work_limit.h"

namespace knitforge {
namespace {

TEST(WorkLimit, RefusesAboveTheLimitWithEstimateAndRemedy) {
  WorkEstimate e{"the surface", 2.0e6, "stitches", 1e6, 2500.0, "raise the limit with --max-stitches N"};
  try {
    check_work(e);
    FAIL() << "no throw";
  } catch (const InvalidInput& x) {
    const std::string m = x.what();
    EXPECT_NE(m.find("about 2 million stitches"), std::string::npos) << m;
    EXPECT_NE(m.find("about 5 GB"), std::string::npos) << m;
    EXPECT_NE(m.find("limit of 1 million"), std::string::npos) << m;
    EXPECT_NE(m.find("--max-stitches"), std::string::npos) << m;
    EXPECT_LT(m.size(), 200u);
  }
  e.count = 1e6;
  EXPECT_NO_THROW(check_work(e));  // at the limit is fine
  e.count = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(check_work(e), InvalidInput);
  e.count = std::numeric_limits<double>::infinity();
  EXPECT_THROW(check_work(e), InvalidInput);
  e.count = 1;
  e.limit = 0;
  EXPECT_THROW(check_work(e), InvalidInput);
}

TEST(WorkLimit, ReadableNumbers) {
  EXPECT_EQ(readable_count(0), "0");
  EXPECT_EQ(readable_count(1234), "1,234");
  EXPECT_EQ(readable_count(999999), "999,999");
  EXPECT_EQ(readable_count(12.3e6), "12.3 million");
  EXPECT_EQ(readable_count(4.5e9), "4.5 billion");
  EXPECT_EQ(readable_count(1.7e308), "1.7e+308");  // never 309 digits
  EXPECT_EQ(readable_bytes(512), "512 bytes");
  EXPECT_EQ(readable_bytes(1.5e9), "1.5 GB");
}

}  // namespace
}  // namespace knitforge

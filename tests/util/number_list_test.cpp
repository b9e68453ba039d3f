#include "knitforge/util/number_list.h"

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(NumberList, ParsesCommaSeparatedNumbersAndNamesTheBadItem) {
  EXPECT_EQ(parse_number_list("1,2.5,-3e1", "--x"), (std::vector<double>{1.0, 2.5, -30.0}));
  EXPECT_TRUE(parse_number_list("", "--x").empty());
  try {
    parse_number_list("1,2x,3", "--bc '1,2x,3'");
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "--bc '1,2x,3': '2x' is not a number");
  }
  EXPECT_THROW(parse_number_list("1,,2", "--x"), InvalidInput);
}

}  // namespace
}  // namespace knitforge

#include "knitforge/util/counting_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

using namespace knitforge;

namespace {

struct Item {
  int a, b, id;
};

}  // namespace

TEST(CountingSort, TwoPassesGiveTheLexicographicOrderWithTiesInInputOrder) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> key(0, 9);
  std::vector<Item> items;
  for (int i = 0; i < 500; ++i) items.push_back({key(rng), key(rng), i});
  std::vector<Item> expected = items;
  std::sort(expected.begin(), expected.end(),
            [](const Item& x, const Item& y) { return std::tie(x.a, x.b, x.id) < std::tie(y.a, y.b, y.id); });
  counting_sort_by(items, 10, [](const Item& x) { return x.b; });
  counting_sort_by(items, 10, [](const Item& x) { return x.a; });
  ASSERT_EQ(items.size(), expected.size());
  for (size_t i = 0; i < items.size(); ++i) {
    EXPECT_EQ(items[i].id, expected[i].id) << i;
  }
}

TEST(CountingSort, EmptyAndSingleKeyInputs) {
  std::vector<Item> none;
  counting_sort_by(none, 4, [](const Item& x) { return x.a; });
  EXPECT_TRUE(none.empty());
  std::vector<Item> same{{0, 0, 2}, {0, 0, 0}, {0, 0, 1}};
  counting_sort_by(same, 1, [](const Item& x) { return x.a; });
  EXPECT_EQ(same[0].id, 2);  // stable: input order kept
  EXPECT_EQ(same[1].id, 0);
  EXPECT_EQ(same[2].id, 1);
}

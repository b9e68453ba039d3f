#include "knitforge/machine/hand_instructions.h"

#include <gtest/gtest.h>

#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"
#include "machine/machine_test_maps.h"

namespace knitforge {
namespace {

const MachineProfile& kh868() { return machine_profile("brother-kh868"); }

bool contains(const std::vector<std::string>& v, const std::string& needle) {
  for (const auto& s : v)
    if (s.find(needle) != std::string::npos) return true;
  return false;
}

TEST(HandInstructions, NeedleLabelsFollowTheMachine) {
  EXPECT_EQ(hand_needle_label(0, 200), "L100");
  EXPECT_EQ(hand_needle_label(99, 200), "L1");
  EXPECT_EQ(hand_needle_label(100, 200), "R1");
  EXPECT_EQ(hand_needle_label(199, 200), "R100");
}

TEST(HandInstructions, RectangleIsCentredAndAlternatesCarriageSides) {
  const auto h = hand_instructions(test::rectangle_map(), kh868());
  ASSERT_EQ(h.rows.size(), 4u);
  // 6 needles centred: L3..R3
  EXPECT_TRUE(contains(h.setup, "L3..R3 (6 needles)"));
  EXPECT_EQ(h.rows[0].knit, "Carriage left -> right: knit L3 to R3 (6 stitches)");
  EXPECT_EQ(h.rows[1].knit, "Carriage right -> left: knit R3 to L3 (6 stitches)");
  for (const auto& r : h.rows) EXPECT_TRUE(r.before.empty());
  EXPECT_EQ(h.hand_transfers, 0);
  EXPECT_EQ(h.stitches, 24);
  const std::string txt = hand_instructions_text(h);
  EXPECT_NE(txt.find("Row 1 (row counter 000 -> 001)"), std::string::npos);
  EXPECT_NE(txt.find("Row 4 (row counter 003 -> 004)"), std::string::npos);
}

TEST(HandInstructions, ShortRowsHoldReturnAndWrap) {
  const auto h = hand_instructions(test::short_row_wedge_map(), kh868());
  // row 1 knits columns 2..5 (L1..R3) right to left; L3, L2 go to hold
  EXPECT_TRUE(contains(h.rows[1].before, "Push L3..L2 to holding position E"));
  EXPECT_EQ(h.rows[1].knit, "Carriage right -> left: knit R3 to L1 (4 stitches)");
  EXPECT_TRUE(contains(h.rows[1].after, "wrap the yarn under held needle L2"));
  EXPECT_TRUE(h.rows[2].before.empty());  // still held, nothing to change
  EXPECT_TRUE(contains(h.rows[3].before, "Return L3..L2 from hold"));
  EXPECT_EQ(h.wraps, 1);
  EXPECT_EQ(h.held_needle_changes, 4);
  EXPECT_TRUE(contains(h.setup, "holding cam lever"));
  HandInstructionOptions o;
  o.wrap_turns = false;
  EXPECT_EQ(hand_instructions(test::short_row_wedge_map(), kh868(), o).wraps, 0);
}

TEST(HandInstructions, IncreaseAndDecreaseUseTheTransferTool) {
  const auto h = hand_instructions(test::short_column_map(), kh868());
  // increase before row 1 (0-based): stitches right of the new wale move right
  EXPECT_EQ(h.rows[1].before.size(), 2u);
  EXPECT_NE(h.rows[1].before[0].find("1 needle to the right"), std::string::npos);
  EXPECT_NE(h.rows[1].before[1].find("Increase: leave needle"), std::string::npos);
  // decrease before row 5: the decrease stitch onto its neighbour, one stitch moves back
  EXPECT_TRUE(contains(h.rows[5].before, "Decrease: move the stitch of"));
  EXPECT_TRUE(contains(h.rows[5].before, "back to non-working position A"));
  EXPECT_EQ(h.hand_transfers, 2 + 3);
}

TEST(HandInstructions, HtmlIsSelfContainedAndEscaped) {
  RandomMapOptions ro;
  ro.seed = 9;
  ro.rows = 24;
  ro.cols = 20;
  ro.short_row_ends = 6;
  ro.short_columns = 2;
  const auto h = hand_instructions(random_knitting_map(ro), kh868());
  const std::string html = hand_instructions_html(h);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
  EXPECT_EQ(html.find("href="), std::string::npos);
  EXPECT_NE(html.find("right -&gt; left"), std::string::npos);  // "->" escaped
  size_t rows = 0;
  for (size_t p = html.find("<tr><td>"); p != std::string::npos; p = html.find("<tr><td>", p + 1)) ++rows;
  EXPECT_EQ(rows, h.rows.size());
  EXPECT_EQ(hand_instructions_html(hand_instructions(random_knitting_map(ro), kh868())), html);
}

TEST(HandInstructions, TooWideForTheBedThrows) {
  KnittingMap wide(2, 201, CellType::Knit);
  EXPECT_THROW(hand_instructions(wide, kh868()), InvalidInput);
  KnittingMap fits(2, 200, CellType::Knit);
  const auto h = hand_instructions(fits, kh868());
  EXPECT_EQ(h.rows[0].knit, "Carriage left -> right: knit L100 to R100 (200 stitches)");
}

}  // namespace
}  // namespace knitforge

namespace knitforge {
namespace {

// Three stitches end at the carriage side of course 1: two are cast off with
// the latch tool (the knitout writer's bind-off chain), the third is knitted
// onto its neighbour.
TEST(HandInstructions, StitchesEndingTogetherAtTheEdgeAreCastOff) {
  const KnittingMap map = test::parse_map({"KKKKK___", "KKKKK___", "KKKKKKKK", "KKKKKKKK"});
  const NeedleLayout L = plan_needle_layout(map);
  ASSERT_EQ(L.chains.size(), 1u);
  EXPECT_EQ(L.chains[0].row, 1);
  EXPECT_EQ(L.chains[0].cols, (std::vector<int>{7, 6}));
  EXPECT_EQ(L.chains[0].onto_col, 5);
  const auto h = hand_instructions(map, machine_profile("brother-kh868"));
  ASSERT_EQ(h.rows.size(), 4u);
  ASSERT_FALSE(h.rows[1].before.empty());
  const std::string& cast = h.rows[1].before.back();
  EXPECT_NE(cast.find("At the carriage side, cast off the 2 stitches"), std::string::npos) << cast;
  // the carriage knits the rest of the row: 6 of its 8 stitches
  EXPECT_NE(h.rows[1].knit.find("(6 stitches)"), std::string::npos) << h.rows[1].knit;
}

}  // namespace
}  // namespace knitforge

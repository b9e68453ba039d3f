#include "knitforge/machine/knitout_parse.h"

#include <gtest/gtest.h>

#include <string>

#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

int count_errors(const KnitoutFile& f) {
  int n = 0;
  for (const auto& d : f.diagnostics) n += d.severity == Severity::Error;
  return n;
}

const KnitoutDiagnostic* first_error(const KnitoutFile& f) {
  for (const auto& d : f.diagnostics) {
    if (d.severity == Severity::Error) return &d;
  }
  return nullptr;
}

}  // namespace

TEST(KnitoutParse, ParsesAllOperations) {
  const std::string text =
      ";!knitout-2\n"
      ";;Machine: SWG091N2\n"
      ";;Gauge: 15\n"
      ";;Carriers: 1 2 3 A\n"
      ";;Position: Keep\n"
      "; a comment line\n"
      "inhook 1 2\n"                     // 7
      "tuck - f-3 1 2 ; trailing\n"      // 8
      "knit + b12 A\n"                   // 9
      "split + f4 bs4 3\n"               // 10
      "miss - fs7 1\n"                   // 11
      "xfer b-2 f0\n"                    // 12
      "drop f5\n"                        // 13
      "amiss b1\n"                       // 14
      "rack -1.25\n"                     // 15
      "stitch 30 .5\n"                   // 16
      "pause\n"                          // 17
      "x-presser-mode on\n"              // 18
      "releasehook 1 2\n"                // 19
      "knit + f1\n"                      // 20 (no carriers: drop)
      "tuck + f1\n"                      // 21 (no carriers: amiss)
      "split + f1 b1\n"                  // 22 (no carriers: xfer)
      "out 3\n"                          // 23
      "outhook 1 2\n";                   // 24
  const KnitoutFile f = parse_knitout(text);
  EXPECT_EQ(count_errors(f), 0) << (first_error(f) ? first_error(f)->message : "");
  EXPECT_EQ(f.version, 2);
  ASSERT_EQ(f.carrier_names.size(), 4u);
  EXPECT_EQ(f.carrier_names[3], "A");
  ASSERT_NE(f.header("Gauge"), nullptr);
  EXPECT_EQ(*f.header("Gauge"), "15");
  EXPECT_EQ(f.header("Width"), nullptr);

  std::vector<KnitoutInstruction> ops;
  for (const auto& i : f.instructions) {
    if (i.op != KnitoutOp::Comment) ops.push_back(i);
  }
  ASSERT_EQ(ops.size(), 18u);
  EXPECT_EQ(ops[0].op, KnitoutOp::Inhook);
  EXPECT_EQ(ops[0].carriers, (std::vector<int>{0, 1}));
  EXPECT_EQ(ops[1].op, KnitoutOp::Tuck);
  EXPECT_EQ(ops[1].line, 8);
  EXPECT_EQ(ops[1].direction, -1);
  EXPECT_EQ(ops[1].needle, (Needle{Bed::Front, -3}));
  EXPECT_EQ(ops[1].comment, " trailing");
  EXPECT_EQ(ops[2].needle, (Needle{Bed::Back, 12}));
  EXPECT_EQ(ops[2].carriers, (std::vector<int>{3}));
  EXPECT_EQ(ops[3].op, KnitoutOp::Split);
  EXPECT_EQ(ops[3].needle2, (Needle{Bed::BackSlider, 4}));
  EXPECT_EQ(ops[4].op, KnitoutOp::Miss);
  EXPECT_EQ(ops[4].needle, (Needle{Bed::FrontSlider, 7}));
  EXPECT_EQ(ops[5].op, KnitoutOp::Xfer);
  EXPECT_EQ(ops[5].needle, (Needle{Bed::Back, -2}));
  EXPECT_EQ(ops[6].op, KnitoutOp::Drop);
  EXPECT_EQ(ops[7].op, KnitoutOp::Amiss);
  EXPECT_EQ(ops[8].op, KnitoutOp::Rack);
  EXPECT_DOUBLE_EQ(ops[8].value, -1.25);
  EXPECT_EQ(ops[9].op, KnitoutOp::Stitch);
  EXPECT_DOUBLE_EQ(ops[9].value, 30.0);
  EXPECT_DOUBLE_EQ(ops[9].value2, 0.5);
  EXPECT_EQ(ops[10].op, KnitoutOp::Pause);
  EXPECT_EQ(ops[11].op, KnitoutOp::Extension);
  EXPECT_EQ(ops[11].extension, "x-presser-mode");
  EXPECT_EQ(ops[12].op, KnitoutOp::Releasehook);
  EXPECT_EQ(ops[13].op, KnitoutOp::Drop);
  EXPECT_EQ(ops[14].op, KnitoutOp::Amiss);
  EXPECT_EQ(ops[15].op, KnitoutOp::Xfer);
  EXPECT_EQ(ops[16].op, KnitoutOp::Out);
  EXPECT_EQ(ops[17].op, KnitoutOp::Outhook);
  // The extension keeps its arguments; the parser says nothing about it (the
  // simulator judges it against the machine).
  EXPECT_EQ(ops[11].args, (std::vector<std::string>{"on"}));
  EXPECT_TRUE(f.diagnostics.empty());
  EXPECT_EQ(to_string(Needle{Bed::BackSlider, -4}), "bs-4");
}

TEST(KnitoutParse, MagicLineMustBeExact) {
  const KnitoutFile a = parse_knitout(";knitout-2\n;;Carriers: 1\n");
  ASSERT_NE(first_error(a), nullptr);
  EXPECT_EQ(first_error(a)->line, 1);
  EXPECT_EQ(first_error(a)->rule, KnitoutRule::Syntax);
  const KnitoutFile b = parse_knitout("; comment first\n;!knitout-2\n;;Carriers: 1\n");
  ASSERT_NE(first_error(b), nullptr);
  EXPECT_EQ(first_error(b)->line, 1);
  const KnitoutFile c = parse_knitout(";!knitout-2x\n;;Carriers: 1\n");
  ASSERT_NE(first_error(c), nullptr);
  EXPECT_EQ(first_error(c)->line, 1);
  const KnitoutFile ok = parse_knitout(";!knitout-2\n;;Carriers: 1\n");
  EXPECT_EQ(count_errors(ok), 0);
}

TEST(KnitoutParse, MissingCarriersHeaderIsAnError) {
  const KnitoutFile f = parse_knitout(";!knitout-2\n;;Machine: X\nin 1\n");
  ASSERT_NE(first_error(f), nullptr);
  EXPECT_EQ(first_error(f)->rule, KnitoutRule::Header);
  EXPECT_EQ(first_error(f)->line, 3);
}

TEST(KnitoutParse, SyntaxErrorsNameTheLine) {
  struct Case {
    const char* op;
    KnitoutRule rule;
  };
  const Case cases[] = {
      {"knit + g5 1", KnitoutRule::Syntax},        {"knit * f5 1", KnitoutRule::Syntax},
      {"knit + f5 7", KnitoutRule::UndeclaredCarrier}, {"knit + f5 1 1", KnitoutRule::Syntax},
      {"frobnicate f1", KnitoutRule::Syntax},      {"rack x", KnitoutRule::Syntax},
      {"rack 1 2", KnitoutRule::Syntax},           {"xfer f1", KnitoutRule::Syntax},
      {"miss + f1", KnitoutRule::Syntax},          {"in", KnitoutRule::Syntax},
      {"pause now", KnitoutRule::Syntax},          {"drop f1 f2", KnitoutRule::Syntax},
      {"knit + f1.5 1", KnitoutRule::Syntax},      {"stitch 1", KnitoutRule::Syntax},
  };
  for (const Case& c : cases) {
    const std::string text = std::string(";!knitout-2\n;;Carriers: 1 2\nin 1\n") + c.op + "\nout 1\n";
    const KnitoutFile f = parse_knitout(text);
    ASSERT_EQ(count_errors(f), 1) << c.op;
    EXPECT_EQ(first_error(f)->line, 4) << c.op;
    EXPECT_EQ(first_error(f)->rule, c.rule) << c.op;
  }
}

TEST(KnitoutParse, HeaderValuesAreChecked) {
  const KnitoutFile f = parse_knitout(";!knitout-2\n;;Carriers: 1\n;;Position: Middle\n;;Gauge: -3\n;;Foo: bar\n");
  int errors = 0, warnings = 0;
  for (const auto& d : f.diagnostics) {
    if (d.severity == Severity::Error) {
      ++errors;
      EXPECT_TRUE(d.line == 3 || d.line == 4);
    } else {
      ++warnings;
      EXPECT_EQ(d.line, 5);
    }
  }
  EXPECT_EQ(errors, 2);
  EXPECT_EQ(warnings, 1);
}

TEST(KnitoutParse, HeaderAfterFirstOperationIsOnlyAComment) {
  const KnitoutFile f = parse_knitout(";!knitout-2\n;;Carriers: 1\nin 1\n;;Gauge: 7\n");
  EXPECT_EQ(f.header("Gauge"), nullptr);
  EXPECT_EQ(count_errors(f), 0);
}

TEST(KnitoutParse, CrLfGivesOneWarning) {
  const KnitoutFile f = parse_knitout(";!knitout-2\r\n;;Carriers: 1\r\nin 1\r\n");
  EXPECT_EQ(count_errors(f), 0);
  ASSERT_EQ(f.diagnostics.size(), 1u);
  EXPECT_EQ(f.diagnostics[0].severity, Severity::Warning);
  ASSERT_EQ(f.carrier_names.size(), 1u);
  EXPECT_EQ(f.carrier_names[0], "1");
}

TEST(KnitoutParse, ReadMissingFileThrows) {
  EXPECT_THROW(read_knitout("/nonexistent/dir/x.k"), IOError);
}

TEST(KnitoutParse, OtherVersionsAreReadWithAWarning) {
  // The spec: readers accept any version and warn about later ones.
  for (const char* magic : {";!knitout-3", ";!knitout-1", ";!knitout-12"}) {
    const KnitoutFile f = parse_knitout(std::string(magic) + "\n;;Carriers: 1\nin 1\nknit + f1 1\nout 1\n");
    EXPECT_EQ(count_errors(f), 0) << magic;
    ASSERT_EQ(f.diagnostics.size(), 1u) << magic;
    EXPECT_EQ(f.diagnostics[0].check, KnitoutCheck::Version);
    EXPECT_EQ(f.diagnostics[0].severity, Severity::Warning);
    EXPECT_EQ(f.diagnostics[0].line, 1);
    EXPECT_EQ(f.instructions.size(), 3u);
  }
  EXPECT_EQ(parse_knitout(";!knitout-3\n;;Carriers: 1\n").version, 3);
  // not a version number at all
  const KnitoutFile bad = parse_knitout(";!knitout-two\n;;Carriers: 1\n");
  ASSERT_NE(first_error(bad), nullptr);
  EXPECT_EQ(first_error(bad)->check, KnitoutCheck::MagicLine);
}

TEST(KnitoutParse, LoneCrLineEndingsAreReadAsLines) {
  const KnitoutFile f = parse_knitout(";!knitout-2\r;;Carriers: 1 2\rin 1\rknit + f1 1\rout 1\r");
  EXPECT_EQ(count_errors(f), 0);
  ASSERT_EQ(f.diagnostics.size(), 1u);
  EXPECT_EQ(f.diagnostics[0].check, KnitoutCheck::LineEndings);
  EXPECT_EQ(f.carrier_names.size(), 2u);
  EXPECT_EQ(f.num_lines, 5);
  ASSERT_EQ(f.instructions.size(), 3u);
  EXPECT_EQ(f.instructions[1].line, 4);
}

TEST(KnitoutParse, LongCarrierHeaderIsLinear) {
  // 20,000 names with one repeated: one error, found without comparing pairs.
  std::string names;
  for (int i = 0; i < 20000; ++i) names += " c" + std::to_string(i);
  names += " c7";
  const KnitoutFile f = parse_knitout(";!knitout-2\n;;Carriers:" + names + "\n");
  EXPECT_EQ(count_errors(f), 1);
  EXPECT_EQ(f.carrier_names.size(), 20000u);
}

TEST(KnitoutParse, MessagesQuoteInputReadably) {
  const KnitoutFile f = parse_knitout(";!knitout-2\n;;Carriers: 1\nfrob\x01nicate f1\n");
  ASSERT_NE(first_error(f), nullptr);
  EXPECT_NE(first_error(f)->message.find("frob\\x01nicate"), std::string::npos) << first_error(f)->message;
  const KnitoutFile g = parse_knitout(";!knitout-2\n;;Carriers: 1\nknit + f1 " + std::string(5000, 'x') + "\n");
  ASSERT_NE(first_error(g), nullptr);
  EXPECT_LT(first_error(g)->message.size(), 250u) << first_error(g)->message;
}

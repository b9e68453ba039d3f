#include "knitforge/machine/knitout_simulate.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/machine_profile.h"

using namespace knitforge;

namespace {

const std::filesystem::path kData = std::filesystem::path(KNITFORGE_TESTS_DIR) / "machine" / "data";

const MachineProfile& shima() { return machine_profile("shima-swg091n2"); }

// A program: magic line, ;;Carriers: 1..10, then `body` from line 3 on.
KnitoutSimulation run(const std::string& body, const MachineProfile& p = shima()) {
  return simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7 8 9 10\n" + body), p);
}

std::string dump(const KnitoutSimulation& s) { return s.text(); }

// The only error of `s` must be of `rule` at `line`.
void expect_single_error(const KnitoutSimulation& s, KnitoutRule rule, int line) {
  ASSERT_EQ(s.errors, 1) << dump(s);
  for (const auto& d : s.diagnostics) {
    if (d.severity == Severity::Error) {
      EXPECT_EQ(d.rule, rule) << d.message;
      EXPECT_EQ(d.line, line) << d.message;
    }
  }
}

// Cast on f1..f4 with carrier 1 and knit one course; lines 3..14; hook released.
const std::string kStart =
    "inhook 1\n"       // 3
    "tuck - f4 1\n"    // 4
    "tuck - f2 1\n"    // 5
    "tuck + f1 1\n"    // 6
    "tuck + f3 1\n"    // 7
    "knit - f4 1\n"    // 8
    "knit - f3 1\n"    // 9
    "knit - f2 1\n"    // 10
    "knit - f1 1\n"    // 11
    "releasehook 1\n"  // 12
    "knit + f1 1\n"    // 13
    "knit + f2 1\n";   // 14
// Ends the program cleanly (loops stay by intention).
const std::string kEnd = "outhook 1\n; leave-loops: test fragment\n";

}  // namespace

TEST(KnitoutSimulate, FragmentIsValid) {
  const KnitoutSimulation s = run(kStart + kEnd);
  EXPECT_TRUE(s.ok()) << dump(s);
  EXPECT_EQ(s.warnings, 0) << dump(s);
  EXPECT_EQ(s.stats.tucks, 4);
  EXPECT_EQ(s.stats.knits, 6);
}

TEST(KnitoutSimulate, HandWrittenProgramsAreAccepted) {
  for (const char* name : {"jersey_alt_tuck.k", "rib1x1.k", "short_row_wedge.k", "decrease.k"}) {
    const KnitoutSimulation s = simulate_knitout(read_knitout((kData / name).string()), shima());
    EXPECT_TRUE(s.ok()) << name << "\n" << dump(s);
    EXPECT_EQ(s.warnings, 0) << name << "\n" << dump(s);
  }
}

TEST(KnitoutSimulate, StatisticsOfJersey) {
  const KnitoutSimulation s = simulate_knitout(read_knitout((kData / "jersey_alt_tuck.k").string()), shima());
  ASSERT_TRUE(s.ok()) << dump(s);
  // Cast-on: 2 tuck passes + 1 knit pass; 6 courses; bind-off 9 knits + 3 tail
  // knits, each its own pass; 9 x 2 transfer passes; 1 drop pass.
  EXPECT_EQ(s.stats.knit_passes, 3 + 6 + 9 + 3);
  EXPECT_EQ(s.stats.transfer_passes, 18);
  EXPECT_EQ(s.stats.carriage_passes, 21 + 18 + 1);
  EXPECT_EQ(s.stats.racks, 18);
  EXPECT_EQ(s.stats.knits, 10 + 60 + 9 + 3);
  EXPECT_EQ(s.stats.tucks, 10);
  EXPECT_EQ(s.stats.transfers, 18);
  EXPECT_EQ(s.stats.min_needle, 1);
  EXPECT_EQ(s.stats.max_needle, 10);
  // Yarn: 92 loops of 4.2 pitches plus the tuck cast-on floats (9 gaps of 2
  // needles, one extra pitch each... first leftward pass 4 gaps, rightward pass
  // from f2 to f1 is 1, then 4 gaps of 2).
  const double pitch = 25.4 / 15.0;
  EXPECT_NEAR(s.stats.yarn_mm[2], (92 * 4.2 + 8) * pitch, 1e-9);
  EXPECT_GT(s.stats.time_s, 0.0);
  // Every other carrier used no yarn.
  EXPECT_EQ(s.stats.yarn_mm[0], 0.0);
}

TEST(KnitoutSimulate, RejectsCarrierNotInHeader) {
  // Parser rule, surfaced by the simulator with its line.
  const KnitoutSimulation s = run(kStart + "knit + f3 11\n" + kEnd);
  expect_single_error(s, KnitoutRule::UndeclaredCarrier, 15);
}

TEST(KnitoutSimulate, RejectsCarrierTheMachineLacks) {
  const KnitoutSimulation s = simulate_knitout(
      parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7\n" + kStart + kEnd), machine_profile("kniterate"));
  // Kniterate: carriers 1..6 and no hook: line 2 (carrier 7) and the hook operations.
  bool header = false;
  for (const auto& d : s.diagnostics) {
    if (d.rule == KnitoutRule::UndeclaredCarrier) {
      header = true;
      EXPECT_EQ(d.line, 2);
    }
  }
  EXPECT_TRUE(header) << dump(s);
  EXPECT_EQ(s.error_counts[static_cast<int>(KnitoutRule::Hook)], 3) << dump(s);  // inhook, releasehook, outhook
}

TEST(KnitoutSimulate, RejectsInactiveCarrier) {
  expect_single_error(run(kStart + "knit + f3 2\n" + kEnd), KnitoutRule::InactiveCarrier, 15);
}

TEST(KnitoutSimulate, RejectsCarrierBroughtInTwice) {
  expect_single_error(run(kStart + "in 1\n" + kEnd), KnitoutRule::InactiveCarrier, 15);
}

TEST(KnitoutSimulate, RejectsOutOfCarrierNotIn) {
  expect_single_error(run(kStart + "out 3\n" + kEnd), KnitoutRule::InactiveCarrier, 15);
}

TEST(KnitoutSimulate, RejectsFirstUseWithOtherCarrierSet) {
  const KnitoutSimulation s = run(kStart + "in 2 3\nknit - f4 2\nknit + f4 2 3\nout 2 3\n" + kEnd);
  expect_single_error(s, KnitoutRule::InactiveCarrier, 16);
}

TEST(KnitoutSimulate, RejectsCarrierLeftIn) {
  const KnitoutSimulation s = run(kStart + "; leave-loops: fragment\n");
  expect_single_error(s, KnitoutRule::CarrierLeftIn, 15);
}

TEST(KnitoutSimulate, RejectsRackingBeyondMachine) {
  expect_single_error(run(kStart + "rack 5\nrack 0\n" + kEnd), KnitoutRule::Racking, 15);
  expect_single_error(run(kStart + "rack 4.25\nrack 0\n" + kEnd), KnitoutRule::Racking, 15);
  EXPECT_TRUE(run(kStart + "rack -4\nrack 0.25\nrack -0.75\nrack 0\n" + kEnd).ok());
}

TEST(KnitoutSimulate, RejectsFractionTheMachineCannotRack) {
  expect_single_error(run(kStart + "rack 0.5\nrack 0\n" + kEnd), KnitoutRule::Racking, 15);
}

TEST(KnitoutSimulate, RejectsMisalignedTransfer) {
  expect_single_error(run(kStart + "xfer f1 b2\n" + kEnd), KnitoutRule::Misaligned, 15);
  expect_single_error(run(kStart + "rack 1\nxfer f1 b1\nrack 0\n" + kEnd), KnitoutRule::Misaligned, 16);
  expect_single_error(run(kStart + "rack 0.25\nxfer f1 b1\nrack 0\n" + kEnd), KnitoutRule::Misaligned, 16);
  // Aligned at racking 1: back n faces front n + 1.
  const KnitoutSimulation ok = run(kStart + "xfer f1 b1\nrack 1\nxfer b1 f2\nrack 0\n" + kEnd);
  EXPECT_TRUE(ok.ok()) << dump(ok);
}

TEST(KnitoutSimulate, RejectsSameBedTransferAndSliderKnit) {
  expect_single_error(run(kStart + "xfer f1 f2\n" + kEnd), KnitoutRule::Slider, 15);
  expect_single_error(run(kStart + "knit + fs3 1\n" + kEnd), KnitoutRule::Slider, 15);
  // Loops can park on a slider and come back.
  const KnitoutSimulation ok = run(kStart + "xfer f1 bs1\nxfer bs1 f1\n" + kEnd);
  EXPECT_TRUE(ok.ok()) << dump(ok);
}

TEST(KnitoutSimulate, RejectsTooManyLoopsOnANeedle) {
  const KnitoutSimulation s =
      run(kStart + "tuck - f2 1\ntuck + f2 1\ntuck - f2 1\ntuck + f2 1\n" + kEnd);  // 1 + 4 loops
  expect_single_error(s, KnitoutRule::LoopsPerNeedle, 18);
}

// The only warning of `s` must be of `rule` at `line`, and no error.
void expect_single_warning(const KnitoutSimulation& s, KnitoutRule rule, int line) {
  ASSERT_EQ(s.errors, 0) << dump(s);
  ASSERT_EQ(s.warnings, 1) << dump(s);
  for (const auto& d : s.diagnostics) {
    EXPECT_EQ(d.rule, rule) << d.message;
    EXPECT_EQ(d.line, line) << d.message;
  }
}

KnitoutSimulation run_strict(const std::string& body, const std::string& strict) {
  SimulateOptions o;
  o.strict = parse_strict_rules(strict);
  return simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7 8 9 10\n" + body), shima(), o);
}

TEST(KnitoutSimulate, LongFloatIsAWarningUnlessStrict) {
  // No translator refuses a float; the fabric snags (the VKM warns).
  expect_single_warning(run(kStart + "tuck + f30 1\n" + kEnd), KnitoutRule::Float, 15);
  EXPECT_EQ(run(kStart + "tuck + f22 1\n" + kEnd).warnings, 0);  // 20 needles from f2
  expect_single_error(run_strict(kStart + "tuck + f30 1\n" + kEnd, "float"), KnitoutRule::Float, 15);
  // another category strict leaves it a warning
  EXPECT_TRUE(run_strict(kStart + "tuck + f30 1\n" + kEnd, "drop,loops-left").ok());
}

TEST(KnitoutSimulate, RejectsSecondInhookWhileHookHolds) {
  const KnitoutSimulation s = run("inhook 1\ninhook 2\ntuck - f2 1\ntuck - f1 2\nreleasehook 1\nouthook 1 2\n"
                                  "; leave-loops\n");
  ASSERT_GE(s.errors, 1) << dump(s);
  EXPECT_EQ(s.diagnostics.front().rule, KnitoutRule::Hook);
  EXPECT_EQ(s.diagnostics.front().line, 4);
}

TEST(KnitoutSimulate, WarnsOfTransferBeforeReleasehook) {
  // The translators do not check it; knitforge's own programs never do it.
  const std::string body =
      "inhook 1\ntuck - f2 1\ntuck + f1 1\nknit - f2 1\nknit - f1 1\n"
      "xfer f1 b1\n"  // 8
      "releasehook 1\nouthook 1\n; leave-loops\n";
  expect_single_warning(run(body), KnitoutRule::Hook, 8);
  expect_single_error(run_strict(body, "hook"), KnitoutRule::Hook, 8);
}

TEST(KnitoutSimulate, RejectsOutWhileHookHolds) {
  expect_single_error(run("inhook 1\ntuck - f2 1\nout 1\n; leave-loops\n"), KnitoutRule::Hook, 5);
}

TEST(KnitoutSimulate, RejectsReleasehookBeforeAnyStitch) {
  expect_single_error(run("inhook 1\nreleasehook 1\ntuck - f2 1\nouthook 1\n; leave-loops\n"), KnitoutRule::Hook,
                      4);
}

TEST(KnitoutSimulate, RejectsReleasehookOfOtherCarrier) {
  expect_single_error(run("inhook 1\ntuck - f2 1\nreleasehook 2\nreleasehook 1\nouthook 1\n; leave-loops\n"),
                      KnitoutRule::Hook, 5);
}

TEST(KnitoutSimulate, RejectsHookLeftHolding) {
  const KnitoutSimulation s = run("inhook 1\ntuck - f2 1\n; leave-loops\n");
  ASSERT_EQ(s.errors, 2) << dump(s);  // carrier left in, hook still holding
  EXPECT_EQ(s.error_counts[static_cast<int>(KnitoutRule::Hook)], 1);
  EXPECT_EQ(s.error_counts[static_cast<int>(KnitoutRule::CarrierLeftIn)], 1);
}

TEST(KnitoutSimulate, WarnsCarrierStartingTowardsItsParkingSide) {
  // Shima-like: carriers wait at the right, so the first pass goes '-'.
  const KnitoutSimulation s = run("inhook 1\ntuck + f2 1\nreleasehook 1\nouthook 1\n; leave-loops\n");
  expect_single_warning(s, KnitoutRule::CarrierDirection, 4);
  EXPECT_EQ(s.diagnostics[0].check, KnitoutCheck::FirstPassDirection);
}

TEST(KnitoutSimulate, KniterateCarriersMustStartRightwards) {
  // The Kniterate translator parks carriers left of needle 0: a first pass to
  // the left writes corrupt k-code ("properly ordered carrier stops").
  const std::string head = ";!knitout-2\n;;Carriers: 1 2 3 4 5 6\n";
  const auto& kn = machine_profile("kniterate");
  const KnitoutSimulation bad =
      simulate_knitout(parse_knitout(head + "in 1\ntuck - f4 1\ntuck - f2 1\nout 1\n; leave-loops\n"), kn);
  expect_single_error(bad, KnitoutRule::CarrierDirection, 4);
  // One 'miss +' first fixes it, as it fixes the translator's output.
  const KnitoutSimulation good = simulate_knitout(
      parse_knitout(head + "in 1\nmiss + f1 1\ntuck - f4 1\ntuck - f2 1\nout 1\n; leave-loops\n"), kn);
  EXPECT_TRUE(good.ok()) << dump(good);
  EXPECT_EQ(good.warnings, 0) << dump(good);
  // The generic profile has no parking side.
  const KnitoutSimulation gen = simulate_knitout(
      parse_knitout(head + "in 1\ntuck - f4 1\ntuck - f2 1\nout 1\n; leave-loops\n"), machine_profile("generic"));
  EXPECT_TRUE(gen.ok()) << dump(gen);
  EXPECT_EQ(gen.warnings, 0) << dump(gen);
}

TEST(KnitoutSimulate, DropOfLiveFabricIsAWarningThatTheWaleRuns) {
  const KnitoutSimulation s = run(kStart + "drop f1\n" + kEnd);
  expect_single_warning(s, KnitoutRule::Drop, 15);
  EXPECT_EQ(s.diagnostics[0].check, KnitoutCheck::Run);
  ASSERT_GE(s.diagnostics[0].loop, 0);
  EXPECT_EQ(s.graph.loops[static_cast<size_t>(s.diagnostics[0].loop)].line, 13);  // the dropped knit loop
  expect_single_error(run_strict(kStart + "drop f1\n" + kEnd, "drop"), KnitoutRule::Drop, 15);
  // Dropping a tuck loop (nothing pulled through, nothing below) is fine.
  const KnitoutSimulation ok = run(kStart + "tuck - f6 1\ndrop f6\n" + kEnd);
  EXPECT_EQ(ok.warnings + ok.errors, 0) << dump(ok);
  // ... and so is dropping loops knitted after a waste (or bind-off) marker,
  // but not fabric loops knitted before it.
  const KnitoutSimulation waste = run(kStart + "; waste yarn\nknit - f2 1\ndrop f2\n" + kEnd);
  EXPECT_EQ(waste.warnings + waste.errors, 0) << dump(waste);
  expect_single_warning(run(kStart + "; waste yarn\ndrop f1\n" + kEnd), KnitoutRule::Drop, 16);
}

TEST(KnitoutSimulate, WarnsKnitOnEmptyNeedle) {
  const KnitoutSimulation s = run(kStart + "knit + f5 1\n" + kEnd);
  EXPECT_TRUE(s.ok()) << dump(s);
  ASSERT_EQ(s.warnings, 1) << dump(s);
  EXPECT_EQ(s.diagnostics[0].rule, KnitoutRule::EmptyNeedleKnit);
  EXPECT_EQ(s.diagnostics[0].line, 15);
}

TEST(KnitoutSimulate, LoopsLeftAreAWarningUnlessStated) {
  const KnitoutSimulation s = run(kStart + "outhook 1\n");
  expect_single_warning(s, KnitoutRule::LoopsLeft, 15);
  int live = 0;
  for (const auto& l : s.graph.loops) live += l.live_at_end;
  EXPECT_EQ(live, 4);
  EXPECT_EQ(run(kStart + kEnd).warnings, 0);  // '; leave-loops' states it
  expect_single_error(run_strict(kStart + "outhook 1\n", "all"), KnitoutRule::LoopsLeft, 15);
}

TEST(KnitoutSimulate, RejectsNeedlesBeyondTheBed) {
  const std::string keep = ";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7 8 9 10\n;;Position: Keep\n";
  const KnitoutSimulation s = simulate_knitout(
      parse_knitout(keep + "in 1\ntuck - f541 1\ntuck + f540 1\nout 1\n; leave-loops\n"), shima());
  expect_single_error(s, KnitoutRule::Width, 5);
  // Without Keep, only the span counts: 541 needles do not fit on 540.
  std::string body = "in 1\n";
  for (int n = 0; n <= 540; n += 10) body += "tuck + f" + std::to_string(n) + " 1\n";
  const KnitoutSimulation wide = run(body + "out 1\n; leave-loops\n");
  expect_single_error(wide, KnitoutRule::Width, 3 + 55);
}

TEST(KnitoutSimulate, RejectsAbsurdNeedleNumbersWithoutAllocating) {
  expect_single_error(run(kStart + "tuck + f2000000000 1\n" + kEnd), KnitoutRule::Width, 15);
}

TEST(KnitoutSimulate, ExtensionsAreCheckedAgainstTheMachinesSoftware) {
  // Known to the SWG translator, with a valid value: nothing to say.
  EXPECT_EQ(run(kStart + "x-speed-number 10\nx-presser-mode auto\n" + kEnd).warnings, 0);
  // Unknown there: ignored with a warning.
  expect_single_warning(run(kStart + "x-roller-advance 300\n" + kEnd), KnitoutRule::Extension, 15);
  // Known with a value the translator refuses.
  expect_single_error(run(kStart + "x-presser-mode sideways\n" + kEnd), KnitoutRule::Extension, 15);
  expect_single_error(run(kStart + "x-stitch-number -3\n" + kEnd), KnitoutRule::Extension, 15);
  // The Kniterate reads stitch numbers 0-9 / A-Z and its roller extensions.
  const auto& kn = machine_profile("kniterate");
  const std::string head = ";!knitout-2\n;;Carriers: 1 2 3 4 5 6\n";
  const std::string tail = "in 1\ntuck + f2 1\nout 1\n; leave-loops\n";
  const KnitoutSimulation k1 =
      simulate_knitout(parse_knitout(head + "x-stitch-number A\nx-roller-advance 400\n" + tail), kn);
  EXPECT_EQ(k1.errors + k1.warnings, 0) << dump(k1);
  const KnitoutSimulation k2 = simulate_knitout(parse_knitout(head + "x-stitch-number 12\n" + tail), kn);
  expect_single_error(k2, KnitoutRule::Extension, 3);
}

TEST(KnitoutSimulate, SyntaxErrorsMakeTheProgramInvalid) {
  expect_single_error(run(kStart + "knit + q3 1\n" + kEnd), KnitoutRule::Syntax, 15);
}

TEST(KnitoutSimulate, KnitGraphOfATinyProgram) {
  // Two needles, a tuck cast-on, two courses, a split and a transfer.
  const KnitoutSimulation s = run(
      "in 1\n"             // 3
      "tuck - f2 1\n"      // 4  loop 0
      "tuck + f1 1\n"      // 5  loop 1
      "knit - f2 1\n"      // 6  loop 2 through 0
      "knit - f1 1\n"      // 7  loop 3 through 1
      "tuck + f1 1\n"      // 8  loop 4 stacked on f1
      "knit + f1 1\n"      // 9  loop 5 through 3 and 4
      "split + f2 b2 1\n"  // 10 loop 6 through 2, which moves to b2
      "xfer b2 f2\n"       // 11 loop 2 back onto f2 (now holding 6 and 2)
      "knit - f2 1\n"      // 12 loop 7 through 6 and 2
      "out 1\n; leave-loops\n");
  ASSERT_TRUE(s.ok()) << dump(s);
  const KnitGraph& g = s.graph;
  ASSERT_EQ(g.num_loops(), 8);
  auto parents = [&](int i) { return std::vector<int>(g.parents_of(i).begin(), g.parents_of(i).end()); };
  EXPECT_EQ(parents(2), (std::vector<int>{0}));
  EXPECT_EQ(parents(3), (std::vector<int>{1}));
  EXPECT_EQ(parents(5), (std::vector<int>{3, 4}));
  EXPECT_EQ(parents(6), (std::vector<int>{2}));
  EXPECT_EQ(parents(7), (std::vector<int>{6, 2}));
  EXPECT_EQ(g.loops[2].child, 7);  // the split moved it; the last knit took it
  EXPECT_EQ(g.loops[4].child, 5);
  EXPECT_EQ(g.loops[4].kind, LoopKind::Tuck);
  EXPECT_FALSE(g.loops[4].on_empty_needle);
  EXPECT_TRUE(g.loops[0].on_empty_needle);
  EXPECT_EQ(g.loops[6].kind, LoopKind::Split);
  EXPECT_EQ(g.loops[2].transfers, 2);
  ASSERT_EQ(g.transfers.size(), 2u);
  EXPECT_EQ(g.transfers[0].line, 10);
  EXPECT_EQ(g.transfers[1].to, (Needle{Bed::Front, 2}));
  EXPECT_TRUE(g.loops[5].live_at_end);
  EXPECT_TRUE(g.loops[7].live_at_end);
  EXPECT_FALSE(g.loops[3].live_at_end);
  EXPECT_EQ(g.loops[7].line, 12);
  EXPECT_EQ(loops_of_carrier(g, 0).size(), 8u);
  EXPECT_TRUE(loops_of_carrier(g, 1).empty());
}

TEST(KnitoutSimulate, DiagnosticsAreCappedButCounted) {
  std::string body = kStart;
  for (int i = 0; i < 150; ++i) body += "rack 6\n";
  body += "rack 0\n" + kEnd;
  SimulateOptions o;
  o.max_diagnostics_per_rule = 10;
  const KnitoutSimulation s =
      simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7 8 9 10\n" + body), shima(), o);
  EXPECT_EQ(s.errors, 150);
  EXPECT_EQ(s.diagnostics.size(), 10u);
}

TEST(KnitoutSimulate, GenericProfileAcceptsEverySpecOperation) {
  // Hook operations on a machine without hook: read as in / (nothing) / out,
  // with a warning on the generic profile, an error on the Kniterate.
  const std::string body = "inhook 1\ntuck - f2 1\ntuck + f1 1\nreleasehook 1\nknit - f2 1\nknit - f1 1\nouthook 1\n"
                           "; leave-loops: fragment\n";
  const KnitoutSimulation g = simulate_knitout(
      parse_knitout(";!knitout-2\n;;Carriers: 1 2 3\n" + body), machine_profile("generic"));
  EXPECT_TRUE(g.ok()) << dump(g);
  EXPECT_EQ(g.warning_counts[static_cast<int>(KnitoutRule::Hook)], 3) << dump(g);
  EXPECT_EQ(g.stats.carriers_in, 1);
  EXPECT_EQ(g.stats.carriers_out, 1);
  const KnitoutSimulation k = simulate_knitout(
      parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6\n" + body), machine_profile("kniterate"));
  EXPECT_EQ(k.error_counts[static_cast<int>(KnitoutRule::Hook)], 3) << dump(k);
  // A carrier left in: the spec does not forbid it (generic: warning), both
  // translators refuse it (Shima, Kniterate: error).
  const std::string left = ";!knitout-2\n;;Carriers: 1 2 3 4 5 6\nin 1\ntuck - f2 1\n; leave-loops\n";
  EXPECT_TRUE(simulate_knitout(parse_knitout(left), machine_profile("generic")).ok());
  EXPECT_FALSE(simulate_knitout(parse_knitout(left), machine_profile("kniterate")).ok());
}

TEST(KnitoutSimulate, KniterateKnitsQuarterPitchAtHalfPitch) {
  // knitout-to-kcode.js adds 0.25 to a racking with fraction .25; other
  // fractions than .0 / .5 are refused.
  const std::string head = ";!knitout-2\n;;Carriers: 1 2 3 4 5 6\nin 1\ntuck + f1 1\n";
  const std::string tail = "rack 0\nout 1\n; leave-loops\n";
  const auto& kn = machine_profile("kniterate");
  const KnitoutSimulation q = simulate_knitout(parse_knitout(head + "rack 0.25\ntuck + b1 1\n" + tail), kn);
  expect_single_warning(q, KnitoutRule::Racking, 5);
  EXPECT_EQ(q.diagnostics[0].check, KnitoutCheck::QuarterPitchAsHalf);
  // at half pitch back needle 1 sits at slot 1.5
  ASSERT_EQ(q.graph.num_loops(), 2);
  EXPECT_DOUBLE_EQ(q.graph.loops[1].slot, 1.5);
  const KnitoutSimulation m = simulate_knitout(parse_knitout(head + "rack -0.75\n" + tail), kn);  // -> -0.5
  EXPECT_TRUE(m.ok()) << dump(m);
  expect_single_error(simulate_knitout(parse_knitout(head + "rack 0.75\n" + tail), kn), KnitoutRule::Racking, 5);
  expect_single_error(simulate_knitout(parse_knitout(head + "rack -0.25\n" + tail), kn), KnitoutRule::Racking, 5);
  // The SWG translator takes quarter pitch and refuses half pitch.
  EXPECT_TRUE(run(kStart + "rack 0.25\nrack 0\n" + kEnd).ok());
  expect_single_error(run(kStart + "rack 0.5\nrack 0\n" + kEnd), KnitoutRule::Racking, 15);
}

TEST(KnitoutSimulate, NamedMachinesNeedTheirTranslatorsCarrierHeader) {
  const std::string body = "in 1\ntuck + f2 1\nout 1\n; leave-loops\n";
  const KnitoutSimulation k =
      simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1 2 3\n" + body), machine_profile("kniterate"));
  expect_single_error(k, KnitoutRule::Header, 2);
  EXPECT_EQ(k.diagnostics[0].check, KnitoutCheck::CarrierNames);
  const KnitoutSimulation g =
      simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1 2 3\n" + body), machine_profile("generic"));
  EXPECT_EQ(g.errors + g.warnings, 0) << dump(g);
}

TEST(KnitoutSimulate, KniterateKnitsWithOneCarrierAtATime) {
  const KnitoutSimulation k = simulate_knitout(
      parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6\nin 1 2\nknit + f1 1 2\nknit + f2 1 2\nout 1 2\n"
                    "; leave-loops\n"),
      machine_profile("kniterate"));
  EXPECT_EQ(k.error_counts[static_cast<int>(KnitoutRule::InactiveCarrier)], 2) << dump(k);  // plating, twice
  EXPECT_TRUE(simulate_knitout(parse_knitout(";!knitout-2\n;;Carriers: 1 2 3 4 5 6 7 8 9 10\nin 1 2\nknit - f2 1 2\n"
                                             "knit - f1 1 2\nout 1 2\n; leave-loops\n"),
                               shima())
                  .ok());
}

TEST(KnitoutSimulate, PassesAreRecordedWithTheirLines) {
  const KnitoutSimulation s = run(kStart + kEnd);
  // tucks -, tucks +, knit -, knit +: four knit passes
  ASSERT_EQ(s.passes.size(), 4u) << dump(s);
  EXPECT_EQ(s.passes[0].first_line, 4);
  EXPECT_EQ(s.passes[0].last_line, 5);
  EXPECT_EQ(s.passes[0].tucks, 2);
  EXPECT_EQ(s.passes[2].knits, 4);
  EXPECT_EQ(s.passes[2].direction, -1);
  EXPECT_DOUBLE_EQ(s.passes[2].min_slot, 1.0);
  EXPECT_DOUBLE_EQ(s.passes[2].max_slot, 4.0);
  double t = 0;
  for (const auto& p : s.passes) t += p.time_s;
  EXPECT_GT(t, 0.0);
  EXPECT_LE(t, s.stats.time_s);
  for (const auto& l : s.graph.loops) EXPECT_GE(l.pass, 0);
}

#include "knitforge/machine/machine_profile.h"

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(MachineProfile, BuiltInProfilesHaveTheDocumentedLimits) {
  const auto& s = machine_profile("shima-swg091n2");
  EXPECT_EQ(s.gauge, 15);
  EXPECT_EQ(s.carriers.size(), 10u);
  EXPECT_EQ(s.carriers.front(), "1");
  EXPECT_EQ(s.carriers.back(), "10");
  EXPECT_TRUE(s.has_yarn_inserting_hook);
  EXPECT_EQ(s.max_racking, 4);
  EXPECT_EQ(s.max_loops_per_needle, 4);
  EXPECT_EQ(s.max_float_needles, 20);
  EXPECT_EQ(s.beds, 2);
  const auto& k = machine_profile("kniterate");
  EXPECT_EQ(k.carriers.size(), 6u);
  EXPECT_FALSE(k.has_yarn_inserting_hook);
  EXPECT_EQ(k.needle_count, 252);
  EXPECT_TRUE(k.width_header);
  EXPECT_EQ(machine_profile("generic").beds, 2);
  const auto& b = machine_profile("brother-kh868");
  EXPECT_EQ(b.beds, 1);
  EXPECT_TRUE(b.manual);
  EXPECT_EQ(b.needle_count, 200);
  EXPECT_NEAR(b.needle_pitch_mm(), 4.5, 1e-12);
  for (const auto& n : machine_profile_names()) EXPECT_NO_THROW(validate_machine_profile(machine_profile(n)));
}

TEST(MachineProfile, NamesAreCaseInsensitiveWithAliasesAndUnknownNamesThrow) {
  EXPECT_EQ(&machine_profile("SWG091N2"), &machine_profile("shima-swg091n2"));
  EXPECT_EQ(&machine_profile("Kniterate"), &machine_profile("kniterate"));
  EXPECT_EQ(&machine_profile("kh868"), &machine_profile("brother-kh868"));
  try {
    machine_profile("stoll");
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("kniterate"), std::string::npos);
  }
  EXPECT_EQ(machine_profile_names().size(), 4u);
}

TEST(MachineProfile, ValidationNamesTheBadField) {
  MachineProfile p = machine_profile("generic");
  p.carriers.push_back("1");
  EXPECT_THROW(validate_machine_profile(p), InvalidInput);
  p = machine_profile("generic");
  p.max_transfer_stack = p.max_loops_per_needle + 1;
  EXPECT_THROW(validate_machine_profile(p), InvalidInput);
  p = machine_profile("generic");
  p.max_racking = 0;
  EXPECT_THROW(validate_machine_profile(p), InvalidInput);
  p = machine_profile("generic");
  p.timing.knit_speed_mm_s = 0;
  EXPECT_THROW(validate_machine_profile(p), InvalidInput);
}

TEST(MachineProfile, PassTimeFollowsTheTimingModel) {
  const auto& s = machine_profile("shima-swg091n2");
  const double pitch = 25.4 / 15;
  EXPECT_NEAR(pass_time_seconds(s, PassKind::Knit, 100),
              s.timing.pass_overhead_s + 100 * pitch / s.timing.knit_speed_mm_s, 1e-12);
  EXPECT_NEAR(pass_time_seconds(s, PassKind::Transfer, 100),
              s.timing.pass_overhead_s + s.timing.transfer_pass_overhead_s +
                  100 * pitch / s.timing.transfer_speed_mm_s,
              1e-12);
  EXPECT_GT(pass_time_seconds(s, PassKind::Transfer, 50), pass_time_seconds(s, PassKind::Knit, 50));
}

}  // namespace
}  // namespace knitforge

#include "knitforge/body/ddr/ddr_losses.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace knitforge;

TEST(DdrLosses, L1SumsAnImageAndAveragesTheBatch) {
  const torch::Tensor a = torch::zeros({2, 2, 4, 4});
  torch::Tensor b = torch::zeros({2, 2, 4, 4});
  b.index_put_({0}, 0.5);  // image 0: 32 values off by 0.5 -> 16; image 1: 0
  EXPECT_NEAR(l1_per_image(a, b).item<double>(), 8.0, 1e-6);
}

TEST(DdrLosses, TheGradientTermIgnoresOffsetsAndSeesRamps) {
  const torch::Tensor zero = torch::zeros({1, 1, 5, 5});
  EXPECT_NEAR(gradient_l1_per_image(zero + 0.3, zero).item<double>(), 0.0, 1e-6);
  // e = 0.1 u: ∇_h e = 0.1, ∇_v e = 0 on the 4 x 4 core: 16 x 0.1.
  const torch::Tensor ramp = 0.1 * torch::arange(5, torch::kFloat).view({1, 1, 1, 5}).expand({1, 1, 5, 5});
  EXPECT_NEAR(gradient_l1_per_image(ramp, zero).item<double>(), 1.6, 1e-5);
  // (∇_h + ∇_v): a ramp along u minus the same along v cancels.
  const torch::Tensor diag = ramp - ramp.transpose(2, 3);
  EXPECT_NEAR(gradient_l1_per_image(diag, zero).item<double>(), 0.0, 1e-5);
}

TEST(DdrLosses, AdversarialTermsAreTheLogLossesOfTheSigmoid) {
  const torch::Tensor z = torch::zeros({2, 1, 3, 3});
  EXPECT_NEAR(discriminator_loss(z, z).item<double>(), 2 * std::log(2.0), 1e-6);
  EXPECT_NEAR(generator_adversarial_loss(z).item<double>(), std::log(2.0), 1e-6);
  // A confident, correct discriminator: small loss; fooled: large.
  EXPECT_LT(discriminator_loss(z + 10, z - 10).item<double>(), 1e-3);
  EXPECT_GT(discriminator_loss(z - 10, z + 10).item<double>(), 19.0);
}

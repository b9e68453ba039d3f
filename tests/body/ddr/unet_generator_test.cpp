#include "knitforge/body/ddr/unet_generator.h"

#include <gtest/gtest.h>

#include "knitforge/body/ddr/patch_discriminator.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

TEST(UNetGenerator, MapsAnImageToAnImageOfTheSameSizeInTheTanhRange) {
  for (int size : {16, 32, 64}) {
    torch::manual_seed(1);
    UNetGenerator g(UNetOptions{21, 2, size, 4, 0.5});
    g->train();
    const torch::Tensor y = g->forward(torch::randn({2, 21, size, size}));
    EXPECT_EQ(y.sizes(), torch::IntArrayRef({2, 2, size, size}));
    EXPECT_LT(y.abs().max().item<float>(), 1.0f);
  }
}

TEST(UNetGenerator, DropoutIsTheNoiseEvenInEvalModeAndSeedsReproduceIt) {
  torch::manual_seed(3);
  UNetGenerator g(UNetOptions{19, 1, 32, 4, 0.5});
  g->eval();
  torch::NoGradGuard no_grad;
  const torch::Tensor x = torch::randn({1, 19, 32, 32});
  torch::manual_seed(7);
  const torch::Tensor a = g->forward(x);
  torch::manual_seed(7);
  const torch::Tensor b = g->forward(x);
  torch::manual_seed(8);
  const torch::Tensor c = g->forward(x);
  EXPECT_TRUE(torch::equal(a, b));
  EXPECT_FALSE(torch::equal(a, c));
  // Without dropout the output does not depend on the seed.
  UNetGenerator plain(UNetOptions{19, 1, 32, 4, 0.0});
  plain->eval();
  torch::manual_seed(7);
  const torch::Tensor d = plain->forward(x);
  torch::manual_seed(8);
  EXPECT_TRUE(torch::equal(d, plain->forward(x)));
}

TEST(UNetGenerator, SkipsCarryFineDetailToTheOutput) {
  // The last decoder layer sees the first encoder layer: a change of one
  // input pixel changes the output near it more than far from it.
  torch::manual_seed(5);
  UNetGenerator g(UNetOptions{1, 1, 32, 4, 0.0});
  g->eval();
  torch::NoGradGuard no_grad;
  torch::Tensor x = torch::zeros({1, 1, 32, 32});
  const torch::Tensor y0 = g->forward(x);
  x.index_put_({0, 0, 8, 8}, 5.0);
  const torch::Tensor dy = (g->forward(x) - y0).abs();
  EXPECT_GT(dy.index({0, 0, 8, 8}).item<float>(), 0.0f);
  EXPECT_GT(dy.index({0, 0, torch::indexing::Slice(6, 11), torch::indexing::Slice(6, 11)}).mean().item<float>(),
            dy.index({0, 0, torch::indexing::Slice(20, 32), torch::indexing::Slice(20, 32)}).mean().item<float>());
}

TEST(UNetGenerator, RefusesSizesThatAreNotPowersOfTwo) {
  EXPECT_THROW(UNetGenerator(UNetOptions{21, 2, 48, 4, 0.5}), InvalidInput);
  EXPECT_THROW(UNetGenerator(UNetOptions{21, 2, 8, 4, 0.5}), InvalidInput);
  EXPECT_THROW(UNetGenerator(UNetOptions{0, 2, 32, 4, 0.5}), InvalidInput);
}

TEST(PatchDiscriminator, JudgesOverlappingPatches) {
  torch::manual_seed(1);
  PatchDiscriminator d(5, 4);
  d->train();
  EXPECT_EQ(d->forward(torch::randn({2, 5, 64, 64})).sizes(), torch::IntArrayRef({2, 1, 6, 6}));
  EXPECT_EQ(d->forward(torch::randn({2, 5, 256, 256})).sizes(), torch::IntArrayRef({2, 1, 30, 30}));
  EXPECT_THROW(PatchDiscriminator(0, 4), InvalidInput);
}

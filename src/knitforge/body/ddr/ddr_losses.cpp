#include "knitforge/body/ddr/ddr_losses.h"

namespace knitforge {

torch::Tensor l1_per_image(const torch::Tensor& a, const torch::Tensor& b) {
  return (a - b).abs().flatten(1).sum(1).mean();
}

torch::Tensor gradient_l1_per_image(const torch::Tensor& a, const torch::Tensor& b) {
  const torch::Tensor e = a - b;
  const int64_t h = e.size(2), w = e.size(3);
  using torch::indexing::Slice;
  const torch::Tensor core = e.index({Slice(), Slice(), Slice(0, h - 1), Slice(0, w - 1)});
  const torch::Tensor dh = e.index({Slice(), Slice(), Slice(0, h - 1), Slice(1, w)}) - core;
  const torch::Tensor dv = e.index({Slice(), Slice(), Slice(1, h), Slice(0, w - 1)}) - core;
  return (dh + dv).abs().flatten(1).sum(1).mean();
}

torch::Tensor discriminator_loss(const torch::Tensor& real_logits, const torch::Tensor& fake_logits) {
  return torch::binary_cross_entropy_with_logits(real_logits, torch::ones_like(real_logits)) +
         torch::binary_cross_entropy_with_logits(fake_logits, torch::zeros_like(fake_logits));
}

torch::Tensor generator_adversarial_loss(const torch::Tensor& fake_logits) {
  return torch::binary_cross_entropy_with_logits(fake_logits, torch::ones_like(fake_logits));
}

}  // namespace knitforge

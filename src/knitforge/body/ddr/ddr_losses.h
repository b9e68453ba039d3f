#pragma once
/// \file ddr_losses.h
/// The seed's objective of the DDR prediction network (eq. 5.6-5.9):
///
///   G* = argmin_G max_D  L_cGAN(G, D) + λ1 L_L1(G) + λ2 L_∇(G),  λ1 = 0.03, λ2 = 0.06
///
/// L_cGAN (eq. 5.6) with D seeing the RGB picture x1 and a DDR (as the
/// seed writes it, not the keypoints); L_L1 (eq. 5.7) = E ‖y - G(x)‖₁ and
/// L_∇ (eq. 5.8) = E ‖(∇_h + ∇_v)(y - G(x))‖₁, the norms summed over an
/// image's pixels and channels and averaged over the batch (the seed's small
/// λ weigh these sums against the GAN's per-patch log-loss: with per-pixel
/// means they would be negligible). ∇_h, ∇_v are forward differences; their
/// sum is taken on the (s-1) x (s-1) pixels that have both neighbours.
/// The generator minimises log(1 - D(G)) in the usual non-saturating form
/// (maximising log D(G)), as pix2pix does.

#include <torch/torch.h>

namespace knitforge {

inline constexpr double kDdrLambdaL1 = 0.03;
inline constexpr double kDdrLambdaGradient = 0.06;

/// E ‖a - b‖₁ per image (sum over C x H x W, mean over N).
torch::Tensor l1_per_image(const torch::Tensor& a, const torch::Tensor& b);

/// E ‖(∇_h + ∇_v)(a - b)‖₁ per image.
torch::Tensor gradient_l1_per_image(const torch::Tensor& a, const torch::Tensor& b);

/// The discriminator's loss: -(log D(real) + log(1 - D(fake))), the mean
/// over patches and images, from logits.
torch::Tensor discriminator_loss(const torch::Tensor& real_logits, const torch::Tensor& fake_logits);

/// The generator's adversarial term: -log D(fake), from logits.
torch::Tensor generator_adversarial_loss(const torch::Tensor& fake_logits);

}  // namespace knitforge

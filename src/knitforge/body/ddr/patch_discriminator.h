#pragma once
/// \file patch_discriminator.h
/// The seed's 70 x 70 PatchGAN discriminator (§5.4.5, after pix2pix):
/// C64 - C128 - C256 - C512 (kernel 4; stride 2, 2, 2, then 1), a final
/// convolution to one channel, each output value judging one 70 x 70 patch
/// of its input as real or generated. No BatchNorm on the first layer,
/// LeakyReLU 0.2 after every layer. The seed ends with a Sigmoid; forward()
/// returns the logits and the losses (ddr_losses.h) apply the Sigmoid
/// inside the log-loss (the same function, computed without overflow).
/// `width` scales 64 as the generator's.

#include <torch/torch.h>

namespace knitforge {

class PatchDiscriminatorImpl : public torch::nn::Module {
 public:
  /// \throw InvalidInput for channels or width below 1.
  PatchDiscriminatorImpl(int in_channels, int width);
  /// x: N x in_channels x H x W -> N x 1 x H' x W' logits (H' = H / 8 - 2).
  torch::Tensor forward(const torch::Tensor& x);

 private:
  torch::nn::Conv2d c1_{nullptr}, c2_{nullptr}, c3_{nullptr}, c4_{nullptr}, out_{nullptr};
  torch::nn::BatchNorm2d n2_{nullptr}, n3_{nullptr}, n4_{nullptr};
};
TORCH_MODULE(PatchDiscriminator);

}  // namespace knitforge

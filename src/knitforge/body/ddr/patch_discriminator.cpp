#include "knitforge/body/ddr/patch_discriminator.h"

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

PatchDiscriminatorImpl::PatchDiscriminatorImpl(int in_channels, int width) {
  if (in_channels < 1 || width < 1)
    throw InvalidInput(fmt::format("PatchGAN: {} channels and width {} must be at least 1", in_channels, width));
  const auto conv = [](int in, int out, int stride) {
    return torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, 4).stride(stride).padding(1));
  };
  c1_ = register_module("c1", conv(in_channels, width, 2));
  c2_ = register_module("c2", conv(width, 2 * width, 2));
  n2_ = register_module("n2", torch::nn::BatchNorm2d(2 * width));
  c3_ = register_module("c3", conv(2 * width, 4 * width, 2));
  n3_ = register_module("n3", torch::nn::BatchNorm2d(4 * width));
  c4_ = register_module("c4", conv(4 * width, 8 * width, 1));
  n4_ = register_module("n4", torch::nn::BatchNorm2d(8 * width));
  out_ = register_module("out", conv(8 * width, 1, 1));
}

torch::Tensor PatchDiscriminatorImpl::forward(const torch::Tensor& x) {
  torch::Tensor h = torch::leaky_relu(c1_->forward(x), 0.2);
  h = torch::leaky_relu(n2_->forward(c2_->forward(h)), 0.2);
  h = torch::leaky_relu(n3_->forward(c3_->forward(h)), 0.2);
  h = torch::leaky_relu(n4_->forward(c4_->forward(h)), 0.2);
  return out_->forward(h);
}

}  // namespace knitforge

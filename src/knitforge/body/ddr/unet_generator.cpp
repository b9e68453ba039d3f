#include "knitforge/body/ddr/unet_generator.h"

#include <algorithm>
#include <string>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

int levels_of(int size) {
  int levels = 0;
  while ((1 << levels) < size) ++levels;
  if (size < 16 || size > 1024 || (1 << levels) != size)
    throw InvalidInput(fmt::format("U-Net image size {} must be a power of two in 16..1024", size));
  return levels;
}

}  // namespace

UNetGeneratorImpl::UNetGeneratorImpl(const UNetOptions& options) : options_(options) {
  const int n = levels_of(options.size);
  if (options.in_channels < 1 || options.out_channels < 1 || options.width < 1)
    throw InvalidInput(fmt::format("U-Net: channels {} -> {} and width {} must be at least 1", options.in_channels,
                                   options.out_channels, options.width));
  const auto width = [&](int level) { return options.width * (1 << std::min(level, 3)); };
  for (int i = 0; i < n; ++i) {
    const int in = i == 0 ? options.in_channels : width(i - 1);
    down_.push_back(register_module("down" + std::to_string(i),
                                    torch::nn::Conv2d(torch::nn::Conv2dOptions(in, width(i), 4).stride(2).padding(1))));
    // No norm on the first layer, nor on the innermost (1 x 1).
    const bool norm = i > 0 && i < n - 1;
    down_norm_.push_back(norm ? register_module("down_norm" + std::to_string(i), torch::nn::BatchNorm2d(width(i)))
                              : torch::nn::BatchNorm2d(nullptr));
  }
  // up_[i] produces the output of level i (the mirror of down_[i]).
  for (int i = 0; i < n; ++i) {
    const int in = i == n - 1 ? width(i) : 2 * width(i);
    const int out = i == 0 ? options.out_channels : width(i - 1);
    up_.push_back(register_module(
        "up" + std::to_string(i),
        torch::nn::ConvTranspose2d(torch::nn::ConvTranspose2dOptions(in, out, 4).stride(2).padding(1))));
    up_norm_.push_back(i > 0 ? register_module("up_norm" + std::to_string(i), torch::nn::BatchNorm2d(out))
                             : torch::nn::BatchNorm2d(nullptr));
  }
}

torch::Tensor UNetGeneratorImpl::forward(const torch::Tensor& x) {
  const int n = static_cast<int>(down_.size());
  std::vector<torch::Tensor> skips;
  torch::Tensor h = x;
  for (int i = 0; i < n; ++i) {
    if (i > 0) h = torch::leaky_relu(h, 0.2);
    h = down_[static_cast<size_t>(i)]->forward(h);
    if (!down_norm_[static_cast<size_t>(i)].is_empty()) h = down_norm_[static_cast<size_t>(i)]->forward(h);
    skips.push_back(h);
  }
  for (int i = n - 1; i >= 0; --i) {
    if (i < n - 1) h = torch::cat({h, skips[static_cast<size_t>(i)]}, 1);
    h = up_[static_cast<size_t>(i)]->forward(torch::relu(h));
    if (i == 0) return torch::tanh(h);
    h = up_norm_[static_cast<size_t>(i)]->forward(h);
    // CDk: the three innermost decoder layers (always on: the cGAN's noise).
    if (i >= n - 3 && options_.dropout > 0) h = torch::dropout(h, options_.dropout, /*train=*/true);
  }
  return h;  // not reached
}

}  // namespace knitforge

#pragma once
/// \file unet_generator.h
/// The encoder-decoder of the seed's DDR prediction and view-based
/// refinement networks (§5.4.5, after pix2pix's U-Net): kernel 4, stride 2,
/// padding 1 everywhere; the encoder halves the image down to 1 x 1
/// (log2(size) layers), the decoder doubles it back, and decoder layer i
/// sees encoder layer n - i concatenated to its input (the skips).
///
///   encoder: C(w) - C(2w) - C(4w) - C(8w) - C(8w) ...   (widths capped at 8w)
///   decoder: the mirror, the three innermost with dropout 0.5 (CDk), the
///            last a transposed convolution to the output channels + Tanh
///
/// Ck = convolution with k filters + BatchNorm; no BatchNorm on the first
/// encoder layer, nor at 1 x 1 (a single value per channel and image, which
/// BatchNorm cannot normalise at batch size 1); LeakyReLU 0.2 before every
/// encoder layer after the first, ReLU before every decoder layer. The seed
/// uses w = 64 at 256 x 256 (8 levels); `width` scales it for this CPU.
///
/// Dropout is the noise z of the cGAN "at both training and testing time"
/// (§5.4.4): it is applied whatever the module's train/eval mode, so
/// forward() is random unless torch::manual_seed() is set; BatchNorm
/// follows the mode (batch statistics in training, running ones in eval).

#include <torch/torch.h>

namespace knitforge {

/// Options of UNetGenerator.
struct UNetOptions {
  int in_channels = 21;
  int out_channels = 2;
  int size = 64;       ///< image side, a power of two in 16..1024
  int width = 64;      ///< filters of the first layer (w)
  double dropout = 0.5;
};

/// The network (file comment).
class UNetGeneratorImpl : public torch::nn::Module {
 public:
  /// \throw InvalidInput for a size that is not a power of two in 16..1024,
  ///        or channels / width below 1.
  explicit UNetGeneratorImpl(const UNetOptions& options);
  /// x: N x in_channels x size x size -> N x out_channels x size x size in (-1, 1).
  torch::Tensor forward(const torch::Tensor& x);
  const UNetOptions& options() const { return options_; }

 private:
  UNetOptions options_;
  std::vector<torch::nn::Conv2d> down_;
  std::vector<torch::nn::BatchNorm2d> down_norm_;   ///< empty modules where there is none
  std::vector<torch::nn::ConvTranspose2d> up_;
  std::vector<torch::nn::BatchNorm2d> up_norm_;
};
TORCH_MODULE(UNetGenerator);

}  // namespace knitforge

#include "knitforge/body/ddr/train_ddr.h"

#include <array>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/ddr_sample.h"
#include "knitforge/body/ddr/ddr_losses.h"
#include "knitforge/body/ddr/patch_discriminator.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// The four refinement views (§5.4.4).
constexpr std::array<double, 4> kViewDegrees = {45.0, -45.0, 135.0, -135.0};

void check(const DdrTrainOptions& o) {
  const auto bad = [](const std::string& what) { throw InvalidInput("ddr-train: " + what); };
  if (o.size < 16 || o.size > 256 || (o.size & (o.size - 1)) != 0) bad(fmt::format("size {} is not a power of two in 16..256", o.size));
  if (o.width < 1 || o.width > 64) bad(fmt::format("width {} is outside 1..64", o.width));
  if (o.samples < o.batch) bad(fmt::format("{} samples are fewer than one batch of {}", o.samples, o.batch));
  if (o.batch < 2 || o.batch > 64) bad(fmt::format("batch {} is outside 2..64 (BatchNorm needs two images)", o.batch));
  if (o.epochs < 1 || o.epochs > 100 || o.refine_epochs < 0 || o.refine_epochs > 100) bad("epochs must be 1..100 (refinement 0..100)");
  if (!(o.learning_rate > 0 && o.learning_rate < 1)) bad("the learning rate must be in (0, 1)");
  if (!(o.max_azimuth_deg >= 0 && o.max_azimuth_deg <= 180)) bad("the azimuth range must be 0..180 degrees");
}

torch::Tensor stack(const std::vector<const std::vector<float>*>& planes, int channels, int size) {
  const int64_t n = static_cast<int64_t>(planes.size());
  torch::Tensor t = torch::empty({n, channels, size, size});
  float* out = t.data_ptr<float>();
  const size_t block = static_cast<size_t>(channels) * static_cast<size_t>(size) * static_cast<size_t>(size);
  for (size_t i = 0; i < planes.size(); ++i) std::copy(planes[i]->begin(), planes[i]->end(), out + i * block);
  return t;
}

std::vector<float> concat(const std::vector<float>& a, const std::vector<float>& b) {
  std::vector<float> c = a;
  c.insert(c.end(), b.begin(), b.end());
  return c;
}

void set_learning_rate(torch::optim::Adam& adam, double lr) {
  for (auto& group : adam.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

double estimate_ddr_training_seconds(const DdrTrainOptions& o) {
  // Per sample and epoch, proportional to pixels x width^2 (the
  // convolutions' work), plus rendering the sample; constants measured on
  // this 2-core machine when idle (docs/bodies.md: 64 px, width 32, 2 threads:
  // 0.0155 s per sample in a cGAN epoch, 0.0185 s in a refinement epoch,
  // which also runs the generator and renders a turned view). A loaded
  // machine takes several times longer.
  const double unit = static_cast<double>(o.size) * o.size * o.width * o.width / (64.0 * 64.0 * 32.0 * 32.0);
  const double render = 0.002 * static_cast<double>(o.size) * o.size / (64.0 * 64.0) + 0.001;
  return o.samples * (o.epochs * (0.0125 * unit + render) + o.refine_epochs * (0.0155 * unit + render));
}

DdrModel train_ddr(const BodyModel& body, const DdrTrainOptions& o) {
  check(o);
  const auto log = [&](const std::string& line) {
    if (o.log) o.log(line);
  };
  const auto t0 = std::chrono::steady_clock::now();
  const BodyKeypointRig rig = body_keypoint_rig(body);
  const DdrSceneOptions scene{o.size, o.max_azimuth_deg, 0.0};
  DdrModelInfo info;
  info.size = o.size;
  info.width = o.width;
  info.max_azimuth_deg = o.max_azimuth_deg;
  DdrModel model = make_ddr_model(info, o.seed);
  PatchDiscriminator disc(3 + 2, o.width);
  torch::optim::Adam opt_g(model.generator->parameters(), torch::optim::AdamOptions(o.learning_rate).betas({0.5, 0.999}));
  torch::optim::Adam opt_d(disc->parameters(), torch::optim::AdamOptions(o.learning_rate).betas({0.5, 0.999}));
  const int batches = o.samples / o.batch;
  nlohmann::json epochs = nlohmann::json::array();
  int steps = 0;

  // 1. The cGAN.
  for (int epoch = 0; epoch < o.epochs; ++epoch) {
    const double lr = epoch < (o.epochs + 1) / 2 ? o.learning_rate : 0.1 * o.learning_rate;
    set_learning_rate(opt_g, lr);
    set_learning_rate(opt_d, lr);
    model.generator->train();
    disc->train();
    double sum_d = 0, sum_adv = 0, sum_l1 = 0, sum_grad = 0;
    for (int b = 0; b < batches; ++b) {
      std::vector<DdrSample> samples;
      for (int k = 0; k < o.batch; ++k) {
        // A different order each epoch: the samples of batch b are drawn from a permutation by a stride.
        const int i = static_cast<int>((static_cast<int64_t>(b * o.batch + k) * 7919 + epoch * 104729) % (batches * o.batch));
        samples.push_back(synthetic_ddr_sample(body, rig, ddr_train_seed(i), scene));
      }
      std::vector<std::vector<float>> inputs;
      std::vector<const std::vector<float>*> in_ptr, rgb_ptr, y_ptr;
      for (const DdrSample& s : samples) inputs.push_back(concat(s.rgb, s.heatmaps));
      for (size_t k = 0; k < samples.size(); ++k) {
        in_ptr.push_back(&inputs[k]);
        rgb_ptr.push_back(&samples[k].rgb);
        y_ptr.push_back(&samples[k].ddr);
      }
      const torch::Tensor x = stack(in_ptr, 21, o.size), x1 = stack(rgb_ptr, 3, o.size), y = stack(y_ptr, 2, o.size);
      const torch::Tensor fake = model.generator->forward(x);
      // Discriminator step.
      opt_d.zero_grad();
      const torch::Tensor loss_d = discriminator_loss(disc->forward(torch::cat({x1, y}, 1)),
                                                      disc->forward(torch::cat({x1, fake.detach()}, 1)));
      loss_d.backward();
      opt_d.step();
      // Generator step.
      opt_g.zero_grad();
      const torch::Tensor adv = generator_adversarial_loss(disc->forward(torch::cat({x1, fake}, 1)));
      const torch::Tensor l1 = l1_per_image(fake, y), grad = gradient_l1_per_image(fake, y);
      const torch::Tensor loss_g = adv + kDdrLambdaL1 * l1 + kDdrLambdaGradient * grad;
      loss_g.backward();
      opt_g.step();
      ++steps;
      sum_d += loss_d.item<double>();
      sum_adv += adv.item<double>();
      sum_l1 += l1.item<double>();
      sum_grad += grad.item<double>();
      if ((b + 1) % 50 == 0 || b + 1 == batches)
        log(fmt::format("cGAN epoch {}/{} batch {}/{}: D {:.3f}, G adversarial {:.3f}, L1 {:.1f}, gradient L1 {:.1f} "
                        "(means so far; {:.0f} s)",
                        epoch + 1, o.epochs, b + 1, batches, sum_d / (b + 1), sum_adv / (b + 1), sum_l1 / (b + 1),
                        sum_grad / (b + 1), seconds_since(t0)));
    }
    epochs.push_back({{"network", "generator"}, {"epoch", epoch + 1}, {"learning_rate", lr},
                      {"discriminator", sum_d / batches}, {"adversarial", sum_adv / batches},
                      {"l1_per_image", sum_l1 / batches}, {"gradient_l1_per_image", sum_grad / batches}});
  }

  // 2. The refinement network, on the generator's own predictions.
  torch::optim::Adam opt_r(model.refiner->parameters(), torch::optim::AdamOptions(o.learning_rate).betas({0.5, 0.999}));
  const double sigma = ddr_heatmap_sigma(scene);
  for (int epoch = 0; epoch < o.refine_epochs; ++epoch) {
    const double lr = epoch < (o.refine_epochs + 1) / 2 ? o.learning_rate : 0.1 * o.learning_rate;
    set_learning_rate(opt_r, lr);
    double sum_l1 = 0, sum_grad = 0;
    int count = 0;
    for (int b = 0; b < batches; ++b) {
      std::vector<std::vector<float>> inputs, targets;
      for (int k = 0; k < o.batch; ++k) {
        const int i = b * o.batch + k;
        const DdrSample s = synthetic_ddr_sample(body, rig, ddr_train_seed(i), scene);
        const std::vector<float> predicted = predict_ddr(model, concat(s.rgb, s.heatmaps), ddr_train_seed(i));
        const OrientedPoints points = ddr_oriented_points(predicted, s.camera, s.pelvis_mm.z());
        std::array<bool, kNumBodyKeypoints> present;
        present.fill(true);
        const double angle = kViewDegrees[static_cast<size_t>((i + epoch) % 4)] * std::numbers::pi / 180.0;
        inputs.push_back(ddr_view_input(points.points, s.keypoints_mm, present, s.pelvis_mm, s.camera, angle, sigma));
        targets.push_back(ddr_view_truth(s, angle));
      }
      std::vector<const std::vector<float>*> in_ptr, t_ptr;
      for (size_t k = 0; k < inputs.size(); ++k) {
        in_ptr.push_back(&inputs[k]);
        t_ptr.push_back(&targets[k]);
      }
      model.refiner->train();
      const torch::Tensor x = stack(in_ptr, 19, o.size), y = stack(t_ptr, 1, o.size);
      opt_r.zero_grad();
      const torch::Tensor out = model.refiner->forward(x);
      const torch::Tensor l1 = l1_per_image(out, y), grad = gradient_l1_per_image(out, y);
      (kDdrLambdaL1 * l1 + kDdrLambdaGradient * grad).backward();
      opt_r.step();
      ++steps;
      ++count;
      sum_l1 += l1.item<double>();
      sum_grad += grad.item<double>();
      if ((b + 1) % 50 == 0 || b + 1 == batches)
        log(fmt::format("refinement epoch {}/{} batch {}/{}: L1 {:.1f}, gradient L1 {:.1f} ({:.0f} s)", epoch + 1,
                        o.refine_epochs, b + 1, batches, sum_l1 / count, sum_grad / count, seconds_since(t0)));
    }
    epochs.push_back({{"network", "refiner"}, {"epoch", epoch + 1}, {"learning_rate", lr},
                      {"l1_per_image", sum_l1 / count}, {"gradient_l1_per_image", sum_grad / count}});
  }
  model.info.training = {{"samples", o.samples},   {"epochs", o.epochs}, {"refine_epochs", o.refine_epochs},
                         {"batch", o.batch},       {"learning_rate", o.learning_rate},
                         {"seed", o.seed},         {"steps", steps},
                         {"seconds", seconds_since(t0)}, {"threads", torch::get_num_threads()},
                         {"lambda_l1", kDdrLambdaL1},   {"lambda_gradient", kDdrLambdaGradient},
                         {"epochs_log", epochs}};
  return model;
}

}  // namespace knitforge

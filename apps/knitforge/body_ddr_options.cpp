#include "body_ddr_options.h"

#include <memory>

namespace knitforge::cli {

void add_body_ddr_commands(CLI::App& body, Action& action, const DdrRunners& runners) {
  auto* train = body.add_subcommand(
      "ddr-train",
      "Train the single-image reconstruction (seed 5.4: DDR cGAN + view-based refinement) on synthetic bodies of "
      "our model, on this CPU (LibTorch), then evaluate it on held-out bodies");
  auto t = std::make_shared<DdrTrainCli>();
  train->add_option("-o,--output", t->outdir, "Model directory: ddr.json, generator.pt, refiner.pt")->required();
  train->add_option("--size", t->size, "Image side in pixels (16, 32, 64, 128, 256; default 64; the seed: 256)")
      ->check(CLI::IsMember({16, 32, 64, 128, 256}));
  train->add_option("--width", t->width, "Filters of the first layer (default 32; the seed: 64)")->check(CLI::Range(1, 64));
  train->add_option("--samples", t->samples, "Training bodies (default 4000)")->check(CLI::Range(4, 1000000));
  train->add_option("--epochs", t->epochs, "cGAN epochs (default 4; the learning rate drops tenfold for the second half)")
      ->check(CLI::Range(1, 100));
  train->add_option("--learning-rate", t->learning_rate, "Adam's learning rate (default 1e-3; the seed: 1e-4, for far longer runs)")
      ->check(number_in(1e-6, 0.1));
  train->add_option("--refine-epochs", t->refine_epochs, "Refinement epochs (default 1; 0: untrained refiner)")
      ->check(CLI::Range(0, 100));
  train->add_option("--test-samples", t->test_samples, "Held-out bodies for EI, EP, EG (default 100)")
      ->check(CLI::Range(1, 100000));
  train->add_option("--test-meshes", t->test_meshes, "Of them, rebuilt in 3D and compared with the truth (default 5)")
      ->check(CLI::Range(0, 1000));
  train->add_option("--max-azimuth", t->max_azimuth, "Views drawn within ±this many degrees of the front (default 90)")
      ->check(number_in(0.0, 180.0));
  train->add_option("--seed", t->seed, "Seed of the networks' initial weights (default 1)");
  train->add_option("--threads", t->threads, "CPU threads (default 2)")->check(CLI::Range(1, 64));
  train->add_option("--max-hours", t->max_hours,
                    "Refuse a run estimated to take longer (CPU hours of this 2-core machine; default 2)")
      ->check(number_in(0.0, 1000.0));
  train->callback([t, &action, r = runners.train] { action = [t, r] { return r(*t); }; });

  auto* evaluate = body.add_subcommand(
      "ddr-evaluate", "Evaluate a trained model on held-out synthetic bodies: EI, EP (cm), EG (seed eq. 5.10-5.12) "
                      "and the 3D distance of rebuilt bodies to the truth");
  auto e = std::make_shared<DdrEvaluateCli>();
  evaluate->add_option("model", e->model, "Model directory (body ddr-train)")->required();
  evaluate->add_option("--samples", e->samples, "Held-out bodies (default 100)")->check(CLI::Range(1, 100000));
  evaluate->add_option("--meshes", e->meshes, "Of them, rebuilt in 3D (default 5)")->check(CLI::Range(0, 1000));
  evaluate->add_flag("--update", e->update, "Write the result into the model's ddr.json");
  evaluate->add_flag("--json", e->json, "Print the result as JSON");
  evaluate->callback([e, &action, r = runners.evaluate] { action = [e, r] { return r(*e); }; });

  auto* reconstruct = body.add_subcommand(
      "reconstruct", "A body mesh from one picture and its 18 keypoints (OpenPose JSON) with a trained model (seed "
                     "5.4): rough (centimetres), not for fitting garments");
  auto c = std::make_shared<ReconstructCli>();
  reconstruct->add_option("image", c->image,
                          "The picture (PNG, square: the whole person upright in the middle, about 7/8 of its "
                          "height, seen horizontally)")
      ->required();
  reconstruct->add_option("--keypoints", c->keypoints,
                          "OpenPose JSON of the picture (COCO-18 or BODY_25; docs/formats.md)")
      ->required();
  reconstruct->add_option("--model", c->model, "Model directory (body ddr-train)")->required();
  reconstruct->add_option("-o,--output", c->output, "Output mesh (.ply, .obj, .off, .stl), mm, z up, facing -y")
      ->required();
  reconstruct->add_option("--ddr", c->ddr_png, "Also write the predicted DDR as a picture (PNG: I_min | I_max)");
  reconstruct->add_flag("--no-refine", c->no_refine, "Only the DDR's own points (no refinement views)");
  reconstruct->add_option("--seed", c->seed, "Seed of the generator's dropout noise (default 1)");
  reconstruct->callback([c, &action, r = runners.reconstruct] { action = [c, r] { return r(*c); }; });
}

}  // namespace knitforge::cli

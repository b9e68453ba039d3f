#include "ddr_commands.h"

#include <filesystem>

#include <fmt/core.h>

#include "knitforge/body/ddr_sample.h"
#include "knitforge/body/openpose_json.h"
#include "knitforge/body/ddr/evaluate_ddr.h"
#include "knitforge/body/ddr/reconstruct_body.h"
#include "knitforge/body/ddr/train_ddr.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/png_image.h"

namespace knitforge::cli {

namespace {

void print_evaluation(const DdrEvaluation& e, const std::string& what) {
  note(fmt::format("{}: {} held-out bodies: EI {:.2f}, EP {:.2f} cm, EG {:.2f} (eq. 5.10-5.12; a flat prediction at "
                   "the pelvis depth: EP {:.2f} cm; the seed at 256 x 256: EP 3.17 cm)",
                   what, e.samples, e.ei, e.ep_cm, e.eg, e.flat_ep_cm));
  if (e.meshes > 0)
    note(fmt::format("{}: {} bodies rebuilt in 3D: {:.2f} cm mean distance to the true body as placed, {:.2f} cm "
                     "(RMS {:.2f}) after the best translation; the true body to the rebuilt one {:.2f} cm",
                     what, e.meshes, e.placed_mesh_to_body_cm, e.mesh_to_body_cm, e.mesh_to_body_rms_cm,
                     e.body_to_mesh_cm));
}

}  // namespace

int run_ddr_train(const DdrTrainCli& o) {
  check_output_dir("-o", o.outdir);
  DdrTrainOptions t;
  t.size = o.size;
  t.width = o.width;
  t.samples = o.samples;
  t.epochs = o.epochs;
  t.refine_epochs = o.refine_epochs;
  t.learning_rate = o.learning_rate;
  t.max_azimuth_deg = o.max_azimuth;
  t.seed = o.seed;
  t.log = [](const std::string& line) { note("body ddr-train: " + line); };
  const double estimate = estimate_ddr_training_seconds(t);
  if (estimate > 3600.0 * o.max_hours)
    throw InvalidInput(fmt::format("body ddr-train: this run is estimated at {:.1f} CPU hours on a 2-core machine, "
                                   "over --max-hours {:g}; use fewer --samples / --epochs, a smaller --size or "
                                   "--width, or raise --max-hours",
                                   estimate / 3600.0, o.max_hours));
  torch::set_num_threads(o.threads);
  note(fmt::format("body ddr-train: {} bodies, {} x {} pixels, width {}, {} + {} epochs (estimated {:.0f} min)",
                   o.samples, o.size, o.size, o.width, o.epochs, o.refine_epochs, estimate / 60.0));
  DdrModel model = train_ddr(ddr_body_model(), t);
  const DdrEvaluation e = evaluate_ddr(model, ddr_body_model(), o.test_samples, o.test_meshes,
                                       [](const std::string& line) { note("body ddr-train: " + line); });
  model.info.evaluation = ddr_evaluation_json(e);
  save_ddr_model(o.outdir, model);
  print_evaluation(e, "body ddr-train");
  note(fmt::format("body ddr-train: wrote {} ({:.0f} s training)", o.outdir,
                   model.info.training.value("seconds", 0.0)));
  return 0;
}

int run_ddr_evaluate(const DdrEvaluateCli& o) {
  DdrModel model = load_ddr_model(o.model);
  const DdrEvaluation e = evaluate_ddr(model, ddr_body_model(), o.samples, o.meshes);
  if (o.update) {
    model.info.evaluation = ddr_evaluation_json(e);
    save_ddr_model(o.model, model);
  }
  if (o.json) std::printf("%s\n", ddr_evaluation_json(e).dump(2).c_str());
  print_evaluation(e, "body ddr-evaluate");
  return 0;
}

int run_reconstruct(const ReconstructCli& o) {
  check_input_file(o.image);
  check_input_file(o.keypoints);
  check_output_file("-o", o.output, {".ply", ".obj", ".off", ".stl"}, {o.image, o.keypoints});
  if (!o.ddr_png.empty()) check_output_file("--ddr", o.ddr_png, {".png"}, {o.image});
  DdrModel model = load_ddr_model(o.model);
  const RgbImage image = read_png(o.image);
  double scale = 1.0;
  ReconstructInput input;
  input.rgb = ddr_picture(image, model.info.size, &scale);
  const PersonKeypoints person = openpose_keypoints_from_json(read_json_file(o.keypoints, "keypoints"), o.keypoints);
  if (person.people_in_file > 1)
    note(fmt::format("body reconstruct: {} lists {} people; the first is used", o.keypoints, person.people_in_file));
  for (size_t k = 0; k < kNumBodyKeypoints; ++k) {
    input.keypoints_px[k] = scale * person.px[k];
    input.present[k] = person.present[k];
  }
  const ReconstructedBody body = reconstruct_body(model, input, {!o.no_refine, o.seed});
  write_mesh(o.output, body.mesh);
  if (!o.ddr_png.empty()) write_png(o.ddr_png, ddr_depth_picture(body.ddr, model.info.size));
  note(fmt::format("body reconstruct: {} points from the DDR, {} from 4 refinement views -> {} fused, mesh of {} "
                   "vertices in {} (mm; a rough shape: the model's held-out error is in {}/ddr.json)",
                   body.ddr_points, body.view_points, body.points.points.size(), body.mesh.vertices.size(), o.output,
                   o.model));
  return 0;
}

}  // namespace knitforge::cli

#include "knitforge/body/make_body.h"

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

MadeBody make_body(const BodyModel& model, const MeasurementTargets& targets, const BodyParams& pose) {
  validate_body_params(model, pose);
  MadeBody out;
  out.fit = shape_from_measurements(model, targets);
  out.params = pose;
  out.params.shape = out.fit.shape;
  out.posed = pose_body(model, out.params);
  out.mesh = posed_mesh(model, out.posed);
  return out;
}

std::vector<std::string> vertex_part_names(const BodyModel& model) {
  if (model.vertex_parts.empty())
    throw InvalidInput(fmt::format("body model '{}' has no part labels{}", model.name,
                                   model.labels_note.empty() ? "" : ": " + model.labels_note));
  std::vector<std::string> names;
  names.reserve(model.vertex_parts.size());
  for (BodyPart p : model.vertex_parts) names.push_back(body_part_name(p));
  return names;
}

}  // namespace knitforge

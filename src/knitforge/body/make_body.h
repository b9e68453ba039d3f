#pragma once
/// \file make_body.h
/// A body from measurements and a pose: what `knitforge body make` does.
/// shape_from_measurements() gives the shape, the pose's joint rotations
/// and translation are kept (its shape is ignored), pose_body() gives the
/// mesh.

#include <vector>

#include "knitforge/body/body_measurements.h"
#include "knitforge/body/body_model.h"
#include "knitforge/body/skin_body.h"

namespace knitforge {

/// Result of make_body().
struct MadeBody {
  BodyParams params;               ///< the shape found and the pose given
  ShapeFromMeasurements fit;       ///< targets, achieved measurements, error
  PosedBody posed;                 ///< the posed body
  TriMesh mesh;                    ///< posed vertices and the model's faces
};

/// \throw InvalidInput as shape_from_measurements() (targets out of range)
///        and validate_body_params() (a pose of another model);
///        SolverError when the targets cannot be met.
MadeBody make_body(const BodyModel& model, const MeasurementTargets& targets, const BodyParams& pose);

/// For each vertex of `model`, the name of its part (body_part_name()).
/// \throw InvalidInput when the model has no part labels.
std::vector<std::string> vertex_part_names(const BodyModel& model);

}  // namespace knitforge

#pragma once
/// \file body_measurements.h
/// Body measurements after ISO 8559-1:2017 (anthropometric definitions for
/// garment construction), taken on a shaped body in its rest pose, and the
/// inverse: the shape parameters that give wanted measurements (how
/// `knitforge body make --height ... --chest ...` drives the model).
///
/// Definitions (mm; on the rest pose, which stands upright, z up):
///  - stature ("body height"): top of the head to the floor (lowest vertex);
///  - inside leg length: crotch landmark to the floor;
///  - arm length: acromion -> elbow -> wrist landmarks (left arm), the sum
///    of the two straight segments;
///  - shoulder width: straight distance between the two acromion landmarks;
///  - girths (chest, waist, hip, neck, head, upper arm, thigh, calf): the
///    perimeter of the convex hull of the body's cross-section with a plane
///    (what a tape measure around the body follows), the plane horizontal
///    through the landmark for the torso, neck and head, perpendicular to the
///    bone (shoulder-elbow, hip-knee, knee-ankle) through the landmark for the
///    limbs (left side); of the section's loops, the one whose hull contains
///    the bone or torso axis.
/// The landmarks are vertices of the model (BodyModel::landmarks), so a
/// measurement follows the shape exactly: our generated body's, or those
/// derived for a loaded SMPL-format model (smpl_body_parts.h); a model
/// without them cannot be measured.

#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "knitforge/body/body_model.h"
#include "knitforge/body/shape_body.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

enum class Measurement : int {
  Stature = 0,
  InsideLegLength,
  ArmLength,
  ShoulderWidth,
  ChestGirth,
  WaistGirth,
  HipGirth,
  NeckGirth,
  UpperArmGirth,
  ThighGirth,
  CalfGirth,
  HeadGirth,
};
inline constexpr int kNumMeasurements = 12;

/// Names of a measurement.
struct MeasurementInfo {
  const char* key;       ///< JSON key and shape parameter name, e.g. "chest_girth"
  const char* option;    ///< CLI option, e.g. "chest"
  const char* iso_term;  ///< the ISO 8559-1 term, e.g. "chest girth"
  bool is_girth;
};
const MeasurementInfo& measurement_info(Measurement m);
/// Inverse of MeasurementInfo::key. \throw InvalidInput listing the keys.
Measurement measurement_from_key(const std::string& key);

/// One value per measurement (mm), indexed by Measurement.
using BodyMeasurements = std::array<double, kNumMeasurements>;

/// Measures a shaped rest body (see the file comment).
/// \throw InvalidInput when the model lacks a landmark or joint the
///        definitions need (naming it), or a section is empty.
BodyMeasurements measure_body(const BodyModel& model, const ShapedBody& shaped);

/// Perimeter (mm) of the convex hull of the loop of the section of `mesh`
/// with the plane (point, unit normal) whose hull contains `axis_point`
/// (projected into the plane); the smallest such hull when several do, the
/// loop nearest to it when none does. \throw InvalidInput when the plane
/// misses the mesh.
double section_girth(const TriMesh& mesh, const Vec3& plane_point, const Vec3& normal, const Vec3& axis_point);

/// Wanted measurements (mm); unset ones are derived (see shape_from_measurements()).
struct MeasurementTargets {
  std::array<std::optional<double>, kNumMeasurements> mm;
};

/// Result of shape_from_measurements().
struct ShapeFromMeasurements {
  Eigen::VectorXd shape;         ///< the shape parameters
  BodyMeasurements targets{};    ///< the targets used (given or derived)
  BodyMeasurements achieved{};   ///< measured on the result
  double max_error_mm = 0.0;     ///< max |achieved - target|
  int iterations = 0;            ///< Newton iterations
};

/// Shape parameters whose measurements are the targets: Newton's method on
/// measure_body() (Jacobian by central differences, 1 mm steps), from zero.
/// Unset targets: lengths (inside leg, arm length, shoulder width) scale
/// with stature / template stature, girths keep the template's values.
/// Converges to 0.05 mm in a few iterations on the generated model, whose
/// shape parameters are the measurements themselves.
/// \throw InvalidInput when a target is not positive, outside
///        [0.5, 1.6] x the template's value (beyond what the linear model
///        represents faithfully), or the model has no measurement-named
///        shape parameters; SolverError when Newton does not reach 0.5 mm.
ShapeFromMeasurements shape_from_measurements(const BodyModel& model, const MeasurementTargets& targets);

}  // namespace knitforge

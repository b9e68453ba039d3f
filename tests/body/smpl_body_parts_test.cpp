// label_smpl_body() and load_smpl_model()'s labels: our generated body,
// written in SMPL's npz layout with SMPL's joints (generated_smpl_npz.h),
// loaded, its parts, fields, landmarks and measurements derived from the
// file's own data and compared with those the generated body has by
// construction; also on a shaped body (the labels must follow the joints),
// in SMPL+H's and SMPL-X's layouts, and a layout we do not map refused.
#include "knitforge/body/smpl_body_parts.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <numbers>

#include <fmt/core.h>

#include "body/generated_smpl_npz.h"
#include "io/io_test_util.h"
#include "knitforge/body/body_measurements.h"
#include "knitforge/body/cut_body_region.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/shape_body.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/body/smpl_model_npz.h"
#include "knitforge/util/errors.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

BodyModel load_written(const TempDir& dir, const std::string& name, const std::string& bytes) {
  return load_smpl_model(dir.write(name, bytes));
}

// Per part: of our vertices with that label, the fraction the loaded model
// labels alike.
std::array<double, kNumBodyParts> agreement(const BodyModel& ours, const BodyModel& loaded) {
  std::array<double, kNumBodyParts> same{}, all{};
  for (size_t i = 0; i < ours.vertex_parts.size(); ++i) {
    const auto q = static_cast<size_t>(ours.vertex_parts[i]);
    all[q] += 1.0;
    if (loaded.vertex_parts[i] == ours.vertex_parts[i]) same[q] += 1.0;
  }
  for (size_t q = 0; q < same.size(); ++q) same[q] = all[q] > 0 ? same[q] / all[q] : 0.0;
  return same;
}

void expect_parts_agree(const BodyModel& ours, const BodyModel& loaded, double least, const char* what) {
  ASSERT_EQ(loaded.vertex_parts.size(), ours.vertex_parts.size()) << loaded.labels_note;
  const auto a = agreement(ours, loaded);
  for (int q = 0; q < kNumBodyParts; ++q) {
    std::printf("%s: %-12s %.4f\n", what, body_part_name(static_cast<BodyPart>(q)).c_str(),
                a[static_cast<size_t>(q)]);
    EXPECT_GE(a[static_cast<size_t>(q)], least) << what << ": " << body_part_name(static_cast<BodyPart>(q));
  }
  // Where the labels differ: ours -> loaded, counts.
  std::map<std::pair<int, int>, int> differ;
  for (size_t i = 0; i < ours.vertex_parts.size(); ++i)
    if (loaded.vertex_parts[i] != ours.vertex_parts[i])
      ++differ[{static_cast<int>(ours.vertex_parts[i]), static_cast<int>(loaded.vertex_parts[i])}];
  for (const auto& [k, n] : differ)
    std::printf("%s: %d vertices %s -> %s\n", what, n, body_part_name(static_cast<BodyPart>(k.first)).c_str(),
                body_part_name(static_cast<BodyPart>(k.second)).c_str());
}

}  // namespace

TEST(SmplBodyParts, OurBodyInSmplLayoutGetsItsOwnLabelsBack) {
  const BodyModel& ours = generated_body();
  TempDir dir;
  const BodyModel loaded = load_written(dir, "ours.npz", generated_body_smpl_npz(ours));
  ASSERT_EQ(loaded.num_joints(), 24);
  ASSERT_TRUE(loaded.labels_note.empty()) << loaded.labels_note;
  for (int i = 0; i < ours.num_vertices(); ++i)
    ASSERT_LT(
        (loaded.template_vertices[static_cast<size_t>(i)] - ours.template_vertices[static_cast<size_t>(i)])
            .norm(),
        1e-6);

  expect_parts_agree(ours, loaded, 0.999, "template");
  // The fields: same sign almost everywhere, roughly the same mm.
  int sign_differs = 0, n = 0;
  double worst = 0.0;
  for (int q = 0; q < kNumBodyParts; ++q) {
    for (int i = 0; i < ours.num_vertices(); ++i, ++n) {
      const double a = ours.part_fields[static_cast<size_t>(q)][static_cast<size_t>(i)];
      const double b = loaded.part_fields[static_cast<size_t>(q)][static_cast<size_t>(i)];
      if ((a > 0) != (b > 0)) ++sign_differs;
      if (std::abs(a) < 100.0) worst = std::max(worst, std::abs(a - b));
    }
  }
  std::printf("fields: sign differs at %d of %d, largest difference within 100 mm of a boundary %.2f mm\n",
              sign_differs, n, worst);
  EXPECT_LT(sign_differs, n / 1000);
  EXPECT_LT(worst, 1.0);
  // Landmarks: the same places.
  for (const auto& [name, v] : ours.landmarks) {
    ASSERT_TRUE(loaded.landmarks.count(name)) << name;
    const double d = (loaded.template_vertices[static_cast<size_t>(loaded.landmarks.at(name))] -
                      ours.template_vertices[static_cast<size_t>(v)])
                         .norm();
    std::printf("landmark %-15s %.1f mm from ours\n", name.c_str(), d);
    EXPECT_LT(d, 1.0) << name;
  }
  // Measurements of the loaded model (betas 0) against ours at the template.
  const BodyMeasurements mo = measure_body(ours, shape_body(ours, Eigen::VectorXd::Zero(ours.num_shapes())));
  const BodyMeasurements ml =
      measure_body(loaded, shape_body(loaded, Eigen::VectorXd::Zero(loaded.num_shapes())));
  for (int k = 0; k < kNumMeasurements; ++k) {
    std::printf("%-18s ours %.1f loaded %.1f mm\n", measurement_info(static_cast<Measurement>(k)).key,
                mo[static_cast<size_t>(k)], ml[static_cast<size_t>(k)]);
    EXPECT_NEAR(ml[static_cast<size_t>(k)], mo[static_cast<size_t>(k)], 0.5)
        << measurement_info(static_cast<Measurement>(k)).key;
  }
}

// A body of another shape as the template: the derived cuts must move with
// the joints (ours are fixed planes of the rest template, so here our labels
// are carried by vertex index).
TEST(SmplBodyParts, LabelsFollowTheShape) {
  const BodyModel& ours = generated_body();
  Eigen::VectorXd shape = Eigen::VectorXd::Zero(ours.num_shapes());
  auto set = [&](Measurement m, double mm) { shape(static_cast<int>(m)) = mm; };
  set(Measurement::Stature, 120.0);
  set(Measurement::InsideLegLength, 60.0);
  set(Measurement::ArmLength, 50.0);
  set(Measurement::ChestGirth, 120.0);
  set(Measurement::WaistGirth, 150.0);
  set(Measurement::HipGirth, 80.0);
  set(Measurement::ThighGirth, 60.0);
  const ShapedBody shaped = shape_body(ours, shape);
  TempDir dir;
  const BodyModel loaded =
      load_written(dir, "shaped.npz", generated_body_smpl_npz(ours, SmplLayout::Smpl24, shaped.vertices));
  ASSERT_TRUE(loaded.labels_note.empty()) << loaded.labels_note;
  expect_parts_agree(ours, loaded, 0.95, "shaped");
  const BodyMeasurements mo = measure_body(ours, shaped);
  const BodyMeasurements ml =
      measure_body(loaded, shape_body(loaded, Eigen::VectorXd::Zero(loaded.num_shapes())));
  for (int k = 0; k < kNumMeasurements; ++k) {
    std::printf("shaped %-18s ours %.1f loaded %.1f mm\n", measurement_info(static_cast<Measurement>(k)).key,
                mo[static_cast<size_t>(k)], ml[static_cast<size_t>(k)]);
    EXPECT_NEAR(ml[static_cast<size_t>(k)], mo[static_cast<size_t>(k)], 20.0)
        << measurement_info(static_cast<Measurement>(k)).key;
  }
  // A garment region of the loaded model cuts as a disk.
  const BodyRegion front =
      cut_body_region(loaded.template_mesh(), body_part_field(loaded, BodyPart::TorsoFront));
  EXPECT_GT(front.area_mm2, 1e5);
}

// The skinning weights keep a limb's label off vertices the limb does not
// move: give the fingers of our left hand (x > 800 mm) to the pelvis and
// none of them may stay left-hand (nor become a leg).
TEST(SmplBodyParts, ALimbsLabelNeedsItsWeights) {
  BodyModel moved = generated_body();
  auto moved_fingers = [&](int i) {
    return moved.vertex_parts[static_cast<size_t>(i)] == BodyPart::LeftHand &&
           moved.template_vertices[static_cast<size_t>(i)].x() > 800.0;
  };
  const int pelvis = moved.joint_index("pelvis");
  std::vector<Eigen::Triplet<double>> trip;
  int hand = 0;
  for (int i = 0; i < moved.num_vertices(); ++i) {
    if (moved_fingers(i)) {
      trip.emplace_back(i, pelvis, 1.0);
      ++hand;
      continue;
    }
    for (RowSparse::InnerIterator it(moved.skinning_weights, i); it; ++it)
      trip.emplace_back(i, static_cast<int>(it.col()), it.value());
  }
  ASSERT_GT(hand, 50);
  moved.skinning_weights.setFromTriplets(trip.begin(), trip.end());
  TempDir dir;
  const BodyModel loaded = load_written(dir, "moved.npz", generated_body_smpl_npz(moved));
  ASSERT_TRUE(loaded.labels_note.empty()) << loaded.labels_note;
  int still_hand = 0;
  for (int i = 0; i < loaded.num_vertices(); ++i) {
    if (!moved_fingers(i)) continue;
    const BodyPart p = loaded.vertex_parts[static_cast<size_t>(i)];
    if (p == BodyPart::LeftHand) ++still_hand;
    EXPECT_NE(p, BodyPart::LeftLeg);
  }
  EXPECT_EQ(still_hand, 0);
  // Elsewhere nothing changes.
  std::printf("%d finger vertices moved to the pelvis: %d still left-hand\n", hand, still_hand);
  const BodyModel& ours = generated_body();
  int changed = 0;
  for (int i = 0; i < ours.num_vertices(); ++i) {
    if (!moved_fingers(i) &&
        loaded.vertex_parts[static_cast<size_t>(i)] != ours.vertex_parts[static_cast<size_t>(i)])
      ++changed;
  }
  EXPECT_EQ(changed, 0);
}

TEST(SmplBodyParts, SmplHAndSmplXLayoutsMapTheirFirst22Joints) {
  const BodyModel& ours = generated_body();
  TempDir dir;
  for (const auto& [layout, J] : {std::pair{SmplLayout::SmplH52, 52}, std::pair{SmplLayout::SmplX55, 55}}) {
    const BodyModel loaded =
        load_written(dir, fmt::format("m{}.npz", J), generated_body_smpl_npz(ours, layout));
    ASSERT_EQ(loaded.num_joints(), J);
    EXPECT_EQ(loaded.joint_names[21], "right_wrist");
    EXPECT_EQ(loaded.joint_names[22], "joint_22");
    ASSERT_TRUE(loaded.labels_note.empty()) << loaded.labels_note;
    expect_parts_agree(ours, loaded, 0.99, J == 52 ? "smpl+h" : "smpl-x");
    EXPECT_EQ(loaded.landmarks, load_written(dir, "m24.npz", generated_body_smpl_npz(ours)).landmarks);
  }
}

TEST(SmplBodyParts, AnUnmappedJointLayoutIsRefusedWithWhatIsMissing) {
  const BodyModel& ours = generated_body();
  TempDir dir;
  // 25 joints: loads (it can be posed and fitted) but has no labels.
  const BodyModel loaded =
      load_written(dir, "odd.npz", generated_body_smpl_npz(ours, SmplLayout::Unmapped25));
  EXPECT_EQ(loaded.num_joints(), 25);
  EXPECT_TRUE(loaded.vertex_parts.empty());
  EXPECT_TRUE(loaded.part_fields.empty());
  EXPECT_TRUE(loaded.landmarks.empty());
  EXPECT_NE(loaded.labels_note.find("odd.npz"), std::string::npos) << loaded.labels_note;
  EXPECT_NE(loaded.labels_note.find("not SMPL's body joints"), std::string::npos) << loaded.labels_note;
  EXPECT_NE(loaded.labels_note.find("missing or elsewhere: pelvis, left_hip"), std::string::npos)
      << loaded.labels_note;
  BodyModel copy = loaded;
  try {
    label_smpl_body(copy);
    ADD_FAILURE() << "labelled";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be given part labels and landmarks"), std::string::npos)
        << e.what();
  }
  // What needs the labels refuses with the reason.
  try {
    (void)measure_body(loaded, shape_body(loaded, Eigen::VectorXd::Zero(loaded.num_shapes())));
    ADD_FAILURE() << "measured";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("has no landmark"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not SMPL's body joints"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)body_part_field(loaded, BodyPart::TorsoFront), InvalidInput);

  // SMPL's names but another tree, or a template that is not upright.
  BodyModel tree = load_written(dir, "ours.npz", generated_body_smpl_npz(ours));
  tree.parents[18] = 13;  // left_elbow under the collar
  EXPECT_NE(smpl_body_parts_missing(tree).find("kinematic tree is not SMPL's: joint 18 ('left_elbow')"),
            std::string::npos)
      << smpl_body_parts_missing(tree);
  BodyModel upside_down = load_written(dir, "ours.npz", generated_body_smpl_npz(ours));
  for (Vec3& p : upside_down.template_vertices) p = -p;
  EXPECT_NE(smpl_body_parts_missing(upside_down).find("not an upright T-pose"), std::string::npos);
  EXPECT_THROW(label_smpl_body(upside_down), InvalidInput);
  // The loader's option.
  SmplLoadOptions no;
  no.derive_labels = false;
  const BodyModel bare = load_smpl_model(dir.path("ours.npz"), no);
  EXPECT_TRUE(bare.vertex_parts.empty());
  EXPECT_FALSE(bare.labels_note.empty());
}

// A template whose arms hang lower than our T-pose (SMPL's templates hold
// them about horizontal): the cuts turn with the upper arm. Measured, per
// part at least: 5° 98.9 %, 10° 97.9 %, 20° 96.0 %, 30° 93.2 % (torso-front
// losing its top at the shoulders to the sleeves).
TEST(SmplBodyParts, ArmsBelowHorizontalKeepTheirLabels) {
  const BodyModel& ours = generated_body();
  TempDir dir;
  for (double deg : {10.0, 20.0}) {
    BodyParams p = zero_params(ours);
    const double a = deg * std::numbers::pi / 180.0;
    p.joint_rotations[static_cast<size_t>(ours.joint_index("left_shoulder"))] = Vec3(0, a, 0);
    p.joint_rotations[static_cast<size_t>(ours.joint_index("right_shoulder"))] = Vec3(0, -a, 0);
    const PosedBody posed = pose_body(ours, p);
    const BodyModel loaded =
        load_written(dir, "posed.npz", generated_body_smpl_npz(ours, SmplLayout::Smpl24, posed.vertices));
    ASSERT_TRUE(loaded.labels_note.empty()) << loaded.labels_note;
    expect_parts_agree(ours, loaded, 0.95, fmt::format("arms {} deg", deg).c_str());
  }
}

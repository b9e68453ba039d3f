#include "knitforge/evaluate/stitch_distortion.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

const KnitParams kP{3.5, 2.8};

// The ideal shape of `type` moved by a rigid motion into 3D, after applying
// the linear map `L` in the stitch plane.
std::vector<Vec3> placed(StitchType type, const Mat2& L) {
  const Mat3 R = Eigen::AngleAxisd(1.2, Vec3(0.2, -1, 0.7).normalized()).toRotationMatrix();
  const Vec3 t(5, -3, 12);
  std::vector<Vec3> out;
  for (const Vec3& p : ideal_stitch_shape(type, kP)) {
    const Eigen::Vector2d q = L * p.head<2>();
    out.push_back(R * Vec3(q.x(), q.y(), 0) + t);
  }
  return out;
}

constexpr StitchType kTypes[] = {StitchType::Knit, StitchType::ShortRowLeft, StitchType::ShortRowRight,
                                 StitchType::Increase, StitchType::Decrease};

TEST(StitchDistortion, IdealStitchesHaveNone) {
  for (StitchType t : kTypes) {
    const StitchDistortion d = polygon_distortion(ideal_stitch_shape(t, kP), placed(t, Mat2::Identity()));
    EXPECT_NEAR(d.sigma1, 1.0, 1e-12) << name(t);
    EXPECT_NEAR(d.sigma2, 1.0, 1e-12) << name(t);
    EXPECT_NEAR(d.distortion, 0.0, 1e-12) << name(t);
    EXPECT_NEAR(d.rigid_rms, 0.0, 1e-9) << name(t);
  }
}

TEST(StitchDistortion, UniformScaleGivesEqualSingularValues) {
  for (const double k : {0.5, 1.3, 2.0}) {
    for (StitchType t : kTypes) {
      const StitchDistortion d = polygon_distortion(ideal_stitch_shape(t, kP), placed(t, k * Mat2::Identity()));
      EXPECT_NEAR(d.sigma1, k, 1e-12) << name(t);
      EXPECT_NEAR(d.sigma2, k, 1e-12) << name(t);
      EXPECT_NEAR(d.distortion, std::abs(k - 1), 1e-12);
      EXPECT_GT(d.rigid_rms, 0.0);  // a scaled stitch cannot be fitted rigidly
    }
  }
}

TEST(StitchDistortion, AnisotropicAndShearMapsGiveTheirSingularValues) {
  Mat2 L;
  L << 1.5, 0.4, -0.2, 0.7;  // an arbitrary linear map (with shear)
  const Eigen::JacobiSVD<Mat2> svd(L);
  for (StitchType t : kTypes) {
    const StitchDistortion d = polygon_distortion(ideal_stitch_shape(t, kP), placed(t, L));
    EXPECT_NEAR(d.sigma1, svd.singularValues()(0), 1e-12) << name(t);
    EXPECT_NEAR(d.sigma2, svd.singularValues()(1), 1e-12) << name(t);
    EXPECT_NEAR(d.distortion,
                std::max(std::abs(svd.singularValues()(0) - 1), std::abs(svd.singularValues()(1) - 1)), 1e-12);
  }
  // A collapsed triangle has sigma2 = 0, distortion >= 1.
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  const StitchDistortion c = polygon_distortion(ideal_stitch_shape(StitchType::Decrease, kP), line);
  EXPECT_NEAR(c.sigma2, 0.0, 1e-12);
  EXPECT_GE(c.distortion, 1.0 - 1e-12);
}

TEST(StitchDistortion, QuadNonAffinePartShowsInTheRigidResidual) {
  // A Knit stitch whose top corners are pulled inwards symmetrically
  // (a trapezoid): the affine part is a shrink along x only.
  std::vector<Vec3> q = ideal_stitch_shape(StitchType::Knit, kP);
  q[2].x() -= 0.4;
  q[3].x() += 0.4;
  const StitchDistortion d = polygon_distortion(ideal_stitch_shape(StitchType::Knit, kP), q);
  EXPECT_NEAR(d.sigma1, 1.0, 1e-12);  // height unchanged
  EXPECT_NEAR(d.sigma2, 1.0 - 0.4 / 3.5, 1e-12);  // least squares: mean width shrink
  EXPECT_NEAR(d.rigid_rms, std::sqrt(0.08), 1e-12);  // top corners 0.4 mm off, bottom ones exact
}

TEST(StitchDistortion, WholeMesh) {
  StitchMesh m;
  const std::vector<Vec3> k = ideal_stitch_shape(StitchType::Knit, kP);
  m.vertices = {k[0], k[1], k[2], k[3], Vec3(2 * kP.stitch_width, 0, 0), Vec3(2 * kP.stitch_width, kP.stitch_height, 0)};
  for (Vec3& p : m.vertices) p *= 2;  // stretch everything by 2
  Stitch a;
  a.v = {0, 1, 2, 3};
  Stitch b;
  b.v = {1, 4, 5, 2};
  m.stitches = {a, b};
  const std::vector<StitchDistortion> d = stitch_distortion(m, kP);
  ASSERT_EQ(d.size(), 2u);
  for (const StitchDistortion& x : d) {
    EXPECT_NEAR(x.sigma1, 2.0, 1e-12);
    EXPECT_NEAR(x.sigma2, 2.0, 1e-12);
  }
  EXPECT_EQ(distortion_values(d), (std::vector<double>{d[0].distortion, d[1].distortion}));
  m.stitches[1].v[2] = 9;
  EXPECT_THROW(stitch_distortion(m, kP), TopologyError);
  m.stitches[1].v[2] = 5;
  EXPECT_THROW(stitch_distortion(m, KnitParams{0, 1}), InvalidInput);
}

TEST(StitchDistortion, BadPolygonsThrow) {
  const std::vector<Vec3> tri = ideal_stitch_shape(StitchType::Decrease, kP);
  const std::vector<Vec3> quad = ideal_stitch_shape(StitchType::Knit, kP);
  EXPECT_THROW(polygon_distortion(tri, quad), InvalidInput);
  const std::vector<Vec3> collinear = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  EXPECT_THROW(polygon_distortion(collinear, tri), InvalidInput);
  const std::vector<Vec3> two = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  EXPECT_THROW(polygon_distortion(two, two), InvalidInput);
}

TEST(ScalarStats, ExactValues) {
  const std::vector<double> v = {4, 1, 3, 2, 5};
  const ScalarStats s = scalar_stats(v);
  EXPECT_EQ(s.count, 5);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.max, 5);
  EXPECT_EQ(s.argmax, 4);
  EXPECT_DOUBLE_EQ(s.mean, 3);
  EXPECT_DOUBLE_EQ(s.rms, std::sqrt(55.0 / 5));
  EXPECT_DOUBLE_EQ(s.p50, 3);
  EXPECT_DOUBLE_EQ(s.p90, 4.6);  // position 3.6 between 4 and 5
  EXPECT_DOUBLE_EQ(s.p99, 4.96);
  const ScalarStats e = scalar_stats(std::vector<double>{});
  EXPECT_EQ(e.count, 0);
  EXPECT_EQ(e.argmax, -1);
  EXPECT_THROW(scalar_stats(std::vector<double>{1, NAN}), InvalidInput);
}

TEST(ScalarColours, EndsClampingAndMonotoneLightness) {
  EXPECT_EQ(viridis_colour(0, 0, 1), (Rgb8{68, 1, 84}));
  EXPECT_EQ(viridis_colour(1, 0, 1), (Rgb8{253, 231, 37}));
  EXPECT_EQ(viridis_colour(-3, 0, 1), viridis_colour(0, 0, 1));
  EXPECT_EQ(viridis_colour(7, 0, 1), viridis_colour(1, 0, 1));
  EXPECT_EQ(viridis_colour(0.5, 0, 1), (Rgb8{33, 145, 140}));
  // Viridis gets lighter monotonically: green channel increases.
  int last = -1;
  for (int i = 0; i <= 100; ++i) {
    const Rgb8 c = viridis_colour(i / 100.0, 0, 1);
    EXPECT_GE(c[1], last);
    last = c[1];
  }
  const std::vector<Rgb8> c = scalar_colours(std::vector<double>{0, 2, 4});
  EXPECT_EQ(c[0], viridis_colour(0, 0, 1));
  EXPECT_EQ(c[1], viridis_colour(0.5, 0, 1));
  EXPECT_EQ(c[2], viridis_colour(1, 0, 1));
  EXPECT_EQ(scalar_colours(std::vector<double>{0, 0})[1], viridis_colour(0, 0, 1));
  EXPECT_THROW(viridis_colour(0, 1, 0), InvalidInput);
  EXPECT_THROW(scalar_colours(std::vector<double>{-1}), InvalidInput);
}

}  // namespace
}  // namespace knitforge

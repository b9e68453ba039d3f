// The lowest eigenvectors of the cotangent Laplacian (geometry/laplacian_eigenvectors.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/geometry/laplacian_eigenvectors.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// |Pearson correlation| of two samples.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return std::abs(ab) / std::sqrt(aa * bb);
}

TEST(LaplacianEigenvectors, TheFiedlerVectorOfALongCylinderRunsAlongItsAxis) {
  const double r = 20.0, h = 200.0;
  const TriMesh m = open_tube(r, h, 5.0);
  const LaplacianEigenvectors e = laplacian_eigenvectors(m, {});
  ASSERT_TRUE(e.converged);
  ASSERT_EQ(e.vectors.size(), 1u);
  // cos(pi z / h), eigenvalue (pi / h)^2: the lowest axial mode lies below
  // the first mode round the tube (1 / r^2) on a tube longer than pi r.
  std::vector<double> axial(m.vertices.size());
  for (size_t v = 0; v < axial.size(); ++v) axial[v] = std::cos(std::numbers::pi * m.vertices[v].z() / h);
  EXPECT_GT(correlation(e.vectors[0], axial), 0.999);
  EXPECT_NEAR(e.values[0], std::pow(std::numbers::pi / h, 2), 0.02 * std::pow(std::numbers::pi / h, 2));
  // its gradient runs along z
  std::vector<double> z(m.vertices.size());
  for (size_t v = 0; v < z.size(); ++v) z[v] = m.vertices[v].z();
  EXPECT_GT(gradient_alignment(m, e.vectors[0], z), 0.99);
  EXPECT_EQ(fiedler_vector(m), e.vectors[0]);
}

TEST(LaplacianEigenvectors, AShortWideCylinderHasItsFiedlerVectorRoundIt) {
  // h < pi r: the first mode round the tube (cos theta, 1 / r^2) comes first.
  const double r = 40.0, h = 60.0;
  const TriMesh m = open_tube(r, h, 4.0);
  const LaplacianEigenvectors e = laplacian_eigenvectors(m, {});
  std::vector<double> z(m.vertices.size());
  for (size_t v = 0; v < z.size(); ++v) z[v] = m.vertices[v].z();
  EXPECT_LT(gradient_alignment(m, e.vectors[0], z), 0.05);
  EXPECT_NEAR(e.values[0], 1.0 / (r * r), 0.03 / (r * r));
}

TEST(LaplacianEigenvectors, EigenpairsAreSortedAndMassOrthonormal) {
  const TriMesh m = hemisphere(50.0, 6.0);
  EigenvectorOptions o;
  o.count = 4;
  const LaplacianEigenvectors e = laplacian_eigenvectors(m, o);
  ASSERT_EQ(e.vectors.size(), 4u);
  for (size_t j = 1; j < e.values.size(); ++j) EXPECT_LE(e.values[j - 1], e.values[j] * (1 + 1e-9));
  EXPECT_GT(e.values[0], 0.0);
}

// f = cos(pi z / h) on a tube: flat at both rims, steepest half-way.
TEST(FlatWeightedDirections, AreUnitWhereTheFieldIsSteepAndFadeWhereItIsFlat) {
  const double h = 100.0;
  const TriMesh m = open_tube(40.0, h, 5.0);
  std::vector<double> f(m.vertices.size());
  for (size_t v = 0; v < f.size(); ++v) f[v] = std::cos(std::numbers::pi * m.vertices[v].z() / h);
  const std::vector<Vec3> g = flat_weighted_directions(m, f, false);
  const std::vector<Vec3> t = flat_weighted_directions(m, f, true);
  ASSERT_EQ(g.size(), m.faces.size());
  // The RMS of |sin| is 1/sqrt(2) of its peak: faces near mid-height are
  // unit, faces of the first row beside a rim weigh about sqrt(2) sin(pi
  // z / h) with z their centroid's height.
  double near_rim = 1.0, mid = 0.0;
  for (size_t i = 0; i < m.faces.size(); ++i) {
    const auto& fc = m.faces[i];
    const double z = (m.vertices[fc[0]].z() + m.vertices[fc[1]].z() + m.vertices[fc[2]].z()) / 3.0;
    EXPECT_LE(g[i].norm(), 1.0 + 1e-12);
    EXPECT_NEAR(t[i].norm(), g[i].norm(), 1e-12);
    EXPECT_NEAR(t[i].dot(g[i]), 0.0, 1e-9);  // the isocurve's tangent is across the gradient
    if (g[i].norm() > 0.0) {
      EXPECT_GT(std::abs(g[i].z()) / g[i].norm(), 0.99);  // along the axis
    }
    if (std::abs(z - 0.5 * h) < 10.0) mid = std::max(mid, 1.0 - g[i].norm());
    if (z < 3.0 || z > h - 3.0) near_rim = std::min(near_rim, 1.0 - g[i].norm());
  }
  EXPECT_LT(mid, 1e-12);       // unit
  EXPECT_GT(near_rim, 0.75);   // at most a quarter
  // A constant field has no direction anywhere (its gradients are round-off).
  for (const Vec3& d : flat_weighted_directions(m, std::vector<double>(f.size(), 2.0), true))
    EXPECT_EQ(d.squaredNorm(), 0.0);
  EXPECT_THROW(flat_weighted_directions(m, std::vector<double>(3, 0.0), false), InvalidInput);
}

TEST(LaplacianEigenvectors, RefusesWhatHasNoFiedlerVector) {
  EigenvectorOptions o;
  o.count = 0;
  EXPECT_THROW(laplacian_eigenvectors(open_tube(), o), InvalidInput);
  TriMesh two = open_tube(20.0, 40.0, 5.0);
  const int n = two.num_vertices();
  const TriMesh other = open_tube(20.0, 40.0, 5.0);
  for (const Vec3& p : other.vertices) two.vertices.push_back(p + Vec3(100, 0, 0));
  for (auto f : other.faces) two.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  try {
    laplacian_eigenvectors(two, {});
    FAIL() << "two pieces accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("2 connected pieces"), std::string::npos) << e.what();
  }
  EXPECT_THROW(gradient_alignment(open_tube(), {1.0}, {1.0}), InvalidInput);
}

}  // namespace
}  // namespace knitforge

// Garment regions cut out of a body (body/cut_body_region.h): a disk with a
// smooth rim on the level of the part field, islands and holes removed, and
// the field carried onto a scan.
#include "knitforge/body/cut_body_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "knitforge/body/body_pose.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// Length of the boundary of the faces whose three vertices satisfy `in`:
// the rim a cut along whole faces would have.
double face_region_rim(const TriMesh& m, const std::vector<double>& f) {
  TriMesh r;
  r.vertices = m.vertices;
  for (const auto& t : m.faces)
    if (f[static_cast<size_t>(t[0])] > 0 && f[static_cast<size_t>(t[1])] > 0 && f[static_cast<size_t>(t[2])] > 0)
      r.faces.push_back(t);
  std::map<std::pair<int, int>, int> n;
  for (const auto& t : r.faces)
    for (int k = 0; k < 3; ++k) ++n[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  double len = 0.0;
  for (const auto& [e, c] : n)
    if (c == 1) len += (m.vertices[static_cast<size_t>(e.first)] - m.vertices[static_cast<size_t>(e.second)]).norm();
  return len;
}

TEST(CutBodyRegion, TheTorsoFrontOfAPosedBodyIsADiskWithASmoothRim) {
  const BodyModel& m = generated_body();
  const TriMesh body = posed_mesh(m, pose_body(m, pose_preset(m, "a-pose")));
  const std::vector<double> field = body_part_field(m, BodyPart::TorsoFront);
  const BodyRegion r = cut_body_region(body, field);
  const SurfaceReport rep = validate_surface(r.mesh);
  EXPECT_TRUE(rep.is_disk) << rep.summary();
  const double rim_faces = face_region_rim(body, field);
  std::printf("torso front: %d vertices, %.0f cm², rim %.0f mm (whole faces: %.0f mm), %d islands, %d holes, %d "
              "snapped, edge %.1f mm\n",
              r.mesh.num_vertices(), r.area_mm2 / 100.0, r.boundary_length_mm, rim_faces, r.islands_removed,
              r.holes_filled, r.snapped_vertices, r.edge_length_mm);
  // The front of a torso: about a seventh of the body's area.
  EXPECT_GT(r.area_mm2, 0.10 * total_area(body));
  EXPECT_LT(r.area_mm2, 0.25 * total_area(body));
  // A zigzag along the triangle edges is longer than the level curve (by
  // about 4/pi on a straight cut); the rim follows the level.
  EXPECT_LT(r.boundary_length_mm, 0.95 * rim_faces);
  // Every rim vertex is on the zero level: the field at its closest point of
  // the body is within a millimetre of 0 (the field is about a distance).
  const SurfaceBvh bvh(body);
  const Halfedges he = build_halfedges(r.mesh.num_vertices(), r.mesh.faces);
  double worst = 0.0;
  for (const auto& loop : he.boundary_loops())
    for (int v : loop) {
      const Vec3& p = r.mesh.vertices[static_cast<size_t>(v)];
      const ClosestPoint cp = bvh.closest_point(p);
      const auto& t = body.faces[static_cast<size_t>(cp.face)];
      const TrianglePoint tp = closest_triangle_point(p, body.vertices[static_cast<size_t>(t[0])],
                                                      body.vertices[static_cast<size_t>(t[1])],
                                                      body.vertices[static_cast<size_t>(t[2])]);
      double g = 0.0;
      for (int k = 0; k < 3; ++k) g += tp.bary[k] * field[static_cast<size_t>(t[static_cast<size_t>(k)])];
      worst = std::max(worst, std::abs(g));
      EXPECT_LT(cp.distance, 0.5);
    }
  std::printf("largest |field| on the rim: %.2f\n", worst);
  EXPECT_LT(worst, 1.0);
  // No sliver left by the remeshing: the shortest edge is a fair fraction of the target.
  EXPECT_GT(edge_length_stats(r.mesh).min, 0.2 * r.edge_length_mm);

  // The field carried onto a scan (here, to build the model once for both checks).
  const TriMesh relaxed = posed_mesh(m, pose_body(m, pose_preset(m, "relaxed")));
  // The "scan": the body 1.5 mm out along its normals.
  const std::vector<Vec3> n = vertex_normals(relaxed);
  TriMesh scan = relaxed;
  for (size_t i = 0; i < scan.vertices.size(); ++i) scan.vertices[i] += 1.5 * n[i];
  const std::vector<double> want = body_part_field(m, BodyPart::TorsoBack);
  const std::vector<double> got = scan_part_field(m, relaxed, scan, BodyPart::TorsoBack);
  double fworst = 0.0, mean = 0.0;
  for (size_t i = 0; i < got.size(); ++i) {
    fworst = std::max(fworst, std::abs(got[i] - want[i]));
    mean += std::abs(got[i] - want[i]) / static_cast<double>(got.size());
  }
  std::printf("field on the offset scan: mean difference %.4f, largest %.3f\n", mean, fworst);
  // Exact where the offset vertex's closest point is its own vertex; in
  // concave places (armpits, crotch) it can land a little beside it.
  EXPECT_LT(mean, 0.05);
  EXPECT_LT(fworst, 3.0);
  TriMesh other = relaxed;
  other.faces.pop_back();
  EXPECT_THROW(scan_part_field(m, other, scan, BodyPart::TorsoBack), InvalidInput);
}

TEST(CutBodyRegion, IslandsAreRemovedAndHolesFilled) {
  const TriMesh m = rectangle(200.0, 120.0, 4.0);
  // A disc of radius 45 at the origin with a hole of radius 10 at (15, 5),
  // and a separate small disc of radius 12 at (80, 40).
  std::vector<double> f;
  for (const Vec3& v : m.vertices) {
    const double big = 45.0 - v.norm(), hole = (v - Vec3(15, 5, 0)).norm() - 10.0;
    const double island = 12.0 - (v - Vec3(80, 40, 0)).norm();
    f.push_back(std::max(std::min(big, hole), island));
  }
  const BodyRegion r = cut_body_region(m, f);
  EXPECT_EQ(r.islands_removed, 1);
  EXPECT_EQ(r.holes_filled, 1);
  EXPECT_TRUE(validate_surface(r.mesh).is_disk);
  EXPECT_NEAR(r.area_mm2, std::numbers::pi * 45.0 * 45.0, 0.01 * std::numbers::pi * 45.0 * 45.0);
  EXPECT_NEAR(r.boundary_length_mm, 2.0 * std::numbers::pi * 45.0, 0.01 * 2.0 * std::numbers::pi * 45.0);
  // A hole that reaches the rectangle's own edge is the outside, not a hole.
  std::vector<double> g;
  for (const Vec3& v : m.vertices) g.push_back(std::min(70.0 - std::abs(v.x()), v.y() + 50.0));
  const BodyRegion s = cut_body_region(m, g);
  EXPECT_EQ(s.holes_filled, 0);
  EXPECT_EQ(s.islands_removed, 0);
}

TEST(CutBodyRegion, RejectsBadInput) {
  const TriMesh m = rectangle(20.0, 10.0, 2.0);
  EXPECT_THROW(cut_body_region(m, {1.0}), InvalidInput);
  EXPECT_THROW(cut_body_region(m, std::vector<double>(m.vertices.size(), -1.0)), InvalidInput);
  // A band around a tube is an annulus (both sides of it reach the tube's
  // ends, so neither is a hole): not a disk.
  const TriMesh tube = open_tube(30.0, 80.0, 5.0);
  std::vector<double> band;
  for (const Vec3& v : tube.vertices) band.push_back(15.0 - std::abs(v.z() - 40.0));
  EXPECT_THROW(cut_body_region(tube, band), TopologyError);
}

}  // namespace
}  // namespace knitforge

#pragma once
/// \file rasterize_mesh.h
/// The z-buffer rasteriser behind the synthetic depth images
/// (render_depth_image.h) and dual-depth images (render_dual_depth.h):
/// every pixel centre (u, v) inside a face's projection, edges inclusive,
/// is one fragment with the face's z-depth there. For a planar triangle
/// 1/z is an affine function of (u, v), so z is the exact depth of the
/// pixel ray's hit (perspective-correct interpolation of 1/z), up to
/// rounding. Faces seen edge-on cover no pixel.

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/depth_image.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

/// Calls fragment(pixel, face, z_mm) for every fragment of `scene` (mm,
/// world frame) seen by `camera` placed by `world_to_camera` (x_c = R x +
/// t); pixel = v * width + u. Faces are not clipped: every vertex must lie
/// at least `near_mm` in front of the camera.
/// \throw InvalidInput naming `who` and the face when one has a vertex
///        nearer than near_mm (or behind the camera), or a non-finite vertex.
template <typename Fragment>
void rasterize_mesh(const TriMesh& scene, const DepthCamera& camera, const RigidTransform& world_to_camera,
                    double near_mm, const char* who, Fragment&& fragment) {
  const Mat3& K = camera.K;
  for (int f = 0; f < scene.num_faces(); ++f) {
    std::array<Vec2, 3> px;
    std::array<double, 3> inv_z{};
    for (int k = 0; k < 3; ++k) {
      const Vec3 x = world_to_camera.apply(scene.vertices[static_cast<size_t>(scene.faces[static_cast<size_t>(f)][k])]);
      if (!x.allFinite() || !(x.z() >= near_mm))
        throw InvalidInput(fmt::format("{}: face {} has a vertex at z = {:.1f} mm in the camera's frame; every "
                                       "vertex must be at least {} mm in front of the camera",
                                       who, f, x.z(), near_mm));
      const Vec3 p = K * x;
      px[static_cast<size_t>(k)] = Vec2(p.x() / p.z(), p.y() / p.z());
      inv_z[static_cast<size_t>(k)] = 1.0 / x.z();
    }
    const auto edge = [](const Vec2& a, const Vec2& b, const Vec2& p) {
      return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
    };
    const double area = edge(px[0], px[1], px[2]);
    if (!(std::abs(area) > 1e-12)) continue;  // seen edge-on: covers no pixel centre's interior
    const double lo_u = std::min({px[0].x(), px[1].x(), px[2].x()}), hi_u = std::max({px[0].x(), px[1].x(), px[2].x()});
    const double lo_v = std::min({px[0].y(), px[1].y(), px[2].y()}), hi_v = std::max({px[0].y(), px[1].y(), px[2].y()});
    const int u0 = std::max(0, static_cast<int>(std::ceil(lo_u))), u1 = std::min(camera.width - 1, static_cast<int>(std::floor(hi_u)));
    const int v0 = std::max(0, static_cast<int>(std::ceil(lo_v))), v1 = std::min(camera.height - 1, static_cast<int>(std::floor(hi_v)));
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const Vec2 p(u, v);
        // Screen-space barycentrics; the sign of `area` makes them positive inside.
        const double b0 = edge(px[1], px[2], p) / area, b1 = edge(px[2], px[0], p) / area, b2 = edge(px[0], px[1], p) / area;
        // A small tolerance: a pixel centre on an edge shared by two faces must
        // not fall through both by rounding.
        if (b0 < -1e-9 || b1 < -1e-9 || b2 < -1e-9) continue;
        const double z = 1.0 / (b0 * inv_z[0] + b1 * inv_z[1] + b2 * inv_z[2]);
        fragment(v * camera.width + u, f, z);
      }
    }
  }
}

}  // namespace knitforge

#include "knitforge/body/render_depth_image.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

DepthImage render_depth_image(const TriMesh& scene, const DepthCamera& camera, const RigidTransform& world_to_camera,
                              double near_mm) {
  DepthImage image{camera.width, camera.height,
                   std::vector<double>(static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height), 0.0)};
  const Mat3& K = camera.K;
  for (int f = 0; f < scene.num_faces(); ++f) {
    std::array<Vec2, 3> px;
    std::array<double, 3> inv_z{};
    for (int k = 0; k < 3; ++k) {
      const Vec3 x = world_to_camera.apply(scene.vertices[static_cast<size_t>(scene.faces[static_cast<size_t>(f)][k])]);
      if (!x.allFinite() || !(x.z() >= near_mm))
        throw InvalidInput(fmt::format("render_depth_image: face {} has a vertex at z = {:.1f} mm in the camera's "
                                       "frame; every vertex must be at least {} mm in front of the camera",
                                       f, x.z(), near_mm));
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
        double& d = image.depth_mm[static_cast<size_t>(v) * static_cast<size_t>(camera.width) + static_cast<size_t>(u)];
        if (d == 0.0 || z < d) d = z;
      }
    }
  }
  return image;
}

}  // namespace knitforge

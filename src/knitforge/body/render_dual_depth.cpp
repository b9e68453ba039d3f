#include "knitforge/body/render_dual_depth.h"

#include "knitforge/body/rasterize_mesh.h"

namespace knitforge {

DualDepthImage render_dual_depth(const TriMesh& scene, const DepthCamera& camera,
                                 const RigidTransform& world_to_camera, double near_mm) {
  const size_t n = static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height);
  DualDepthImage image{camera.width, camera.height, std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
                       std::vector<int>(n, -1)};
  rasterize_mesh(scene, camera, world_to_camera, near_mm, "render_dual_depth", [&](int pixel, int face, double z) {
    const size_t i = static_cast<size_t>(pixel);
    if (image.min_face[i] < 0 || z < image.min_mm[i]) {
      image.min_mm[i] = z;
      image.min_face[i] = face;
    }
    if (z > image.max_mm[i]) image.max_mm[i] = z;
  });
  return image;
}

}  // namespace knitforge

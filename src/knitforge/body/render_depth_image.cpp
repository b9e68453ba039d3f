#include "knitforge/body/render_depth_image.h"

#include "knitforge/body/rasterize_mesh.h"

namespace knitforge {

DepthImage render_depth_image(const TriMesh& scene, const DepthCamera& camera, const RigidTransform& world_to_camera,
                              double near_mm) {
  DepthImage image{camera.width, camera.height,
                   std::vector<double>(static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height), 0.0)};
  rasterize_mesh(scene, camera, world_to_camera, near_mm, "render_depth_image", [&](int pixel, int, double z) {
    double& d = image.depth_mm[static_cast<size_t>(pixel)];
    if (d == 0.0 || z < d) d = z;
  });
  return image;
}

}  // namespace knitforge

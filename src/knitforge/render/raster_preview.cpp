#include "knitforge/render/raster_preview.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

struct Raster {
  int w, h;
  std::vector<double> z;
  RgbImage img;
};

// Pixel coordinates (continuous; pixel (i, j) covers [i, i+1) x [j, j+1)).
inline Vec3 to_pixel(const Vec3& ndc, int w, int h) {
  return {0.5 * (ndc.x() + 1.0) * w, 0.5 * (1.0 - ndc.y()) * h, ndc.z()};
}

inline void put(RgbImage& img, int x, int y, const Vec3& c) {
  const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x));
  for (int k = 0; k < 3; ++k) {
    img.pixels[i + static_cast<size_t>(k)] = static_cast<uint8_t>(std::clamp(std::lround(c[k]), 0L, 255L));
  }
}

Vec3 to_vec(const RenderColour& c) { return {double(c[0]), double(c[1]), double(c[2])}; }

}  // namespace

RgbImage rasterize(std::span<const RenderMesh> meshes, const Camera& camera_in, const RasterOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384) {
    throw InvalidInput(
        fmt::format("image size {}x{} px must be within 1..16384 in each direction", o.width, o.height));
  }
  if (!(o.ambient >= 0.0 && o.ambient <= 1.0))
    throw InvalidInput(fmt::format("ambient = {} must be in [0, 1]", o.ambient));
  if (!o.light.allFinite() || o.light.norm() <= 0.0)
    throw InvalidInput("the light direction must be finite and non-zero");
  Camera camera = camera_in;
  camera.aspect = static_cast<double>(o.width) / o.height;
  const ViewTransform view = view_transform(camera);
  const Vec3 light = o.light.normalized();
  const int W = o.width, H = o.height;

  RgbImage img;
  img.width = W;
  img.height = H;
  img.pixels.resize(3 * static_cast<size_t>(W) * static_cast<size_t>(H));
  for (size_t i = 0; i < img.pixels.size(); i += 3) {
    img.pixels[i] = o.background[0];
    img.pixels[i + 1] = o.background[1];
    img.pixels[i + 2] = o.background[2];
  }
  std::vector<double> zbuf(static_cast<size_t>(W) * static_cast<size_t>(H),
                           std::numeric_limits<double>::infinity());

  std::vector<std::vector<Vec3>> pix(meshes.size());
  std::vector<std::vector<char>> ok(meshes.size());
  double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
  for (size_t mi = 0; mi < meshes.size(); ++mi) {
    validate_render_mesh(meshes[mi]);
    const auto& vs = meshes[mi].mesh.vertices;
    pix[mi].resize(vs.size());
    ok[mi].resize(vs.size());
    for (size_t v = 0; v < vs.size(); ++v) {
      ok[mi][v] = view.in_front(vs[v]) ? 1 : 0;
      if (!ok[mi][v]) continue;
      pix[mi][v] = to_pixel(view.to_ndc(vs[v]), W, H);
      zlo = std::min(zlo, pix[mi][v].z());
      zhi = std::max(zhi, pix[mi][v].z());
    }
  }
  // view-space normal: (n . right, n . up, -n . forward)
  auto to_view = [&](const Vec3& n) { return Vec3(n.dot(view.right), n.dot(view.up), -n.dot(view.forward)); };

  std::vector<std::vector<char>> drawn(meshes.size());
  for (size_t mi = 0; mi < meshes.size(); ++mi) {
    const RenderMesh& m = meshes[mi];
    drawn[mi].assign(m.mesh.faces.size(), 0);
    for (size_t f = 0; f < m.mesh.faces.size(); ++f) {
      const auto& t = m.mesh.faces[f];
      const size_t i0 = static_cast<size_t>(t[0]), i1 = static_cast<size_t>(t[1]),
                   i2 = static_cast<size_t>(t[2]);
      if (!ok[mi][i0] || !ok[mi][i1] || !ok[mi][i2]) continue;
      const Vec3 &a = pix[mi][i0], &b = pix[mi][i1], &c = pix[mi][i2];
      // pixel y points down, so a counter-clockwise (front) NDC triangle has negative area here
      const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      if (area == 0.0 || !std::isfinite(area)) continue;
      const bool front = area < 0.0;
      if (!front && o.cull_back_faces) continue;
      drawn[mi][f] = 1;
      const Vec3 fn_world =
          (m.mesh.vertices[i1] - m.mesh.vertices[i0]).cross(m.mesh.vertices[i2] - m.mesh.vertices[i0]);
      const Vec3 face_normal = fn_world.norm() > 0.0 ? Vec3(fn_world.normalized()) : Vec3::Zero();
      Vec3 col[3];
      for (int k = 0; k < 3; ++k) {
        const size_t v = static_cast<size_t>(t[static_cast<size_t>(k)]);
        col[k] = !m.face_colours.empty()     ? to_vec(m.face_colours[f])
                 : !m.vertex_colours.empty() ? to_vec(m.vertex_colours[v])
                                             : to_vec(m.colour);
      }
      Vec3 nrm[3];
      for (int k = 0; k < 3; ++k) {
        const size_t v = static_cast<size_t>(t[static_cast<size_t>(k)]);
        nrm[k] = to_view(m.normals.empty() || m.normals[v].norm() == 0.0 ? face_normal : m.normals[v]);
      }
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
      const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
      const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
      const double inv = 1.0 / area;
      for (int y = y0; y <= y1; ++y) {
        const double py = y + 0.5;
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5;
          const double w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) * inv;
          const double w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) * inv;
          const double w2 = 1.0 - w0 - w1;
          if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
          const double z = w0 * a.z() + w1 * b.z() + w2 * c.z();
          const size_t p = static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
          if (!(z < zbuf[p])) continue;
          zbuf[p] = z;
          Vec3 colour = w0 * col[0] + w1 * col[1] + w2 * col[2];
          if (o.shading) {
            Vec3 n = w0 * nrm[0] + w1 * nrm[1] + w2 * nrm[2];
            if (!front) n = -n;
            const double len = n.norm();
            const double lambert = len > 0.0 ? std::max(0.0, n.dot(light) / len) : 0.0;
            colour *= o.ambient + (1.0 - o.ambient) * lambert;
          }
          put(img, x, y, colour);
        }
      }
    }
  }

  if (o.edges) {
    const double bias = 5e-3 * std::max(zhi - zlo, 1e-12);
    const Vec3 ec = to_vec(o.edge_colour);
    auto line = [&](const Vec3& a0, const Vec3& b0) {
      // Liang-Barsky clip to the image rectangle, so the step count stays bounded
      double t0 = 0.0, t1 = 1.0;
      const double ddx = b0.x() - a0.x(), ddy = b0.y() - a0.y();
      const double pq[4][2] = {{-ddx, a0.x()}, {ddx, W - a0.x()}, {-ddy, a0.y()}, {ddy, H - a0.y()}};
      for (const auto& [p, q] : pq) {
        if (p == 0.0) {
          if (q < 0.0) return;
          continue;
        }
        const double r = q / p;
        if (p < 0.0)
          t0 = std::max(t0, r);
        else
          t1 = std::min(t1, r);
      }
      if (t0 > t1) return;
      const Vec3 a = a0 + t0 * (b0 - a0), b = a0 + t1 * (b0 - a0);
      const double dx = b.x() - a.x(), dy = b.y() - a.y();
      const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)))));
      for (int s = 0; s <= steps; ++s) {
        const double u = static_cast<double>(s) / steps;
        const double x = a.x() + u * dx, y = a.y() + u * dy;
        if (x < 0.0 || y < 0.0 || x >= W || y >= H) continue;
        const int ix = static_cast<int>(x), iy = static_cast<int>(y);
        const size_t p = static_cast<size_t>(iy) * static_cast<size_t>(W) + static_cast<size_t>(ix);
        const double z = a.z() + u * (b.z() - a.z());
        if (z <= zbuf[p] + bias) put(img, ix, iy, ec);
      }
    };
    for (size_t mi = 0; mi < meshes.size(); ++mi) {
      const RenderMesh& m = meshes[mi];
      if (!m.lines.empty()) {
        for (const auto& l : m.lines) {
          const size_t u = static_cast<size_t>(l[0]), v = static_cast<size_t>(l[1]);
          if (ok[mi][u] && ok[mi][v]) line(pix[mi][u], pix[mi][v]);
        }
      } else {
        for (size_t f = 0; f < m.mesh.faces.size(); ++f) {
          if (!drawn[mi][f]) continue;
          const auto& t = m.mesh.faces[f];
          for (int k = 0; k < 3; ++k) {
            line(pix[mi][static_cast<size_t>(t[static_cast<size_t>(k)])],
                 pix[mi][static_cast<size_t>(t[static_cast<size_t>((k + 1) % 3)])]);
          }
        }
      }
    }
  }
  return img;
}

RenderMesh stitch_mesh_render_mesh(const StitchMesh& sm, const StitchColourOptions& o) {
  if (o.course_colours.empty()) throw InvalidInput("stitch mesh colours: course_colours is empty");
  RenderMesh out;
  out.name = "stitch mesh";
  out.mesh.vertices = sm.vertices;
  const int nv = sm.num_vertices();
  std::vector<std::array<int, 2>> lines;
  for (int s = 0; s < sm.num_stitches(); ++s) {
    const Stitch& st = sm.stitches[static_cast<size_t>(s)];
    const int nc = st.corners();
    for (int k = 0; k < nc; ++k) {
      if (st.v[static_cast<size_t>(k)] < 0 || st.v[static_cast<size_t>(k)] >= nv) {
        throw InvalidInput(fmt::format("stitch {}: corner {} has vertex index {} out of range [0, {})", s, k,
                                       st.v[static_cast<size_t>(k)], nv));
      }
    }
    RenderColour c;
    if (is_shaping(st.type)) {
      c = o.type_colours[static_cast<size_t>(st.type)];
    } else {
      const size_t n = o.course_colours.size();
      c = o.course_colours[st.course < 0 ? 0 : static_cast<size_t>(st.course) % n];
    }
    const auto& v = st.v;
    if (nc == 4) {
      const double d02 =
          (sm.vertices[static_cast<size_t>(v[0])] - sm.vertices[static_cast<size_t>(v[2])]).squaredNorm();
      const double d13 =
          (sm.vertices[static_cast<size_t>(v[1])] - sm.vertices[static_cast<size_t>(v[3])]).squaredNorm();
      if (d02 <= d13) {
        out.mesh.faces.push_back({v[0], v[1], v[2]});
        out.mesh.faces.push_back({v[0], v[2], v[3]});
      } else {
        out.mesh.faces.push_back({v[0], v[1], v[3]});
        out.mesh.faces.push_back({v[1], v[2], v[3]});
      }
      out.face_colours.push_back(c);
      out.face_colours.push_back(c);
    } else {
      out.mesh.faces.push_back({v[0], v[1], v[2]});
      out.face_colours.push_back(c);
    }
    for (int k = 0; k < nc; ++k) {
      const int a = v[static_cast<size_t>(k)], b = v[static_cast<size_t>((k + 1) % nc)];
      lines.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  out.lines = std::move(lines);
  out.normals = vertex_normals(out.mesh);
  return out;
}

}  // namespace knitforge

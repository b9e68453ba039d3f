#include "knitforge/design/flatten/flattening_distortion.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <Eigen/SVD>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {
double signed_area_2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e1 = b - a;
  const Vec2 e2 = c - a;
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}
}  // namespace

double FaceDistortion::dominant_log() const {
  const double l1 = std::log(std::max(sigma1, 1e-300));
  const double l2 = std::log(std::max(sigma2, 1e-300));
  return std::abs(l1) >= std::abs(l2) ? l1 : l2;
}

Mat2 triangle_map(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& q0, const Vec2& q1,
                  const Vec2& q2) {
  const Vec3 e1 = p1 - p0;
  const Vec3 e2 = p2 - p0;
  const double l1 = e1.norm();
  const double up = l1 > 0.0 ? e1.cross(e2).norm() / l1 : 0.0;
  if (!(l1 > 0.0) || !(up > 0.0)) return Mat2::Zero();
  Mat2 P;
  P << l1, e2.dot(e1) / l1, 0.0, up;
  Mat2 Q;
  Q.col(0) = q1 - q0;
  Q.col(1) = q2 - q0;
  return Q * P.inverse();
}

FaceDistortion decompose_map(const Mat2& T) {
  FaceDistortion d;
  Eigen::JacobiSVD<Mat2> svd(T, Eigen::ComputeFullU | Eigen::ComputeFullV);
  d.sigma1 = svd.singularValues()[0];
  d.sigma2 = svd.singularValues()[1];
  d.dir1 = svd.matrixU().col(0);
  d.dir2 = svd.matrixU().col(1);
  d.flipped = !(T.determinant() > 0.0);
  return d;
}

std::vector<FaceDistortion> flattening_distortion(const TriMesh& mesh, const std::vector<Vec2>& uv) {
  if (static_cast<int>(uv.size()) != mesh.num_vertices()) {
    throw InvalidInput(fmt::format("flattening_distortion: {} 2D positions for {} vertices", uv.size(),
                                   mesh.num_vertices()));
  }
  std::vector<FaceDistortion> out(mesh.faces.size());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    for (int v : t) {
      if (v < 0 || v >= mesh.num_vertices()) {
        throw InvalidInput(fmt::format("flattening_distortion: face {} uses vertex {} out of range", f, v));
      }
    }
    out[f] = decompose_map(triangle_map(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]],
                                        uv[t[0]], uv[t[1]], uv[t[2]]));
  }
  return out;
}

DistortionStats distortion_stats(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                 const std::vector<FaceDistortion>& faces) {
  if (static_cast<int>(faces.size()) != mesh.num_faces() ||
      static_cast<int>(uv.size()) != mesh.num_vertices()) {
    throw InvalidInput("distortion_stats: sizes of faces / uv do not match the mesh");
  }
  DistortionStats s;
  double sum = 0.0;
  double sum_sq = 0.0;
  bool first = true;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const double a =
        0.5 *
        (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
    const Vec2 e1 = uv[t[1]] - uv[t[0]];
    const Vec2 e2 = uv[t[2]] - uv[t[0]];
    s.area_2d += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    if (faces[f].flipped) ++s.flipped_faces;
    if (!(a > 0.0)) continue;
    const double l1 = std::log(std::max(faces[f].sigma1, 1e-300));
    const double l2 = std::log(std::max(faces[f].sigma2, 1e-300));
    s.area_3d += a;
    sum += a * (l1 + l2);
    sum_sq += a * (l1 * l1 + l2 * l2);
    if (first) {
      s.min_log_sigma = l2;
      s.max_log_sigma = l1;
      first = false;
    } else {
      s.min_log_sigma = std::min(s.min_log_sigma, l2);
      s.max_log_sigma = std::max(s.max_log_sigma, l1);
    }
  }
  if (s.area_3d > 0.0) {
    s.mean_log_sigma = sum / (2.0 * s.area_3d);
    s.rms_log_sigma = std::sqrt(sum_sq / (2.0 * s.area_3d));
  }
  return s;
}

std::vector<Rgb8> distortion_colours(const std::vector<FaceDistortion>& faces, double saturation) {
  if (!(saturation > 0.0)) throw InvalidInput("distortion_colours: saturation must be > 0");
  std::vector<Rgb8> out;
  out.reserve(faces.size());
  for (const auto& d : faces) {
    const double v = d.dominant_log();
    const double t = std::clamp(std::abs(v) / saturation, 0.0, 1.0);
    const auto fade = static_cast<uint8_t>(std::lround(255.0 * (1.0 - t)));
    if (v < 0.0) {
      out.push_back(Rgb8{fade, fade, 255});  // compression: blue
    } else {
      out.push_back(Rgb8{255, fade, fade});  // stretching: red
    }
  }
  return out;
}

std::vector<double> vertex_distortion_energy(const TriMesh& mesh, const std::vector<FaceDistortion>& faces) {
  if (static_cast<int>(faces.size()) != mesh.num_faces()) {
    throw InvalidInput("vertex_distortion_energy: one distortion per face needed");
  }
  std::vector<double> num(mesh.vertices.size(), 0.0);
  std::vector<double> den(mesh.vertices.size(), 0.0);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const double a =
        0.5 *
        (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
    const double l1 = std::log(std::max(faces[f].sigma1, 1e-300));
    const double l2 = std::log(std::max(faces[f].sigma2, 1e-300));
    for (int v : t) {
      num[v] += a * (l1 * l1 + l2 * l2);
      den[v] += a;
    }
  }
  for (size_t v = 0; v < num.size(); ++v) num[v] = den[v] > 0.0 ? num[v] / den[v] : 0.0;
  return num;
}

double patch_max_abs_log_sigma(const TriMesh& mesh, const std::vector<FaceDistortion>& faces, double radius) {
  const int nf = mesh.num_faces();
  if (static_cast<int>(faces.size()) != nf) throw InvalidInput("patch_max_abs_log_sigma: one distortion per face needed");
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw InvalidInput("patch_max_abs_log_sigma: the radius must be finite and >= 0");
  std::vector<Vec3> centre(nf);
  std::vector<double> area(nf), l1(nf), l2(nf);
  // Faces around each vertex, in increasing order (compressed rows).
  const size_t nv = mesh.vertices.size();
  std::vector<int> vf_start(nv + 1, 0), vf(3 * static_cast<size_t>(nf));
  for (const auto& t : mesh.faces)
    for (int v : t) ++vf_start[static_cast<size_t>(v) + 1];
  for (size_t v = 0; v < nv; ++v) vf_start[v + 1] += vf_start[v];
  {
    std::vector<int> next(vf_start.begin(), vf_start.end() - 1);
    for (int f = 0; f < nf; ++f)
      for (int v : mesh.faces[f]) vf[next[v]++] = f;
  }
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    centre[f] = (a + b + c) / 3.0;
    area[f] = 0.5 * (b - a).cross(c - a).norm();
    l1[f] = std::log(std::max(faces[f].sigma1, 1e-300));
    l2[f] = std::log(std::max(faces[f].sigma2, 1e-300));
  }
  std::vector<int> mark(nf, -1), queue;
  const double radius2 = radius * radius;
  double best = 0.0;
  for (int f = 0; f < nf; ++f) {
    queue.assign(1, f);
    mark[f] = f;
    double w = 0.0, m1 = 0.0, m2 = 0.0;
    for (size_t k = 0; k < queue.size(); ++k) {
      const int g = queue[k];
      w += area[g];
      m1 += area[g] * l1[g];
      m2 += area[g] * l2[g];
      for (int v : mesh.faces[g]) {
        for (int i = vf_start[v]; i < vf_start[v + 1]; ++i) {
          const int h = vf[i];
          if (mark[h] == f || (centre[h] - centre[f]).squaredNorm() > radius2) continue;
          mark[h] = f;
          queue.push_back(h);
        }
      }
    }
    if (w > 0.0) best = std::max({best, std::abs(m1 / w), std::abs(m2 / w)});
    else best = std::max({best, std::abs(l1[f]), std::abs(l2[f])});
  }
  return best;
}

std::string pattern_svg(const TriMesh& mesh, const std::vector<Vec2>& uv,
                        const std::vector<FaceDistortion>& faces, const std::vector<Vec2>& marks,
                        int max_glyphs) {
  if (static_cast<int>(uv.size()) != mesh.num_vertices() ||
      static_cast<int>(faces.size()) != mesh.num_faces()) {
    throw InvalidInput("pattern_svg: sizes of uv / faces do not match the mesh");
  }
  Vec2 lo(1e300, 1e300);
  Vec2 hi(-1e300, -1e300);
  for (const auto& t : mesh.faces) {
    for (int v : t) {
      lo = lo.cwiseMin(uv[v]);
      hi = hi.cwiseMax(uv[v]);
    }
  }
  if (mesh.faces.empty()) {
    lo = Vec2::Zero();
    hi = Vec2::Ones();
  }
  const double margin = 0.03 * std::max((hi - lo).maxCoeff(), 1e-9);
  lo -= Vec2(margin, margin);
  hi += Vec2(margin, margin);
  const double w = hi.x() - lo.x();
  const double h = hi.y() - lo.y();
  // y up: svg y = hi.y - y.
  auto X = [&](const Vec2& p) { return p.x() - lo.x(); };
  auto Y = [&](const Vec2& p) { return hi.y() - p.y(); };
  std::string s;
  s += fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.2f}mm\" height=\"{:.2f}mm\" "
      "viewBox=\"0 0 {:.3f} {:.3f}\">\n",
      w, h, w, h);
  s += "<title>knitforge flattened pattern (blue: compression, red: stretching)</title>\n";
  s += fmt::format("<rect x=\"0\" y=\"0\" width=\"{:.3f}\" height=\"{:.3f}\" fill=\"white\"/>\n", w, h);
  const auto colours = distortion_colours(faces);
  s += "<g stroke-width=\"0.05\">\n";
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const auto& c = colours[f];
    s += fmt::format(
        "<polygon points=\"{:.3f},{:.3f} {:.3f},{:.3f} {:.3f},{:.3f}\" fill=\"#{:02x}{:02x}{:02x}\" "
        "stroke=\"#{:02x}{:02x}{:02x}\"/>\n",
        X(uv[t[0]]), Y(uv[t[0]]), X(uv[t[1]]), Y(uv[t[1]]), X(uv[t[2]]), Y(uv[t[2]]), c[0], c[1], c[2], c[0],
        c[1], c[2]);
  }
  s += "</g>\n";
  // Boundary edges: half-edges without a partner.
  std::vector<std::array<int, 3>> edges;  // (min, max, from)
  edges.reserve(mesh.faces.size() * 3);
  for (const auto& t : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), a});
    }
  }
  std::sort(edges.begin(), edges.end());
  const double stroke = 0.002 * std::max(w, h);
  s += fmt::format("<g stroke=\"black\" stroke-width=\"{:.3f}\" fill=\"none\">\n", stroke);
  for (size_t i = 0; i < edges.size(); ++i) {
    const bool paired =
        (i + 1 < edges.size() && edges[i + 1][0] == edges[i][0] && edges[i + 1][1] == edges[i][1]) ||
        (i > 0 && edges[i - 1][0] == edges[i][0] && edges[i - 1][1] == edges[i][1]);
    if (paired) continue;
    const Vec2& a = uv[edges[i][0]];
    const Vec2& b = uv[edges[i][1]];
    s += fmt::format("<line x1=\"{:.3f}\" y1=\"{:.3f}\" x2=\"{:.3f}\" y2=\"{:.3f}\"/>\n", X(a), Y(a), X(b),
                     Y(b));
  }
  s += "</g>\n";
  if (max_glyphs > 0 && mesh.num_faces() > 0) {
    const int step = std::max(1, (mesh.num_faces() + max_glyphs - 1) / max_glyphs);
    s += fmt::format("<g stroke=\"#333333\" stroke-width=\"{:.3f}\">\n", 0.6 * stroke);
    for (int f = 0; f < mesh.num_faces(); f += step) {
      const auto& t = mesh.faces[f];
      const Vec2 c = (uv[t[0]] + uv[t[1]] + uv[t[2]]) / 3.0;
      const double size = 0.3 * std::sqrt(std::abs(signed_area_2d(uv[t[0]], uv[t[1]], uv[t[2]])) + 1e-300);
      const FaceDistortion& d = faces[f];
      for (int k = 0; k < 2; ++k) {
        const Vec2 half = (k == 0 ? d.sigma1 * d.dir1 : d.sigma2 * d.dir2) * size;
        const Vec2 a = c - half;
        const Vec2 b = c + half;
        s += fmt::format("<line x1=\"{:.3f}\" y1=\"{:.3f}\" x2=\"{:.3f}\" y2=\"{:.3f}\"/>\n", X(a), Y(a),
                         X(b), Y(b));
      }
    }
    s += "</g>\n";
  }
  if (!marks.empty()) {
    s += "<g fill=\"black\">\n";
    for (const auto& m : marks) {
      s += fmt::format("<circle cx=\"{:.3f}\" cy=\"{:.3f}\" r=\"{:.3f}\"/>\n", X(m), Y(m), 4.0 * stroke);
    }
    s += "</g>\n";
  }
  s += "</svg>\n";
  return s;
}

}  // namespace knitforge

#include "knitforge/geometry/mesh_measures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "knitforge/util/errors.h"

namespace knitforge {

Vec3 triangle_area_vector(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b - a).cross(c - a);
}

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * triangle_area_vector(a, b, c).norm();
}

Vec3 face_normal(const TriMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  const Vec3 n = triangle_area_vector(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

std::vector<Vec3> face_normals(const TriMesh& mesh) {
  std::vector<Vec3> out(mesh.faces.size());
  for (int f = 0; f < mesh.num_faces(); ++f) out[f] = face_normal(mesh, f);
  return out;
}

std::vector<double> face_areas(const TriMesh& mesh) {
  std::vector<double> out(mesh.faces.size());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    out[f] = triangle_area(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  }
  return out;
}

double total_area(const TriMesh& mesh) {
  double sum = 0.0;
  for (double a : face_areas(mesh)) sum += a;
  return sum;
}

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> out(mesh.vertices.size(), Vec3::Zero());
  for (const auto& t : mesh.faces) {
    const Vec3 n = triangle_area_vector(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    for (int v : t) out[v] += n;
  }
  for (Vec3& n : out) {
    const double len = n.norm();
    if (len > 0.0) n /= len;
  }
  return out;
}

BoundingBox bounding_box(const TriMesh& mesh) {
  if (mesh.vertices.empty()) throw InvalidInput("bounding_box: the mesh has no vertices");
  BoundingBox box{mesh.vertices[0], mesh.vertices[0]};
  for (const Vec3& p : mesh.vertices) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

std::vector<double> edge_lengths(const TriMesh& mesh) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * mesh.faces.size());
  for (const auto& t : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> out;
  out.reserve(edges.size());
  for (const auto& [a, b] : edges) out.push_back((mesh.vertices[a] - mesh.vertices[b]).norm());
  return out;
}

EdgeLengthStats edge_length_stats(const TriMesh& mesh) {
  const std::vector<double> lengths = edge_lengths(mesh);
  EdgeLengthStats s;
  if (lengths.empty()) return s;
  s.count = static_cast<int>(lengths.size());
  s.min = std::numeric_limits<double>::infinity();
  s.max = 0.0;
  double sum = 0.0;
  for (double l : lengths) {
    s.min = std::min(s.min, l);
    s.max = std::max(s.max, l);
    sum += l;
  }
  s.mean = sum / static_cast<double>(lengths.size());
  return s;
}

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

namespace {

// Three doubles with the arithmetic closest_triangle_point() needs, in the
// operations and order of the Eigen expressions it replaced (same bits; an
// Eigen sum of three is (x0 + x1) + x2). Closest points are queried millions
// of times (body fitting, surface distances), and unoptimised Eigen
// temporaries were most of their time under the sanitizers.
struct D3 {
  double x, y, z;
  explicit D3(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
  D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  D3 operator-(const D3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  D3 operator+(const D3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  D3 operator*(double s) const { return {x * s, y * s, z * s}; }
  double dot(const D3& o) const { return (x * o.x + y * o.y) + z * o.z; }
  double squared_norm() const { return dot(*this); }
  D3 cross(const D3& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
  Vec3 vec() const { return {x, y, z}; }
};

}  // namespace

// Ericson, Real-Time Collision Detection, 5.1.5 (Voronoi regions of the
// triangle), with a fallback to the edges for degenerate triangles.
TrianglePoint closest_triangle_point(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  using R = TrianglePoint::Region;
  auto at_vertex = [](const Vec3& q, int k) {
    TrianglePoint t{q, Vec3::Zero(), R::Vertex, k};
    t.bary[k] = 1.0;
    return t;
  };
  // Point q on edge k (from corner k to corner k+1) at parameter s.
  auto on_edge = [](const Vec3& q, int k, double s) {
    TrianglePoint t{q, Vec3::Zero(), R::Edge, k};
    t.bary[k] = 1.0 - s;
    t.bary[(k + 1) % 3] = s;
    return t;
  };
  const D3 P(p), A(a), B(b), C(c);
  const D3 ab = B - A, ac = C - A, ap = P - A;
  const double n2 = ab.cross(ac).squared_norm();
  const double ab2 = ab.squared_norm(), ac2 = ac.squared_norm();
  if (!(n2 > 1e-24 * std::max(ab2, ac2) * std::max(ab2, ac2))) {
    const Vec3* corner[3] = {&a, &b, &c};
    TrianglePoint best;
    double best2 = INFINITY;
    for (int k = 0; k < 3; ++k) {
      const Vec3& u = *corner[k];
      const Vec3& v = *corner[(k + 1) % 3];
      const Vec3 d = v - u;
      const double l2 = d.squaredNorm();
      const double s = l2 > 0 ? std::clamp((p - u).dot(d) / l2, 0.0, 1.0) : 0.0;
      const TrianglePoint t = on_edge(l2 > 0 ? Vec3(u + s * d) : u, k, s);
      const double e2 = (t.point - p).squaredNorm();
      if (e2 < best2) best2 = e2, best = t;
    }
    return best;
  }
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return at_vertex(a, 0);
  const D3 bp = P - B;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return at_vertex(b, 1);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double s = d1 / (d1 - d3);
    return on_edge((A + ab * s).vec(), 0, s);
  }
  const D3 cp = P - C;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return at_vertex(c, 2);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double s = d2 / (d2 - d6);
    return on_edge((A + ac * s).vec(), 2, 1.0 - s);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double s = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return on_edge((B + (C - B) * s).vec(), 1, s);
  }
  const double denom = 1.0 / (va + vb + vc);
  TrianglePoint t;
  t.bary = Vec3(1.0 - (vb + vc) * denom, vb * denom, vc * denom);
  t.point = ((A + ab * (vb * denom)) + ac * (vc * denom)).vec();
  t.region = R::Face;
  return t;
}

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return closest_triangle_point(p, a, b, c).point;
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (closest_point_on_triangle(p, a, b, c) - p).norm();
}

}  // namespace knitforge

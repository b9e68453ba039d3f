#include "knitforge/geometry/marching_tetrahedra.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

// Corner c of a cube: bit 0 = +x, bit 1 = +y, bit 2 = +z.
// The six Kuhn tetrahedra: 0 -> 0 + e_a -> 0 + e_a + e_b -> 7.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

}  // namespace

TriMesh marching_tetrahedra(const ImplicitFunction& f, const BoundingBox& box, double cell) {
  if (!(cell > 0.0) || !std::isfinite(cell))
    throw InvalidInput(fmt::format("marching_tetrahedra: cell size {} must be positive and finite", cell));
  const Vec3 size = box.size();
  if (!(size.minCoeff() > 0.0) || !size.allFinite())
    throw InvalidInput("marching_tetrahedra: the box is empty or not finite");
  const int nx = static_cast<int>(std::ceil(size.x() / cell)) + 1;
  const int ny = static_cast<int>(std::ceil(size.y() / cell)) + 1;
  const int nz = static_cast<int>(std::ceil(size.z() / cell)) + 1;
  const double nodes = static_cast<double>(nx) * ny * nz;
  if (nodes > 5e7)
    throw InvalidInput(fmt::format("marching_tetrahedra: a grid of {} x {} x {} nodes is too large (limit 50 "
                                   "million); use a larger cell",
                                   nx, ny, nz));
  auto id = [&](int i, int j, int k) { return (static_cast<int64_t>(k) * ny + j) * nx + i; };
  auto pos = [&](int i, int j, int k) { return Vec3(box.min.x() + i * cell, box.min.y() + j * cell, box.min.z() + k * cell); };
  std::vector<double> value(static_cast<size_t>(nodes));
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const Vec3 p = pos(i, j, k);
        const double v = f(p);
        if (!std::isfinite(v))
          throw InvalidInput(fmt::format("marching_tetrahedra: f({}, {}, {}) is not finite", p.x(), p.y(), p.z()));
        value[static_cast<size_t>(id(i, j, k))] = v;
      }
    }
  }
  TriMesh mesh;
  std::unordered_map<uint64_t, int> edge_vertex;
  const uint64_t n64 = static_cast<uint64_t>(nodes);
  auto vertex_on = [&](int64_t a, int64_t b, const Vec3& pa, const Vec3& pb) {
    const int64_t lo = std::min(a, b), hi = std::max(a, b);
    const uint64_t key = static_cast<uint64_t>(lo) * n64 + static_cast<uint64_t>(hi);
    auto [it, fresh] = edge_vertex.try_emplace(key, mesh.num_vertices());
    if (fresh) {
      const double fa = value[static_cast<size_t>(a)], fb = value[static_cast<size_t>(b)];
      const double t = std::clamp(fa / (fa - fb), 1e-3, 1.0 - 1e-3);
      mesh.vertices.push_back(pa + t * (pb - pa));
    }
    return it->second;
  };
  for (int k = 0; k + 1 < nz; ++k) {
    for (int j = 0; j + 1 < ny; ++j) {
      for (int i = 0; i + 1 < nx; ++i) {
        int64_t cid[8];
        Vec3 cp[8];
        bool any_in = false, any_out = false;
        for (int c = 0; c < 8; ++c) {
          const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
          cid[c] = id(i + di, j + dj, k + dk);
          cp[c] = pos(i + di, j + dj, k + dk);
          (value[static_cast<size_t>(cid[c])] < 0.0 ? any_in : any_out) = true;
        }
        if (!any_in || !any_out) continue;
        for (const auto& tet : kTets) {
          int v[4] = {tet[0], tet[1], tet[2], tet[3]};
          // Make the tetrahedron positively oriented.
          if ((cp[v[1]] - cp[v[0]]).cross(cp[v[2]] - cp[v[0]]).dot(cp[v[3]] - cp[v[0]]) < 0.0) std::swap(v[2], v[3]);
          int inside[4], outside[4], ni = 0, no = 0;
          for (int q = 0; q < 4; ++q) (value[static_cast<size_t>(cid[v[q]])] < 0.0 ? inside[ni++] : outside[no++]) = q;
          if (ni == 0 || no == 0) continue;
          auto ev = [&](int qa, int qb) { return vertex_on(cid[v[qa]], cid[v[qb]], cp[v[qa]], cp[v[qb]]); };
          // Even permutation (a, b, c, d) of (0, 1, 2, 3) with the given first elements.
          auto even = [](int a, int b, int& c, int& d) {
            int rest[2], n = 0;
            for (int q = 0; q < 4; ++q)
              if (q != a && q != b) rest[n++] = q;
            c = rest[0];
            d = rest[1];
            // parity of (a, b, c, d)
            const int perm[4] = {a, b, c, d};
            int inv = 0;
            for (int x = 0; x < 4; ++x)
              for (int y = x + 1; y < 4; ++y) inv += perm[x] > perm[y];
            if (inv % 2) std::swap(c, d);
          };
          if (ni == 1 || no == 1) {
            const bool lone_inside = ni == 1;
            const int a = lone_inside ? inside[0] : outside[0];
            const int b = a == 0 ? 1 : 0;
            int c = -1, d = -1;
            even(a, b, c, d);
            const int e1 = ev(a, b), e2 = ev(a, c), e3 = ev(a, d);
            if (lone_inside) mesh.faces.push_back({e1, e2, e3});
            else mesh.faces.push_back({e1, e3, e2});
          } else {
            const int a = inside[0];
            int b = inside[1], c = -1, d = -1;
            even(a, b, c, d);
            // For a positive (a, b, c, d) with a, b inside, the quad (ac, ad, bd, bc)
            // faces the outside pair (c, d).
            const int q0 = ev(a, c), q1 = ev(a, d), q2 = ev(b, d), q3 = ev(b, c);
            const Vec3& p0 = mesh.vertices[static_cast<size_t>(q0)];
            const Vec3& p1 = mesh.vertices[static_cast<size_t>(q1)];
            const Vec3& p2 = mesh.vertices[static_cast<size_t>(q2)];
            const Vec3& p3 = mesh.vertices[static_cast<size_t>(q3)];
            if ((p0 - p2).squaredNorm() <= (p1 - p3).squaredNorm()) {
              mesh.faces.push_back({q0, q1, q2});
              mesh.faces.push_back({q0, q2, q3});
            } else {
              mesh.faces.push_back({q0, q1, q3});
              mesh.faces.push_back({q1, q2, q3});
            }
          }
        }
      }
    }
  }
  return mesh;
}

TriMesh largest_component(const TriMesh& mesh) {
  UnionFind uf(mesh.num_vertices());
  for (const auto& t : mesh.faces) {
    uf.unite(t[0], t[1]);
    uf.unite(t[0], t[2]);
  }
  std::unordered_map<int, int> count;
  for (const auto& t : mesh.faces) ++count[uf.find(t[0])];
  int best = -1, best_count = 0;
  for (const auto& t : mesh.faces) {
    const int r = uf.find(t[0]);
    if (count[r] > best_count) {
      best_count = count[r];
      best = r;
    }
  }
  TriMesh out;
  std::vector<int> map(static_cast<size_t>(mesh.num_vertices()), -1);
  for (const auto& t : mesh.faces) {
    if (uf.find(t[0]) != best) continue;
    std::array<int, 3> nt{};
    for (int q = 0; q < 3; ++q) {
      int& m = map[static_cast<size_t>(t[static_cast<size_t>(q)])];
      if (m < 0) {
        m = out.num_vertices();
        out.vertices.push_back(mesh.vertices[static_cast<size_t>(t[static_cast<size_t>(q)])]);
      }
      nt[static_cast<size_t>(q)] = m;
    }
    out.faces.push_back(nt);
  }
  return out;
}

}  // namespace knitforge

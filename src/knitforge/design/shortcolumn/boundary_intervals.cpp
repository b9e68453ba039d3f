#include "knitforge/design/shortcolumn/boundary_intervals.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/number_list.h"

namespace knitforge {

int BoundaryParameterisation::nearest(double u) const {
  double w = u - std::floor(u);
  if (!(w >= 0.0 && w < 1.0)) w = 0.0;
  // t is increasing from 0: binary search, then compare the two neighbours
  // (and the wrap to 1 = entry 0).
  const auto it = std::upper_bound(t.begin(), t.end(), w);
  const int hi = static_cast<int>(it - t.begin());  // first entry with t > w (size() when none)
  const int lo = hi - 1;                            // t[lo] <= w
  const double d_lo = w - t[static_cast<size_t>(lo)];
  const double d_hi = (hi < size() ? t[static_cast<size_t>(hi)] : 1.0) - w;
  if (d_lo <= d_hi) return lo;
  return hi < size() ? hi : 0;
}

double BoundaryParameterisation::unwrapped(int k, double u) const {
  double x = t[static_cast<size_t>(k)];
  while (x < u) x += 1.0;
  while (x >= u + 1.0) x -= 1.0;
  return x;
}

BoundaryParameterisation parameterise_boundary(const TriMesh& mesh) {
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  const auto loops = he.boundary_loops();
  if (loops.size() != 1) {
    throw TopologyError(fmt::format(
        "boundary parameterisation: the surface has {} boundary loops; the short-column route needs a disk "
        "(exactly one boundary loop): cut it open first",
        loops.size()));
  }
  const std::vector<int>& loop = loops.front();
  size_t start = 0;
  for (size_t k = 1; k < loop.size(); ++k) {
    const Vec3& p = mesh.vertices[loop[k]];
    const Vec3& q = mesh.vertices[loop[start]];
    const bool better = p.x() != q.x()   ? p.x() > q.x()
                        : p.y() != q.y() ? p.y() < q.y()
                        : p.z() != q.z() ? p.z() < q.z()
                                         : loop[k] < loop[start];
    if (better) start = k;
  }
  BoundaryParameterisation b;
  b.loop.reserve(loop.size());
  for (size_t k = 0; k < loop.size(); ++k) b.loop.push_back(loop[(start + k) % loop.size()]);
  std::vector<double> s(loop.size(), 0.0);
  for (size_t k = 1; k < b.loop.size(); ++k)
    s[k] = s[k - 1] + (mesh.vertices[b.loop[k]] - mesh.vertices[b.loop[k - 1]]).norm();
  b.length = s.back() + (mesh.vertices[b.loop.front()] - mesh.vertices[b.loop.back()]).norm();
  if (!(b.length > 0.0)) throw InvalidInput("boundary parameterisation: the boundary loop has zero length");
  b.t.resize(s.size());
  for (size_t k = 0; k < s.size(); ++k) b.t[k] = s[k] / b.length;
  return b;
}

bool is_feasible(const BoundaryVector& b) {
  for (double x : b)
    if (!std::isfinite(x)) return false;
  return 0.0 <= b[0] && b[0] <= b[1] && b[1] < b[2] && b[2] <= b[3] && b[3] < 1.0 + b[0] && 1.0 + b[0] < 2.0;
}

std::string format_boundary_vector(const BoundaryVector& b) {
  return fmt::format("{:.6f},{:.6f},{:.6f},{:.6f}", b[0], b[1], b[2], b[3]);
}

BoundaryVector parse_boundary_vector(const std::string& text) {
  const std::vector<double> v = parse_number_list(text, fmt::format("--bc '{}'", text));
  if (v.size() != 4) {
    throw InvalidInput(fmt::format("--bc '{}': give four numbers b0,b1,b2,b3 (boundary parameters)", text));
  }
  const BoundaryVector b{v[0], v[1], v[2], v[3]};
  if (!is_feasible(b)) {
    throw InvalidInput(fmt::format(
        "--bc '{}': not in the feasible set 0 <= b0 <= b1 < b2 <= b3 < 1 + b0 < 2 (seed eq. 3.8; the "
        "boundary is parameterised anticlockwise from 0 to 1, values above 1 wrap around)",
        text));
  }
  return b;
}

namespace {

/// Loop indices from `first` forward to `last` (inclusive, circular).
std::vector<int> run(int first, int last, int n) {
  std::vector<int> r;
  for (int k = first;; k = (k + 1) % n) {
    r.push_back(k);
    if (k == last || static_cast<int>(r.size()) == n) break;
  }
  return r;
}

}  // namespace

DirichletSets dirichlet_sets(const TriMesh& mesh, const BoundaryParameterisation& boundary,
                             const BoundaryVector& b) {
  if (!is_feasible(b)) {
    throw InvalidInput(fmt::format("Dirichlet regions: b = ({}) is not in the feasible set 0 <= b0 <= b1 < b2 <= "
                                   "b3 < 1 + b0 < 2 (seed eq. 3.8)",
                                   format_boundary_vector(b)));
  }
  const int n = boundary.size();
  if (n < 3) throw InvalidInput(fmt::format("Dirichlet regions: the boundary has only {} vertices", n));
  // Faces at each boundary vertex, for the one-triangle test.
  std::vector<std::vector<int>> faces_at(static_cast<size_t>(mesh.num_vertices()));
  {
    std::vector<char> on(static_cast<size_t>(mesh.num_vertices()), 0);
    for (int v : boundary.loop) on[static_cast<size_t>(v)] = 1;
    for (int f = 0; f < mesh.num_faces(); ++f)
      for (int v : mesh.faces[f])
        if (on[static_cast<size_t>(v)]) faces_at[static_cast<size_t>(v)].push_back(f);
  }
  auto in_one_triangle = [&](const std::vector<int>& zero, const std::vector<int>& one) {
    std::set<int> u;
    for (int k : zero) u.insert(boundary.loop[static_cast<size_t>(k)]);
    for (int k : one) u.insert(boundary.loop[static_cast<size_t>(k)]);
    if (u.size() > 3) return false;
    for (int f : faces_at[static_cast<size_t>(*u.begin())]) {
      bool all = true;
      for (int v : u) all = all && std::find(mesh.faces[f].begin(), mesh.faces[f].end(), v) != mesh.faces[f].end();
      if (all) return true;
    }
    return false;
  };

  DirichletSets d;
  const std::vector<int> zero = run(boundary.nearest(b[0]), boundary.nearest(b[1]), n);
  std::vector<char> in_zero(static_cast<size_t>(n), 0);
  for (int k : zero) in_zero[static_cast<size_t>(k)] = 1;
  const int one_first = boundary.nearest(b[2]);
  const std::vector<int> one0 = run(one_first, boundary.nearest(b[3]), n);
  const int len = static_cast<int>(one0.size());
  std::vector<int> one;
  for (int shift = 0; shift < n; ++shift) {
    std::vector<int> cand;
    for (int k : run((one_first + shift) % n, (one_first + shift + len - 1) % n, n))
      if (!in_zero[static_cast<size_t>(k)]) cand.push_back(k);
    // The remaining run must be contiguous (it is unless it wrapped over R_s).
    bool contiguous = !cand.empty();
    for (size_t k = 1; contiguous && k < cand.size(); ++k) contiguous = cand[k] == (cand[k - 1] + 1) % n;
    if (contiguous && !in_one_triangle(zero, cand)) {
      one = std::move(cand);
      d.adjusted = shift > 0 || static_cast<int>(one.size()) != len;
      break;
    }
  }
  if (one.empty()) {
    throw TopologyError(fmt::format(
        "Dirichlet regions: no placement of R_e next to R_s on a boundary of {} vertices; the boundary is too "
        "coarse for b = ({})",
        n, format_boundary_vector(b)));
  }
  d.zero_first = zero.front();
  d.zero_last = zero.back();
  d.one_first = one.front();
  d.one_last = one.back();
  for (int k : zero) d.zero.push_back(boundary.loop[static_cast<size_t>(k)]);
  for (int k : one) d.one.push_back(boundary.loop[static_cast<size_t>(k)]);
  return d;
}

}  // namespace knitforge

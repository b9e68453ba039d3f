#include "knitforge/design/shortcolumn/divergence_metric.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

DivergenceOperator::DivergenceOperator(const TriMesh& mesh, const DivergenceOptions& options)
    : options_(options), faces_(mesh.faces) {
  if (mesh.num_faces() == 0) throw InvalidInput("divergence metric: the mesh has no faces");
  const int n = mesh.num_vertices();
  for (int v = 0; v < n; ++v)
    if (!mesh.vertices[v].allFinite())
      throw InvalidInput(fmt::format("divergence metric: vertex {} has a non-finite coordinate", v));
  if (!(options.gradient_epsilon >= 0.0) || !std::isfinite(options.gradient_epsilon))
    throw InvalidInput("divergence metric: gradient_epsilon must be finite and >= 0");
  const Halfedges he = build_halfedges(n, mesh.faces);  // validates indices and manifoldness
  vertex_area_ = mixed_voronoi_areas(mesh);
  ring_area_.assign(static_cast<size_t>(n), 0.0);
  interior_.assign(static_cast<size_t>(n), 0);
  grad_basis_.resize(faces_.size());
  normal_.resize(faces_.size());
  out_edge_.resize(faces_.size());
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (size_t f = 0; f < faces_.size(); ++f) {
    const auto& t = faces_[f];
    const Vec3 av = triangle_area_vector(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    const double two_a = av.norm();
    const Vec3 nrm = two_a > 0.0 ? Vec3(av / two_a) : Vec3::Zero();
    normal_[f] = nrm;
    area_ += 0.5 * two_a;
    for (int k = 0; k < 3; ++k) {
      const Vec3& xj = mesh.vertices[t[(k + 1) % 3]];
      const Vec3& xk = mesh.vertices[t[(k + 2) % 3]];
      const Vec3 je = nrm.cross(xj - xk);  // J e_kj, out of the 1-ring of corner k
      out_edge_[f][k] = je;
      grad_basis_[f][k] = two_a > 0.0 ? Vec3(-je / two_a) : Vec3::Zero();
      ring_area_[static_cast<size_t>(t[k])] += 0.5 * two_a;
      used[static_cast<size_t>(t[k])] = 1;
    }
  }
  for (int v = 0; v < n; ++v) interior_[static_cast<size_t>(v)] = used[static_cast<size_t>(v)] && !he.is_boundary_vertex(v);
  diagonal_ = bounding_box(mesh).diagonal();
}

void DivergenceOperator::face_directions(const std::vector<double>& field, std::vector<Vec3>& v,
                                         int& flat) const {
  if (field.size() != vertex_area_.size())
    throw InvalidInput(fmt::format("divergence metric: field has {} values for {} vertices", field.size(),
                                   vertex_area_.size()));
  double lo = field.empty() ? 0.0 : field[0], hi = lo;
  for (size_t i = 0; i < field.size(); ++i) {
    if (!std::isfinite(field[i]))
      throw InvalidInput(fmt::format("divergence metric: field value {} (vertex {}) is not finite", field[i], i));
    lo = std::min(lo, field[i]);
    hi = std::max(hi, field[i]);
  }
  // Relative to the field's range; a constant field has no direction
  // anywhere (its computed gradients are rounding noise).
  const bool constant = !(hi - lo > 1e-12 * std::max(std::abs(hi), std::abs(lo)));
  const double eps = options_.gradient_epsilon * (hi - lo) / std::max(diagonal_, 1e-300);
  v.resize(faces_.size());
  flat = 0;
  for (size_t f = 0; f < faces_.size(); ++f) {
    const auto& t = faces_[f];
    const Vec3 g = field[t[0]] * grad_basis_[f][0] + field[t[1]] * grad_basis_[f][1] + field[t[2]] * grad_basis_[f][2];
    const double len = g.norm();
    if (constant || !(len > eps) || !(len > 0.0)) {
      v[f] = Vec3::Zero();
      ++flat;
      continue;
    }
    v[f] = options_.along_gradient ? Vec3(g / len) : Vec3(normal_[f].cross(g) / len);
  }
}

DivergenceMetric DivergenceOperator::evaluate(const std::vector<double>& field) const {
  std::vector<Vec3> v;
  DivergenceMetric m;
  face_directions(field, v, m.flat_faces);
  const size_t n = vertex_area_.size();
  std::vector<double> flux(n, 0.0);
  for (size_t f = 0; f < faces_.size(); ++f)
    for (int k = 0; k < 3; ++k) flux[static_cast<size_t>(faces_[f][k])] += v[f].dot(out_edge_[f][k]);
  m.divergence.assign(n, 0.0);
  m.contribution.assign(n, 0.0);
  m.interior = interior_;
  m.area = area_;
  for (size_t i = 0; i < n; ++i) {
    if (!interior_[i] || !(ring_area_[i] > 0.0)) continue;
    const double d = flux[i] / ring_area_[i];
    m.divergence[i] = d;
    m.contribution[i] = vertex_area_[i] * std::abs(d);
    m.total += m.contribution[i];
    (d > 0.0 ? m.positive : m.negative) += m.contribution[i];
  }
  return m;
}

double DivergenceOperator::total(const std::vector<double>& field) const {
  std::vector<Vec3> v;
  int flat = 0;
  face_directions(field, v, flat);
  std::vector<double> flux(vertex_area_.size(), 0.0);
  for (size_t f = 0; f < faces_.size(); ++f)
    for (int k = 0; k < 3; ++k) flux[static_cast<size_t>(faces_[f][k])] += v[f].dot(out_edge_[f][k]);
  double total = 0.0;
  for (size_t i = 0; i < flux.size(); ++i)
    if (interior_[i] && ring_area_[i] > 0.0) total += vertex_area_[i] * std::abs(flux[i] / ring_area_[i]);
  return total;
}

DivergenceMetric divergence_metric(const TriMesh& mesh, const std::vector<double>& field,
                                   const DivergenceOptions& options) {
  return DivergenceOperator(mesh, options).evaluate(field);
}

}  // namespace knitforge

#include "knitforge/sim/energy_eval.h"

#include <algorithm>

#include <fmt/core.h>

#include "knitforge/sim/sim_model.h"
#include "knitforge/util/errors.h"

namespace knitforge {

HessianPattern::HessianPattern(int num_vertices, std::span<const std::array<int, 4>> stencils) : n_(num_vertices) {
  if (num_vertices <= 0) throw InvalidInput("Hessian pattern: no vertices");
  // Neighbours i > j of every vertex j.
  std::vector<std::vector<int>> nb(num_vertices);
  for (const auto& s : stencils) {
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        const int i = s[a], j = s[b];
        if (i < 0 || j < 0 || i <= j) continue;
        if (i >= num_vertices) {
          throw InvalidInput(fmt::format("Hessian pattern: vertex {} out of range ({} vertices)", i, num_vertices));
        }
        nb[j].push_back(i);
      }
    }
  }
  neighbour_start_.assign(num_vertices + 1, 0);
  for (int j = 0; j < num_vertices; ++j) {
    auto& v = nb[j];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    neighbour_start_[j + 1] = neighbour_start_[j] + static_cast<int>(v.size());
  }
  neighbours_.reserve(neighbour_start_.back());
  for (const auto& v : nb) neighbours_.insert(neighbours_.end(), v.begin(), v.end());
  // Columns 3j + q: the diagonal block's rows 3j + q .. 3j + 2, then 3 rows per neighbour.
  outer_.assign(3 * static_cast<size_t>(num_vertices) + 1, 0);
  for (int j = 0; j < num_vertices; ++j) {
    const int k = neighbour_start_[j + 1] - neighbour_start_[j];
    for (int q = 0; q < 3; ++q) outer_[3 * j + q + 1] = outer_[3 * j + q] + (3 - q) + 3 * k;
  }
  inner_.resize(outer_.back());
  for (int j = 0; j < num_vertices; ++j) {
    for (int q = 0; q < 3; ++q) {
      int64_t at = outer_[3 * j + q];
      for (int p = q; p < 3; ++p) inner_[at++] = 3 * j + p;
      for (int t = neighbour_start_[j]; t < neighbour_start_[j + 1]; ++t)
        for (int p = 0; p < 3; ++p) inner_[at++] = 3 * neighbours_[t] + p;
    }
  }
}

int HessianPattern::rank(int i, int j) const {
  if (i <= j || j < 0 || i >= n_) return -1;
  const auto first = neighbours_.begin() + neighbour_start_[j];
  const auto last = neighbours_.begin() + neighbour_start_[j + 1];
  const auto it = std::lower_bound(first, last, i);
  if (it == last || *it != i) return -1;
  return static_cast<int>(it - first);
}

int64_t HessianPattern::index(int i, int p, int j, int q) const {
  if (i == j) return p >= q ? outer_[3 * j + q] + (p - q) : -1;
  const int r = rank(i, j);
  if (r < 0) return -1;
  return outer_[3 * j + q] + (3 - q) + 3 * r + p;
}

SparseMatrix HessianPattern::matrix(std::span<const double> values) const {
  if (static_cast<int64_t>(values.size()) != nonzeros()) {
    throw InvalidInput(fmt::format("Hessian pattern: {} values for {} entries", values.size(), nonzeros()));
  }
  const int dim = 3 * n_;
  SparseMatrix m(dim, dim);
  m.resizeNonZeros(static_cast<Eigen::Index>(values.size()));
  std::copy(values.begin(), values.end(), m.valuePtr());
  std::copy(inner_.begin(), inner_.end(), m.innerIndexPtr());
  for (int c = 0; c <= dim; ++c) m.outerIndexPtr()[c] = static_cast<SparseMatrix::StorageIndex>(outer_[c]);
  return m;
}

std::shared_ptr<const HessianPattern> build_hessian_pattern(const SimModel& model) {
  std::vector<std::array<int, 4>> stencils;
  stencils.reserve(model.elements.size() + model.hinges.size());
  for (const MembraneElement& e : model.elements) stencils.push_back({e.v[0], e.v[1], e.v[2], -1});
  for (const BendingHinge& h : model.hinges) stencils.push_back(h.v);
  return std::make_shared<const HessianPattern>(model.num_vertices(), stencils);
}

EnergyEval::EnergyEval(int num_vertices, Derivatives what, std::shared_ptr<const HessianPattern> p)
    : pattern(std::move(p)) {
  if (what != Derivatives::Value) gradient = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(num_vertices));
  if (what == Derivatives::Hessian) {
    if (!pattern || pattern->num_vertices() != num_vertices) {
      throw InvalidInput("energy evaluation: a Hessian needs the model's pattern");
    }
    hessian_values.assign(pattern->nonzeros(), 0.0);
  }
}

void EnergyEval::add_hessian_block(int i, int j, const Mat3& block) {
  if (i < j) return;
  double* h = hessian_values.data();
  if (i == j) {
    for (int q = 0; q < 3; ++q) {
      const int64_t base = pattern->diagonal_index(3 * j + q);
      for (int p = q; p < 3; ++p) h[base + (p - q)] += block(p, q);
    }
    return;
  }
  const int r = pattern->rank(i, j);
  if (r < 0) throw InvalidInput(fmt::format("energy evaluation: block ({}, {}) is not in the Hessian pattern", i, j));
  const auto& starts = pattern->column_starts();
  for (int q = 0; q < 3; ++q) {
    const int64_t col = starts[3 * j + q] + (3 - q) + 3 * r;
    for (int p = 0; p < 3; ++p) h[col + p] += block(p, q);
  }
}

}  // namespace knitforge

#pragma once
/// \file psd_projection.h
/// Positive semi-definite projection of small symmetric element Hessians,
/// so that the sum a Newton step solves is positive semi-definite even where
/// single elements are not (compressed membranes, barriers).
///
///  - None: the exact Hessian;
///  - Clamp: eigenvalues below zero set to zero (Teran et al. 2005);
///  - Abs: eigenvalues replaced by their absolute values (Chen et al. 2024,
///    "Stabler Neo-Hookean simulation: absolute eigenvalue filtering for
///    projected Newton"), which keeps the curvature information of
///    compressed elements.
/// A matrix whose Cholesky factorisation succeeds is returned as it is
/// (it is positive definite already).

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace knitforge {

enum class PsdProjection { None, Clamp, Abs };

/// Projects the symmetric matrix `h` in place (see the file comment).
/// Returns true when it changed.
template <int N>
bool project_psd(Eigen::Matrix<double, N, N>& h, PsdProjection mode) {
  if (mode == PsdProjection::None) return false;
  if (Eigen::LLT<Eigen::Matrix<double, N, N>>(h).info() == Eigen::Success) return false;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(h);
  Eigen::Matrix<double, N, 1> l = eig.eigenvalues();
  for (int i = 0; i < N; ++i) l[i] = mode == PsdProjection::Clamp ? std::max(l[i], 0.0) : std::abs(l[i]);
  h = eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
  return true;
}

}  // namespace knitforge

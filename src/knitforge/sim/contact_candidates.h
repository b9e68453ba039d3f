#pragma once
/// \file contact_candidates.h
/// Contact candidates: every fabric vertex within the contact distance d̂ of
/// the body, with its closest body point (face, barycentrics, region). One
/// pair per vertex, the closest body point: the barrier then acts on the
/// vertex's distance to the body as a whole, so a vertex near an edge or a
/// corner of the body is not counted once per face.

#include <vector>

#include <Eigen/Core>

#include "knitforge/sim/kinematic_body.h"

namespace knitforge {

struct ContactPair {
  int vertex = -1;
  BodyPoint body;  ///< closest body point, distance2 < d̂²
};

/// Pairs of vertices of x (3n, mm) closer than dhat_mm to the body, in
/// vertex order; vertices with skip[v] != 0 (pins) are left out.
std::vector<ContactPair> find_contact_candidates(const KinematicBody& body, const Eigen::VectorXd& x, double dhat_mm,
                                                 const std::vector<char>& skip = {});

}  // namespace knitforge

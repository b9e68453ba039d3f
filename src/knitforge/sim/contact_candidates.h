#pragma once
/// \file contact_candidates.h
/// Contact candidates: every fabric vertex within the contact distance d̂ of
/// the body, with the closest point (face, barycentrics, region) of each
/// body part (kinematic_body.h) within d̂. One pair per vertex and part:
/// within a part the barrier acts on the vertex's distance to the part as a
/// whole (a vertex near an edge or a corner of it is not counted once per
/// face); a vertex between two parts (the crook of an elbow, an armpit) has
/// a pair with each and is pushed away from both. With only the closer one,
/// the other part exerts no force until the vertex becomes closer to it,
/// when the pair jumps from one part to the other: the energy is then not
/// smooth there and Newton stalls.

#include <vector>

#include <Eigen/Core>

#include "knitforge/sim/kinematic_body.h"

namespace knitforge {

struct ContactPair {
  int vertex = -1;
  BodyPoint body;  ///< closest point of one body part (body.part), distance2 < d̂²
};

/// Pairs of vertices of x (3n, mm) closer than dhat_mm to the body, in
/// vertex order and, per vertex, in part order; vertices with skip[v] != 0
/// (pins) are left out. The vertices are searched on all hardware threads
/// (util/parallel_ranges.h); the result does not depend on how many.
std::vector<ContactPair> find_contact_candidates(const KinematicBody& body, const Eigen::VectorXd& x, double dhat_mm,
                                                 const std::vector<char>& skip = {});

}  // namespace knitforge

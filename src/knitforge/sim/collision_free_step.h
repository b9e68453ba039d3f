#pragma once
/// \file collision_free_step.h
/// Continuous collision detection of fabric vertices against the body:
/// the largest fraction t in [0, 1] of a straight move x0 -> x1 such that no
/// vertex comes closer to the body than a tenth of its distance at the start
/// (so none can touch or cross it). Additive conservative advancement (Li et
/// al. 2021, "Codimensional incremental potential contact"): a vertex whose
/// distance to the body is d can move by at most l Δt in Δt (l bounds the
/// relative speed: its own displacement plus the body's vertex
/// displacements), so it advances by Δt = 0.9 (d - d₀/10) / l and measures
/// the distance again. Distances are exact point-to-triangle distances
/// through the body's tree. Deterministic; the result is the minimum over
/// vertices (searched in ranges on all hardware threads, util/parallel_ranges.h:
/// the same value as one thread's search).

#include <vector>

#include <Eigen/Core>

#include "knitforge/sim/kinematic_body.h"

namespace knitforge {

/// The body stays where it is; vertices with skip[v] != 0 are ignored.
double collision_free_step(const KinematicBody& body, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                           const std::vector<char>& skip = {});

/// The body moves linearly from its current positions to `body_end` while
/// the vertices move x0 -> x1 (the start of a time step whose body frame
/// changes). Here the bound is per body face: a face's distance to a vertex
/// changes at most at the vertex's speed plus that face's (its corners'
/// largest displacement), and every face keeps a tenth of its own start
/// distance to every vertex. With `per_vertex`, each vertex's own fraction is
/// stored there too (1 for skipped vertices).
double collision_free_step(const KinematicBody& body, const std::vector<Vec3>& body_end, const Eigen::VectorXd& x0,
                           const Eigen::VectorXd& x1, const std::vector<char>& skip = {},
                           std::vector<double>* per_vertex = nullptr);

/// The smallest distance (mm) of any vertex (not skipped) to the body, +inf
/// for an empty body or none within max_distance.
double min_distance_to_body(const KinematicBody& body, const Eigen::VectorXd& x, double max_distance,
                            const std::vector<char>& skip = {});

}  // namespace knitforge

#include "knitforge/body/fit_body.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "knitforge/body/axis_angle.h"
#include "knitforge/body/body_jacobian.h"
#include "knitforge/body/body_measurements.h"
#include "knitforge/body/one_plus_one_es.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/parallel_ranges.h"

namespace knitforge {

namespace {

// The objective at one parameter vector, optionally linearised:
// cost = sum of squared residuals (data, truncated at max distance, and
// priors); rows of A are d(residual)/d(increment).
struct Linearised {
  double cost = 0.0;
  double data_sq = 0.0;  // sum w d² over the pairs kept
  double data_w = 0.0;   // sum w over the pairs kept
  PosedBody posed;
  Eigen::MatrixXd A;
  Eigen::VectorXd r;
};

Vec3 barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
  const double d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 0.0)) return {1.0, 0.0, 0.0};
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return {1.0 - v - w, v, w};
}

class Fitter {
 public:
  Fitter(const BodyModel& model, const TriMesh& scan, const BodyParams& initial, const BodyFitOptions& o)
      : model_(model), scan_(scan), initial_(initial), o_(o), layout_(model) {
    if (o.direction != BodyFitDirection::ScanToTemplate) {
      scan_bvh_ = std::make_unique<SurfaceBvh>(scan);
      const std::vector<double> area = mixed_voronoi_areas(model.template_mesh());
      weight_.assign(area.size(), 0.0);
      double total = 0.0;
      for (size_t i = 0; i < area.size(); ++i) {
        const bool unfitted = !model.vertex_parts.empty() && is_unfitted_part(model.vertex_parts[i]);
        weight_[i] = unfitted ? 0.0 : area[i];
        total += weight_[i];
      }
      if (!(total > 0.0)) throw InvalidInput("fit_body: the model has no vertex outside the head, hands and feet");
      for (double& w : weight_) w /= total;
    }
    if (o.direction != BodyFitDirection::TemplateToScan) {
      const int n = scan.num_vertices();
      const int stride = std::max(1, (n + o.max_cloud_points - 1) / o.max_cloud_points);
      for (int i = 0; i < n; i += stride) cloud_.push_back(scan.vertices[static_cast<size_t>(i)]);
    }
  }

  Linearised evaluate(const BodyParams& p, bool jacobian) const {
    Linearised L;
    L.posed = pose_body(model_, p);
    std::vector<double> rows_r;
    std::vector<Eigen::RowVectorXd> rows_a;
    const double dmax = o_.max_distance_mm;
    if (o_.direction != BodyFitDirection::ScanToTemplate) {
      std::vector<int> ids;
      std::vector<Vec3> normals;
      std::vector<double> res;
      // The searches on all cores; the sums below in vertex order.
      std::vector<ClosestPoint> closest(static_cast<size_t>(model_.num_vertices()));
      parallel_ranges(closest.size(), 1024, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
          if (weight_[i] > 0.0) closest[i] = scan_bvh_->closest_point(L.posed.vertices[i]);
      });
      for (int i = 0; i < model_.num_vertices(); ++i) {
        const double w = weight_[static_cast<size_t>(i)];
        if (w <= 0.0) continue;
        const Vec3& v = L.posed.vertices[static_cast<size_t>(i)];
        const ClosestPoint& cp = closest[static_cast<size_t>(i)];
        if (cp.distance > dmax) {
          L.cost += w * dmax * dmax;
          continue;
        }
        Vec3 n = cp.normal;
        if (n.squaredNorm() == 0.0) n = cp.distance > 0.0 ? Vec3((v - cp.point) / cp.distance) : Vec3::UnitZ();
        const double sw = std::sqrt(w);
        const double plane = n.dot(v - cp.point);
        // The cost is the true squared distance; the step uses its
        // point-to-plane linearisation.
        L.cost += w * cp.distance * cp.distance;
        L.data_sq += w * cp.distance * cp.distance;
        L.data_w += w;
        ids.push_back(i);
        normals.push_back(sw * n);
        res.push_back(sw * plane);
      }
      if (jacobian && !ids.empty()) {
        const Eigen::MatrixXd J = posed_vertex_jacobian(model_, L.posed, ids);
        for (size_t k = 0; k < ids.size(); ++k) {
          rows_a.push_back(normals[k].transpose() * J.middleRows<3>(3 * static_cast<Eigen::Index>(k)));
          rows_r.push_back(res[k]);
        }
      }
    }
    if (o_.direction != BodyFitDirection::TemplateToScan) {
      const TriMesh body = posed_mesh(model_, L.posed);
      const SurfaceBvh bvh(body);
      const double w = 1.0 / static_cast<double>(cloud_.size());
      const double sw = std::sqrt(w);
      struct Pair {
        int face;
        Vec3 bary, n;
        double plane;
      };
      std::vector<Pair> pairs;
      std::vector<ClosestPoint> closest(cloud_.size());
      parallel_ranges(cloud_.size(), 1024, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) closest[i] = bvh.closest_point(cloud_[i]);
      });
      for (size_t i = 0; i < cloud_.size(); ++i) {
        const Vec3& p = cloud_[i];
        const ClosestPoint& cp = closest[i];
        if (cp.distance > dmax) {
          L.cost += w * dmax * dmax;
          continue;
        }
        const auto& f = model_.faces[static_cast<size_t>(cp.face)];
        Vec3 n = cp.normal;
        if (n.squaredNorm() == 0.0) n = cp.distance > 0.0 ? Vec3((cp.point - p) / cp.distance) : Vec3::UnitZ();
        L.cost += w * cp.distance * cp.distance;
        L.data_sq += w * cp.distance * cp.distance;
        L.data_w += w;
        pairs.push_back({cp.face,
                         barycentric(cp.point, body.vertices[static_cast<size_t>(f[0])],
                                     body.vertices[static_cast<size_t>(f[1])], body.vertices[static_cast<size_t>(f[2])]),
                         n, n.dot(cp.point - p)});
      }
      if (jacobian && !pairs.empty()) {
        std::unordered_map<int, int> slot;
        std::vector<int> ids;
        for (const Pair& q : pairs)
          for (int v : model_.faces[static_cast<size_t>(q.face)])
            if (slot.try_emplace(v, static_cast<int>(ids.size())).second) ids.push_back(v);
        const Eigen::MatrixXd J = posed_vertex_jacobian(model_, L.posed, ids);
        for (const Pair& q : pairs) {
          Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(layout_.size());
          const auto& f = model_.faces[static_cast<size_t>(q.face)];
          for (int k = 0; k < 3; ++k)
            row += q.bary[k] * (q.n.transpose() * J.middleRows<3>(3 * static_cast<Eigen::Index>(slot.at(f[static_cast<size_t>(k)]))));
          rows_a.push_back(sw * row);
          rows_r.push_back(sw * q.plane);
        }
      }
    }
    // Priors.
    const double sp = std::sqrt(o_.pose_prior), ss = std::sqrt(o_.shape_prior);
    for (int j = 0; j < model_.num_joints(); ++j) {
      const auto sj = static_cast<size_t>(j);
      const Vec3 d = axis_angle_from_rotation(rotation_from_axis_angle(initial_.joint_rotations[sj]).transpose() *
                                              rotation_from_axis_angle(p.joint_rotations[sj]));
      L.cost += o_.pose_prior * d.squaredNorm();
      if (jacobian) {
        for (int a = 0; a < 3; ++a) {
          Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(layout_.size());
          row(layout_.rotation(j) + a) = sp;
          rows_a.push_back(row);
          rows_r.push_back(sp * d[a]);
        }
      }
    }
    if (o_.fit_shape) {
      for (int k = 0; k < model_.num_shapes(); ++k) {
        const double d = p.shape(k) - initial_.shape(k);
        L.cost += o_.shape_prior * d * d;
        if (jacobian) {
          Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(layout_.size());
          row(layout_.shape(k)) = ss;
          rows_a.push_back(row);
          rows_r.push_back(ss * d);
        }
      }
    }
    if (jacobian) {
      L.A.resize(static_cast<Eigen::Index>(rows_a.size()), layout_.size());
      L.r.resize(static_cast<Eigen::Index>(rows_r.size()));
      for (size_t k = 0; k < rows_a.size(); ++k) {
        L.A.row(static_cast<Eigen::Index>(k)) = rows_a[k];
        L.r(static_cast<Eigen::Index>(k)) = rows_r[k];
      }
      if (!o_.fit_shape && model_.num_shapes() > 0) L.A.middleCols(layout_.shape(0), model_.num_shapes()).setZero();
    }
    return L;
  }

  BodyFitResult run() const {
    return o_.optimizer == BodyFitOptimizer::EvolutionStrategy ? run_evolution_strategy() : run_gauss_newton();
  }

 private:
  double rms(const Linearised& L) const { return L.data_w > 0.0 ? std::sqrt(L.data_sq / L.data_w) : 0.0; }

  // The unit steps of the evolution strategy (fit_body.h, BodyFitOptimizer).
  Eigen::VectorXd evolution_scales() const {
    Eigen::VectorXd s = Eigen::VectorXd::Zero(layout_.size());
    s.segment<3>(BodyParamLayout::translation()).setConstant(10.0);
    for (int j = 0; j < model_.num_joints(); ++j) s.segment<3>(layout_.rotation(j)).setConstant(0.05);
    if (o_.fit_shape) {
      for (int k = 0; k < model_.num_shapes(); ++k) {
        const double vertex_rms =
            model_.shape_basis.col(k).norm() / std::sqrt(static_cast<double>(std::max(1, model_.num_vertices())));
        if (vertex_rms > 0.0) s[layout_.shape(k)] = 10.0 / vertex_rms;
      }
    }
    return s;
  }

  BodyFitResult run_evolution_strategy() const {
    BodyFitResult out;
    out.initial_rms_mm = rms(evaluate(initial_, false));
    OnePlusOneEsOptions es;
    es.max_evaluations = o_.max_evaluations;
    es.seed = o_.seed;
    // The body's objective is ill-conditioned (a root rotation moves the
    // hands a metre away): the step shrinks to the narrow directions while
    // the cost still falls along the others, so only the stall test and the
    // budget end the search, not the step size.
    es.min_step = 1e-7;
    const OnePlusOneEsResult r = minimise_one_plus_one_es(
        [&](const Eigen::VectorXd& x) { return evaluate(apply_increment(model_, initial_, x), false).cost; },
        Eigen::VectorXd::Zero(layout_.size()), evolution_scales(), es);
    out.params = apply_increment(model_, initial_, r.x);
    const Linearised last = evaluate(out.params, false);
    out.posed = last.posed;
    out.rms_mm = rms(last);
    out.rms_history_mm = {out.rms_mm};
    out.iterations = r.evaluations - 1;
    out.evaluations = r.evaluations + 2;
    out.converged = r.converged;
    return out;
  }

  BodyFitResult run_gauss_newton() const {
    BodyFitResult out;
    BodyParams p = initial_;
    Linearised cur = evaluate(p, true);
    out.evaluations = 1;
    out.initial_rms_mm = rms(cur);
    double lambda = 1e-3;
    const int N = layout_.size();
    for (out.iterations = 0; out.iterations < o_.max_iterations;) {
      const Eigen::MatrixXd H = cur.A.transpose() * cur.A;
      const Eigen::VectorXd g = cur.A.transpose() * cur.r;
      bool accepted = false;
      Linearised next;
      BodyParams trial;
      for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
        Eigen::MatrixXd D = H;
        for (int c = 0; c < N; ++c) D(c, c) += lambda * std::max(H(c, c), 1e-9) + 1e-12;
        const Eigen::VectorXd delta = -D.ldlt().solve(g);
        if (!delta.allFinite()) {
          lambda *= 10.0;
          continue;
        }
        trial = apply_increment(model_, p, delta);
        next = evaluate(trial, false);
        ++out.evaluations;
        if (next.cost < cur.cost) {
          accepted = true;
          lambda = std::max(lambda / 3.0, 1e-9);
        } else {
          lambda *= 4.0;
        }
      }
      if (!accepted) {
        out.converged = true;  // no descent direction left at this damping
        break;
      }
      ++out.iterations;
      const double rel = (cur.cost - next.cost) / std::max(cur.cost, 1e-300);
      p = trial;
      cur = evaluate(p, true);
      ++out.evaluations;
      out.rms_history_mm.push_back(rms(cur));
      if (rel < o_.relative_tolerance) {
        out.converged = true;
        break;
      }
    }
    out.params = p;
    out.posed = cur.posed;
    out.rms_mm = rms(cur);
    return out;
  }

  const BodyModel& model_;
  const TriMesh& scan_;
  const BodyParams& initial_;
  const BodyFitOptions& o_;
  BodyParamLayout layout_;
  std::unique_ptr<SurfaceBvh> scan_bvh_;
  std::vector<double> weight_;
  std::vector<Vec3> cloud_;
};

}  // namespace

BodyFitResult fit_body(const BodyModel& model, const TriMesh& scan, const BodyParams& initial,
                       const BodyFitOptions& options) {
  if (options.max_iterations < 1)
    throw InvalidInput(fmt::format("fit_body: max_iterations {} must be at least 1", options.max_iterations));
  if (!(options.max_distance_mm > 0.0))
    throw InvalidInput(fmt::format("fit_body: max_distance_mm {} must be positive", options.max_distance_mm));
  if (!(options.pose_prior >= 0.0) || !(options.shape_prior >= 0.0))
    throw InvalidInput("fit_body: the priors must be non-negative");
  if (options.max_cloud_points < 1) throw InvalidInput("fit_body: max_cloud_points must be at least 1");
  if (options.max_evaluations < 1)
    throw InvalidInput(fmt::format("fit_body: max_evaluations {} must be at least 1", options.max_evaluations));
  if (scan.vertices.empty()) throw InvalidInput("fit_body: the scan has no points");
  for (size_t i = 0; i < scan.vertices.size(); ++i)
    if (!scan.vertices[i].allFinite()) throw InvalidInput(fmt::format("fit_body: scan point {} is not finite", i));
  if (options.direction != BodyFitDirection::ScanToTemplate && scan.faces.empty())
    throw InvalidInput("fit_body: template-to-scan fitting (eq. 5.1) needs a scan mesh with faces; for a point "
                       "cloud use the scan-to-template direction (eq. 5.4)");
  validate_body_params(model, initial);
  const Fitter fitter(model, scan, initial, options);
  return fitter.run();
}

double symmetric_rms_mm(const BodyModel& model, const TriMesh& scan, const BodyParams& params,
                        const BodyFitOptions& options) {
  BodyFitOptions o = options;
  o.direction = BodyFitDirection::Both;
  const Fitter fitter(model, scan, params, o);
  const Linearised L = fitter.evaluate(params, false);
  return L.data_w > 0.0 ? std::sqrt(L.data_sq / L.data_w) : 0.0;
}

BodyFitResult fit_body_multistart(const BodyModel& model, const TriMesh& scan, const BodyParams& initial,
                                  const BodyFitOptions& options) {
  BodyFitOptions one = options, both = options;
  one.direction = BodyFitDirection::TemplateToScan;
  both.direction = BodyFitDirection::Both;
  std::vector<BodyFitResult> runs;
  runs.push_back(fit_body(model, scan, initial, one));
  runs.push_back(fit_body(model, scan, runs[0].params, both));
  runs.push_back(fit_body(model, scan, initial, both));
  if (const std::optional<Eigen::VectorXd> shape = shape_from_scan_girths(model, scan)) {
    BodyParams wide = initial;
    wide.shape = *shape;
    runs.push_back(fit_body(model, scan, place_on_scan(model, wide, scan), one));
    runs.push_back(fit_body(model, scan, runs.back().params, both));
  }
  size_t best = 0;
  double best_rms = 1e300;
  std::vector<double> run_rms;
  for (size_t k = 0; k < runs.size(); ++k) {
    const double r = symmetric_rms_mm(model, scan, runs[k].params, options);
    run_rms.push_back(r);
    if (r < best_rms) {
      best_rms = r;
      best = k;
    }
  }
  BodyFitResult out = runs[best];
  out.initial_rms_mm = symmetric_rms_mm(model, scan, initial, options);
  out.rms_mm = best_rms;
  out.iterations = 0;
  for (const BodyFitResult& r : runs) out.iterations += r.iterations;
  out.chosen_run = static_cast<int>(best);
  out.run_rms_mm = run_rms;
  return out;
}

std::optional<Eigen::VectorXd> shape_from_scan_girths(const BodyModel& model, const TriMesh& scan) {
  if (scan.vertices.empty() || model.landmarks.empty()) return std::nullopt;
  try {
    const ShapedBody rest = shape_body(model, Eigen::VectorXd::Zero(model.num_shapes()));
    const BodyMeasurements base = measure_body(model, rest);
    double zmin = 1e300;
    for (const Vec3& p : rest.vertices) zmin = std::min(zmin, p.z());
    const BoundingBox box = bounding_box(scan);
    const double height = box.max.z() - box.min.z();
    const double stature = base[static_cast<size_t>(Measurement::Stature)];
    MeasurementTargets targets;
    const auto clamp = [](double value, double of) { return std::clamp(value, 0.55 * of, 1.55 * of); };
    targets.mm[static_cast<size_t>(Measurement::Stature)] = clamp(height, stature);
    const std::array<std::pair<Measurement, const char*>, 3> girths = {
        {{Measurement::ChestGirth, "chest"}, {Measurement::WaistGirth, "waist"}, {Measurement::HipGirth, "hip"}}};
    for (const auto& [m, name] : girths) {
      const auto it = model.landmarks.find(name);
      if (it == model.landmarks.end()) return std::nullopt;
      const double fraction = (rest.vertices[static_cast<size_t>(it->second)].z() - zmin) / stature;
      const Vec3 at(0.5 * (box.min.x() + box.max.x()), 0.5 * (box.min.y() + box.max.y()), box.min.z() + fraction * height);
      targets.mm[static_cast<size_t>(m)] = clamp(section_girth(scan, at, Vec3::UnitZ(), at), base[static_cast<size_t>(m)]);
    }
    return shape_from_measurements(model, targets).shape;
  } catch (const InvalidInput&) {
    return std::nullopt;
  } catch (const SolverError&) {
    return std::nullopt;
  }
}

BodyParams place_on_scan(const BodyModel& model, const BodyParams& params, const TriMesh& scan) {
  if (scan.vertices.empty()) throw InvalidInput("place_on_scan: the scan has no points");
  BodyParams p = params;
  p.translation_mm = Vec3::Zero();
  const BoundingBox body = bounding_box(posed_mesh(model, pose_body(model, p)));
  const BoundingBox target = bounding_box(scan);
  const Vec3 d = target.center() - body.center();
  p.translation_mm = {d.x(), d.y(), target.min.z() - body.min.z()};
  return p;
}

std::vector<BodyPart> scan_vertex_parts(const BodyModel& model, const PosedBody& posed, const TriMesh& scan) {
  if (model.vertex_parts.empty())
    throw InvalidInput(fmt::format("body model '{}' has no part labels to carry onto the scan{}", model.name,
                                   model.labels_note.empty() ? "" : ": " + model.labels_note));
  if (static_cast<int>(posed.vertices.size()) != model.num_vertices())
    throw InvalidInput("scan_vertex_parts: the posed body does not belong to this model");
  const SurfaceBvh bvh(posed_mesh(model, posed));
  std::vector<BodyPart> parts(scan.vertices.size());
  for (size_t i = 0; i < scan.vertices.size(); ++i) {
    const ClosestPoint cp = bvh.closest_point(scan.vertices[i]);
    const auto& f = model.faces[static_cast<size_t>(cp.face)];
    int best = f[0];
    for (int v : f)
      if ((posed.vertices[static_cast<size_t>(v)] - cp.point).squaredNorm() <
          (posed.vertices[static_cast<size_t>(best)] - cp.point).squaredNorm())
        best = v;
    parts[i] = model.vertex_parts[static_cast<size_t>(best)];
  }
  return parts;
}

std::vector<double> vertex_distances_mm(const TriMesh& body, const TriMesh& scan) {
  if (scan.faces.empty()) throw InvalidInput("vertex_distances_mm: the scan has no faces");
  return distances_to_surface(scan, body.vertices);
}

}  // namespace knitforge

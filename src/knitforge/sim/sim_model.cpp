#include "knitforge/sim/sim_model.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/core.h>

#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

TriMesh SimModel::triangles() const {
  TriMesh t;
  t.vertices = rest_positions;
  t.faces.reserve(elements.size());
  for (const MembraneElement& e : elements) t.faces.push_back(e.v);
  return t;
}

namespace {

// An element's rest corners in its material frame (mm), used for the hinges.
struct RestTriangle {
  std::array<Vec2, 3> p;
};

void check_materials(const std::vector<KnitMaterial>& materials) {
  if (materials.empty()) throw InvalidInput("simulation model: no material given");
  for (const KnitMaterial& m : materials) validate_material(m);
}

MembraneElement make_element(const std::array<int, 3>& v, const RestTriangle& r, int material, int stitch,
                             const std::string& where) {
  Mat2 D;
  D.col(0) = r.p[1] - r.p[0];
  D.col(1) = r.p[2] - r.p[0];
  const double det = D.determinant();
  const double scale = std::max({D.col(0).squaredNorm(), D.col(1).squaredNorm(), 1e-300});
  if (!(det > 1e-10 * scale)) {
    throw InvalidInput(fmt::format("simulation model: {} has a degenerate or inverted rest shape (area {:.3g} mm²); "
                                   "check its corners",
                                   where, 0.5 * det));
  }
  MembraneElement e;
  e.v = v;
  e.rest_inverse = D.inverse();
  e.rest_area_mm2 = 0.5 * det;
  e.material = material;
  e.stitch = stitch;
  return e;
}

// Bending rigidity of a hinge side: D_c (n·x)² + D_w (n·y)² with n the unit
// in-plane normal of the edge (a, b) in the element's rest frame.
double edge_rigidity(const RestTriangle& r, int a, int b, const KnitMaterial& m) {
  const Vec2 e = (r.p[b] - r.p[a]).normalized();
  const Vec2 n(-e.y(), e.x());
  return m.bending_course_un_m * n.x() * n.x() + m.bending_wale_un_m * n.y() * n.y();
}

// Hinges and masses from the elements and their rest triangles.
void finish_model(SimModel& model, const std::vector<RestTriangle>& rest) {
  const int nv = model.num_vertices();
  model.vertex_mass_kg.assign(nv, 0.0);
  model.vertex_damping_kg_s.assign(nv, 0.0);
  model.vertex_area_mm2.assign(nv, 0.0);
  for (const MembraneElement& e : model.elements) {
    const KnitMaterial& mat = model.materials[e.material];
    const double m = e.rest_area_mm2 * areal_density_kg_mm2(mat) / 3.0;
    for (int v : e.v) {
      model.vertex_mass_kg[v] += m;
      model.vertex_damping_kg_s[v] += mat.damping_per_s * m;
      model.vertex_area_mm2[v] += e.rest_area_mm2 / 3.0;
    }
  }
  // Directed edges: (a, b) -> (element, local index of a).
  std::map<std::pair<int, int>, std::pair<int, int>> directed;
  for (int f = 0; f < model.num_elements(); ++f) {
    const auto& v = model.elements[f].v;
    for (int k = 0; k < 3; ++k) {
      const auto key = std::make_pair(v[k], v[(k + 1) % 3]);
      if (!directed.emplace(key, std::make_pair(f, k)).second) {
        const int g = directed[key].first;
        const int sf = model.elements[f].stitch, sg = model.elements[g].stitch;
        throw TopologyError(fmt::format(
            "simulation model: the edge ({}, {}) is used twice in the same direction{} (faces {} and {}): the "
            "mesh is non-manifold or not consistently oriented",
            key.first, key.second,
            sf >= 0 ? fmt::format(" by stitches {} and {}", sg, sf) : std::string(), g, f));
      }
    }
  }
  for (const auto& [key, fk] : directed) {
    const auto [a, b] = key;
    if (a > b) continue;
    const auto other = directed.find({b, a});
    if (other == directed.end()) continue;
    const auto [f0, k0] = fk;
    const auto [f1, k1] = other->second;
    const MembraneElement& e0 = model.elements[f0];
    const MembraneElement& e1 = model.elements[f1];
    BendingHinge h;
    h.v = {a, b, e0.v[(k0 + 2) % 3], e1.v[(k1 + 2) % 3]};
    h.elements = {f0, f1};
    const double len0 = (rest[f0].p[(k0 + 1) % 3] - rest[f0].p[k0]).norm();
    const double len1 = (rest[f1].p[(k1 + 1) % 3] - rest[f1].p[k1]).norm();
    const double d0 = edge_rigidity(rest[f0], k0, (k0 + 1) % 3, model.materials[e0.material]);
    const double d1 = edge_rigidity(rest[f1], k1, (k1 + 1) % 3, model.materials[e1.material]);
    const double len = 0.5 * (len0 + len1);
    // ½ D |e|² / (A0 + A1): exact for a cylinder bent across a strip of
    // rectangles split into triangles (docs/sim.md).
    h.stiffness = 0.5 * (0.5 * (d0 + d1)) * len * len / (e0.rest_area_mm2 + e1.rest_area_mm2);
    if (e0.stitch >= 0 && e0.stitch == e1.stitch) h.stiffness *= kStitchDiagonalStiffening;
    model.hinges.push_back(h);
  }
}

void check_positions(const std::vector<Vec3>& x, const char* what) {
  for (size_t i = 0; i < x.size(); ++i) {
    if (!x[i].allFinite()) throw InvalidInput(fmt::format("simulation model: {} vertex {} is not finite", what, i));
  }
}

}  // namespace

SimModel build_sim_model(const StitchMesh& mesh, const KnitParams& params, const SimModelOptions& options) {
  if (mesh.stitches.empty()) throw InvalidInput("simulation model: the stitch mesh has no stitches");
  if (!(params.stitch_width > 0 && params.stitch_height > 0 && std::isfinite(params.stitch_width) &&
        std::isfinite(params.stitch_height))) {
    throw InvalidInput(fmt::format("simulation model: the stitch size {} x {} mm must be positive",
                                   params.stitch_width, params.stitch_height));
  }
  check_materials(options.materials);
  check_positions(mesh.vertices, "stitch mesh");
  SimModel model;
  model.rest_positions = mesh.vertices;
  model.materials = options.materials;
  std::vector<Vec3> shapes[kNumStitchTypes];
  for (int t = 0; t < kNumStitchTypes; ++t) shapes[t] = ideal_stitch_shape(static_cast<StitchType>(t), params);
  std::vector<RestTriangle> rest;
  const int nv = mesh.num_vertices();
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    const int nc = st.corners();
    for (int k = 0; k < nc; ++k) {
      if (st.v[k] < 0 || st.v[k] >= nv) {
        throw TopologyError(fmt::format("simulation model: stitch {} corner {} is vertex {} (valid: 0..{})", s, k,
                                        st.v[k], nv - 1));
      }
      for (int j = 0; j < k; ++j) {
        if (st.v[j] == st.v[k]) {
          throw TopologyError(fmt::format("simulation model: stitch {} uses vertex {} twice", s, st.v[k]));
        }
      }
    }
    const int material = st.yarn >= 0 && st.yarn < static_cast<int>(model.materials.size()) ? st.yarn : 0;
    const std::vector<Vec3>& ideal = shapes[static_cast<int>(st.type)];
    auto add = [&](int a, int b, int c) {
      RestTriangle r;
      r.p = {ideal[a].head<2>(), ideal[b].head<2>(), ideal[c].head<2>()};
      model.elements.push_back(
          make_element({st.v[a], st.v[b], st.v[c]}, r, material, s, fmt::format("stitch {}", s)));
      rest.push_back(r);
    };
    if (nc == 3) {
      add(0, 1, 2);
    } else {
      // The shorter designed diagonal, so the split follows the design's own
      // fold; ties (a flat rectangle) alternate like a checkerboard, so the
      // triangulation has no preferred diagonal direction.
      const double d02 = (mesh.vertices[st.v[0]] - mesh.vertices[st.v[2]]).squaredNorm();
      const double d13 = (mesh.vertices[st.v[1]] - mesh.vertices[st.v[3]]).squaredNorm();
      const bool tie = std::abs(d13 - d02) <= 1e-9 * (d13 + d02);
      const bool odd = ((st.course >= 0 ? st.course : 0) + (st.wale >= 0 ? st.wale : s)) % 2 != 0;
      if (tie ? odd : d13 < d02) {
        add(0, 1, 3);
        add(1, 2, 3);
      } else {
        add(0, 1, 2);
        add(0, 2, 3);
      }
    }
  }
  finish_model(model, rest);
  return model;
}

SimModel build_sim_model(const TriMesh& mesh, const std::vector<Vec3>& course_directions,
                         const std::vector<int>& face_materials, const SimModelOptions& options) {
  const int nf = mesh.num_faces();
  const int nv = mesh.num_vertices();
  if (nf == 0) throw InvalidInput("simulation model: the mesh has no faces");
  check_materials(options.materials);
  check_positions(mesh.vertices, "mesh");
  if (course_directions.size() != 1 && static_cast<int>(course_directions.size()) != nf) {
    throw InvalidInput(fmt::format("simulation model: {} course directions for {} faces (give one, or one per face)",
                                   course_directions.size(), nf));
  }
  if (!face_materials.empty() && static_cast<int>(face_materials.size()) != nf) {
    throw InvalidInput(
        fmt::format("simulation model: {} face materials for {} faces", face_materials.size(), nf));
  }
  SimModel model;
  model.rest_positions = mesh.vertices;
  model.materials = options.materials;
  std::vector<RestTriangle> rest;
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= nv) {
        throw InvalidInput(fmt::format("simulation model: face {} corner {} is vertex {} (valid: 0..{})", f, k, t[k],
                                       nv - 1));
      }
    }
    const Vec3 &x0 = mesh.vertices[t[0]], &x1 = mesh.vertices[t[1]], &x2 = mesh.vertices[t[2]];
    const Vec3 n = (x1 - x0).cross(x2 - x0);
    if (!(n.norm() > 0)) throw InvalidInput(fmt::format("simulation model: face {} is degenerate (zero area)", f));
    const Vec3 nh = n.normalized();
    const Vec3 c = course_directions.size() == 1 ? course_directions[0] : course_directions[f];
    Vec3 u = c - c.dot(nh) * nh;
    if (!c.allFinite() || !(u.norm() > 1e-6 * std::max(c.norm(), 1e-300))) {
      throw InvalidInput(fmt::format(
          "simulation model: the course direction of face {} is zero or normal to the face; give a direction "
          "along the surface",
          f));
    }
    u.normalize();
    const Vec3 w = nh.cross(u);
    RestTriangle r;
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = mesh.vertices[t[k]] - x0;
      r.p[k] = Vec2(d.dot(u), d.dot(w));
    }
    const int material = face_materials.empty() ? 0 : face_materials[f];
    if (material < 0 || material >= static_cast<int>(model.materials.size())) {
      throw InvalidInput(fmt::format("simulation model: face {} has material {} (valid: 0..{})", f, material,
                                     model.materials.size() - 1));
    }
    model.elements.push_back(make_element(t, r, material, -1, fmt::format("face {}", f)));
    rest.push_back(r);
  }
  finish_model(model, rest);
  return model;
}

}  // namespace knitforge

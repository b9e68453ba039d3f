#pragma once
// Our generated body written in SMPL's npz layout with SMPL's 24 joints, for
// the tests of the part labels derived for a loaded SMPL-format model
// (smpl_body_parts.h) and of `body ... --model FILE.npz` on a human-shaped
// model. No SMPL data is used: the model is ours, only the layout is SMPL's.
//
// Our 19 joints map onto SMPL's of the same name, except our spine2 (at the
// chest) which becomes SMPL's spine3 (SMPL's spine3 is the chest joint, the
// parent of neck and collars). The joints SMPL has and we do not are
// zero-weight joints (no vertex follows them): spine2, midway between our
// spine1 and spine2 (regressed as the mean of their rows), the feet (the
// vertex nearest the ball of each foot) and the hands (the vertex nearest
// 90 mm past each wrist). SMPL+H's and SMPL-X's layouts (52, 55 joints) add
// zero-weight finger (and face) joints, children of the wrists (the head).
// Our skinning weights, shape directions and regressor rows carry over
// unchanged; no pose-corrective directions (posedirs is optional).
//
// SMPL's axes: metres, y up, facing +z: a point p of ours is C^T p / 1000
// (smpl_to_knitforge_axes()).

#include <string>
#include <vector>

#include "io/npz_test_writer.h"
#include "knitforge/body/body_model.h"
#include "knitforge/body/smpl_model_npz.h"

namespace knitforge::test {

/// Which SMPL-family joint layout to write.
enum class SmplLayout { Smpl24, SmplH52, SmplX55, Unmapped25 };

/// `model` (ours; its template replaced by `template_mm` when not empty,
/// e.g. a shaped body) as an SMPL-format .npz archive.
inline std::string generated_body_smpl_npz(const BodyModel& model, SmplLayout layout = SmplLayout::Smpl24,
                                           const std::vector<Vec3>& template_mm = {}) {
  const std::vector<Vec3>& tv = template_mm.empty() ? model.template_vertices : template_mm;
  const int V = model.num_vertices(), K = model.num_shapes();
  const Mat3 Ct = smpl_to_knitforge_axes().transpose();
  auto ours = [&](const char* name) {
    const int j = model.joint_index(name);
    if (j < 0) throw std::runtime_error(std::string("generated body has no joint ") + name);
    return j;
  };
  auto nearest = [&](const Vec3& p) {
    int best = 0;
    for (int i = 1; i < V; ++i)
      if ((tv[static_cast<size_t>(i)] - p).squaredNorm() < (tv[static_cast<size_t>(best)] - p).squaredNorm())
        best = i;
    return best;
  };
  std::vector<Vec3> J0(static_cast<size_t>(model.num_joints()), Vec3::Zero());
  for (int j = 0; j < model.joint_regressor.outerSize(); ++j)
    for (RowSparse::InnerIterator it(model.joint_regressor, j); it; ++it)
      J0[static_cast<size_t>(j)] += it.value() * tv[static_cast<size_t>(it.col())];

  // SMPL joint -> our joint (-1: a zero-weight joint of SMPL's own).
  const std::vector<std::string> smpl = smpl_joint_names();
  std::vector<int> from(24, -1);
  for (int s = 0; s < 24; ++s) {
    const std::string& n = smpl[static_cast<size_t>(s)];
    if (n == "spine3")
      from[static_cast<size_t>(s)] = ours("spine2");
    else if (n != "spine2" && model.joint_index(n) >= 0)
      from[static_cast<size_t>(s)] = model.joint_index(n);
  }
  const std::vector<int> smpl_parents = {-1, 0, 0, 0,  1,  2,  3,  4,  5,  6,  7,  8,
                                         9,  9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};
  std::vector<int> parents;
  int J = 24;
  if (layout == SmplLayout::Smpl24) {
    parents = smpl_parents;
  } else {
    // 22 body joints, then hand joints (and for SMPL-X first jaw and eyes).
    parents.assign(smpl_parents.begin(), smpl_parents.begin() + 22);
    if (layout == SmplLayout::SmplX55) parents.insert(parents.end(), {15, 15, 15});
    if (layout == SmplLayout::Unmapped25) {
      parents = smpl_parents;
      parents.push_back(15);  // one joint more than SMPL: not a layout we map
    } else {
      for (int side = 0; side < 2; ++side)
        for (int finger = 0; finger < 5; ++finger)
          for (int k = 0; k < 3; ++k)
            parents.push_back(k == 0 ? 20 + side : static_cast<int>(parents.size()) - 1);
    }
    J = static_cast<int>(parents.size());
    from.resize(static_cast<size_t>(J), -1);  // our joints are among the first 22
  }

  // Regressor rows (ours, or those of SMPL's extra joints).
  std::vector<double> reg(static_cast<size_t>(J) * static_cast<size_t>(V), 0.0);
  auto add_row = [&](int s, int ours_j, double f) {
    for (RowSparse::InnerIterator it(model.joint_regressor, ours_j); it; ++it)
      reg[static_cast<size_t>(s) * static_cast<size_t>(V) + static_cast<size_t>(it.col())] += f * it.value();
  };
  const Vec3 lw = J0[static_cast<size_t>(ours("left_wrist"))],
             rw = J0[static_cast<size_t>(ours("right_wrist"))];
  const Vec3 la = J0[static_cast<size_t>(ours("left_ankle"))],
             ra = J0[static_cast<size_t>(ours("right_ankle"))];
  auto ancestor_in = [&](int s, std::initializer_list<int> roots) {
    for (int q = s; q >= 0; q = parents[static_cast<size_t>(q)])
      for (int r : roots)
        if (q == r) return r;
    return -1;
  };
  for (int s = 0; s < J; ++s) {
    if (from[static_cast<size_t>(s)] >= 0) {
      add_row(s, from[static_cast<size_t>(s)], 1.0);
    } else if (s == 6) {
      add_row(s, ours("spine1"), 0.5);
      add_row(s, ours("spine2"), 0.5);
    } else {
      // A zero-weight joint at one vertex: the feet at the ball of the foot,
      // hands and fingers past the wrists, face joints in the face.
      Vec3 at;
      switch (ancestor_in(s, {7, 8, 20, 21, 15})) {
        case 7:
          at = la + Vec3(0, -120, -40);
          break;
        case 8:
          at = ra + Vec3(0, -120, -40);
          break;
        case 20:
          at = lw + Vec3(90, 0, 0);
          break;
        case 21:
          at = rw + Vec3(-90, 0, 0);
          break;
        default:
          at = J0[static_cast<size_t>(ours("head"))] + Vec3(0, -60, 40);
          break;
      }
      reg[static_cast<size_t>(s) * static_cast<size_t>(V) + static_cast<size_t>(nearest(at))] = 1.0;
    }
  }

  std::vector<double> vt, sd(static_cast<size_t>(V) * 3 * static_cast<size_t>(K)),
      w(static_cast<size_t>(V) * static_cast<size_t>(J), 0.0);
  for (int i = 0; i < V; ++i) {
    const Vec3 p = Ct * tv[static_cast<size_t>(i)] / 1000.0;
    vt.insert(vt.end(), {p.x(), p.y(), p.z()});
    for (int k = 0; k < K; ++k) {
      const Vec3 d = Ct * Vec3(model.shape_basis.block<3, 1>(3 * i, k)) / 1000.0;
      for (int c = 0; c < 3; ++c)
        sd[(3 * static_cast<size_t>(i) + static_cast<size_t>(c)) * static_cast<size_t>(K) +
           static_cast<size_t>(k)] = d(c);
    }
  }
  for (int s = 0; s < J; ++s) {
    const int o = from[static_cast<size_t>(s)];
    if (o < 0) continue;
    for (int i = 0; i < V; ++i)
      w[static_cast<size_t>(i) * static_cast<size_t>(J) + static_cast<size_t>(s)] =
          model.skinning_weights.coeff(i, o);
  }
  std::vector<int64_t> f, kt(2 * static_cast<size_t>(J));
  for (const auto& t : model.faces) f.insert(f.end(), {t[0], t[1], t[2]});
  for (int s = 0; s < J; ++s) {
    kt[static_cast<size_t>(s)] = s == 0 ? 4294967295LL : parents[static_cast<size_t>(s)];
    kt[static_cast<size_t>(J + s)] = s;
  }
  std::vector<ZipEntry> entries = {
      {"v_template.npy", npy_f8({V, 3}, vt), true},
      {"f.npy", npy_bytes("<u4", {static_cast<int64_t>(model.faces.size()), 3}, raw_bytes<uint32_t>(f)),
       false},
      {"shapedirs.npy", npy_f8({V, 3, K}, sd), true},
      {"J_regressor.npy", npy_f8({J, V}, reg), false},
      {"kintree_table.npy", npy_i8({2, J}, kt), false},
      {"weights.npy", npy_f8({V, J}, w), true},
  };
  return zip_bytes(entries);
}

}  // namespace knitforge::test

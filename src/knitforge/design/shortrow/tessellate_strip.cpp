#include "knitforge/design/shortrow/tessellate_strip.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// The most recent apex is forgotten beyond this many diffusion lengths.
constexpr double kForgetDistance = 3.5;

struct Bridge {
  int k;  ///< index on A
  int l;  ///< index on B
};

struct OpShape {
  int di = 0, dj = 0;
  std::vector<Bridge> bridges;  ///< new bridges, bottom to top
  std::vector<int> apexes;      ///< vertex ids, one per triangle pair
};

class Strip {
 public:
  Strip(const std::vector<Vec3>& a, const std::vector<Vec3>& b) : a_(a), b_(b) {
    na_ = static_cast<int>(a.size()) / 2;
    nb_ = static_cast<int>(b.size()) / 2;
  }
  int na() const { return na_; }
  int nb() const { return nb_; }
  int num_vertices() const { return static_cast<int>(a_.size() + b_.size()); }
  int vid_a(int k) const { return k; }
  int vid_b(int l) const { return static_cast<int>(a_.size()) + l; }
  const Vec3& pos(int v) const {
    return v < static_cast<int>(a_.size()) ? a_[static_cast<size_t>(v)]
                                           : b_[static_cast<size_t>(v) - a_.size()];
  }
  double bridge(int k, int l) const {
    return (a_[static_cast<size_t>(k)] - b_[static_cast<size_t>(l)]).norm();
  }
  bool on_wale_end(int v) const {
    return v == 0 || v == vid_a(2 * na_) || v == vid_b(0) || v == vid_b(2 * nb_);
  }

  /// Shape of operator op at node (i, j); false when it leaves the wales.
  bool shape(StripOperator op, int i, int j, OpShape& s) const {
    s.bridges.clear();
    s.apexes.clear();
    const int k = 2 * i, l = 2 * j;
    switch (op) {
      case StripOperator::ABAdvance:
        s.di = 1, s.dj = 1;
        s.bridges = {{k + 1, l + 1}, {k + 2, l + 2}};
        break;
      case StripOperator::AAdvance:
        s.di = 1, s.dj = 0;
        s.bridges = {{k + 1, l}, {k + 2, l}};
        s.apexes = {vid_b(l)};
        break;
      case StripOperator::BAdvance:
        s.di = 1, s.dj = 2;
        s.bridges = {{k + 1, l + 1}, {k + 1, l + 2}, {k + 1, l + 3}, {k + 2, l + 4}};
        s.apexes = {vid_a(k + 1)};
        break;
      case StripOperator::BBAdvance:
        s.di = 1, s.dj = 3;
        s.bridges = {{k + 1, l + 1}, {k + 1, l + 2}, {k + 1, l + 3},
                     {k + 1, l + 4}, {k + 1, l + 5}, {k + 2, l + 6}};
        s.apexes = {vid_a(k + 1), vid_a(k + 1)};
        break;
      case StripOperator::BFan:
        if (i != 0 && i != na_) return false;
        s.di = 0, s.dj = 1;
        s.bridges = {{k, l + 1}, {k, l + 2}};
        s.apexes = {vid_a(k)};
        break;
      // Short-column ends: the first (last) quad of an AB-, B- or BB-advance
      // becomes the Increase (Decrease).
      case StripOperator::Increase:
      case StripOperator::IncreaseDecrease:
        if (i != 0 || j != 0) return false;
        s.di = 1, s.dj = 1;
        s.bridges = op == StripOperator::Increase ? std::vector<Bridge>{{1, 1}, {2, 2}} : std::vector<Bridge>{{1, 1}};
        break;
      case StripOperator::IncreaseB:
        if (i != 0 || j != 0) return false;
        s.di = 1, s.dj = 2;
        s.bridges = {{1, 1}, {1, 2}, {1, 3}, {2, 4}};
        s.apexes = {vid_a(1)};
        break;
      case StripOperator::IncreaseBB:
        if (i != 0 || j != 0) return false;
        s.di = 1, s.dj = 3;
        s.bridges = {{1, 1}, {1, 2}, {1, 3}, {1, 4}, {1, 5}, {2, 6}};
        s.apexes = {vid_a(1), vid_a(1)};
        break;
      case StripOperator::Decrease:
        s.di = 1, s.dj = 1;
        s.bridges = {{k + 1, l + 1}};
        break;
      case StripOperator::DecreaseB:
        s.di = 1, s.dj = 2;
        s.bridges = {{k + 1, l + 1}, {k + 1, l + 2}, {k + 1, l + 3}};
        s.apexes = {vid_a(k + 1)};
        break;
      case StripOperator::DecreaseBB:
        s.di = 1, s.dj = 3;
        s.bridges = {{k + 1, l + 1}, {k + 1, l + 2}, {k + 1, l + 3}, {k + 1, l + 4}, {k + 1, l + 5}};
        s.apexes = {vid_a(k + 1), vid_a(k + 1)};
        break;
    }
    return i + s.di <= na_ && j + s.dj <= nb_;
  }

  /// Appends the faces of op at (i, j), courses from `course`.
  void faces(StripOperator op, int i, int j, int& course, std::vector<StripFace>& out) const {
    const int k = 2 * i, l = 2 * j;
    auto add = [&](StitchType t, std::array<int, 4> c) {
      StripFace f;
      f.type = t;
      f.corners = c;
      f.course = course;
      f.direction = course % 2 == 0 ? 1 : -1;
      ++course;
      out.push_back(f);
    };
    auto quad = [&](int ka, int lb) {  // (a_ka, b_lb, b_lb+1, a_ka+1)
      add(StitchType::Knit, {vid_a(ka), vid_b(lb), vid_b(lb + 1), vid_a(ka + 1)});
    };
    auto left = [&](int ka, int lb) {  // apex a_ka, (b_lb, b_lb+1)
      add(StitchType::ShortRowLeft, {vid_a(ka), vid_b(lb), vid_b(lb + 1), -1});
    };
    switch (op) {
      case StripOperator::ABAdvance:
        quad(k, l);
        quad(k + 1, l + 1);
        break;
      case StripOperator::AAdvance:
        add(StitchType::ShortRowRight, {vid_a(k), vid_b(l), vid_a(k + 1), -1});
        add(StitchType::ShortRowRight, {vid_a(k + 1), vid_b(l), vid_a(k + 2), -1});
        break;
      case StripOperator::BAdvance:
        quad(k, l);
        left(k + 1, l + 1);
        left(k + 1, l + 2);
        quad(k + 1, l + 3);
        break;
      case StripOperator::BBAdvance:
        quad(k, l);
        for (int m = 1; m <= 4; ++m) left(k + 1, l + m);
        quad(k + 1, l + 5);
        break;
      case StripOperator::BFan:
        left(k, l);
        left(k, l + 1);
        break;
      case StripOperator::Increase:
        add(StitchType::Increase, {vid_a(0), vid_b(1), vid_a(1), -1});
        quad(1, 1);
        break;
      case StripOperator::IncreaseB:
        add(StitchType::Increase, {vid_a(0), vid_b(1), vid_a(1), -1});
        left(1, 1);
        left(1, 2);
        quad(1, 3);
        break;
      case StripOperator::IncreaseBB:
        add(StitchType::Increase, {vid_a(0), vid_b(1), vid_a(1), -1});
        for (int m = 1; m <= 4; ++m) left(1, m);
        quad(1, 5);
        break;
      case StripOperator::Decrease:
        quad(k, l);
        add(StitchType::Decrease, {vid_a(k + 1), vid_b(l + 1), vid_a(k + 2), -1});
        break;
      case StripOperator::DecreaseB:
        quad(k, l);
        left(k + 1, l + 1);
        left(k + 1, l + 2);
        add(StitchType::Decrease, {vid_a(k + 1), vid_b(l + 3), vid_a(k + 2), -1});
        break;
      case StripOperator::DecreaseBB:
        quad(k, l);
        for (int m = 1; m <= 4; ++m) left(k + 1, l + m);
        add(StitchType::Decrease, {vid_a(k + 1), vid_b(l + 5), vid_a(k + 2), -1});
        break;
      case StripOperator::IncreaseDecrease:
        add(StitchType::Increase, {vid_a(0), vid_b(1), vid_a(1), -1});
        add(StitchType::Decrease, {vid_a(1), vid_b(1), vid_a(2), -1});
        break;
    }
  }

 private:
  const std::vector<Vec3>& a_;
  const std::vector<Vec3>& b_;
  int na_ = 0, nb_ = 0;
};

constexpr std::array<StripOperator, 12> kOps = {
    StripOperator::ABAdvance, StripOperator::AAdvance,   StripOperator::BAdvance,  StripOperator::BBAdvance,
    StripOperator::BFan,      StripOperator::Increase,   StripOperator::IncreaseB, StripOperator::IncreaseBB,
    StripOperator::Decrease,  StripOperator::DecreaseB,  StripOperator::DecreaseBB, StripOperator::IncreaseDecrease};

bool starts_fork(StripOperator op) {
  return op == StripOperator::Increase || op == StripOperator::IncreaseB || op == StripOperator::IncreaseBB ||
         op == StripOperator::IncreaseDecrease;
}
bool ends_fork(StripOperator op) {
  return op == StripOperator::Decrease || op == StripOperator::DecreaseB || op == StripOperator::DecreaseBB ||
         op == StripOperator::IncreaseDecrease;
}

struct Diffusion {
  double mu = 0.0;
  double length = 1.0;
};

/// Normalised distance from vertex v to the nearest of `apexes` (inf if none).
std::vector<double> nearest_apex_distances(const Strip& s, const std::vector<Vec3>& apexes,
                                           double length) {
  std::vector<double> d(static_cast<size_t>(s.num_vertices()), kInf);
  for (int v = 0; v < s.num_vertices(); ++v)
    for (const Vec3& p : apexes) d[static_cast<size_t>(v)] = std::min(d[static_cast<size_t>(v)], (s.pos(v) - p).norm() / length);
  return d;
}

/// Diffusion penalty of the apexes of an operator; `last` is the most recent
/// in-strip apex on the path (-1 if none); updates it.
double apex_penalty(const Strip& s, const OpShape& sh, const std::vector<double>& fixed,
                    const Diffusion& dif, int& last) {
  if (dif.mu <= 0.0) {  // no penalty, but the most recent apex is still tracked (stacked A-advances)
    for (int v : sh.apexes)
      if (!s.on_wale_end(v)) last = v;
    return 0.0;
  }
  double pen = 0.0;
  for (int v : sh.apexes) {
    if (s.on_wale_end(v)) continue;
    double d = fixed[static_cast<size_t>(v)];
    if (last >= 0) d = std::min(d, (s.pos(v) - s.pos(last)).norm() / dif.length);
    pen += dif.mu * std::exp(-d * d);
    last = v;
  }
  return pen;
}

struct SearchResult {
  bool found = false;
  std::vector<StripStep> steps;
};

/// Shortest path over states (node, most recent apex) from `from` to `to`.
/// Every operator moves the node forward in the lexicographic order of
/// (i, j) (all of them advance i except the B-fan, which advances j), so the
/// graph is acyclic and one sweep in that order gives the same optimum as
/// Dijkstra's algorithm, without a priority queue. Ties keep the label found
/// first (operators are tried in enum order), so the result is deterministic.
SearchResult search(const Strip& s, std::array<int, 2> from, std::array<int, 2> to,
                    double lambda, bool allow_fan, const std::vector<double>& fixed,
                    const Diffusion& dif, bool fork_start = false, bool fork_end = false,
                    bool allow_double = true, bool allow_stacked_a = true) {
  auto node_ok = [&](int i, int j) {
    if ((i == from[0] && j == from[1]) || (i == to[0] && j == to[1])) return true;
    return s.bridge(2 * i, 2 * j) <= lambda;
  };
  struct Label {
    double cost;
    int last;  ///< most recent in-strip apex vertex, -1 if none
    int pred;  ///< label index of the predecessor, -1 at the start
    int next;  ///< next label of the same node, -1 at the end of the chain
    StripOperator op;
    int i, j;
  };
  std::vector<Label> labels;
  // Reached nodes not yet swept, in lexicographic order, with their label chain.
  std::map<std::pair<int, int>, int> open;
  labels.push_back({0.0, -1, -1, -1, StripOperator::ABAdvance, from[0], from[1]});
  open[{from[0], from[1]}] = 0;
  int goal_head = -1;
  OpShape sh;
  while (!open.empty()) {
    const auto [i, j] = open.begin()->first;
    const int node_head = open.begin()->second;
    open.erase(open.begin());
    if (i == to[0] && j == to[1]) {  // the lexicographically last node of the box
      goal_head = node_head;
      break;
    }
    {
      for (int li = node_head; li >= 0; li = labels[static_cast<size_t>(li)].next) {
        const double cost = labels[static_cast<size_t>(li)].cost;
        const int last0 = labels[static_cast<size_t>(li)].last;
        const bool at_fork = fork_start && i == from[0] && j == from[1];
        for (StripOperator op : kOps) {
          if (op == StripOperator::BFan && !allow_fan) continue;
          if (!allow_double && (op == StripOperator::BBAdvance || op == StripOperator::IncreaseBB ||
                                op == StripOperator::DecreaseBB))
            continue;
          if (starts_fork(op) != at_fork) continue;  // a fork start takes a fork operator, nothing else does
          if (!s.shape(op, i, j, sh)) continue;
          // Two A-advances in a row share their apex b_2j: four stacked
          // short-row ends, the same rule the double advances break.
          if (!allow_stacked_a && op == StripOperator::AAdvance && last0 >= 0 && last0 == s.vid_b(2 * j)) continue;
          const int i2 = i + sh.di, j2 = j + sh.dj;
          if (ends_fork(op) != (fork_end && i2 == to[0] && j2 == to[1])) continue;
          if (i2 > to[0] || j2 > to[1] || !node_ok(i2, j2)) continue;
          double len = 0.0;
          bool ok = true;
          for (const Bridge& br : sh.bridges) {
            const double bl = s.bridge(br.k, br.l);
            if (bl > lambda && !(br.k == 2 * to[0] && br.l == 2 * to[1])) ok = false;
            len += bl;
          }
          if (!ok) continue;
          int last = last0;
          const double c2 = cost + len + apex_penalty(s, sh, fixed, dif, last);
          if (last >= 0) {
            const double da = (s.pos(last) - s.pos(s.vid_a(2 * i2))).norm();
            const double db = (s.pos(last) - s.pos(s.vid_b(2 * j2))).norm();
            if (std::min(da, db) > kForgetDistance * dif.length) last = -1;
          }
          int& h = open.try_emplace({i2, j2}, -1).first->second;
          int found = -1;
          for (int m = h; m >= 0; m = labels[static_cast<size_t>(m)].next)
            if (labels[static_cast<size_t>(m)].last == last) {
              found = m;
              break;
            }
          if (found < 0) {
            labels.push_back({c2, last, li, h, op, i2, j2});
            h = static_cast<int>(labels.size()) - 1;
          } else if (c2 < labels[static_cast<size_t>(found)].cost) {
            Label& l = labels[static_cast<size_t>(found)];
            l.cost = c2;
            l.pred = li;
            l.op = op;
          }
        }
      }
    }
  }
  SearchResult r;
  int goal = -1;
  for (int m = goal_head; m >= 0; m = labels[static_cast<size_t>(m)].next)
    if (goal < 0 || labels[static_cast<size_t>(m)].cost < labels[static_cast<size_t>(goal)].cost)
      goal = m;
  if (goal < 0) return r;
  r.found = true;
  for (int m = goal; labels[static_cast<size_t>(m)].pred >= 0;) {
    const Label& lab = labels[static_cast<size_t>(m)];
    const Label& prev = labels[static_cast<size_t>(lab.pred)];
    r.steps.push_back({lab.op, prev.i, prev.j});
    m = lab.pred;
  }
  std::reverse(r.steps.begin(), r.steps.end());
  return r;
}

/// Apexes (non-wale-end positions) of a list of steps.
void collect_apexes(const Strip& s, const std::vector<StripStep>& steps, std::vector<Vec3>& out) {
  OpShape sh;
  for (const StripStep& st : steps) {
    s.shape(st.op, st.i, st.j, sh);
    for (int v : sh.apexes)
      if (!s.on_wale_end(v)) out.push_back(s.pos(v));
  }
}

void check_wale(const std::vector<Vec3>& w, const char* which, int strip) {
  if (w.size() < 3 || w.size() % 2 == 0)
    throw InvalidInput(fmt::format(
        "tessellate_strip: strip {}: wale {} has {} samples; it needs an even number (>= 2) of "
        "segments, i.e. an odd number >= 3 of samples",
        strip, which, w.size()));
  for (size_t k = 0; k < w.size(); ++k)
    if (!w[k].allFinite())
      throw InvalidInput(fmt::format("tessellate_strip: strip {}: sample {} of wale {} is not finite",
                                     strip, k, which));
}

}  // namespace

std::string_view name(StripOperator op) {
  switch (op) {
    case StripOperator::ABAdvance: return "AB-advance";
    case StripOperator::AAdvance: return "A-advance";
    case StripOperator::BAdvance: return "B-advance";
    case StripOperator::BBAdvance: return "BB-advance";
    case StripOperator::BFan: return "B-fan";
    case StripOperator::Increase: return "increase";
    case StripOperator::IncreaseB: return "increase-B";
    case StripOperator::IncreaseBB: return "increase-BB";
    case StripOperator::Decrease: return "decrease";
    case StripOperator::DecreaseB: return "decrease-B";
    case StripOperator::DecreaseBB: return "decrease-BB";
    case StripOperator::IncreaseDecrease: return "increase-decrease";
  }
  return "unknown";
}

Vec3 wale_tangent(const std::vector<Vec3>& w, size_t k) {
  const size_t lo = k > 1 ? k - 2 : 0;
  const size_t hi = std::min(k + 2, w.size() - 1);
  return w[hi] - w[lo];
}

namespace {

/// tessellate_strip() with two A-advances in a row at one apex allowed or not.
StripTessellation tessellate_strip_with(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                        const StripOptions& o, bool allow_stacked_a) {
  const int strip = o.strip_index;
  check_wale(a, "A (left)", strip);
  check_wale(b, "B (right)", strip);
  const double sw = o.stitch_width, sh = o.stitch_height;
  if (!(sw > 0.0) || !std::isfinite(sw) || !(sh > 0.0) || !std::isfinite(sh))
    throw InvalidInput(fmt::format(
        "tessellate_strip: strip {}: stitch size {} x {} mm must be positive and finite", strip, sw,
        sh));
  const double lambda0 = o.lambda.value_or(sw + 2.0 * sh);
  Diffusion dif;
  dif.mu = o.mu.value_or(100.0 * sw);
  dif.length = o.diffusion_length.value_or(sw);
  if (!(lambda0 > 0.0) || !std::isfinite(lambda0))
    throw InvalidInput(fmt::format("tessellate_strip: strip {}: lambda {} must be positive", strip,
                                   lambda0));
  if (!(dif.mu >= 0.0) || !std::isfinite(dif.mu))
    throw InvalidInput(fmt::format(
        "tessellate_strip: strip {}: diffusion weight mu {} must be >= 0 and finite", strip, dif.mu));
  if (!(dif.length > 0.0) || !std::isfinite(dif.length))
    throw InvalidInput(fmt::format(
        "tessellate_strip: strip {}: diffusion length {} must be positive", strip, dif.length));
  if (o.max_lambda_growths < 0)
    throw InvalidInput(fmt::format("tessellate_strip: strip {}: max_lambda_growths {} < 0", strip,
                                   o.max_lambda_growths));
  for (size_t p = 0; p < o.previous_apexes.size(); ++p)
    if (!o.previous_apexes[p].allFinite())
      throw InvalidInput(fmt::format("tessellate_strip: strip {}: previous apex {} is not finite",
                                     strip, p));

  const Strip s(a, b);
  const int na = s.na(), nb = s.nb();

  // Bijective closest pairs among the even samples, counting only samples
  // where the two wales run the same way (a wale that folds back next to
  // the other, around a cut, must not pair its returning half).
  auto dist2 = [&](int i, int j) {
    const size_t ka = static_cast<size_t>(2 * i), kb = static_cast<size_t>(2 * j);
    const double d = (a[ka] - b[kb]).squaredNorm();
    return wale_tangent(a, ka).dot(wale_tangent(b, kb)) > 0.0 ? d : kInf;
  };
  // Ties (samples at one position: the two lips of a seam that a wale runs
  // around, so that its ends meet) go to the sample at the nearest relative
  // position along the wale, then to the lower index.
  auto offset = [&](int i, int j) {
    return std::abs(static_cast<double>(i) / std::max(na, 1) - static_cast<double>(j) / std::max(nb, 1));
  };
  // Distances within a hundredth of the stitch height tie: the wale ends on
  // the two lips of a seam lie that close (up to the field's tolerance).
  const double tie_mm = 0.01 * o.stitch_height;
  auto tie = [&](double d, double e) {
    return d < kInf && e < kInf && std::abs(std::sqrt(d) - std::sqrt(e)) <= tie_mm;
  };
  std::vector<int> near_b(static_cast<size_t>(na + 1), -1), near_a(static_cast<size_t>(nb + 1), -1);
  for (int i = 0; i <= na; ++i) {
    double best_d = kInf;
    int& best = near_b[static_cast<size_t>(i)];
    for (int j = 0; j <= nb; ++j) {
      const double d = dist2(i, j);
      if (tie(d, best_d) ? offset(i, j) < offset(i, best) : d < best_d) best = j, best_d = std::min(d, best_d);
    }
  }
  for (int j = 0; j <= nb; ++j) {
    double best_d = kInf;
    int& best = near_a[static_cast<size_t>(j)];
    for (int i = 0; i <= na; ++i) {
      const double d = dist2(i, j);
      if (tie(d, best_d) ? offset(i, j) < offset(best, j) : d < best_d) best = i, best_d = std::min(d, best_d);
    }
  }
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i <= na; ++i) {
    const int j = near_b[static_cast<size_t>(i)];
    if (j >= 0 && near_a[static_cast<size_t>(j)] == i) pairs.push_back({i, j});
  }
  // There is one whenever some pair runs the same way (the closest such pair
  // is mutual); wales that run against each other everywhere are joined
  // from their starts.
  const bool fork_lo = o.start_increase, fork_hi = o.end_decrease;
  if (fork_lo || fork_hi) {
    double size = 0.0;
    for (const Vec3& p : a) size = std::max(size, (p - a[0]).norm());
    const double tol = 1e-6 * std::max(size, sw);
    if (fork_lo && (a.front() - b.front()).norm() > tol)
      throw InvalidInput(fmt::format("tessellate_strip: strip {}: a short column starts at a fork, but a_0 and b_0 "
                                     "are {:.3g} mm apart",
                                     strip, (a.front() - b.front()).norm()));
    if (fork_hi && (a.back() - b.back()).norm() > tol)
      throw InvalidInput(fmt::format("tessellate_strip: strip {}: a short column ends at a join, but its last "
                                     "samples are {:.3g} mm apart",
                                     strip, (a.back() - b.back()).norm()));
  }
  std::array<int, 2> source{0, 0}, target{na, nb};
  if (!fork_lo) {
    source = pairs.empty() ? std::array<int, 2>{0, 0} : pairs.front();
    if (fork_hi && !(source[0] < na)) source = {0, 0};
  }
  if (!fork_hi) {
    target = source;
    for (const auto& p : pairs)
      if (p[0] > source[0] && p[1] >= source[1] && p[1] - source[1] <= 3 * (p[0] - source[0]) && (!fork_lo || p[1] > 0))
        target = p;
    // Below a fork there is no bottom part: the middle part starts at (0, 0)
    // with a fork operator, so it must lead somewhere.
    if (fork_lo && target == source) target = {na, nb};
  }

  StripTessellation r;
  r.source = source;
  r.target = target;

  std::vector<Vec3> placed = o.previous_apexes;
  auto run_part = [&](std::array<int, 2> from, std::array<int, 2> to, double lambda, bool allow_fan,
                      bool fork_start, bool fork_end) {
    const std::vector<double> fixed = nearest_apex_distances(s, placed, dif.length);
    return search(s, from, to, lambda, allow_fan, fixed, dif, fork_start, fork_end, o.allow_double_advance,
                  allow_stacked_a);
  };

  // Bottom part (no lambda limit; always has a path thanks to the B-fan at a_0);
  // none below a fork.
  SearchResult bottom;
  bottom.found = true;
  if (!fork_lo) bottom = run_part({0, 0}, source, kInf, true, false, false);
  if (!bottom.found)
    throw SolverError(fmt::format(
        "tessellate_strip: strip {}: internal error: no tessellation below the source node "
        "(a_{}, b_{})",
        strip, 2 * source[0], 2 * source[1]));
  collect_apexes(s, bottom.steps, placed);

  // Middle part with the bridge limit lambda, grown by 10 % until a path
  // exists; it starts (ends) with a fork operator at a fork end.
  double max_bridge = -1.0;  // longest bridge between source and target, computed on demand
  double lambda = lambda0;
  int growths = 0;
  SearchResult middle;
  const bool empty_middle = source == target && !fork_lo && !fork_hi;
  bool fallback = false;
  for (;;) {
    if (empty_middle) {
      middle.found = true;
      break;
    }
    middle = run_part(source, target, lambda, false, fork_lo, fork_hi);
    if (middle.found) break;
    if (max_bridge < 0.0) {
      max_bridge = 0.0;
      for (int k = 2 * source[0]; k <= 2 * target[0]; ++k)
        for (int l = 2 * source[1]; l <= 2 * target[1]; ++l)
          max_bridge = std::max(max_bridge, s.bridge(k, l));
    }
    if ((growths >= o.max_lambda_growths || lambda >= max_bridge) && fork_lo != fork_hi && !fallback) {
      // One end is a fork, the other a wale end: the fork operators may need
      // more of the other wale than the bridge-limited part gives; search the
      // whole strip from (to) the wale end instead, with its fans.
      fallback = true;
      if (!fork_lo) {
        source = {0, 0};
        bottom.steps.clear();
        placed = o.previous_apexes;
      } else {
        target = {na, nb};
      }
      r.source = source;
      r.target = target;
      middle = run_part(source, target, kInf, true, fork_lo, fork_hi);
      if (middle.found) {
        lambda = max_bridge;
        break;
      }
    }
    if (growths >= o.max_lambda_growths || lambda >= max_bridge)
      throw SolverError(fmt::format(
          "tessellate_strip: strip {}: no knittable tessellation between the source bridge "
          "(a_{}, b_{}) and the target bridge (a_{}, b_{}) even with lambda = {:.4g} mm after {} "
          "growths (initial {:.4g} mm, longest bridge {:.4g} mm); the wales may be too far apart "
          "or of too different length for the stitch size{}",
          strip, 2 * source[0], 2 * source[1], 2 * target[0], 2 * target[1], lambda, growths,
          lambda0, max_bridge, fork_lo || fork_hi ? " (a short column's wales differ by more than the fork operators allow)" : ""));
    lambda *= 1.1;
    ++growths;
  }
  collect_apexes(s, middle.steps, placed);

  // Top part (no lambda limit; always has a path thanks to the B-fan at a_2na);
  // none above a join.
  SearchResult top;
  top.found = true;
  if (!fork_hi) top = run_part(target, {na, nb}, kInf, true, false, false);
  if (!top.found)
    throw SolverError(fmt::format(
        "tessellate_strip: strip {}: internal error: no tessellation above the target node "
        "(a_{}, b_{})",
        strip, 2 * target[0], 2 * target[1]));

  r.steps = std::move(bottom.steps);
  r.steps.insert(r.steps.end(), middle.steps.begin(), middle.steps.end());
  r.steps.insert(r.steps.end(), top.steps.begin(), top.steps.end());
  r.lambda = lambda;
  r.lambda_growths = growths;

  // Faces, apexes and the exact cost of the path.
  int course = 0;
  std::vector<Vec3> seen = o.previous_apexes;
  OpShape shp;
  for (const StripStep& st : r.steps) {
    s.shape(st.op, st.i, st.j, shp);
    s.faces(st.op, st.i, st.j, course, r.faces);
    for (const Bridge& br : shp.bridges) r.cost += s.bridge(br.k, br.l);
    for (int v : shp.apexes) {
      const bool end = s.on_wale_end(v);
      r.apexes.push_back({v, s.pos(v), end});
      if (end) continue;
      if (dif.mu > 0.0) {
        double d = kInf;
        for (const Vec3& p : seen) d = std::min(d, (s.pos(v) - p).norm() / dif.length);
        r.cost += dif.mu * std::exp(-d * d);
      }
      seen.push_back(s.pos(v));
    }
  }
  return r;
}

}  // namespace

StripTessellation tessellate_strip(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                   const StripOptions& o) {
  if (o.allow_double_advance) return tessellate_strip_with(a, b, o, true);
  // Without double advances, two A-advances in a row are refused too (their
  // shared apex holds four stacked short-row ends); only a strip with no
  // path without them gets them.
  try {
    return tessellate_strip_with(a, b, o, false);
  } catch (const SolverError&) {
    return tessellate_strip_with(a, b, o, true);
  }
}

}  // namespace knitforge

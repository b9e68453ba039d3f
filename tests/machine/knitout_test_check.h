#pragma once
// Test-only checker for the knitout programs write_knitout() produces: an
// independent little two-bed machine (loops per needle with their yarn
// parents, racking, carriers and the hook) plus the map correspondence given
// by the "; course r:" blocks. Strict: any rule broken is recorded as an
// error string with the line number.

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge::test {

struct CheckResult {
  std::vector<std::string> errors;
  int max_abs_rack = 0;
  int max_loops = 0;
  int max_float = 0;
  std::vector<int> course_ops;           // per map row: knit/tuck ops in its block
  std::vector<std::vector<int>> parents_ok;  // unused placeholder for readability
  int wale_links_checked = 0;
  int knits_outside_courses = 0;
  std::set<std::string> carriers_used;
};

inline std::vector<std::string> split_ws(const std::string& s) {
  std::istringstream is(s);
  std::vector<std::string> t;
  std::string w;
  while (is >> w) t.push_back(w);
  return t;
}

// Parses "f12" / "b-3"; returns false when malformed.
inline bool parse_needle(const std::string& s, char& bed, int& n) {
  if (s.size() < 2 || (s[0] != 'f' && s[0] != 'b')) return false;
  bed = s[0];
  char* end = nullptr;
  n = static_cast<int>(std::strtol(s.c_str() + 1, &end, 10));
  return end && *end == '\0';
}

inline CheckResult check_knitout(const std::string& text, const KnittingMap& map,
                                 const MachineProfile& prof) {
  CheckResult res;
  auto err = [&](int line, const std::string& what) {
    res.errors.push_back("line " + std::to_string(line) + ": " + what);
  };
  std::vector<std::string> lines;
  {
    std::string cur;
    for (char ch : text) {
      if (ch == '\n') {
        lines.push_back(cur);
        cur.clear();
      } else {
        cur.push_back(ch);
      }
    }
    if (!cur.empty()) err(static_cast<int>(lines.size()) + 1, "last line without LF");
  }
  if (lines.empty() || lines[0] != ";!knitout-2") err(1, "first line is not ;!knitout-2");
  std::set<std::string> declared;
  std::map<std::string, std::string> headers;
  size_t li = 1;
  for (; li < lines.size() && lines[li].rfind(";;", 0) == 0; ++li) {
    const auto colon = lines[li].find(": ");
    if (colon == std::string::npos) {
      err(static_cast<int>(li) + 1, "header without ': '");
      continue;
    }
    headers[lines[li].substr(2, colon - 2)] = lines[li].substr(colon + 2);
  }
  for (const char* h : {"Machine", "Gauge", "Carriers", "Position"})
    if (!headers.count(h)) err(0, std::string("missing header ;;") + h);
  for (const auto& c : split_ws(headers["Carriers"])) declared.insert(c);

  // machine state
  struct Loop {
    int id;
  };
  std::map<std::pair<char, int>, std::vector<int>> bed;  // needle -> loop ids
  int racking = 0;
  std::set<std::string> active;
  std::string hook;  // carrier held by the hook ("" none)
  std::map<std::string, int> last_needle;  // carrier -> last stitch needle
  std::map<std::string, bool> in_seen;
  int next_loop = 0;
  std::vector<std::vector<int>> loop_parents;
  // map correspondence
  const int R = map.rows, C = map.cols;
  res.course_ops.assign(R, 0);
  std::vector<int> loop_of_cell(static_cast<size_t>(R) * C, -1);
  int cur_course = -1;
  std::vector<int> course_cells;
  size_t course_pos = 0;

  auto stitch_op = [&](int ln, const std::string& op, const std::vector<std::string>& t) {
    if (t.size() < 4) {
      err(ln, "too few operands");
      return;
    }
    char b;
    int n;
    if (!parse_needle(t[2], b, n)) {
      err(ln, "bad needle " + t[2]);
      return;
    }
    if (t[1] != "+" && t[1] != "-") err(ln, "bad direction");
    if (n < 1 || n > prof.needle_count) err(ln, "needle outside the bed");
    for (size_t i = 3; i < t.size(); ++i) {
      const std::string& c = t[i];
      res.carriers_used.insert(c);
      if (!declared.count(c)) err(ln, "carrier " + c + " not declared");
      if (!active.count(c)) err(ln, "carrier " + c + " not in");
      if (last_needle.count(c)) {
        res.max_float = std::max(res.max_float, std::abs(n - last_needle[c]));
        if (std::abs(n - last_needle[c]) > prof.max_float_needles) err(ln, "float too long");
      }
      last_needle[c] = n;
    }
    if (op == "miss") return;
    auto& L = bed[{b, n}];
    if (op == "knit" && L.empty() && cur_course >= 0) err(ln, "knit on an empty needle");
    const int id = next_loop++;
    loop_parents.push_back(op == "knit" ? L : std::vector<int>{});
    if (op == "knit") L.clear();
    L.push_back(id);
    res.max_loops = std::max(res.max_loops, static_cast<int>(L.size()));
    if (static_cast<int>(L.size()) > prof.max_loops_per_needle) err(ln, "too many loops on a needle");
    if (cur_course >= 0) {
      ++res.course_ops[cur_course];
      if (course_pos < course_cells.size()) {
        loop_of_cell[static_cast<size_t>(cur_course) * C + course_cells[course_pos]] = id;
        // a map stitch without a loop below is made by a tuck, others by knit
        ++course_pos;
      } else {
        err(ln, "more stitch operations than stitches in the course");
      }
    } else if (op == "knit") {
      ++res.knits_outside_courses;
    }
  };

  for (; li < lines.size(); ++li) {
    const int ln = static_cast<int>(li) + 1;
    const std::string& s = lines[li];
    if (s.rfind(";", 0) == 0) {
      if (s.rfind(";;", 0) == 0) err(ln, "header after the header block");
      if (cur_course >= 0 && course_pos != course_cells.size())
        err(ln, "course " + std::to_string(cur_course) + " knitted fewer stitches than the map");
      cur_course = -1;
      if (s.rfind("; course ", 0) == 0) {
        cur_course = std::atoi(s.c_str() + 9);
        if (cur_course < 0 || cur_course >= R) {
          err(ln, "bad course number");
          cur_course = -1;
          continue;
        }
        course_cells.clear();
        course_pos = 0;
        const int d = map.direction[cur_course];
        for (int k = 0; k < C; ++k) {
          const int c = d > 0 ? k : C - 1 - k;
          if (is_stitch(map.at(cur_course, c))) course_cells.push_back(c);
        }
      }
      continue;
    }
    const auto t = split_ws(s.substr(0, s.find(';')));
    if (t.empty()) continue;
    const std::string& op = t[0];
    if (op == "knit" || op == "tuck" || op == "miss") {
      stitch_op(ln, op, t);
    } else if (op == "xfer") {
      char b1, b2;
      int n1, n2;
      if (t.size() != 3 || !parse_needle(t[1], b1, n1) || !parse_needle(t[2], b2, n2) || b1 == b2) {
        err(ln, "bad xfer");
        continue;
      }
      const int front = b1 == 'f' ? n1 : n2, back = b1 == 'f' ? n2 : n1;
      if (front != back + racking) err(ln, "xfer between misaligned needles");
      if (!hook.empty()) err(ln, "xfer while the hook holds carrier " + hook);
      auto& src = bed[{b1, n1}];
      auto& dst = bed[{b2, n2}];
      dst.insert(dst.end(), src.begin(), src.end());
      src.clear();
      res.max_loops = std::max(res.max_loops, static_cast<int>(dst.size()));
      if (static_cast<int>(dst.size()) > prof.max_loops_per_needle) err(ln, "too many loops after xfer");
    } else if (op == "rack") {
      if (t.size() != 2) {
        err(ln, "bad rack");
        continue;
      }
      const double r = std::atof(t[1].c_str());
      if (r != std::floor(r)) err(ln, "fractional racking");
      racking = static_cast<int>(r);
      res.max_abs_rack = std::max(res.max_abs_rack, std::abs(racking));
      if (std::abs(racking) > prof.max_racking) err(ln, "racking beyond the machine");
    } else if (op == "in" || op == "inhook") {
      if (op == "inhook" && !prof.has_yarn_inserting_hook) err(ln, "inhook without a hook");
      if (op == "in" && prof.has_yarn_inserting_hook) err(ln, "plain in on a hook machine");
      for (size_t i = 1; i < t.size(); ++i) {
        if (!declared.count(t[i])) err(ln, "carrier not declared");
        if (active.count(t[i])) err(ln, "carrier already in");
        active.insert(t[i]);
        last_needle.erase(t[i]);
        if (op == "inhook") {
          if (!hook.empty()) err(ln, "hook already holds a carrier");
          hook = t[i];
        }
      }
    } else if (op == "releasehook") {
      if (t.size() != 2 || hook != t[1]) err(ln, "releasehook of a carrier the hook does not hold");
      hook.clear();
    } else if (op == "out" || op == "outhook") {
      for (size_t i = 1; i < t.size(); ++i) {
        if (!active.count(t[i])) err(ln, "out of a carrier that is not in");
        if (hook == t[i]) err(ln, "out while the hook still holds the carrier");
        active.erase(t[i]);
      }
    } else if (op == "drop") {
      char b;
      int n;
      if (t.size() != 2 || !parse_needle(t[1], b, n)) err(ln, "bad drop");
      else bed[{b, n}].clear();
    } else if (op.rfind("x-", 0) == 0) {
      // extension
    } else {
      err(ln, "unknown operation " + op);
    }
  }
  if (!active.empty()) err(0, "carriers still in at the end");
  if (!hook.empty()) err(0, "hook still holds a carrier at the end");
  for (const auto& [k, v] : bed)
    if (!v.empty()) err(0, "loops left on a needle at the end");
  if (racking != 0) err(0, "racking not 0 at the end");

  // wale links: each stitch whose wale continues from below is knitted through
  // the loop of the wale's previous stitch.
  for (int c = 0; c < C; ++c) {
    int prev = -1;
    for (int r = 0; r < R; ++r) {
      const int id = loop_of_cell[static_cast<size_t>(r) * C + c];
      if (!is_stitch(map.at(r, c))) {
        if (map.at(r, c) == CellType::Empty) prev = -1;
        continue;
      }
      if (id < 0) {
        err(0, "map stitch (" + std::to_string(r) + "," + std::to_string(c) + ") never knitted");
        continue;
      }
      if (prev >= 0 && map.at(r, c) != CellType::Increase) {
        bool found = false;
        for (int p : loop_parents[id]) found |= p == prev;
        if (!found)
          err(0, "stitch (" + std::to_string(r) + "," + std::to_string(c) +
                     ") is not knitted through the loop of its wale below");
        ++res.wale_links_checked;
      }
      prev = map.at(r, c) == CellType::Decrease ? -1 : id;
    }
  }
  return res;
}

}  // namespace knitforge::test

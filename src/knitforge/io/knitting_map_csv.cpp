#include "knitforge/io/knitting_map_csv.h"

#include <cctype>
#include <ostream>

#include <fmt/core.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using namespace io_detail;

namespace {

constexpr char kCodes[] = {'K', 'L', 'R', 'I', 'D', 'C', '.'};  // indexed by CellType

[[noreturn]] void fail_at(const std::string& source, int64_t line, size_t column, std::string_view msg) {
  throw IOError(fmt::format("{}:{}, column {}: {}", source, line, column, msg));
}

// Splits at `sep`, trims spaces and one pair of surrounding double quotes.
void split_fields(std::string_view line, char sep, std::vector<std::string_view>& out) {
  out.clear();
  size_t i = 0;
  while (true) {
    const size_t j = line.find(sep, i);
    std::string_view f = trim(line.substr(i, j == std::string_view::npos ? std::string_view::npos : j - i));
    if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = trim(f.substr(1, f.size() - 2));
    out.push_back(f);
    if (j == std::string_view::npos) break;
    i = j + 1;
  }
}

bool all_empty(const std::vector<std::string_view>& fields) {
  for (auto f : fields) {
    if (!f.empty()) return false;
  }
  return true;
}

}  // namespace

std::string knitting_map_to_csv(const KnittingMap& map) {
  if (map.rows < 0 || map.cols < 0 || map.cells.size() != static_cast<size_t>(map.rows) * map.cols ||
      map.direction.size() != static_cast<size_t>(map.rows) ||
      (!map.yarn.empty() && map.yarn.size() != map.cells.size())) {
    throw InvalidInput(fmt::format("knitting map {}x{}: cells ({}), direction ({}) or yarn ({}) have the "
                                   "wrong size",
                                   map.rows, map.cols, map.cells.size(), map.direction.size(), map.yarn.size()));
  }
  if (!map.seam.empty() && map.seam.size() != static_cast<size_t>(map.rows))
    throw InvalidInput(fmt::format("knitting map {}x{}: {} seam entries (expected none or {})", map.rows, map.cols,
                                   map.seam.size(), map.rows));
  const bool tube = map.tubular();
  std::string out = tube ? "course,dir,seam" : "course,dir";
  for (int c = 0; c < map.cols; ++c) out += fmt::format(",{}", c);
  out += '\n';
  for (int r = map.rows - 1; r >= 0; --r) {
    const int d = map.direction[r];
    if (d != 1 && d != -1) {
      throw InvalidInput(fmt::format("knitting map row {} has direction {}; it must be +1 or -1", r, d));
    }
    out += fmt::format("{},{}", r, d > 0 ? '>' : '<');
    if (tube) out += map.closed(r) ? fmt::format(",{}", map.seam[static_cast<size_t>(r)]) : std::string(",-");
    if (tube && map.closed_end && r == map.rows - 1) out += ":close";
    for (int c = 0; c < map.cols; ++c) {
      const int t = static_cast<int>(map.at(r, c));
      if (t < 0 || t > static_cast<int>(CellType::Empty)) {
        throw InvalidInput(fmt::format("knitting map cell ({}, {}) has unknown type {}", r, c, t));
      }
      const int y = map.yarn_at(r, c);
      if (y < 0) throw InvalidInput(fmt::format("knitting map cell ({}, {}) has negative yarn {}", r, c, y));
      out += ',';
      out += kCodes[t];
      if (y != 0) out += fmt::format("{}", y);
    }
    out += '\n';
  }
  return out;
}

KnittingMap knitting_map_from_csv(std::string_view text, const std::string& source) {
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> fields;
  // Header.
  bool found = false;
  while (lines.next(line)) {
    if (!trim(line).empty()) {
      found = true;
      break;
    }
  }
  if (!found) throw IOError(fmt::format("{}: file is empty (expected the header 'course,dir,0,1,...')", source));
  const char sep = line.find(';') != std::string_view::npos ? ';' : ',';
  const int64_t header_line = lines.line_number();
  split_fields(line, sep, fields);
  auto lower_eq = [](std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
      if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
    }
    return true;
  };
  if (fields.size() < 2 || !lower_eq(fields[0], "course") || !lower_eq(fields[1], "dir")) {
    fail_at(source, header_line, 1, "the header must start with 'course' and 'dir', then the column indices 0, 1, ...");
  }
  // A tube: a `seam` column after `dir`.
  const bool tube = fields.size() >= 3 && lower_eq(fields[2], "seam");
  const size_t first = tube ? 3 : 2;  // field index of column 0
  const size_t cols = fields.size() - first;
  for (size_t c = 0; c < cols; ++c) {
    int64_t v = -1;
    if (!parse_int64(fields[c + first], v) || v != static_cast<int64_t>(c)) {
      fail_at(source, header_line, c + first + 1,
              fmt::format("column header '{}' should be {} (the columns are numbered 0, 1, ... from the left)",
                          fields[c + first], c));
    }
  }
  // Courses, top first.
  struct Row {
    int8_t dir;
    int seam = -1;
    std::vector<CellType> cells;
    std::vector<int> yarn;
  };
  std::vector<Row> rows;
  bool closed_end = false;
  int64_t expected = -1, last_line = header_line;
  bool any_yarn = false;
  while (lines.next(line)) {
    const int64_t ln = lines.line_number();
    split_fields(line, sep, fields);
    if (all_empty(fields)) continue;
    last_line = ln;
    if (fields.size() != cols + first) {
      fail_at(source, ln, fields.size() > cols + first ? cols + first + 1 : fields.size() + 1,
              fmt::format("{} fields, but the header has {} (course, dir, {}{} cells)", fields.size(), cols + first,
                          tube ? "seam and " : "", cols));
    }
    int64_t r = -1;
    if (!parse_int64(fields[0], r) || r < 0) {
      fail_at(source, ln, 1, fmt::format("'{}' is not a course index (a non-negative integer)", fields[0]));
    }
    if (rows.empty()) {
      expected = r;
    } else if (expected < 0) {
      fail_at(source, ln, 1, "a line after the bottom course 0: courses are listed from the top course down to 0, "
                             "one per line");
    } else if (r != expected) {
      fail_at(source, ln, 1,
              fmt::format("course {} where {} was expected: courses are listed from the top course down to 0, "
                          "one per line", r, expected));
    }
    --expected;
    Row row;
    if (fields[1] == ">") row.dir = 1;
    else if (fields[1] == "<") row.dir = -1;
    else {
      fail_at(source, ln, 2, fmt::format("unknown direction '{}' (expected > for left to right or < for right "
                                         "to left)", fields[1]));
    }
    std::string_view seam_field = tube ? std::string_view(fields[2]) : std::string_view();
    constexpr std::string_view kClose = ":close";
    if (seam_field.size() > kClose.size() && seam_field.substr(seam_field.size() - kClose.size()) == kClose) {
      if (!rows.empty()) {
        fail_at(source, ln, 3, fmt::format("seam '{}': only the last course (the top line) can close the tube "
                                           "(:close)", seam_field));
      }
      closed_end = true;
      seam_field.remove_suffix(kClose.size());
    }
    if (tube && seam_field != "-" && !seam_field.empty()) {
      int64_t v = -1;
      if (!parse_int64(seam_field, v) || v < 0 || v >= static_cast<int64_t>(cols)) {
        fail_at(source, ln, 3,
                fmt::format("seam '{}': expected - for an open row (a short row) or the line 0..{} where the "
                            "round starts (0 = left of column 0)",
                            fields[2], cols == 0 ? 0 : cols - 1));
      }
      row.seam = static_cast<int>(v);
    }
    row.cells.resize(cols);
    row.yarn.assign(cols, 0);
    for (size_t c = 0; c < cols; ++c) {
      const std::string_view f = fields[c + first];
      if (f.empty()) {
        row.cells[c] = CellType::Empty;
        continue;
      }
      const char code = static_cast<char>(std::toupper(static_cast<unsigned char>(f[0])));
      int t = -1;
      for (int k = 0; k < 7; ++k) {
        if (kCodes[k] == code) t = k;
      }
      if (t < 0) {
        fail_at(source, ln, c + first + 1, fmt::format("unknown cell code '{}' (expected K, L, R, I, D, C or .)", f));
      }
      row.cells[c] = static_cast<CellType>(t);
      if (f.size() > 1) {
        int64_t y = -1;
        const std::string_view suffix = f.substr(1);
        if (suffix.front() == '+' || suffix.front() == '-' || !parse_int64(suffix, y) || y > 1000000) {
          fail_at(source, ln, c + first + 1,
                  fmt::format("unknown cell code '{}': a code may only be followed by a yarn index (e.g. K2)", f));
        }
        row.yarn[c] = static_cast<int>(y);
        any_yarn = any_yarn || y != 0;
      }
    }
    rows.push_back(std::move(row));
  }
  if (!rows.empty() && expected != -1) {
    fail_at(source, last_line, 1,
            fmt::format("the last course is {}, but the bottom course must be 0 (lines for courses {}..0 are "
                        "missing)", expected + 1, expected));
  }
  KnittingMap map(static_cast<int>(rows.size()), static_cast<int>(cols));
  if (tube) map.seam.assign(rows.size(), -1);
  map.closed_end = closed_end;
  for (int r = 0; r < map.rows; ++r) {
    const Row& row = rows[rows.size() - 1 - r];
    map.direction[r] = row.dir;
    if (tube) map.seam[static_cast<size_t>(r)] = row.seam;
    for (int c = 0; c < map.cols; ++c) {
      map.at(r, c) = row.cells[c];
      if (any_yarn) map.set_yarn(r, c, row.yarn[c]);
    }
  }
  return map;
}

void write_knitting_map_csv(const std::string& path, const KnittingMap& map) {
  const std::string text = knitting_map_to_csv(map);
  write_file_atomically(path, [&](std::ostream& o) { o << text; }, true);
}

KnittingMap read_knitting_map_csv(const std::string& path) {
  return knitting_map_from_csv(load_file(path), path);
}

}  // namespace knitforge

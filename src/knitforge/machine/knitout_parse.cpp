#include "knitforge/machine/knitout_parse.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

#include <unordered_map>
#include <unordered_set>

#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/printable.h"

namespace knitforge {

std::string_view name(KnitoutOp op) {
  switch (op) {
    case KnitoutOp::In: return "in";
    case KnitoutOp::Inhook: return "inhook";
    case KnitoutOp::Releasehook: return "releasehook";
    case KnitoutOp::Out: return "out";
    case KnitoutOp::Outhook: return "outhook";
    case KnitoutOp::Knit: return "knit";
    case KnitoutOp::Tuck: return "tuck";
    case KnitoutOp::Split: return "split";
    case KnitoutOp::Miss: return "miss";
    case KnitoutOp::Xfer: return "xfer";
    case KnitoutOp::Drop: return "drop";
    case KnitoutOp::Amiss: return "amiss";
    case KnitoutOp::Rack: return "rack";
    case KnitoutOp::Stitch: return "stitch";
    case KnitoutOp::Pause: return "pause";
    case KnitoutOp::Extension: return "x-";
    case KnitoutOp::Comment: return "";
  }
  return "";
}

std::string to_string(const Needle& n) {
  static constexpr const char* kBed[] = {"f", "b", "fs", "bs"};
  return fmt::format("{}{}", kBed[static_cast<int>(n.bed)], n.index);
}

const std::string* KnitoutFile::header(std::string_view key) const {
  const std::string* v = nullptr;
  for (const auto& h : headers) {
    if (h.key == key) v = &h.value;
  }
  return v;
}

bool KnitoutFile::has_errors() const {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const KnitoutDiagnostic& d) { return d.severity == Severity::Error; });
}

namespace {

// A syntax problem on the current line; caught per line.
struct LineError {
  KnitoutCheck check;
  std::string message;
};

bool is_space(char c) { return c == ' ' || c == '\t'; }

std::vector<std::string_view> tokenize(std::string_view s) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    size_t j = i;
    while (j < s.size() && !is_space(s[j])) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// [-+]?(\d+|\d+\.\d*|\.\d+), as the spec's reference parser accepts.
double parse_number(std::string_view tok, const char* what) {
  std::string_view s = tok;
  bool neg = false;
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
    neg = s[0] == '-';
    s.remove_prefix(1);
  }
  int digits = 0, dots = 0;
  for (char c : s) {
    if (c >= '0' && c <= '9') {
      ++digits;
    } else if (c == '.') {
      ++dots;
    } else {
      digits = -1000;
      break;
    }
  }
  if (digits <= 0 || dots > 1) {
    throw LineError{KnitoutCheck::Malformed, fmt::format("{} '{}' is not a number", what, printable(tok))};
  }
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) {
    // "5." is accepted by the spec's pattern but not by from_chars.
    std::string tmp(s);
    if (!tmp.empty() && tmp.back() == '.') tmp.pop_back();
    const auto r2 = std::from_chars(tmp.data(), tmp.data() + tmp.size(), v);
    if (r2.ec != std::errc() || r2.ptr != tmp.data() + tmp.size()) {
      throw LineError{KnitoutCheck::Malformed, fmt::format("{} '{}' is not a number", what, printable(tok))};
    }
  }
  return neg ? -v : v;
}

int8_t parse_direction(std::string_view tok) {
  if (tok == "+") return 1;
  if (tok == "-") return -1;
  throw LineError{KnitoutCheck::Malformed, fmt::format("direction '{}' must be '+' or '-'", printable(tok))};
}

Needle parse_needle(std::string_view tok) {
  Needle n;
  std::string_view s = tok;
  if (s.size() >= 2 && (s.substr(0, 2) == "fs" || s.substr(0, 2) == "bs")) {
    n.bed = s[0] == 'f' ? Bed::FrontSlider : Bed::BackSlider;
    s.remove_prefix(2);
  } else if (!s.empty() && (s[0] == 'f' || s[0] == 'b')) {
    n.bed = s[0] == 'f' ? Bed::Front : Bed::Back;
    s.remove_prefix(1);
  } else {
    throw LineError{KnitoutCheck::Malformed,
                    fmt::format("needle '{}' must be f, b, fs or bs followed by an integer", printable(tok))};
  }
  bool neg = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    neg = s[0] == '-';
    s.remove_prefix(1);
  }
  int v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size()) {
    throw LineError{KnitoutCheck::Malformed,
                    fmt::format("needle '{}' must be f, b, fs or bs followed by an integer", printable(tok))};
  }
  n.index = neg ? -v : v;
  return n;
}

}  // namespace

KnitoutFile parse_knitout(std::string_view text) {
  KnitoutFile prog;
  auto diag = [&](Severity s, KnitoutCheck c, int line, std::string msg) {
    prog.diagnostics.push_back({s, knitout_check_rule(c), c, line, std::move(msg)});
  };

  // Split into lines at LF, CR LF or a lone CR; other line endings than LF
  // give one warning (the spec asks readers to accept them and warn).
  std::vector<std::string_view> lines;
  int odd_ending_line = 0;
  {
    size_t start = 0;
    for (size_t k = 0; k < text.size(); ++k) {
      if (text[k] != '\n' && text[k] != '\r') continue;
      lines.push_back(text.substr(start, k - start));
      if (text[k] == '\r') {
        if (odd_ending_line == 0) odd_ending_line = static_cast<int>(lines.size());
        if (k + 1 < text.size() && text[k + 1] == '\n') ++k;
      }
      start = k + 1;
    }
    if (start < text.size()) lines.push_back(text.substr(start));
  }
  prog.num_lines = static_cast<int>(lines.size());
  if (odd_ending_line > 0) {
    diag(Severity::Warning, KnitoutCheck::LineEndings, odd_ending_line,
         "CR LF (or CR) line endings are not standard knitout (use LF); read as LF");
  }

  if (lines.empty() || lines[0].substr(0, 10) != ";!knitout-") {
    diag(Severity::Error, KnitoutCheck::MagicLine, 1,
         "the first line must be the magic line ';!knitout-2'; this is not a knitout file");
  } else {
    int v = 0;
    const std::string_view num = lines[0].substr(10);
    const auto r = std::from_chars(num.data(), num.data() + num.size(), v);
    if (num.empty() || r.ec != std::errc() || r.ptr != num.data() + num.size() || v < 0) {
      diag(Severity::Error, KnitoutCheck::MagicLine, 1,
           fmt::format("malformed magic line '{}'; expected ';!knitout-N' with a version number, e.g. "
                       "';!knitout-2'",
                       printable(lines[0])));
    } else {
      prog.version = v;
      if (v != 2) {
        diag(Severity::Warning, KnitoutCheck::Version, 1,
             fmt::format("knitout version {}: read as version 2 (the version this reader implements){}", v,
                         v > 2 ? "; operations of later versions are reported as unknown" : ""));
      }
    }
  }

  bool in_header = true;
  bool have_carriers = false;
  std::unordered_map<std::string, int> carrier_index;
  for (size_t li = 1; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    const std::string_view raw = lines[li];

    // Header lines: ";;Key: value" before the first operation.
    if (raw.size() >= 2 && raw.substr(0, 2) == ";;") {
      const size_t colon = raw.find(": ");
      if (in_header && colon != std::string_view::npos && colon > 2) {
        KnitoutHeader h{std::string(raw.substr(2, colon - 2)), std::string(raw.substr(colon + 2)), line};
        if (h.key == "Carriers") {
          if (have_carriers) {
            diag(Severity::Warning, KnitoutCheck::HeaderUnknown, line,
                 "';;Carriers:' given twice; the last one is used");
          }
          prog.carrier_names.clear();
          have_carriers = true;
          std::unordered_set<std::string_view> seen;
          for (auto t : tokenize(h.value)) {
            if (!seen.insert(t).second) {
              diag(Severity::Error, KnitoutCheck::HeaderValue, line,
                   fmt::format("carrier '{}' is named twice in ';;Carriers:'", printable(t)));
              continue;
            }
            prog.carrier_names.emplace_back(t);
          }
          carrier_index.clear();
          for (size_t k = 0; k < prog.carrier_names.size(); ++k)
            carrier_index.emplace(prog.carrier_names[k], static_cast<int>(k));
          if (prog.carrier_names.empty()) {
            diag(Severity::Error, KnitoutCheck::CarriersHeader, line, "';;Carriers:' names no carrier");
          }
        } else if (h.key == "Position") {
          if (h.value != "Left" && h.value != "Center" && h.value != "Right" && h.value != "Keep") {
            diag(Severity::Error, KnitoutCheck::HeaderValue, line,
                 fmt::format("';;Position:' is '{}'; it must be Left, Center, Right or Keep", printable(h.value)));
          }
        } else if (h.key == "Gauge") {
          try {
            if (parse_number(h.value, "gauge") <= 0.0) throw LineError{KnitoutCheck::HeaderValue, ""};
          } catch (const LineError&) {
            diag(Severity::Error, KnitoutCheck::HeaderValue, line,
                 fmt::format("';;Gauge:' is '{}'; it must be a positive number", printable(h.value)));
          }
        } else if (h.key == "Width") {
          try {
            const double w = parse_number(h.value, "width");
            if (w <= 0.0 || w != static_cast<int>(w)) throw LineError{KnitoutCheck::HeaderValue, ""};
          } catch (const LineError&) {
            diag(Severity::Error, KnitoutCheck::HeaderValue, line,
                 fmt::format("';;Width:' is '{}'; it must be a positive integer", printable(h.value)));
          }
        } else if (h.key != "Machine" && h.key.rfind("Yarn-", 0) != 0) {
          diag(Severity::Warning, KnitoutCheck::HeaderUnknown, line,
               fmt::format("unknown header ';;{}:' (ignored)", printable(h.key)));
        }
        prog.headers.push_back(std::move(h));
        continue;
      }
      if (!in_header && colon != std::string_view::npos) {
        diag(Severity::Warning, KnitoutCheck::HeaderUnknown, line,
             "header-like line after the first operation is only a comment");
      }
    }

    // Split operation and comment.
    const size_t semi = raw.find(';');
    const std::string_view op_part = raw.substr(0, semi);
    std::string_view comment = semi == std::string_view::npos ? std::string_view{} : raw.substr(semi + 1);
    std::vector<std::string_view> tok = tokenize(op_part);
    if (tok.empty()) {
      if (semi != std::string_view::npos) {
        KnitoutInstruction c;
        c.op = KnitoutOp::Comment;
        c.line = line;
        c.comment = std::string(comment);
        prog.instructions.push_back(std::move(c));
      }
      continue;
    }
    if (in_header) {
      in_header = false;
      if (!have_carriers) {
        diag(Severity::Error, KnitoutCheck::CarriersHeader, line,
             "the required ';;Carriers:' header is missing before the first operation");
      }
    }

    KnitoutInstruction ins;
    ins.line = line;
    ins.comment = std::string(comment);
    const std::string_view op = tok[0];
    std::vector<std::string_view> args(tok.begin() + 1, tok.end());
    auto carrier_set = [&](size_t from) {
      std::vector<int> cs;
      for (size_t i = from; i < args.size(); ++i) {
        const auto it = carrier_index.find(std::string(args[i]));
        if (it == carrier_index.end()) {
          throw LineError{KnitoutCheck::UndeclaredCarrier,
                          fmt::format("carrier '{}' is not named in the ';;Carriers:' header", printable(args[i]))};
        }
        const int c = it->second;
        if (std::find(cs.begin(), cs.end(), c) != cs.end()) {
          throw LineError{KnitoutCheck::Malformed,
                          fmt::format("carrier '{}' appears twice in the carrier set", printable(args[i]))};
        }
        cs.push_back(c);
      }
      return cs;
    };
    auto need = [&](bool ok, const char* usage) {
      if (!ok) throw LineError{KnitoutCheck::Malformed, fmt::format("'{}' takes {}", op, usage)};
    };

    try {
      if (op == "in" || op == "inhook" || op == "releasehook" || op == "out" || op == "outhook") {
        ins.op = op == "in"            ? KnitoutOp::In
                 : op == "inhook"      ? KnitoutOp::Inhook
                 : op == "releasehook" ? KnitoutOp::Releasehook
                 : op == "out"         ? KnitoutOp::Out
                                       : KnitoutOp::Outhook;
        need(!args.empty(), "a non-empty carrier set");
        ins.carriers = carrier_set(0);
      } else if (op == "knit" || op == "tuck") {
        ins.op = op == "knit" ? KnitoutOp::Knit : KnitoutOp::Tuck;
        need(args.size() >= 2, "a direction, a needle and a carrier set");
        ins.direction = parse_direction(args[0]);
        ins.needle = parse_needle(args[1]);
        ins.carriers = carrier_set(2);
        if (ins.carriers.empty()) ins.op = ins.op == KnitoutOp::Knit ? KnitoutOp::Drop : KnitoutOp::Amiss;
      } else if (op == "split") {
        ins.op = KnitoutOp::Split;
        need(args.size() >= 3, "a direction, two needles and a carrier set");
        ins.direction = parse_direction(args[0]);
        ins.needle = parse_needle(args[1]);
        ins.needle2 = parse_needle(args[2]);
        ins.carriers = carrier_set(3);
        if (ins.carriers.empty()) ins.op = KnitoutOp::Xfer;
      } else if (op == "miss") {
        ins.op = KnitoutOp::Miss;
        need(args.size() >= 3, "a direction, a needle and a non-empty carrier set");
        ins.direction = parse_direction(args[0]);
        ins.needle = parse_needle(args[1]);
        ins.carriers = carrier_set(2);
      } else if (op == "xfer") {
        ins.op = KnitoutOp::Xfer;
        need(args.size() == 2, "exactly two needles");
        ins.needle = parse_needle(args[0]);
        ins.needle2 = parse_needle(args[1]);
      } else if (op == "drop" || op == "amiss") {
        ins.op = op == "drop" ? KnitoutOp::Drop : KnitoutOp::Amiss;
        need(args.size() == 1, "exactly one needle");
        ins.needle = parse_needle(args[0]);
      } else if (op == "rack") {
        ins.op = KnitoutOp::Rack;
        need(args.size() == 1, "exactly one racking value");
        ins.value = parse_number(args[0], "racking");
      } else if (op == "stitch") {
        ins.op = KnitoutOp::Stitch;
        need(args.size() == 2, "exactly two values (loop length and stitch)");
        ins.value = parse_number(args[0], "stitch value");
        ins.value2 = parse_number(args[1], "stitch value");
      } else if (op == "pause") {
        ins.op = KnitoutOp::Pause;
        need(args.empty(), "no arguments");
      } else if (op.size() > 2 && op.substr(0, 2) == "x-") {
        ins.op = KnitoutOp::Extension;
        ins.extension = std::string(op);
        for (auto a : args) ins.args.emplace_back(a);
      } else {
        throw LineError{KnitoutCheck::UnknownOperation, fmt::format("unknown operation '{}'", printable(op))};
      }
      prog.instructions.push_back(std::move(ins));
    } catch (const LineError& e) {
      diag(Severity::Error, e.check, line, e.message);
    }
  }
  if (in_header && !have_carriers) {
    diag(Severity::Error, KnitoutCheck::CarriersHeader, lines.empty() ? 1 : static_cast<int>(lines.size()),
         "the required ';;Carriers:' header is missing");
  }
  return prog;
}

KnitoutFile read_knitout(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError(fmt::format("cannot open knitout file '{}'", path));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IOError(fmt::format("cannot read knitout file '{}'", path));
  return parse_knitout(ss.str());
}

}  // namespace knitforge

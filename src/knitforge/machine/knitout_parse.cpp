#include "knitforge/machine/knitout_parse.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

std::string_view name(KnitoutRule rule) {
  switch (rule) {
    case KnitoutRule::Syntax: return "syntax";
    case KnitoutRule::Header: return "header";
    case KnitoutRule::Extension: return "extension";
    case KnitoutRule::UndeclaredCarrier: return "undeclared-carrier";
    case KnitoutRule::InactiveCarrier: return "inactive-carrier";
    case KnitoutRule::CarrierLeftIn: return "carrier-left-in";
    case KnitoutRule::Racking: return "racking";
    case KnitoutRule::Misaligned: return "misaligned";
    case KnitoutRule::Slider: return "slider";
    case KnitoutRule::LoopsPerNeedle: return "loops-per-needle";
    case KnitoutRule::Float: return "float";
    case KnitoutRule::Hook: return "hook";
    case KnitoutRule::Drop: return "drop";
    case KnitoutRule::EmptyNeedleKnit: return "empty-needle-knit";
    case KnitoutRule::LoopsLeft: return "loops-left";
    case KnitoutRule::Width: return "width";
  }
  return "unknown";
}

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
  KnitoutRule rule;
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
    throw LineError{KnitoutRule::Syntax, fmt::format("{} '{}' is not a number", what, tok)};
  }
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) {
    // "5." is accepted by the spec's pattern but not by from_chars.
    std::string tmp(s);
    if (!tmp.empty() && tmp.back() == '.') tmp.pop_back();
    const auto r2 = std::from_chars(tmp.data(), tmp.data() + tmp.size(), v);
    if (r2.ec != std::errc() || r2.ptr != tmp.data() + tmp.size()) {
      throw LineError{KnitoutRule::Syntax, fmt::format("{} '{}' is not a number", what, tok)};
    }
  }
  return neg ? -v : v;
}

int8_t parse_direction(std::string_view tok) {
  if (tok == "+") return 1;
  if (tok == "-") return -1;
  throw LineError{KnitoutRule::Syntax, fmt::format("direction '{}' must be '+' or '-'", tok)};
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
    throw LineError{KnitoutRule::Syntax,
                    fmt::format("needle '{}' must be f, b, fs or bs followed by an integer", tok)};
  }
  bool neg = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    neg = s[0] == '-';
    s.remove_prefix(1);
  }
  int v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size()) {
    throw LineError{KnitoutRule::Syntax,
                    fmt::format("needle '{}' must be f, b, fs or bs followed by an integer", tok)};
  }
  n.index = neg ? -v : v;
  return n;
}

}  // namespace

KnitoutFile parse_knitout(std::string_view text) {
  KnitoutFile prog;
  auto diag = [&](Severity s, KnitoutRule r, int line, std::string msg) {
    prog.diagnostics.push_back({s, r, line, std::move(msg)});
  };

  // Split into lines (LF); strip a CR before LF with one warning.
  std::vector<std::string_view> lines;
  {
    size_t start = 0;
    while (start <= text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string_view::npos) {
        if (start < text.size()) lines.push_back(text.substr(start));
        break;
      }
      lines.push_back(text.substr(start, end - start));
      start = end + 1;
    }
  }
  prog.num_lines = static_cast<int>(lines.size());
  bool warned_cr = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (!lines[i].empty() && lines[i].back() == '\r') {
      lines[i].remove_suffix(1);
      if (!warned_cr) {
        diag(Severity::Warning, KnitoutRule::Syntax, static_cast<int>(i) + 1,
             "CR LF line endings are not standard knitout (use LF)");
        warned_cr = true;
      }
    }
  }

  if (lines.empty() || lines[0].substr(0, 10) != ";!knitout-") {
    diag(Severity::Error, KnitoutRule::Syntax, 1,
         "the first line must be the magic line ';!knitout-2'; this is not a knitout file");
  } else {
    int v = 0;
    const std::string_view num = lines[0].substr(10);
    const auto r = std::from_chars(num.data(), num.data() + num.size(), v);
    if (num.empty() || r.ec != std::errc() || r.ptr != num.data() + num.size()) {
      diag(Severity::Error, KnitoutRule::Syntax, 1,
           fmt::format("malformed magic line '{}'; expected ';!knitout-2'", lines[0]));
    } else {
      prog.version = v;
      if (v != 2) {
        diag(v > 2 ? Severity::Error : Severity::Warning, KnitoutRule::Syntax, 1,
             fmt::format("knitout version {} (this reader implements version 2)", v));
      }
    }
  }

  bool in_header = true;
  bool have_carriers = false;
  std::map<std::string, int, std::less<>> carrier_index;  // name -> first index
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
            diag(Severity::Warning, KnitoutRule::Header, line,
                 "';;Carriers:' given twice; the last one is used");
          }
          prog.carrier_names.clear();
          for (auto t : tokenize(h.value)) prog.carrier_names.emplace_back(t);
          have_carriers = true;
          // Sorted lookup (a pairwise check was quadratic in the header's length).
          carrier_index.clear();
          for (size_t a = 0; a < prog.carrier_names.size(); ++a) {
            const auto [it, fresh] = carrier_index.emplace(prog.carrier_names[a], static_cast<int>(a));
            if (!fresh) {
              diag(Severity::Error, KnitoutRule::Header, line,
                   fmt::format("carrier '{}' is named twice in ';;Carriers:'", prog.carrier_names[a]));
            }
          }
          if (prog.carrier_names.empty()) {
            diag(Severity::Error, KnitoutRule::Header, line, "';;Carriers:' names no carrier");
          }
        } else if (h.key == "Position") {
          if (h.value != "Left" && h.value != "Center" && h.value != "Right" && h.value != "Keep") {
            diag(Severity::Error, KnitoutRule::Header, line,
                 fmt::format("';;Position:' is '{}'; it must be Left, Center, Right or Keep", h.value));
          }
        } else if (h.key == "Gauge") {
          try {
            if (parse_number(h.value, "gauge") <= 0.0) throw LineError{KnitoutRule::Header, ""};
          } catch (const LineError&) {
            diag(Severity::Error, KnitoutRule::Header, line,
                 fmt::format("';;Gauge:' is '{}'; it must be a positive number", h.value));
          }
        } else if (h.key == "Width") {
          try {
            const double w = parse_number(h.value, "width");
            if (w <= 0.0 || w != static_cast<int>(w)) throw LineError{KnitoutRule::Header, ""};
          } catch (const LineError&) {
            diag(Severity::Error, KnitoutRule::Header, line,
                 fmt::format("';;Width:' is '{}'; it must be a positive integer", h.value));
          }
        } else if (h.key != "Machine" && h.key.rfind("Yarn-", 0) != 0) {
          diag(Severity::Warning, KnitoutRule::Header, line, fmt::format("unknown header ';;{}:'", h.key));
        }
        prog.headers.push_back(std::move(h));
        continue;
      }
      if (!in_header && colon != std::string_view::npos) {
        diag(Severity::Warning, KnitoutRule::Header, line,
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
        diag(Severity::Error, KnitoutRule::Header, line,
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
        const auto it = carrier_index.find(args[i]);
        if (it == carrier_index.end()) {
          throw LineError{KnitoutRule::UndeclaredCarrier,
                          fmt::format("carrier '{}' is not named in the ';;Carriers:' header", args[i])};
        }
        const int c = it->second;
        if (std::find(cs.begin(), cs.end(), c) != cs.end()) {
          throw LineError{KnitoutRule::Syntax, fmt::format("carrier '{}' appears twice in the carrier set", args[i])};
        }
        cs.push_back(c);
      }
      return cs;
    };
    auto need = [&](bool ok, const char* usage) {
      if (!ok) throw LineError{KnitoutRule::Syntax, fmt::format("'{}' takes {}", op, usage)};
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
        diag(Severity::Warning, KnitoutRule::Extension, line,
             fmt::format("extension '{}' is not simulated and is ignored", op));
      } else {
        throw LineError{KnitoutRule::Syntax, fmt::format("unknown operation '{}'", op)};
      }
      prog.instructions.push_back(std::move(ins));
    } catch (const LineError& e) {
      diag(Severity::Error, e.rule, line, e.message);
    }
  }
  if (in_header && !have_carriers) {
    diag(Severity::Error, KnitoutRule::Header, lines.empty() ? 1 : static_cast<int>(lines.size()),
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

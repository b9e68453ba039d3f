#include "knitforge/machine/knitout_simulate.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <unordered_set>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/machine/knitout_extensions.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/printable.h"

namespace knitforge {

namespace {

using C = KnitoutCheck;

// Loops held by the needles of one bed; grows to whatever indices are used.
class BedLoops {
 public:
  std::vector<int>& at(int n) {
    if (slots_.empty()) {
      offset_ = n;
      slots_.resize(1);
    } else if (n < offset_) {
      slots_.insert(slots_.begin(), static_cast<size_t>(offset_ - n), {});
      offset_ = n;
    } else if (n - offset_ >= static_cast<int>(slots_.size())) {
      slots_.resize(static_cast<size_t>(n - offset_) + 1);
    }
    return slots_[static_cast<size_t>(n - offset_)];
  }
  template <class F>
  void for_each(F&& f) const {
    for (size_t i = 0; i < slots_.size(); ++i) {
      if (!slots_[i].empty()) f(offset_ + static_cast<int>(i), slots_[i]);
    }
  }

 private:
  int offset_ = 0;
  std::vector<std::vector<int>> slots_;
};

struct CarrierState {
  bool in = false;
  bool hooked = false;       // held by the yarn-inserting hook
  bool stitched = false;     // has made a loop since it came in
  bool pending_first = false;  // the next operation is its first after `in`
  bool reported_inactive = false;  // used while out, reported once
  uint32_t in_set = 0;       // carrier set it was brought in with
  int in_line = 0;
  bool has_pos = false;
  double last_slot = 0.0;    // slot of the last stitch
};

enum class PassType { None, Knit, Drop, Xfer };

struct Pass {
  PassType type = PassType::None;
  int8_t dir = 0;
  uint32_t cs = 0;
  double rack = 0.0;
  double last_slot = 0.0;
  Needle last_needle;
  double min_slot = 0.0, max_slot = 0.0;
  std::unordered_set<int> xfer_slots;
};

std::string lower_first_word(std::string_view s) {
  size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == ';')) ++i;
  std::string w;
  while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != ':' && s[i] != ',' && s[i] != '.' &&
         s[i] != '(') {
    char c = s[i++];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    w.push_back(c == '_' ? '-' : c);
  }
  return w;
}

// Section marked by a comment-only line, or -1 when the comment is no marker.
int section_marker(std::string_view comment) {
  const std::string w = lower_first_word(comment);
  if (w == "cast-on" || w == "caston") return static_cast<int>(LoopSection::CastOn);
  if (w == "bind-off" || w == "bindoff" || w == "cast-off" || w == "castoff") {
    return static_cast<int>(LoopSection::BindOff);
  }
  if (w == "waste" || w == "draw-thread") return static_cast<int>(LoopSection::Waste);
  if (w == "course" || w == "row" || w == "fabric" || w == "short-row") {
    return static_cast<int>(LoopSection::Fabric);
  }
  return -1;
}

std::string carrier_list(const std::vector<std::string>& names, uint32_t mask) {
  std::string s;
  for (size_t c = 0; c < names.size() && c < 32; ++c) {
    if (mask & (1u << c)) {
      if (!s.empty()) s += ' ';
      s += names[c];
    }
  }
  return s;
}

int popcount(uint32_t m) {
  int n = 0;
  for (; m; m &= m - 1) ++n;
  return n;
}

const char* side_name(BedSide s) { return s == BedSide::Left ? "left" : "right"; }

class Simulator {
 public:
  Simulator(const KnitoutFile& prog, const MachineProfile& profile, const SimulateOptions& opt)
      : prog_(prog), p_(profile), opt_(opt) {
    out_.machine = profile.name;
    out_.graph.carrier_names = prog.carrier_names;
    carriers_.resize(prog.carrier_names.size());
    out_.stats.yarn_mm.assign(prog.carrier_names.size(), 0.0);
    // The parser judged by the spec; the machine's software decides.
    for (const auto& d : prog.diagnostics) add(d.check, d.line, d.message);
  }

  KnitoutSimulation run() {
    check_headers();
    for (const auto& ins : prog_.instructions) step(ins);
    end_pass();
    finish();
    std::stable_sort(out_.diagnostics.begin(), out_.diagnostics.end(),
                     [](const KnitoutDiagnostic& a, const KnitoutDiagnostic& b) { return a.line < b.line; });
    return std::move(out_);
  }

 private:
  const KnitoutFile& prog_;
  const MachineProfile& p_;
  const SimulateOptions& opt_;
  KnitoutSimulation out_;
  BedLoops beds_[4];
  std::vector<CarrierState> carriers_;
  std::vector<int> hook_;  // carriers the hook holds
  std::vector<char> on_needle_;
  double rack_ = 0.0;      // racking as the machine racks it
  LoopSection section_ = LoopSection::Fabric;
  bool position_keep_ = false;
  bool have_slot_ = false;
  double min_slot_ = 0.0, max_slot_ = 0.0;
  bool width_reported_ = false;
  double pitch_ = 1.0;
  Pass pass_;
  int knit_pass_index_ = -1;  // index in out_.passes of the open knit pass
  int last_line_ = 0;

  // Reports a failed check at the profile's level (strict categories count
  // as errors).
  void add(KnitoutCheck check, int line, std::string msg, int loop = -1) {
    const CheckLevel level = p_.level(check);
    if (level == CheckLevel::Off) return;
    const KnitoutRule r = knitout_check_rule(check);
    const int ri = static_cast<int>(r);
    Severity s = level == CheckLevel::Error ? Severity::Error : Severity::Warning;
    if (s == Severity::Warning && opt_.strict[static_cast<size_t>(ri)]) s = Severity::Error;
    int& count = s == Severity::Error ? out_.error_counts[ri] : out_.warning_counts[ri];
    ++count;
    (s == Severity::Error ? out_.errors : out_.warnings)++;
    const int kept = out_.error_counts[ri] + out_.warning_counts[ri];
    if (opt_.max_diagnostics_per_rule > 0 && kept > opt_.max_diagnostics_per_rule) return;
    out_.diagnostics.push_back({s, r, check, line, std::move(msg), loop});
  }

  BedLoops& bed(const Needle& n) { return beds_[static_cast<int>(n.bed)]; }
  double slot(const Needle& n) const { return n.is_front_side() ? n.index : n.index + rack_; }
  std::string cname(int c) const { return prog_.carrier_names[static_cast<size_t>(c)]; }
  uint32_t mask(const std::vector<int>& cs) const {
    uint32_t m = 0;
    for (int c : cs) {
      if (c < 32) m |= 1u << c;
    }
    return m;
  }
  bool has_hook() const { return p_.has_yarn_inserting_hook; }

  void check_headers() {
    int carriers_line = 1;
    for (const auto& h : prog_.headers) {
      if (h.key == "Carriers") carriers_line = h.line;
      if (h.key == "Position" && h.value == "Keep") position_keep_ = true;
    }
    if (prog_.carrier_names.size() > 32) {
      add(C::HeaderValue, carriers_line, "more than 32 carriers declared; only the first 32 are simulated");
      carriers_.resize(32);
    }
    if (!p_.required_carriers_header.empty() && prog_.header("Carriers") != nullptr &&
        fmt::format("{}", fmt::join(prog_.carrier_names, " ")) != p_.required_carriers_header) {
      add(C::CarrierNames, carriers_line,
          fmt::format("';;Carriers: {}': machine '{}' needs exactly ';;Carriers: {}' (its translator refuses "
                      "other lists)",
                      printable(*prog_.header("Carriers")), p_.name, p_.required_carriers_header));
    }
    for (const auto& c : prog_.carrier_names) {
      if (!p_.has_carrier(c)) {
        add(C::CarrierNotOnMachine, carriers_line,
            fmt::format("carrier '{}' does not exist on machine '{}' (its carriers: {})", printable(c), p_.name,
                        fmt::join(p_.carriers, " ")));
      }
    }
    double gauge = p_.gauge;
    if (const std::string* g = prog_.header("Gauge")) {
      double v = 0.0;
      const auto r = std::from_chars(g->data(), g->data() + g->size(), v);
      if (r.ec == std::errc() && v > 0.0) {
        if (std::abs(v - p_.gauge) > 1e-9) {
          int line = 1;
          for (const auto& h : prog_.headers) {
            if (h.key == "Gauge") line = h.line;
          }
          add(C::HeaderUnknown, line,
              fmt::format("';;Gauge: {}' differs from machine '{}' (gauge {}); the header's gauge is used for yarn "
                          "lengths",
                          printable(*g), p_.name, p_.gauge));
        }
        gauge = v;
      }
    }
    out_.stats.gauge = gauge;
    pitch_ = 25.4 / gauge;
  }

  // --- passes and statistics -------------------------------------------------
  void end_pass() {
    if (pass_.type == PassType::None) return;
    const int span = static_cast<int>(std::ceil(pass_.max_slot - pass_.min_slot)) + 1;
    const double t =
        pass_time_seconds(p_, pass_.type == PassType::Xfer ? PassKind::Transfer : PassKind::Knit, span);
    out_.stats.time_s += t;
    ++out_.stats.carriage_passes;
    if (pass_.type == PassType::Knit) {
      ++out_.stats.knit_passes;
      SimulatedPass& kp = out_.passes[static_cast<size_t>(knit_pass_index_)];
      kp.min_slot = pass_.min_slot;
      kp.max_slot = pass_.max_slot;
      kp.time_s = t;
    }
    if (pass_.type == PassType::Xfer) ++out_.stats.transfer_passes;
    pass_.type = PassType::None;
    pass_.xfer_slots.clear();
  }
  void start_pass(PassType t, double s) {
    end_pass();
    pass_.type = t;
    pass_.rack = rack_;
    pass_.min_slot = pass_.max_slot = s;
  }
  void extend_pass(double s) {
    pass_.min_slot = std::min(pass_.min_slot, s);
    pass_.max_slot = std::max(pass_.max_slot, s);
  }
  SimulatedPass& knit_pass(const KnitoutInstruction& ins, uint32_t cs, const Needle& n) {
    const double s = slot(n);
    const int8_t dir = ins.direction;
    bool cont = pass_.type == PassType::Knit && pass_.dir == dir && pass_.cs == cs && pass_.rack == rack_ &&
                !(pass_.last_needle == n);
    if (cont) cont = dir > 0 ? s >= pass_.last_slot : s <= pass_.last_slot;
    if (!cont) {
      start_pass(PassType::Knit, s);
      pass_.dir = dir;
      pass_.cs = cs;
      SimulatedPass kp;
      kp.first_line = ins.line;
      kp.carriers = cs;
      kp.direction = dir;
      kp.rack = rack_;
      kp.section = section_;
      out_.passes.push_back(kp);
      knit_pass_index_ = static_cast<int>(out_.passes.size()) - 1;
    }
    extend_pass(s);
    pass_.last_slot = s;
    pass_.last_needle = n;
    SimulatedPass& kp = out_.passes[static_cast<size_t>(knit_pass_index_)];
    kp.last_line = ins.line;
    return kp;
  }
  void drop_pass(const Needle& n) {
    const double s = slot(n);
    if (pass_.type != PassType::Drop || pass_.rack != rack_) start_pass(PassType::Drop, s);
    extend_pass(s);
  }
  void xfer_pass(double front_slot) {
    const int key = static_cast<int>(std::lround(front_slot));
    if (pass_.type != PassType::Xfer || pass_.rack != rack_ || pass_.xfer_slots.count(key)) {
      start_pass(PassType::Xfer, front_slot);
    }
    pass_.xfer_slots.insert(key);
    extend_pass(front_slot);
  }

  void use_needle(const Needle& n, int line) {
    if (n.bed != Bed::Front && n.bed != Bed::FrontSlider && p_.beds < 2) {
      add(C::BackBedOnOneBed, line,
          fmt::format("needle {} is on the back bed, but machine '{}' has one bed", to_string(n), p_.name));
    }
    if (position_keep_ && (n.index < 1 || n.index > p_.needle_count)) {
      add(C::NeedleRange, line,
          fmt::format("needle {} is outside 1..{} of machine '{}' (';;Position: Keep' uses needle numbers as "
                      "written)",
                      to_string(n), p_.needle_count, p_.name));
    }
    const double s = slot(n);
    if (!have_slot_) {
      min_slot_ = max_slot_ = s;
      have_slot_ = true;
    }
    min_slot_ = std::min(min_slot_, s);
    max_slot_ = std::max(max_slot_, s);
    if (!width_reported_ && max_slot_ - min_slot_ + 1 > p_.needle_count) {
      width_reported_ = true;
      add(C::NeedleRange, line,
          fmt::format("the program spans {} needles (slots {} to {}), more than the {} of machine '{}'",
                      static_cast<int>(std::ceil(max_slot_ - min_slot_)) + 1, min_slot_, max_slot_, p_.needle_count,
                      p_.name));
    }
  }

  void check_loops(const Needle& n, const std::vector<int>& held, int line, bool after_transfer) {
    const size_t count = held.size();
    const int top = held.empty() ? -1 : held.back();
    if (static_cast<int>(count) > p_.max_loops_per_needle) {
      add(C::LoopsPerNeedle, line,
          fmt::format("needle {} holds {} loops; machine '{}' holds at most {}", to_string(n), count, p_.name,
                      p_.max_loops_per_needle),
          top);
    } else if (after_transfer && static_cast<int>(count) > p_.max_transfer_stack) {
      add(C::TransferStack, line,
          fmt::format("needle {} holds {} loops after a transfer; more than {} risks stretching and miss-transfer "
                      "on machine '{}'",
                      to_string(n), count, p_.max_transfer_stack, p_.name),
          top);
    }
  }

  bool hook_busy(int line, const char* what) {
    if (hook_.empty()) return false;
    add(C::HookTransfer, line,
        fmt::format("{} while the yarn-inserting hook holds carrier(s) {}; 'releasehook' first", what,
                    carrier_list(prog_.carrier_names, hook_mask())));
    return true;
  }
  uint32_t hook_mask() const {
    uint32_t m = 0;
    for (int c : hook_) {
      if (c < 32) m |= 1u << c;
    }
    return m;
  }

  // --- carriers -----------------------------------------------------------------
  // Checks the carriers of a stitch-forming or miss operation; returns their mask.
  uint32_t use_carriers(const KnitoutInstruction& ins) {
    const uint32_t cs = mask(ins.carriers);
    if (ins.op != KnitoutOp::Miss && popcount(cs) > 1) {
      add(C::Plating, ins.line,
          fmt::format("'{}' with carriers {} at once (plating); machine '{}' knits with one carrier per pass",
                      name(ins.op), carrier_list(prog_.carrier_names, cs), p_.name));
    }
    for (int c : ins.carriers) {
      if (c >= static_cast<int>(carriers_.size())) continue;
      CarrierState& st = carriers_[static_cast<size_t>(c)];
      if (!st.in) {
        if (!st.reported_inactive) {
          add(C::CarrierNotIn, ins.line,
              fmt::format("carrier {} is used by '{}' but is not in; bring it in with 'in' or 'inhook' first",
                          cname(c), name(ins.op)));
        }
        st.reported_inactive = true;  // once until it comes in
        continue;
      }
      if (st.pending_first) {
        if (st.in_set != cs) {
          add(C::FirstUseSet, ins.line,
              fmt::format("the first operation after bringing in carrier(s) {} (line {}) uses carrier set {}; it "
                          "must use exactly the set brought in",
                          carrier_list(prog_.carrier_names, st.in_set), st.in_line,
                          carrier_list(prog_.carrier_names, cs)));
        }
        const BedSide park = p_.carrier_park_side;
        if ((park == BedSide::Left && ins.direction < 0) || (park == BedSide::Right && ins.direction > 0)) {
          add(C::FirstPassDirection, ins.line,
              fmt::format("carrier {} comes in from the {} of the bed on machine '{}' but its first pass (line {}) "
                          "goes '{}'; start it with a pass to the {} (e.g. 'miss {} {} {}' first)",
                          cname(c), side_name(park), p_.name, ins.line, ins.direction > 0 ? '+' : '-',
                          park == BedSide::Left ? "right" : "left", park == BedSide::Left ? '+' : '-',
                          to_string(ins.needle), cname(c)));
        }
      }
    }
    for (int c : ins.carriers) {
      if (c < static_cast<int>(carriers_.size())) carriers_[static_cast<size_t>(c)].pending_first = false;
    }
    return cs;
  }

  // Float check, yarn accounting and carrier position for a stitch at needle n.
  void stitch_yarn(const KnitoutInstruction& ins, const Needle& n, int loop) {
    const double s = slot(n);
    for (int c : ins.carriers) {
      if (c >= static_cast<int>(carriers_.size())) continue;
      CarrierState& st = carriers_[static_cast<size_t>(c)];
      double& yarn = out_.stats.yarn_mm[static_cast<size_t>(c)];
      yarn += opt_.loop_length_pitches * pitch_;
      if (st.has_pos) {
        const double d = std::abs(s - st.last_slot);
        if (d > 1.0) yarn += (d - 1.0) * pitch_;
        if (d > p_.max_float_needles) {
          add(C::Float, ins.line,
              fmt::format("carrier {} floats {} needles (from slot {} to {}); machine '{}' allows at most {}",
                          cname(c), d, st.last_slot, s, p_.name, p_.max_float_needles),
              loop);
        }
      }
      st.has_pos = true;
      st.last_slot = s;
      st.stitched = true;
    }
  }

  // A hook operation on a machine without a hook: reported at the level of
  // hook-unavailable; the simulation goes on as if plain in / nothing / out.
  bool hook_unavailable(const KnitoutInstruction& ins) {
    if (has_hook()) return false;
    const char* plain = ins.op == KnitoutOp::Inhook ? "in" : ins.op == KnitoutOp::Outhook ? "out" : nullptr;
    add(C::HookUnavailable, ins.line,
        plain ? fmt::format("machine '{}' has no yarn-inserting hook; '{}' is read as '{}'", p_.name, name(ins.op),
                            plain)
              : fmt::format("machine '{}' has no yarn-inserting hook; 'releasehook' is ignored", p_.name));
    return true;
  }

  void carrier_in(const KnitoutInstruction& ins) {
    end_pass();
    bool hook = ins.op == KnitoutOp::Inhook;
    if (hook && hook_unavailable(ins)) hook = false;
    if (hook && !hook_.empty()) {
      add(C::HookBusy, ins.line,
          fmt::format("'inhook' while the yarn-inserting hook holds carrier(s) {}; 'releasehook' first",
                      carrier_list(prog_.carrier_names, hook_mask())));
    }
    const uint32_t cs = mask(ins.carriers);
    for (int c : ins.carriers) {
      if (c >= static_cast<int>(carriers_.size())) continue;
      CarrierState& st = carriers_[static_cast<size_t>(c)];
      if (st.in) {
        add(C::CarrierInTwice, ins.line,
            fmt::format("carrier {} is brought in but is already in (since line {})", cname(c), st.in_line));
        continue;
      }
      st = CarrierState{};
      st.in = true;
      st.pending_first = true;
      st.in_set = cs;
      st.in_line = ins.line;
      ++out_.stats.carriers_in;
    }
    if (hook && hook_.empty()) {
      hook_ = ins.carriers;
      for (int c : ins.carriers) {
        if (c < static_cast<int>(carriers_.size())) carriers_[static_cast<size_t>(c)].hooked = true;
      }
    }
  }

  void release_hook(const KnitoutInstruction& ins) {
    end_pass();
    if (hook_unavailable(ins)) return;
    if (hook_.empty()) {
      add(C::ReleasehookMismatch, ins.line, "'releasehook' but the yarn-inserting hook holds no carrier");
      return;
    }
    if (mask(ins.carriers) != hook_mask()) {
      add(C::ReleasehookMismatch, ins.line,
          fmt::format("'releasehook {}' but the hook holds carrier(s) {}",
                      carrier_list(prog_.carrier_names, mask(ins.carriers)),
                      carrier_list(prog_.carrier_names, hook_mask())));
      return;
    }
    for (int c : hook_) {
      CarrierState& st = carriers_[static_cast<size_t>(c)];
      if (!st.stitched) {
        add(C::ReleasehookEarly, ins.line,
            fmt::format("'releasehook' before carrier {} made any stitch: the yarn end is not held", cname(c)));
      }
      st.hooked = false;
    }
    hook_.clear();
  }

  void carrier_out(const KnitoutInstruction& ins) {
    end_pass();
    bool hook = ins.op == KnitoutOp::Outhook;
    if (hook && hook_unavailable(ins)) hook = false;
    if (hook && !hook_.empty()) {
      add(C::OutWhileHooked, ins.line,
          fmt::format("'outhook' while the yarn-inserting hook holds carrier(s) {}; 'releasehook' first",
                      carrier_list(prog_.carrier_names, hook_mask())));
    }
    for (int c : ins.carriers) {
      if (c >= static_cast<int>(carriers_.size())) continue;
      CarrierState& st = carriers_[static_cast<size_t>(c)];
      if (!st.in) {
        add(C::OutNotIn, ins.line, fmt::format("carrier {} is taken out but is not in", cname(c)));
        continue;
      }
      if (!hook && st.hooked) {
        add(C::OutWhileHooked, ins.line,
            fmt::format("carrier {} is taken out while the yarn-inserting hook still holds it; 'releasehook {}' "
                        "first",
                        cname(c), cname(c)));
      }
      if (!st.stitched) {
        add(C::OutBeforeStitch, ins.line,
            fmt::format("carrier {} is taken out without having made a stitch", cname(c)));
      }
      if (st.hooked) {
        hook_.erase(std::remove(hook_.begin(), hook_.end(), c), hook_.end());
      }
      st = CarrierState{};
      ++out_.stats.carriers_out;
    }
  }

  void rack(const KnitoutInstruction& ins) {
    end_pass();
    double r = ins.value;
    const double written = r;
    if (p_.quarter_pitch_as_half && r - std::floor(r) == 0.25) {
      r += 0.25;
      add(C::QuarterPitchAsHalf, ins.line,
          fmt::format("'rack {}' is knitted at half pitch ({}) on machine '{}', as its translator does", written, r,
                      p_.name));
    }
    if (std::abs(r) > p_.max_racking) {
      add(C::RackingRange, ins.line,
          fmt::format("racking {} exceeds the maximum {} of machine '{}'", written, p_.max_racking, p_.name));
    }
    const double frac = r - std::floor(r);
    if (frac != 0.0 &&
        std::find(p_.racking_fractions.begin(), p_.racking_fractions.end(), frac) == p_.racking_fractions.end()) {
      add(C::RackingFraction, ins.line,
          fmt::format("racking {} has a fractional part machine '{}' cannot rack to{}", written, p_.name,
                      p_.racking_fractions.empty()
                          ? std::string(" (it racks by whole needles)")
                          : fmt::format(" (its fractions: {})", fmt::join(p_.racking_fractions, ", "))));
    }
    if (r != rack_) {
      ++out_.stats.racks;
      out_.stats.time_s += p_.timing.rack_s;
    }
    rack_ = r;
  }

  void extension(const KnitoutInstruction& ins) {
    const ExtensionRule* rule = p_.extension(ins.extension);
    if (!rule) {
      add(C::ExtensionUnknown, ins.line,
          fmt::format("extension '{}' is not read by machine '{}' and is ignored", printable(ins.extension),
                      p_.name));
      return;
    }
    const std::string problem = extension_value_problem(*rule, ins.args);
    if (!problem.empty()) add(C::ExtensionValue, ins.line, problem + fmt::format(" (machine '{}')", p_.name));
  }

  // --- loops --------------------------------------------------------------------
  int new_loop(const KnitoutInstruction& ins, LoopKind kind, uint32_t cs, std::span<const int> parents,
               bool empty_needle) {
    KnitLoop l;
    l.on_empty_needle = empty_needle;
    l.carriers = cs;
    l.needle = ins.needle;
    l.direction = ins.direction;
    l.kind = kind;
    l.section = section_;
    l.line = ins.line;
    l.pass = knit_pass_index_;
    l.slot = slot(ins.needle);
    const int id = out_.graph.add_loop(l, parents);
    on_needle_.push_back(1);
    return id;
  }

  void move_loops(std::vector<int>& from, const Needle& src, const Needle& dst, int line) {
    if (from.empty()) return;
    std::vector<int>& to = bed(dst).at(dst.index);
    for (int l : from) {
      to.push_back(l);
      ++out_.graph.loops[static_cast<size_t>(l)].transfers;
      out_.graph.transfers.push_back({l, src, dst, line});
    }
    from.clear();
    check_loops(dst, to, line, true);
  }

  // Checks that a (split or xfer) move n -> n2 is possible; returns false if not.
  bool check_move(const KnitoutInstruction& ins) {
    const Needle& a = ins.needle;
    const Needle& b = ins.needle2;
    if (a.is_front_side() == b.is_front_side()) {
      add(C::SameBedMove, ins.line,
          fmt::format("'{}' from {} to {}: both needles are on the same bed; transfers go between the beds",
                      name(ins.op), to_string(a), to_string(b)));
      return false;
    }
    if (a.is_slider() && b.is_slider()) {
      add(C::SameBedMove, ins.line,
          fmt::format("'{}' from slider {} to slider {} is not possible", name(ins.op), to_string(a), to_string(b)));
      return false;
    }
    const Needle& f = a.is_front_side() ? a : b;
    const Needle& bk = a.is_front_side() ? b : a;
    if (static_cast<double>(f.index) != bk.index + rack_) {
      add(C::Misaligned, ins.line,
          fmt::format("'{}' between {} and {}: not aligned at racking {} (back needle {} faces front needle {})",
                      name(ins.op), to_string(a), to_string(b), rack_, bk.index, bk.index + rack_));
      return false;
    }
    return true;
  }

  // Needle numbers no machine has would only make the virtual beds huge.
  bool needle_in_range(const KnitoutInstruction& ins) {
    const bool two = ins.op == KnitoutOp::Split || ins.op == KnitoutOp::Xfer;
    for (const Needle* n : {&ins.needle, two ? &ins.needle2 : &ins.needle}) {
      if (n->index < -kMaxNeedleIndex || n->index > kMaxNeedleIndex) {
        add(C::NeedleRange, ins.line,
            fmt::format("needle {} is beyond any machine (|index| > {}); the operation is skipped", to_string(*n),
                        kMaxNeedleIndex));
        return false;
      }
    }
    return true;
  }
  static constexpr int kMaxNeedleIndex = 100000;

  void stitch(const KnitoutInstruction& ins) {
    use_needle(ins.needle, ins.line);
    if (ins.op == KnitoutOp::Split) use_needle(ins.needle2, ins.line);
    const uint32_t cs = use_carriers(ins);
    if (ins.needle.is_slider()) {
      add(C::SliderStitch, ins.line,
          fmt::format("'{}' on slider {}: sliders hold loops but cannot form them", name(ins.op),
                      to_string(ins.needle)));
      return;
    }
    if (ins.op == KnitoutOp::Split) {
      hook_busy(ins.line, "'split'");
      if (!check_move(ins)) return;
    }
    SimulatedPass& kp = knit_pass(ins, cs, ins.needle);
    std::vector<int>& held = bed(ins.needle).at(ins.needle.index);
    if (ins.op == KnitoutOp::Tuck) {
      ++out_.stats.tucks;
      ++kp.tucks;
      const int id = new_loop(ins, LoopKind::Tuck, cs, {}, held.empty());
      stitch_yarn(ins, ins.needle, id);
      held.push_back(id);
      check_loops(ins.needle, held, ins.line, false);
      return;
    }
    const std::vector<int> old = held;
    int id = -1;
    if (ins.op == KnitoutOp::Knit) {
      ++out_.stats.knits;
      ++kp.knits;
      for (int l : old) on_needle_[static_cast<size_t>(l)] = 0;
      id = new_loop(ins, LoopKind::Knit, cs, old, old.empty());
      held.assign(1, id);
    } else {
      ++out_.stats.splits;
      ++kp.splits;
      id = new_loop(ins, LoopKind::Split, cs, old, old.empty());
      move_loops(held, ins.needle, ins.needle2, ins.line);
      bed(ins.needle).at(ins.needle.index).assign(1, id);
    }
    stitch_yarn(ins, ins.needle, id);
    if (old.empty() && section_ != LoopSection::CastOn && section_ != LoopSection::Waste) {
      add(C::EmptyNeedleKnit, ins.line,
          fmt::format("'{}' on empty needle {} outside a cast-on: the new loop is held by nothing below",
                      name(ins.op), to_string(ins.needle)),
          id);
    }
  }

  void drop(const KnitoutInstruction& ins) {
    use_needle(ins.needle, ins.line);
    drop_pass(ins.needle);
    ++out_.stats.drops;
    std::vector<int>& held = bed(ins.needle).at(ins.needle.index);
    for (int l : held) {
      KnitLoop& loop = out_.graph.loops[static_cast<size_t>(l)];
      loop.dropped = true;
      on_needle_[static_cast<size_t>(l)] = 0;
      if (loop.kind == LoopKind::Tuck || loop.section != LoopSection::Fabric) continue;
      bool runs = false;
      for (int q : out_.graph.parents_of(l)) runs = runs || !on_needle_[static_cast<size_t>(q)];
      if (!runs) continue;
      add(C::Run, ins.line,
          fmt::format("drop of needle {} releases the {} loop formed at line {}, which was pulled through loops no "
                      "needle holds: the wale runs (unravels) unless it is secured by hand",
                      to_string(ins.needle), name(loop.kind), loop.line),
          l);
    }
    held.clear();
  }

  void step(const KnitoutInstruction& ins) {
    last_line_ = ins.line;
    switch (ins.op) {
      case KnitoutOp::Miss:
      case KnitoutOp::Knit:
      case KnitoutOp::Tuck:
      case KnitoutOp::Split:
      case KnitoutOp::Xfer:
      case KnitoutOp::Drop:
      case KnitoutOp::Amiss:
        if (!needle_in_range(ins)) return;
        break;
      default: break;
    }
    switch (ins.op) {
      case KnitoutOp::Comment: {
        if (ins.comment.find("leave-loops") != std::string::npos) out_.leave_loops_stated = true;
        const int s = section_marker(ins.comment);
        if (s >= 0) section_ = static_cast<LoopSection>(s);
        return;
      }
      case KnitoutOp::In:
      case KnitoutOp::Inhook: carrier_in(ins); return;
      case KnitoutOp::Releasehook: release_hook(ins); return;
      case KnitoutOp::Out:
      case KnitoutOp::Outhook: carrier_out(ins); return;
      case KnitoutOp::Rack: rack(ins); return;
      case KnitoutOp::Extension: extension(ins); return;
      case KnitoutOp::Stitch:
      case KnitoutOp::Pause: return;
      case KnitoutOp::Miss: {
        use_needle(ins.needle, ins.line);
        const uint32_t cs = use_carriers(ins);
        ++knit_pass(ins, cs, ins.needle).misses;
        ++out_.stats.misses;
        return;
      }
      case KnitoutOp::Knit:
      case KnitoutOp::Tuck:
      case KnitoutOp::Split: stitch(ins); return;
      case KnitoutOp::Xfer: {
        use_needle(ins.needle, ins.line);
        use_needle(ins.needle2, ins.line);
        hook_busy(ins.line, "transfer");
        if (!check_move(ins)) return;
        ++out_.stats.transfers;
        ++out_.stats.transfers_by_section[static_cast<size_t>(section_)];
        xfer_pass(ins.needle.is_front_side() ? ins.needle.index : ins.needle2.index);
        move_loops(bed(ins.needle).at(ins.needle.index), ins.needle, ins.needle2, ins.line);
        return;
      }
      case KnitoutOp::Amiss: {
        use_needle(ins.needle, ins.line);
        if (ins.needle.is_slider()) {
          add(C::SliderStitch, ins.line, fmt::format("'amiss' on slider {}", to_string(ins.needle)));
          return;
        }
        drop_pass(ins.needle);
        return;
      }
      case KnitoutOp::Drop: drop(ins); return;
    }
  }

  void finish() {
    const int end_line = std::max(prog_.num_lines, last_line_);
    for (size_t c = 0; c < carriers_.size(); ++c) {
      if (carriers_[c].in) {
        add(C::CarrierLeftIn, end_line,
            fmt::format("carrier {} is still in at the end of the program (brought in at line {}); take it out "
                        "with 'out' or 'outhook'",
                        prog_.carrier_names[c], carriers_[c].in_line));
      }
    }
    if (!hook_.empty()) {
      add(C::HookLeft, end_line,
          fmt::format("the yarn-inserting hook still holds carrier(s) {} at the end",
                      carrier_list(prog_.carrier_names, hook_mask())));
    }
    int left = 0, first_left = -1;
    std::string where;
    for (const BedLoops& b : beds_) {
      const int bi = static_cast<int>(&b - beds_);
      b.for_each([&](int n, const std::vector<int>& loops) {
        for (int l : loops) {
          out_.graph.loops[static_cast<size_t>(l)].live_at_end = true;
          if (first_left < 0) first_left = l;
          ++left;
        }
        if (where.size() < 60) {
          if (!where.empty()) where += ' ';
          where += to_string(Needle{static_cast<Bed>(bi), n});
        }
      });
    }
    if (left > 0 && !out_.leave_loops_stated) {
      add(C::LoopsLeft, end_line,
          fmt::format("{} loop(s) are left on the needles at the end ({}...) and will unravel when the fabric comes "
                      "off; bind off, or state the intention with a '; leave-loops: <why>' comment",
                      left, where),
          first_left);
    }
    out_.stats.min_needle = have_slot_ ? static_cast<int>(std::floor(min_slot_)) : 0;
    out_.stats.max_needle = have_slot_ ? static_cast<int>(std::ceil(max_slot_)) : 0;
    out_.stats.time_s += (out_.stats.carriers_in + out_.stats.carriers_out) * p_.timing.carrier_in_out_s;
  }
};

}  // namespace

KnitoutSimulation simulate_knitout(const KnitoutFile& program, const MachineProfile& profile,
                                   const SimulateOptions& options) {
  validate_machine_profile(profile);
  Simulator sim(program, profile, options);
  return sim.run();
}

std::string KnitoutSimulation::text() const {
  std::string s;
  s += fmt::format("{} on machine '{}': {} error(s), {} warning(s)\n", ok() ? "VALID" : "INVALID", machine, errors,
                   warnings);
  const SimulationStats& st = stats;
  s += fmt::format("  carriage passes: {} ({} knit, {} transfer, {} drop)\n", st.carriage_passes, st.knit_passes,
                   st.transfer_passes, st.carriage_passes - st.knit_passes - st.transfer_passes);
  s += fmt::format("  racks: {}\n", st.racks);
  s += fmt::format("  stitches: {} knit, {} tuck, {} split, {} miss; {} transfers ({} in the fabric, {} cast-on/"
                   "bind-off/waste), {} drops\n",
                   st.knits, st.tucks, st.splits, st.misses, st.transfers, st.transfers_by_section[0],
                   st.transfers - st.transfers_by_section[0], st.drops);
  s += fmt::format("  loops: {} (knit graph), needles {}..{}\n", graph.num_loops(), st.min_needle, st.max_needle);
  s += fmt::format("  estimated knitting time: {:.1f} s ({:.1f} min)\n", st.time_s, st.time_s / 60.0);
  for (size_t c = 0; c < st.yarn_mm.size(); ++c) {
    if (st.yarn_mm[c] > 0.0) {
      s += fmt::format("  yarn carrier {}: {:.2f} m (estimate, gauge {})\n", graph.carrier_names[c],
                       st.yarn_mm[c] / 1000.0, st.gauge);
    }
  }
  for (const auto& d : diagnostics) {
    s += fmt::format("  line {}: {} [{}/{}]: {}\n", d.line, d.severity == Severity::Error ? "error" : "warning",
                     name(d.rule), knitout_check_id(d.check), d.message);
  }
  const int shown = static_cast<int>(diagnostics.size());
  if (shown < errors + warnings) {
    s += fmt::format("  ({} more diagnostics not shown)\n", errors + warnings - shown);
  }
  return s;
}

}  // namespace knitforge

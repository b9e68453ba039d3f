#pragma once
/// \file knitout_parse.h
/// Parsing knitout (textiles-lab knitout specification, version 0.6, magic
/// line `;!knitout-2`) into a list of instructions, with diagnostics that name
/// the line. See docs/machines.md, "The simulator".
///
/// What is accepted (the spec's syntax; where the spec tells readers to be
/// lenient, as the open translators are):
///  - line 1 is the magic line `;!knitout-N`, N an integer (a missing or
///    malformed magic line is an error; a version other than 2 is read as
///    version 2 with a warning: the spec says readers accept any version);
///  - lines end with LF; CR LF and lone CR line endings are accepted with one
///    warning;
///  - header lines `;;Key: value` before the first operation; `;;Carriers:`
///    is required and names the carriers front to back, separated by spaces;
///    `;;Position:` must be Left, Center, Right or Keep; `;;Gauge:` a positive
///    number; unknown headers give a warning;
///  - everything after `;` is a comment; comment-only lines are kept (the
///    simulator reads section markers from them);
///  - needles `f`, `b`, `fs`, `bs` followed by an integer (may be negative);
///    directions `+` / `-`; carrier sets are space separated names from the
///    `;;Carriers:` header, each at most once;
///  - operations `in`, `inhook`, `releasehook`, `out`, `outhook` (carrier set,
///    non-empty), `knit`/`tuck` (D N CS, CS may be empty: drop / amiss),
///    `split` (D N N2 CS), `miss` (D N CS, CS non-empty), `xfer` (N N2),
///    `drop` (N), `amiss` (N), `rack` (number, may be fractional), `stitch`
///    (two numbers), `pause`; `x-...` extensions are kept with their
///    arguments (the simulator checks them against the machine); anything
///    else is an error.
/// Parsing does not stop at the first error: every malformed line gives one
/// error and is skipped.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "knitforge/machine/knitout_rules.h"
#include "knitforge/util/severity.h"

namespace knitforge {

/// One finding, tied to a line of the knitout file (1-based; 0 = the file as
/// a whole). The parser gives every finding the severity the knitout spec
/// implies; the simulator re-levels it by the machine profile
/// (knitout_rules.h).
struct KnitoutDiagnostic {
  Severity severity = Severity::Error;
  KnitoutRule rule = KnitoutRule::Syntax;
  KnitoutCheck check = KnitoutCheck::Malformed;
  int line = 0;
  std::string message;
  int loop = -1;  ///< the knit-graph loop it concerns (simulator findings), -1 when none
};

enum class KnitoutOp : uint8_t {
  In, Inhook, Releasehook, Out, Outhook,
  Knit, Tuck, Split, Miss, Xfer, Drop, Amiss,
  Rack, Stitch, Pause, Extension, Comment,
};
/// The operation's keyword ("knit", "x-..." for extensions, "" for comments).
std::string_view name(KnitoutOp op);

enum class Bed : uint8_t { Front = 0, Back = 1, FrontSlider = 2, BackSlider = 3 };

/// A needle: bed and (possibly negative) index.
struct Needle {
  Bed bed = Bed::Front;
  int index = 0;
  bool is_front_side() const { return bed == Bed::Front || bed == Bed::FrontSlider; }
  bool is_slider() const { return bed == Bed::FrontSlider || bed == Bed::BackSlider; }
  bool operator==(const Needle&) const = default;
};
/// "f12", "bs-3", ...
std::string to_string(const Needle& n);

/// One parsed line that carries an operation or a comment.
struct KnitoutInstruction {
  KnitoutOp op = KnitoutOp::Comment;
  int line = 0;               ///< 1-based line number in the file
  int8_t direction = 0;       ///< +1, -1, or 0 (no direction)
  Needle needle;              ///< N
  Needle needle2;             ///< N2 (split, xfer)
  std::vector<int> carriers;  ///< indices into KnitoutFile::carrier_names, in written order
  double value = 0.0;         ///< rack: racking; stitch: first value
  double value2 = 0.0;        ///< stitch: second value
  std::string extension;      ///< the x- operation's keyword
  std::vector<std::string> args;  ///< the x- operation's arguments
  std::string comment;        ///< text after ';' (without it), "" when none
};

struct KnitoutHeader {
  std::string key, value;
  int line = 0;
};

/// A parsed knitout file.
struct KnitoutFile {
  int version = 0;                          ///< from the magic line (2)
  std::vector<KnitoutHeader> headers;       ///< in file order
  std::vector<std::string> carrier_names;   ///< from ;;Carriers:, front to back
  std::vector<KnitoutInstruction> instructions;
  std::vector<KnitoutDiagnostic> diagnostics;  ///< syntax and header findings
  int num_lines = 0;

  /// Value of the last header with this key, or nullptr.
  const std::string* header(std::string_view key) const;
  bool has_errors() const;
};

/// Parses knitout text (see the file comment). Never throws on malformed
/// content: every problem is a diagnostic with its line.
KnitoutFile parse_knitout(std::string_view text);

/// Reads and parses a knitout file.
/// \throw IOError when the file cannot be read.
KnitoutFile read_knitout(const std::string& path);

}  // namespace knitforge

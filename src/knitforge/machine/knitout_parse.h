#pragma once
/// \file knitout_parse.h
/// Parsing knitout (textiles-lab knitout specification, version 0.6, magic
/// line `;!knitout-2`) into a list of instructions, with diagnostics that name
/// the line. See docs/machines.md, "The simulator".
///
/// What is accepted (the spec's syntax, nothing looser):
///  - line 1 is exactly `;!knitout-2` (a missing or different magic line is an
///    error; a CR before the LF is accepted with one warning);
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
///    (two numbers), `pause`; `x-...` extensions are kept but flagged with a
///    warning ("ignored"); anything else is an error.
/// Parsing does not stop at the first error: every malformed line gives one
/// error and is skipped.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace knitforge {

/// Severity of a diagnostic: an error makes the program invalid; a warning
/// does not.
enum class Severity : uint8_t { Warning = 0, Error = 1 };

/// What a diagnostic is about (one entry per rule the parser and the
/// simulator check; docs/machines.md lists them).
enum class KnitoutRule : uint8_t {
  Syntax,              ///< malformed line, unknown operation, bad magic line
  Header,              ///< missing or malformed header
  Extension,           ///< x- extension (ignored)
  UndeclaredCarrier,   ///< carrier not named in ;;Carriers: (or beyond the machine)
  InactiveCarrier,     ///< carrier used while not in, brought in twice, out while not in
  CarrierLeftIn,       ///< carrier still in at the end
  Racking,             ///< racking beyond the machine or an unsupported fraction
  Misaligned,          ///< transfer/split between needles not aligned at the racking
  Slider,              ///< knit/tuck on a slider, slider-to-slider move, same-bed move
  LoopsPerNeedle,      ///< more loops on a needle than the machine holds
  Float,               ///< carrier floats over more needles than allowed
  Hook,                ///< yarn-inserting hook misuse
  Drop,                ///< live fabric dropped (a run), drop of an empty needle
  EmptyNeedleKnit,     ///< knit on an empty needle outside a cast-on
  LoopsLeft,           ///< loops left on needles at the end without stated intention
  Width,               ///< needles beyond the machine's bed width
};
inline constexpr int kNumKnitoutRules = 16;

/// Short name of a rule for messages and JSON ("syntax", "hook", ...).
std::string_view name(KnitoutRule rule);

/// One finding, tied to a line of the knitout file (1-based; 0 = the file as
/// a whole).
struct KnitoutDiagnostic {
  Severity severity = Severity::Error;
  KnitoutRule rule = KnitoutRule::Syntax;
  int line = 0;
  std::string message;
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

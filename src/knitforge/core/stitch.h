#pragma once
/// \file stitch.h
/// Stitch and map-cell types, and the corner/edge layout of each stitch type
/// (seed §1.2.1).
///
/// Every stitch is drawn in its own frame as in the knitting map: x to the
/// right (the "left-to-right" knitting direction), y up (later courses).
/// A stitch's vertices are stored counter-clockwise starting from a fixed
/// corner, so the role of each edge follows from the type alone:
///
/// | type          | shape            | corners (CCW)  | edges (edge k joins corner k and k+1) |
/// |---------------|------------------|----------------|----------------------------------------|
/// | Knit          | quad             | BL BR TR TL    | Bottom Right Top Left                  |
/// | ShortRowLeft  | apex on the left | A  BR TR       | Bottom Right Top                       |
/// | ShortRowRight | apex on the right| BL A  TL       | Bottom Top   Left                      |
/// | Increase      | apex at the bottom | A TR TL      | Right  Top   Left                      |
/// | Decrease      | apex at the top  | BL BR A        | Bottom Right Left                      |
///
/// A = apex: the vertex where the short row turns (left/right) or where the
/// short column starts (increase) or ends (decrease).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace knitforge {

/// The five stitch (face) types of a stitch mesh.
enum class StitchType : uint8_t {
  Knit = 0,           ///< regular stitch, a quad
  ShortRowLeft = 1,   ///< left end of a short row (triangle, apex left)
  ShortRowRight = 2,  ///< right end of a short row (triangle, apex right)
  Increase = 3,       ///< start of a short column (triangle, apex at the bottom)
  Decrease = 4,       ///< end of a short column (triangle, apex at the top)
};
inline constexpr int kNumStitchTypes = 5;

/// Knitting-map cell types: the five stitch types plus Collapsed and Empty.
/// Values 0-4 coincide with StitchType.
enum class CellType : uint8_t {
  Knit = 0,
  ShortRowLeft = 1,
  ShortRowRight = 2,
  Increase = 3,
  Decrease = 4,
  Collapsed = 5,  ///< a position the fabric skips (inside short rows / short columns)
  Empty = 6,      ///< outside the fabric
};

/// Side of a stitch in its own frame.
enum class Side : uint8_t { Bottom = 0, Right = 1, Top = 2, Left = 3 };

/// The side opposite to s (Bottom <-> Top, Left <-> Right).
constexpr Side opposite_side(Side s) { return static_cast<Side>((static_cast<int>(s) + 2) % 4); }

/// Boundary roles of a stitch, as bit flags (a stitch can be cast-on and
/// outside-increase at once).
enum BoundaryRole : uint8_t {
  kRoleNone = 0,
  kRoleCastOn = 1,
  kRoleBindOff = 2,
  kRoleOutsideIncrease = 4,
  kRoleOutsideDecrease = 8,
  /// A stitch of a closed tube's last round (KnittingMap::closed_end): its
  /// loop is joined with the one opposite it across the tube and bound off.
  kRoleClosingSeam = 16,
};

/// Number of corners of a stitch type: 4 for Knit, 3 for the shaping stitches.
constexpr int corner_count(StitchType t) { return t == StitchType::Knit ? 4 : 3; }

/// True for the four triangular (shaping) stitch types.
constexpr bool is_shaping(StitchType t) { return t != StitchType::Knit; }

/// The side each edge of a stitch lies on; edge k joins corners k and k+1.
/// The returned span has corner_count(t) entries.
std::span<const Side> edge_sides(StitchType t);

/// The edge index of side s for type t, or -1 when the type has no such side
/// (ShortRowLeft has no Left edge, Increase no Bottom edge, ...).
int edge_of_side(StitchType t, Side s);

/// Index of the apex among the corners (0 for ShortRowLeft and Increase,
/// 1 for ShortRowRight, 2 for Decrease), -1 for Knit.
int apex_corner(StitchType t);

/// True when a stitch cell type (not Collapsed / Empty).
constexpr bool is_stitch(CellType c) { return static_cast<uint8_t>(c) < kNumStitchTypes; }
constexpr StitchType to_stitch_type(CellType c) { return static_cast<StitchType>(c); }
constexpr CellType to_cell_type(StitchType t) { return static_cast<CellType>(t); }

/// True when cell c is a stitch that has side s (a ShortRowLeft has no Left
/// side, an Increase no Bottom side, ...).
inline bool has_side(CellType c, Side s) { return is_stitch(c) && edge_of_side(to_stitch_type(c), s) >= 0; }

/// Short names used in files and messages: "knit", "short-row-left",
/// "short-row-right", "increase", "decrease", "collapsed", "empty".
std::string_view name(StitchType t);
std::string_view name(CellType c);
/// Parses a name() back; std::nullopt when unknown.
std::optional<StitchType> parse_stitch_type(std::string_view s);

}  // namespace knitforge

#pragma once
/// \file knittability.h
/// Knittability check of a stitch mesh (seed §1.2.2): does the mesh describe a
/// weft-knitted sheet that one yarn can knit in one stroke, with shaping
/// stitches a machine handles robustly? The answer is a report listing every
/// violation, not an exception, so a design tool can show all problems at
/// once. The map-level check (convert/map_knittability.h) uses the same
/// report type. docs/knittability.md explains each rule on the machine.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "knitforge/core/stitch_mesh.h"
#include "knitforge/geometry/vec.h"
#include "knitforge/util/severity.h"

namespace knitforge {

/// The knittability rules. Stable string ids (rule_id) are used in text
/// reports and JSON; new rules are appended, never renumbered.
enum class KnitRule : uint8_t {
  // --- stitch-mesh rules (seed §1.2.2) ---
  MalformedAdjacency = 0,     ///< "malformed-adjacency": a shared edge whose two sides are not opposite
  CyclicRow = 1,              ///< "cyclic-row": a course closes on itself via Left/Right neighbours
  CyclicColumn = 2,           ///< "cyclic-column": a wale closes on itself via Bottom/Top neighbours
  HelicalRows = 3,            ///< "helical-rows": the row order (Alg. 1.1 D_r) has a cycle
  HelicalColumns = 4,         ///< "helical-columns": the column order (Alg. 1.1 D_c) has a cycle
  InconsistentDirection = 5,  ///< "inconsistent-direction": one course mixes directions
  InRowContinuity = 6,        ///< "in-row-continuity": one course (by its label) is several runs
  BetweenRowContinuity = 7,   ///< "between-row-continuity": the one-stroke order breaks or repeats
  FirstCourseDirection = 8,   ///< "first-course-direction" (warning): first course knitted right to left
  BoundaryApex = 9,           ///< "boundary-apex": a shaping stitch's apex lies on the boundary
  NeighbouringIncreases = 10, ///< "neighbouring-increases": two increases side by side in a course
  NeighbouringDecreases = 11, ///< "neighbouring-decreases": two decreases side by side in a course
  StackedShortRowEnds = 12,   ///< "stacked-short-row-ends": four or more short-row ends stacked in a wale
  UnpairedShortRowEnd = 13,   ///< "unpaired-short-row-end": a short-row end without its partner
  // --- knitting-map rules (convert/map_knittability.h) ---
  CollapsedCrossing = 14,     ///< "collapsed-crossing": a Collapsed cell inside both its row and its column
  SplitRow = 15,              ///< "split-row": a map row holds two separate runs of stitches
  InvalidDirection = 16,      ///< "invalid-direction": a map row direction other than +1 / -1
  InvalidYarn = 17,           ///< "invalid-yarn": a negative yarn index
  EmptyRow = 18,              ///< "empty-row": a map row without any stitch
  MapTopology = 19,           ///< "map-topology": the map's cells do not form a valid stitch mesh
  // --- machine rules (machine/machine_knittability.h) ---
  MachineLimit = 20,          ///< "machine-limit": the machine cannot knit the map within its limits
  // --- tube rules (convert/map_knittability.h, docs/tubes.md) ---
  TubeLayout = 21,            ///< "tube-layout": a tube's columns, first row or seams cannot be knitted round
  ClosedRow = 22,             ///< "closed-row": a round holds a cell a round cannot hold (short-row end, empty)
  TubeShaping = 23,           ///< "tube-shaping": a short row or short column a tube cannot knit
};
inline constexpr int kNumKnitRules = 24;



/// The stable id of a rule ("cyclic-row", ...).
std::string_view rule_id(KnitRule r);
/// The rule with that id, or throws InvalidInput naming the unknown id.
KnitRule parse_rule_id(std::string_view id);
/// Severity of a rule: Warning only for FirstCourseDirection (a machine can
/// start the carrier at either side; knitforge's convention, seed §1.2.1, is
/// left to right, so the other start is flagged but does not make ok() false).
Severity rule_severity(KnitRule r);

/// A grid position: a map cell (row, col) or a stitch's (course, wale).
struct GridCell {
  int row = -1;
  int col = -1;
  bool operator==(const GridCell&) const = default;
};

/// One violation of one rule.
struct KnittabilityViolation {
  KnitRule rule = KnitRule::MalformedAdjacency;
  Severity severity = Severity::Error;
  /// Stitches involved, in a documented order per rule (ascending unless the
  /// rule's message says "in order": then along the course / wale / cycle).
  std::vector<int> stitches;
  /// Grid positions of the involved stitches (same order and size as
  /// `stitches`) when known: the stitches' (course, wale) for the mesh check
  /// when every involved stitch has both labels, the map cells for the map
  /// check; map-level rules list the offending cells here and no stitches
  /// (col = -1 stands for a whole row).
  std::vector<GridCell> cells;
  /// Where to look: the mean of the involved stitches' centroids (mm). The
  /// map check gives positions in the flat map layout: cell (r, c) is centred
  /// at ((c + 0.5) * stitch_width, (r + 0.5) * stitch_height, 0).
  Vec3 position = Vec3::Zero();
  std::string message;  ///< one line, names the stitches / cells and the fix
};

struct KnittabilityReport {
  /// Violations in deterministic order: by rule (enum order), then by the
  /// smallest stitch / cell involved. At most KnittabilityOptions::max_violations.
  std::vector<KnittabilityViolation> violations;
  /// Number of violations of each rule, including those left out of the list.
  std::array<int, kNumKnitRules> counts{};
  /// Violations found but not listed because of the cap.
  int omitted = 0;

  /// True when no Error-severity violation was found (warnings allowed).
  bool ok() const;
  int num_errors() const;
  int num_warnings() const;
  /// Human-readable: one line per listed violation
  /// ("error [cyclic-row] <message>"), a line for omitted ones, and a summary
  /// line ("knittable: ..." / "not knittable: N errors, M warnings (rule n, ...)").
  std::string text() const;
};

struct KnittabilityOptions {
  /// Cap on the listed violations (the counts are always complete).
  int max_violations = 10000;
  /// A tube (docs/tubes.md): courses that close on themselves are rounds,
  /// not cyclic-row errors, and between-row-continuity follows the stitch
  /// order (stitches numbered in knitting order, as
  /// map_to_stitch_mesh_topology() numbers them): stitch k+1 follows k along
  /// its course, or k ends its course and k+1, the next course's first
  /// stitch, touches it. Set by the map check for tubular maps.
  bool closed_courses = false;
};

/// Builds a report from violations found in any order: fills severity from
/// the rule, sorts (by rule, then smallest stitch, then smallest cell),
/// counts every rule and keeps at most opt.max_violations in the list.
/// Used by the mesh and the map checker.
/// \throw InvalidInput when opt.max_violations < 0.
KnittabilityReport make_knittability_report(std::vector<KnittabilityViolation> all,
                                            const KnittabilityOptions& opt = {});

/// Checks the knittability constraints of seed §1.2.2 on a stitch mesh.
///
/// Row (course) edges are shared edges with Right against Left, column (wale)
/// edges Top against Bottom; malformed edges are reported and then ignored.
/// Rules checked, each reported once per defect:
/// - malformed-adjacency: per edge whose two sides are not opposite.
/// - cyclic-row / cyclic-column: per course / wale component that is a cycle.
/// - helical-rows / helical-columns: per cycle of the row order D_r (edges
///   from the Bottom stitch's row to the Top stitch's row) / column order D_c
///   (Left stitch's column to Right stitch's column) of Alg. 1.1, including a
///   course joined to itself across Bottom/Top; edges inside a cyclic wale
///   (resp. course) are left out so a cyclic column is not reported twice.
///   The stitches listed are one witnessing edge pair per cycle edge.
/// - inconsistent-direction: per course whose stitches differ in direction;
///   lists the stitches against the course's majority direction.
/// - in-row-continuity: when every stitch has a course label (Stitch::course
///   >= 0), per label whose stitches form more than one course component
///   (the yarn would float between the runs, seed Fig. 1.3 yellow).
/// - between-row-continuity: the one-stroke order (StitchAdjacency::next_stitch
///   from the first stitch) must visit every stitch once. Each break (the
///   order stops at stitch a while stitches remain; the next run starts at b)
///   is reported with {a, b}; a run that reaches an already knitted stitch is
///   reported with {a, b} too. The first stitch is the lowest-index stitch
///   without a previous_stitch (stitch 0 when every stitch has one).
/// - first-course-direction (warning): the first stitch is knitted right to left.
/// - boundary-apex: per shaping stitch whose apex vertex is on the boundary.
/// - neighbouring-increases / -decreases: per course edge joining two
///   Increase / two Decrease stitches.
/// - stacked-short-row-ends: per maximal run of >= 4 short-row ends
///   (ShortRowLeft or ShortRowRight) stacked consecutively in a wale
///   (listed bottom to top).
/// - unpaired-short-row-end: short-row ends pair up with the stitch of the
///   same type directly above or below (a turn is two stacked ends): in each
///   maximal stacked run of one type, paired bottom-up; the odd one out (and
///   every isolated end) is reported.
///
/// \pre none beyond what StitchAdjacency needs.
/// \throw TopologyError (from StitchAdjacency) when the mesh is not an
///        oriented edge-manifold polygon mesh, a corner list is invalid or a
///        direction is not +1/-1: such a mesh is not a stitch mesh at all, so
///        it is an error rather than a report entry.
/// \throw InvalidInput when opt.max_violations < 0.
KnittabilityReport check_knittability(const StitchMesh& mesh, const KnittabilityOptions& opt = {});

}  // namespace knitforge

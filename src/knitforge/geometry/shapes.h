#pragma once
/// \file shapes.h
/// Built-in test surfaces, meshed to a target edge length (mm) by isotropic
/// remeshing with exact projection (seed §2.C.2, Algorithm 2.3): the
/// triple-peak model (eq. 2.5), the monkey saddle (eq. 2.7) and simple
/// reference shapes. The hemisphere and the tube are instead built directly
/// from rings (no remeshing; well under a millisecond at the default size).
///
/// Every shape but three is a disk (one component, one boundary loop, genus
/// 0; the `beanie` too: a dome closed at the top, and the `sock`: a bent tube
/// closed at the toe); the `cap` (a dome with a face opening and a neck opening, like a
/// skull cap or a balaclava), the open `tube` and the `sleeve` are annuli (two boundary
/// loops, genus 0), the inputs that the design routes cut into a disk
/// themselves (cut_to_disk.h). All are consistently oriented with normals
/// towards +z (outward for the hemisphere, the cylinder patch, the cap,
/// the tube, the sleeve, the beanie and the sock) and deterministic. Every vertex lies
/// on the analytic surface (up to rounding) and every boundary vertex on the analytic boundary
/// curve; corners of rectangular domains are mesh vertices.
///
/// \throw InvalidInput (all functions) when a size or the edge length is not
///        positive and finite, the edge length exceeds a quarter of the
///        shape's smallest dimension, or it is so small that the mesh would
///        have more than 20 million faces.

#include <string>
#include <string_view>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The default edge length (mm) of make_shape() when none is given.
inline constexpr double kDefaultShapeEdgeLength = 2.5;

/// Upper hemisphere x²+y²+z² = r², z >= 0, centred at the origin; boundary
/// the circle of radius r in z = 0. Area 2πr².
///
/// Built from K + 1 rings of latitude, K = round((πr/2) / (√3/2 l)) for the
/// edge length l (neighbouring rings an equilateral triangle's height apart):
/// ring 0 is the pole (0, 0, r), ring K the boundary circle (z = 0 exactly);
/// ring k has max(6, round(2πr sin θ_k / l)) vertices uniformly spaced in
/// longitude, θ_k = kπ/(2K), placed symmetrically about the plane x = 0
/// (odd rings with a vertex on the +y axis, even rings turned by half a
/// spacing), and neighbouring rings are joined by the triangulation that
/// always takes the shorter diagonal. All edges are
/// within [0.8 l, 1.4 l] (from the ring spacing to the diagonal of a ring
/// pair whose vertices are aligned) and all triangle angles within [38°, 94°]
/// for every r/l >= 4; the vertex count is about 2πr² / (√3/2 l²).
TriMesh hemisphere(double radius = 75.0, double edge_length = kDefaultShapeEdgeLength);

/// Height of the triple-peak surface (mm) at (x, y) (mm): seed eq. 2.5,
/// f = w Σ exp(-|p - c_i|²/σ²) with c_i = (0,0), (1,0), (-1,0), w = 1.2,
/// σ² = 0.1 on [-1.5, 1.5] x [-1, 1], uniformly scaled by 50 so that the
/// domain is [-75, 75] x [-50, 50] mm: z = 50 f(x/50, y/50).
double triple_peak_height(double x, double y);

/// The triple-peak surface z = triple_peak_height(x, y) over
/// [-75, 75] x [-50, 50] mm (150 mm wide, about 60 mm tall).
TriMesh triple_peak(double edge_length = kDefaultShapeEdgeLength);

/// Height of the monkey saddle (mm) at (x, y) (mm): seed eq. 2.7,
/// z = x³ - 3xy² on the unit disk, uniformly scaled by 50:
/// z = 50 ((x/50)³ - 3 (x/50)(y/50)²).
double monkey_saddle_height(double x, double y);

/// The monkey saddle z = monkey_saddle_height(x, y) over the disk of radius
/// 50 mm (100 x 100 x 100 mm); boundary above the circle x² + y² = 50².
TriMesh monkey_saddle(double edge_length = kDefaultShapeEdgeLength);

/// The disk of the given radius in z = 0, centred at the origin. Area πr².
TriMesh flat_disk(double radius = 50.0, double edge_length = kDefaultShapeEdgeLength);

/// The rectangle [-w/2, w/2] x [-h/2, h/2] in z = 0. Area w h.
TriMesh rectangle(double width = 150.0, double height = 100.0,
                  double edge_length = kDefaultShapeEdgeLength);

/// An open patch of the cylinder x² + y² = r²: angles in [-a/2, a/2] around
/// the +x axis (a in radians, 0 < a, r (2π - a) >= edge length so that the
/// patch does not close), z in [0, height]. Normals point outward. Area r a h.
TriMesh cylinder_patch(double radius = 50.0, double angle = 3.14159265358979323846,
                       double height = 100.0, double edge_length = kDefaultShapeEdgeLength);

/// The open tube x² + y² = r², z in [0, height] (both ends open: two
/// boundary loops). Normals point outward. Area 2π r h.
///
/// Built from K + 1 rings of n = max(6, round(2πr / l)) vertices, K =
/// max(1, round(h / (√3/2 l))) (neighbouring rings an equilateral
/// triangle's height apart), rings at z = h k / K: odd rings have a vertex
/// on the +y axis, even rings are turned by half a spacing, so neighbouring
/// rings are staggered (nearly equilateral triangles) and every ring is
/// mirror-symmetric about the plane x = 0.
TriMesh open_tube(double radius = 40.0, double height = 100.0, double edge_length = kDefaultShapeEdgeLength);

/// Parameters of sleeve() (mm and degrees).
struct SleeveShape {
  double start_radius = 50.0;  ///< radius of the tube at its start (the upper arm)
  double end_radius = 30.0;    ///< radius at its end (the wrist)
  double bend_radius = 300.0;  ///< radius of the circular arc the axis follows
  double bend_deg = 50.0;      ///< angle of that arc (0 < angle <= 180)
};

/// A sleeve: a tapered, bent tube, the circle of radius r(t) = start +
/// (end - start) t swept along a circular arc of the axis (t in [0, 1]
/// along the arc). The axis starts at the origin along +z and bends toward
/// +x round the centre (bend_radius, 0, 0) in the plane y = 0 (its mirror
/// plane); the cross-sections are normal to the axis. An annulus (two
/// boundary loops, both exact circles), normals outward. With the
/// defaults: axis 262 mm long, circumference 314 mm at the start and 188 mm
/// at the end; area 2π r_mean L (Pappus) ≈ 65,800 mm². Built like
/// open_tube(): staggered rings of n = max(6, round(2π r_mean / l))
/// vertices, round(L / (√3/2 l)) + 1 rings, mapped onto the sweep.
/// \throw InvalidInput (besides the common conditions) when a radius is
///        not below the bend radius or the angle is not in (0, 180].
TriMesh sleeve(const SleeveShape& shape = {}, double edge_length = kDefaultShapeEdgeLength);

/// Parameters of cap() (mm and degrees).
struct CapShape {
  double radius = 90.0;  ///< radius of the head sphere, centred at the origin
  /// Face opening: the points of the sphere within this angle of the
  /// direction (0, -cos e, -sin e), e = face_elevation_deg below the
  /// equator (the front is -y).
  double face_angle_deg = 35.0;
  double face_elevation_deg = 0.0;
  /// Neck opening: the points within this angle of the south pole (0, 0, -r).
  double neck_angle_deg = 40.0;
};

/// A skull cap / balaclava: the sphere of CapShape::radius minus a face
/// opening at the front (-y) and a neck opening at the bottom (-z); an
/// annulus (two boundary loops: the face rim and the neck rim, both exact
/// circles on the sphere), mirror-symmetric about the plane x = 0 (the
/// symmetry plane of the garment). With the defaults: 162 x 180 x 159 mm,
/// area 4πr² - 2πr²(2 - cos 35° - cos 40°) ≈ 80,600 mm², the face rim
/// 103 mm wide, the neck rim 116 mm across, and the shortest seam between
/// the rims the 15° of the front meridian below the face (23.6 mm, chin to
/// neck). Meshed by isotropic remeshing with exact projection onto the
/// sphere and the two rim circles, from rings of latitude with the faces of
/// the face opening removed.
/// \throw InvalidInput (besides the common conditions) when the openings
///        overlap or one is not between 5° and 85°.
TriMesh cap(const CapShape& shape = {}, double edge_length = kDefaultShapeEdgeLength);

/// Parameters of beanie() (mm).
struct BeanieShape {
  double radius = 89.13;       ///< head radius: circumference 2π r = 560 mm
  double crown_height = 100.0;  ///< height of the dome above the band (its vertical semi-axis)
  double band_height = 40.0;    ///< height of the straight band above the rim (0: no band)
};

/// A beanie: a dome closed at the top on a short cylindrical band, open at
/// the bottom. The band is the cylinder x² + y² = r², z in [0, band], the
/// crown the upper half of the spheroid x² + y² over r² plus (z - band)² over
/// crown_height² = 1; the rim is the circle of radius r in z = 0 (one
/// boundary loop: a disk), the crown the point (0, 0, band + crown_height).
/// Mirror-symmetric about the planes x = 0 and y = 0 up to the ring
/// phases (exactly about x = 0); normals outward. With the defaults: 178 mm
/// across, 140 mm tall, rim 560 mm round, meridian from rim to crown
/// 40 + 148 = 188 mm, area about 22,400 + 61,300 ≈ 83,700 mm². Built like
/// hemisphere(): rings of latitude an equilateral triangle's height apart
/// along the meridian (tabulated by arc length), ring 0 the crown.
/// \throw InvalidInput (besides the common conditions) when the band
///        height is negative.
TriMesh beanie(const BeanieShape& shape = {}, double edge_length = kDefaultShapeEdgeLength);

/// Parameters of sock() (mm).
struct SockShape {
  double radius = 38.0;        ///< radius of the tube (foot and leg): 239 mm round
  double foot_length = 110.0;  ///< straight foot, from the toe cap's centre to the heel's bend
  double heel_radius = 70.0;   ///< radius of the quarter circle the axis follows round the heel
  double leg_length = 120.0;   ///< straight leg above the bend, up to the rim
};

/// A sock: a tube of constant radius closed by a hemisphere at the toe,
/// whose axis runs from the toe cap's centre (foot_length, 0, 0) along -x,
/// bends up round the heel on the quarter circle of heel_radius about
/// (0, 0, heel_radius), and goes up along +z to the rim, the circle of the
/// radius in the plane z = heel_radius + leg_length centred on
/// (-heel_radius, 0, .). The cross-sections are normal to the axis; the
/// inside of the bend (the instep) faces the bend's centre, the outside is
/// the heel. One boundary loop (a disk, like the beanie), mirror-symmetric
/// about the plane y = 0, normals outward. With the defaults: 256 mm from
/// heel to toe, 228 mm from the sole to the rim, area 2π r² + 2π r
/// (foot + π/2 heel_radius + leg) ≈ 93,400 mm² (Pappus for the bend). Built
/// as a surface of revolution from rings (like beanie()), toe tip first,
/// then swept along the bent axis (like sleeve()): rings are one equilateral
/// triangle's height apart on the axis, so the triangles are squashed along
/// the axis on the instep side of the bend and stretched on the heel side,
/// by (heel_radius -+ radius) / heel_radius.
/// \throw InvalidInput (besides the common conditions) when the radius is
///        not below the heel radius or a length is not positive.
TriMesh sock(const SockShape& shape = {}, double edge_length = kDefaultShapeEdgeLength);

/// Names accepted by make_shape(), with their default sizes:
/// hemisphere (r 75), triple-peak (150 x 100), monkey-saddle (100 x 100 x 100),
/// disk (r 50), rectangle (150 x 100), cylinder-patch (r 50, 180°, height 100),
/// cap (CapShape defaults: r 90, two openings), tube (r 40, height 100, open),
/// sleeve (SleeveShape defaults: r 50 to 30, bent 50° round a 300 mm arc),
/// beanie (BeanieShape defaults: 560 mm round, dome 100 mm on a 40 mm band),
/// sock (SockShape defaults: 239 mm round, 256 mm heel to toe, 228 mm high).
std::vector<std::string> shape_names();

/// The named shape at its default size, meshed with the given edge length.
/// \throw InvalidInput for an unknown name (the message lists the names) or
///        an invalid edge length.
TriMesh make_shape(std::string_view name, double edge_length = kDefaultShapeEdgeLength);

}  // namespace knitforge

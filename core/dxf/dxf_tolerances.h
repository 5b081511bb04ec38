// Tolerances and fixed limits of the DXF front end, in one place.
// Lengths are mm (after the drawing's units are applied), angles radians.
#pragma once

#include <cstddef>

namespace lcnc::dxf {

// Two entity ends are joined into one contour vertex when closer than this.
// One machine step (1 µm, docs/design.md §4): CAD files print 6–16 digits, so real
// gaps between touching entities are far below it, and a gap the machine
// could resolve is an open contour, not noise.
inline constexpr double kJoinToleranceMm = 1e-3;

// A SPLINE's arc-length table has a node wherever the curve would leave the
// chord by more than this: the finest step a user may ask for. The table only
// brackets arc lengths — each interval's length is a 5-point Gauss–Legendre
// sum and every point is the curve's own, found by Newton's method — so
// lengths and points come out the same to 12 digits as with a table ten
// or a hundred times finer (the test drawings, the sample part).
inline constexpr double kSplineFlatnessMm = 1e-3;

// Deepest subdivision of one spline knot span for that table (2^20 nodes).
inline constexpr int kSplineMaxDepth = 20;

// Most nodes of one spline's table: a 2 m curve bent at 1 mm radius all along
// takes ~22,000 at kSplineFlatnessMm, so this is reached only by a curve
// kilometres long — a drawing in the wrong units — whose table would
// otherwise take minutes.
inline constexpr std::size_t kSplineMaxNodes = 1u << 16;

// Most nodes of all the spline tables of one drawing (an INSERT array of a
// spline block tabulates each copy): ~23 m of spline bent at 1 mm radius
// all along, ~75 m at 10 mm; a twentieth of a second.
inline constexpr std::size_t kMaxDrawingSplineNodes = 1u << 18;

// Highest SPLINE degree read (DXF writers use 2 and 3; de Boor's scratch
// space is sized by it).
inline constexpr int kSplineMaxDegree = 15;

// Edges shorter than this are dropped (zero-length lines, repeated vertices).
inline constexpr double kMinEdgeMm = 1e-9;

// Largest polyline bulge (tan of a quarter of the arc's included angle):
// 10⁴ is an arc of 359.98° whose radius is 2,500 times its chord. Beyond it a
// drawing holds no arc but an overflow (1e300 gives an infinite centre).
inline constexpr double kMaxBulge = 1e4;

// An INSERT inside a block inside ... deeper than this is an error.
inline constexpr int kMaxBlockDepth = 16;

// Most entities the INSERTs of one drawing may place, counted before any is
// (nested arrays multiply: 16 levels of 2 × 2 are 4^16 copies).
inline constexpr std::size_t kMaxPlacedEntities = 1'000'000;

// Sanity limits against malformed counts: a DXF that declares more vertices,
// knots or array copies than these is rejected before anything is allocated.
inline constexpr std::size_t kMaxDeclaredCount = 10'000'000;

// The longest line dxflib reads (DL_DXF_MAXLINE, 1024, with its terminator):
// a longer one leaves its stream failed but not at the end, and its reading
// loop never ends — found by fuzzing. The scanner refuses longer lines first.
inline constexpr std::size_t kMaxDxfLine = 1023;

// Largest DXF file read: 128 MiB, a million entities (kMaxPlacedEntities) as
// CAD programs write them (~100 bytes each) with room to spare. A larger
// regular file is refused before reading; a pipe or device is read only up
// to this, so a stream without end (/dev/zero, /dev/urandom) fails instead
// of filling the memory.
inline constexpr std::size_t kMaxDxfFileBytes = std::size_t{128} << 20;
inline constexpr std::size_t kMaxInsertCopies = 100'000;

// Affine maps of arcs (INSERT scale, OCS) must be similarities: |M^T M − s² I|
// relative to s² within this.
inline constexpr double kSimilarityRel = 1e-9;

// The extrusion direction of a 2D entity must be ±Z within this.
inline constexpr double kExtrusionTol = 1e-9;

}  // namespace lcnc::dxf

namespace lcnc::dxf {

// The finest discretization step a user may ask for (Kondratenko et al. 2015: "down to
// microns between neighbouring points"; docs/design.md §5.7: 1 µm).
inline constexpr double kMinStepMm = 1e-3;

// Fewest points of a discretized contour, and the most of one drawing
// (a 100 m contour at 1 µm; beyond it the tables stop fitting in memory).
inline constexpr std::size_t kMinContourPoints = 8;
inline constexpr std::size_t kMaxDrawingPoints = 100'000'000;

}  // namespace lcnc::dxf

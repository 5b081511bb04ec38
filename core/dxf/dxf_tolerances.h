// Tolerances and fixed limits of the DXF front end, in one place (STYLE §4).
// Lengths are mm (after the drawing's units are applied), angles radians.
#pragma once

#include <cstddef>

namespace lcnc::dxf {

// Two entity ends are joined into one contour vertex when closer than this.
// One machine step (1 µm, DESIGN §4): CAD files print 6–16 digits, so real
// gaps between touching entities are far below it, and a gap the machine
// could resolve is an open contour, not noise.
inline constexpr double kJoinToleranceMm = 1e-3;

// A SPLINE's arc-length table has a node wherever the curve would leave the
// chord by more than this: a tenth of the finest step a user may ask for.
inline constexpr double kSplineFlatnessMm = 1e-4;

// Deepest subdivision of one spline knot span for that table (2^20 nodes).
inline constexpr int kSplineMaxDepth = 20;

// Most nodes of one spline's table: a 2 m curve of 1 mm radius takes ~6,000
// at kSplineFlatnessMm, so this is reached only by a curve kilometres long —
// a drawing in the wrong units — whose table would otherwise take minutes.
inline constexpr std::size_t kSplineMaxNodes = 1u << 17;

// Highest SPLINE degree read (DXF writers use 2 and 3; de Boor's scratch
// space is sized by it).
inline constexpr int kSplineMaxDegree = 15;

// Edges shorter than this are dropped (zero-length lines, repeated vertices).
inline constexpr double kMinEdgeMm = 1e-9;

// An INSERT inside a block inside ... deeper than this is an error (and
// catches a block that inserts itself).
inline constexpr int kMaxBlockDepth = 16;

// Sanity limits against malformed counts: a DXF that declares more vertices,
// knots or array copies than these is rejected before anything is allocated.
inline constexpr std::size_t kMaxDeclaredCount = 10'000'000;

// The longest line dxflib reads (DL_DXF_MAXLINE, 1024, with its terminator):
// a longer one leaves its stream failed but not at the end, and its reading
// loop never ends — found by fuzzing. The scanner refuses longer lines first.
inline constexpr std::size_t kMaxDxfLine = 1023;
inline constexpr std::size_t kMaxInsertCopies = 100'000;

// Affine maps of arcs (INSERT scale, OCS) must be similarities: |M^T M − s² I|
// relative to s² within this.
inline constexpr double kSimilarityRel = 1e-9;

// The extrusion direction of a 2D entity must be ±Z within this.
inline constexpr double kExtrusionTol = 1e-9;

}  // namespace lcnc::dxf

namespace lcnc::dxf {

// The finest discretization step a user may ask for (seed 004: "down to
// microns between neighbouring points"; DESIGN §5.7: 1 µm).
inline constexpr double kMinStepMm = 1e-3;

// Fewest points of a discretized contour, and the most of one drawing
// (a 100 m contour at 1 µm; beyond it the tables stop fitting in memory).
inline constexpr std::size_t kMinContourPoints = 8;
inline constexpr std::size_t kMaxDrawingPoints = 100'000'000;

}  // namespace lcnc::dxf

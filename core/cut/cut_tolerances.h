// Tolerances and fixed numbers of laser cutting from a DXF drawing
// (lasercnc cut), in one place. Lengths mm, angles radians.
//
// The cut path stays within kChordToleranceMm + kKerfArcToleranceMm +
// kOffsetSimplifyMm (+ half a unit of the last printed digit) of kerf/2 from
// the drawing: arcs and splines are chords at most kChordToleranceMm inside
// the curve, the polygon offset has dropped no vertex farther than
// kOffsetSimplifyMm from its chords, the round joins of the offset chords
// are at most kKerfArcToleranceMm inside their circle, and the integer grid
// moves a point by at most kClipperUnitMm·√2/2.
#pragma once

#include <cstddef>

namespace lcnc::cut {

// Arcs, circles and splines of the drawing become chords no farther than
// this from the curve (sagitta), before the offset: a tenth of a typical
// 0.01 mm contour tolerance, a machine step.
inline constexpr double kChordToleranceMm = 1e-3;

// Clipper works on integer coordinates: one unit is this many mm (10 nm).
// 64-bit units then reach ±9.2e13 mm, so any sheet fits, and rounding to
// the grid (≤ 7.1 nm) is far below the machine's 1 µm step.
inline constexpr double kClipperUnitMm = 1e-5;

// Before the kerf offset, runs of vertices that lie within this of one chord
// become that chord (a dense polyline of 10⁶ points on a circle keeps a few
// thousand): the offset of n chords costs Clipper up to n² where their
// offsets overlap, while 0.1 µm is a tenth of the machine's step.
inline constexpr double kOffsetSimplifyMm = 1e-4;

// The round joins of the kerf offset (ClipperOffset jtRound) are chords no
// farther than this from their circle of radius kerf/2.
inline constexpr double kKerfArcToleranceMm = 1e-3;

// A vertex of a part's outline is a corner (a preferred pierce place: a
// lead-in there leaves no visible mark on a straight edge) when the outline
// turns there by at least this: 30°. A flattened arc turns by far less per
// chord (2·acos(1 − kChordToleranceMm / r) ≈ 5° at r = 1 mm).
inline constexpr double kCornerMinTurnRad = 0.5235987755982988;

// A lead-in that would cross a cut path or leave the scrap side is halved
// until it fits; below this fraction of the asked length it is dropped
// (the pierce is then on the path itself) — never the case for a hole whose
// offset path is at least one lead-in wide.
inline constexpr double kMinLeadInFraction = 1.0 / 64.0;

// Candidate pierce vertices tried per contour (nearest first), bounding the
// lead-in fitting on contours of many thousand vertices.
inline constexpr std::size_t kMaxPierceCandidates = 64;

// G64 P: the path blending tolerance written into the program.
inline constexpr double kBlendToleranceMm = 0.01;

// A part smaller than this or larger than kMaxPartMm across (after the
// drawing's units) is taken for a drawing in the wrong units.
inline constexpr double kMinPartMm = 1.0;
inline constexpr double kMaxPartMm = 10'000.0;

// Rapid speed for the time estimate (the default machine's X/Y limit,
// 30 m/min); the real machine's planner decides the true time.
inline constexpr double kEstimateRapidMmS = 500.0;

}  // namespace lcnc::cut

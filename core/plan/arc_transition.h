// Corner arc transition (docs/design.md §5.1, Shao (2022) §3, Chi, Wu and Cui (2020) §3): the corner
// between two lines P(i−1)→P(i)→P(i+1) is replaced by a tangent arc whose
// distance from the corner point P(i) is at most the tolerance E.
//
//   turning angle θ (between the two directions d1, d2)
//   tangent length under the tolerance   l_c = E·sin(θ/2) / (1 − cos(θ/2))
//   length bound                         l ≤ max_trim on each side (≤ half a line)
//   l = min(l_c, bounds),  radius r = l / tan(θ/2)
//   tangent points Q0 = P(i) − l·d1,  Q2 = P(i) + l·d2
//   centre C = P(i) + r/cos(θ/2) · (d2 − d1)/|d2 − d1|
//   distance from P(i) to the arc = r/cos(θ/2) − r = E when l = l_c (less otherwise)
// The arc lies in the plane of d1 and d2 (any plane in 3D) and turns about
// n = d1 × d2. Rotary axes move linearly from their value at Q0 to that at Q2.
#pragma once

#include "path/segment.h"
#include "path/segment_geometry.h"

namespace lcnc {

struct ArcTransition {
  bool blended = false;
  double trim = 0.0;  // l: length cut off the end of the first and the start of the second line
  Pose q0 = Pose::Zero(), q2 = Pose::Zero();
  Segment arc;  // Plane::Free arc from q0 to q2
};

// Sets `arc` to the blend arc's segment from q0 to q2: feed, laser and modes
// from `a`, the source line of `b`; the caller sets its plane, centre and
// turning sense.
void set_blend_arc(const Segment& a, const Segment& b, const Pose& q0, const Pose& q2, Segment& arc);

// `a` ends where `b` starts; both are lines with X Y Z motion. The arc takes
// its feed, laser and modes from `a`. Not blended when the lines are
// collinear (nothing to blend), reversed, or the tolerance leaves no length.
[[nodiscard]] ArcTransition arc_transition(const Segment& a, const Segment& b, double tolerance_mm,
                                           double max_trim_a, double max_trim_b);
// The same in place (the blender's, per corner): t's blended, trim, q0 and
// q2 are set, and when blended the arc goes to `arc` and its geometry as
// constructed (SegmentGeometry(arc) up to rounding, without deriving it
// again) to `geo`; t.arc is not touched. la and lb are the lines' X Y Z
// lengths, as the caller has them already. Returns t.blended.
bool arc_transition(const Segment& a, const Segment& b, double la, double lb, double tolerance_mm,
                    double max_trim_a, double max_trim_b, ArcTransition& t, Segment& arc,
                    SegmentGeometry& geo);

}  // namespace lcnc

namespace lcnc {

// Corner arc transition where one or both neighbours are arcs (Shao (2022)
// eq. 15–21): a fillet circle tangent to both curves, in their common plane,
// found as the crossing of the two curves offset by its radius r toward the
// inside of the corner (a line offsets to a parallel line, a circle of
// radius R to one of radius R ∓ r). The largest r is taken whose fillet stays
// within the tolerance of the corner point (| |P − c| − r | ≤ E) and uses at
// most max_trim of each neighbour (bisection: both grow with r).
//
// Handles line–arc, arc–line and arc–arc corners whose curves lie in one of
// the planes G17/G18/G19 with no helix and no rotary motion; anything else is
// not blended. The trimmed neighbours are `a` ending at q0 and `b` starting at
// q2; the fillet takes its feed, laser and modes from `a`.
[[nodiscard]] ArcTransition fillet_transition(const Segment& a, const Segment& b, double tolerance_mm,
                                              double max_trim_a, double max_trim_b);

}  // namespace lcnc

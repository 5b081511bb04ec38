// Where a contour is pierced and how the beam enters and leaves it.
//
// Piercing blows a crater wider than the kerf, so it happens off the part:
// at the start of a straight lead-in on the scrap side (outside a part's
// outline, inside a hole), which meets the cut path at the start vertex.
// The lead-in leaves along the scrap-side normal there (the mean of the two
// edges' normals: the corner's bisector at a corner). At the end the beam
// goes on along the path past the start for the lead-out (an overcut: the
// slot is closed for sure where it began) and only then goes off.
//
// The start vertex: for a part's outline a corner of the drawing (a turn of
// at least kCornerMinTurnRad; the lead-in's mark hides in it), the one
// nearest to where the beam is; without corners, and for holes, the vertex
// nearest to where the beam is. Of those, the nearest kMaxPierceCandidates
// are tried in turn: the first whose full lead-in stays on the scrap side
// and crosses no cut path (this contour's or another's) wins. When none
// does (a hole too small for the lead-in), the longest that fits among the
// halvings L, L/2, L/4, ... down to L·kMinLeadInFraction is taken and
// `shortened` says so (the caller warns).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace lcnc::cut {

using Vec2 = Eigen::Vector2d;

struct LeadInRequest {
  bool hole = false;         // the scrap is inside the path (else outside)
  double lead_in_mm = 2.0;   // asked length; 0 = pierce on the path
  double lead_out_mm = 0.5;  // overcut past the start; 0 = none
  double offset_mm = 0.0;    // the path's distance from the drawing (kerf/2)
};

struct LeadIn {
  std::vector<Vec2> path;      // the contour's path from the start vertex, same direction
  Vec2 pierce = Vec2::Zero();  // where the beam pierces (== path[0] without a lead-in)
  double lead_in_mm = 0.0;     // its length as placed
  bool shortened = false;      // shorter than asked (it did not fit)
  std::vector<Vec2> overcut;   // after coming back to path[0]: the lead-out's points
};

// `path`: the oriented cut path (closed); `drawing`: the drawn contour's
// polygon (its corners); `from`: where the beam is; `others`: the other
// contours' cut paths, which a lead-in must not cross.
[[nodiscard]] LeadIn place_lead_in(const std::vector<Vec2>& path, const std::vector<Vec2>& drawing,
                                   const Vec2& from, const LeadInRequest& req,
                                   const std::vector<const std::vector<Vec2>*>& others);

// The normal at vertex i of a closed polygon pointing to its inside (the
// mean of the two edges' inward normals, normalized).
[[nodiscard]] Vec2 inward_normal(const std::vector<Vec2>& poly, std::size_t i);

}  // namespace lcnc::cut

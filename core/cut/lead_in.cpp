#include "cut/lead_in.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cut/contour_polygon.h"
#include "cut/cut_tolerances.h"
#include "geom/plane.h"

namespace lcnc::cut {
namespace {

using geom::cross;

// Segments ab and cd meet (touching counts).
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on = [](const Vec2& p, const Vec2& q, const Vec2& r, double o) {  // r on pq, collinear
    return o == 0.0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

// The lead-in s → path[i] stays on the scrap side and meets no path but at
// its end (the two edges at path[i] start there and are skipped).
bool lead_in_fits(const Vec2& s, const std::vector<Vec2>& path, std::size_t i, bool hole,
                  const std::vector<const std::vector<Vec2>*>& others) {
  if (inside(s, path) != hole) return false;
  const Vec2& e = path[i];
  const std::size_t n = path.size();
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t k = (j + 1) % n;
    if (j == i || k == i) continue;
    if (segments_meet(s, e, path[j], path[k])) return false;
  }
  for (const std::vector<Vec2>* o : others) {
    for (std::size_t j = 0, m = o->size(); j < m; ++j) {
      if (segments_meet(s, e, (*o)[j], (*o)[(j + 1) % m])) return false;
    }
  }
  return true;
}

// Turning angle at vertex i, radians (0 straight on).
double turn(const std::vector<Vec2>& p, std::size_t i) {
  const std::size_t n = p.size();
  const Vec2 u = p[i] - p[(i + n - 1) % n], v = p[(i + 1) % n] - p[i];
  return std::abs(std::atan2(cross(u, v), u.dot(v)));
}

std::size_t nearest_vertex(const std::vector<Vec2>& path, const Vec2& q) {
  std::size_t best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double d = (path[i] - q).squaredNorm();
    if (d < bd) {
      bd = d;
      best = i;
    }
  }
  return best;
}

}  // namespace

Vec2 inward_normal(const std::vector<Vec2>& poly, std::size_t i) {
  const std::size_t n = poly.size();
  const Vec2 u = (poly[i] - poly[(i + n - 1) % n]).normalized();
  const Vec2 v = (poly[(i + 1) % n] - poly[i]).normalized();
  Vec2 left = Vec2(-u.y(), u.x()) + Vec2(-v.y(), v.x());  // left of travel
  if (left.norm() < 1e-12) left = Vec2(-u.y(), u.x());    // folds back: either edge's
  left.normalize();
  return signed_area(poly) > 0.0 ? left : Vec2(-left);  // counter-clockwise: inside is left
}

LeadIn place_lead_in(const std::vector<Vec2>& path, const std::vector<Vec2>& drawing, const Vec2& from,
                     const LeadInRequest& req, const std::vector<const std::vector<Vec2>*>& others) {
  // Candidate start vertices, preferred first.
  std::vector<std::size_t> cand;
  if (!req.hole) {
    for (std::size_t i = 0; i < drawing.size(); ++i) {
      if (turn(drawing, i) < kCornerMinTurnRad) continue;
      // the path vertex across the kerf from the corner, along its bisector
      const Vec2 scrap = -inward_normal(drawing, i);
      cand.push_back(nearest_vertex(path, drawing[i] + req.offset_mm * scrap));
    }
  }
  if (cand.empty()) {
    for (std::size_t i = 0; i < path.size(); ++i) cand.push_back(i);
  }
  std::sort(cand.begin(), cand.end(), [&](std::size_t a, std::size_t b) {
    return (path[a] - from).squaredNorm() < (path[b] - from).squaredNorm();
  });
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  if (cand.size() > kMaxPierceCandidates) cand.resize(kMaxPierceCandidates);

  std::size_t start = cand.front();
  double length = 0.0;
  if (req.lead_in_mm > 0.0) {
    for (std::size_t c : cand) {
      const Vec2 n = req.hole ? inward_normal(path, c) : Vec2(-inward_normal(path, c));
      for (double l = req.lead_in_mm; l >= req.lead_in_mm * kMinLeadInFraction; l *= 0.5) {
        if (l <= length) break;  // a longer one was found already
        if (lead_in_fits(path[c] + l * n, path, c, req.hole, others)) {
          start = c;
          length = l;
          break;
        }
      }
      if (length == req.lead_in_mm) break;
    }
  }

  LeadIn out;
  out.path.reserve(path.size());
  for (std::size_t k = 0; k < path.size(); ++k) out.path.push_back(path[(start + k) % path.size()]);
  const Vec2 n = req.hole ? inward_normal(out.path, 0) : Vec2(-inward_normal(out.path, 0));
  out.pierce = out.path[0] + length * n;
  out.lead_in_mm = length;
  out.shortened = req.lead_in_mm > 0.0 && length < req.lead_in_mm;
  // Lead-out: on along the path from the start for lead_out_mm.
  double left = req.lead_out_mm;
  for (std::size_t k = 1; left > 0.0 && k <= out.path.size(); ++k) {
    const Vec2& a = out.path[k - 1];
    const Vec2& b = out.path[k % out.path.size()];
    const double l = (b - a).norm();
    if (l >= left) {
      out.overcut.push_back(a + (b - a) * (left / l));
      break;
    }
    out.overcut.push_back(b);
    left -= l;
  }
  return out;
}

}  // namespace lcnc::cut

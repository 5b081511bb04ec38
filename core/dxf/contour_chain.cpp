#include "dxf/contour_chain.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <unordered_map>

#include "common/error.h"
#include "dxf/dxf_tolerances.h"

namespace lcnc::dxf {
namespace {

// The ends of all entities in a hash grid of cell kJoinToleranceMm: the ends
// within the tolerance of a point are in its 3×3 cells.
class EndIndex {
 public:
  explicit EndIndex(const std::vector<Entity>& es) : es_(es) {
    for (std::size_t i = 0; i < es.size(); ++i) {
      cells_[key(es[i].start())].push_back(2 * i);
      cells_[key(es[i].end())].push_back(2 * i + 1);
    }
  }
  [[nodiscard]] Vec2 end_point(std::size_t end_id) const {
    const Entity& e = es_[end_id / 2];
    return end_id % 2 == 0 ? e.start() : e.end();
  }
  // Ends (entity·2 + 0 start / 1 end) within the tolerance of p.
  [[nodiscard]] std::vector<std::size_t> near(const Vec2& p) const {
    std::vector<std::size_t> out;
    const auto [cx, cy] = cell(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(pack(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (std::size_t id : it->second) {
          if ((end_point(id) - p).norm() <= kJoinToleranceMm) out.push_back(id);
        }
      }
    }
    return out;
  }

 private:
  static std::pair<std::int64_t, std::int64_t> cell(const Vec2& p) {
    return {static_cast<std::int64_t>(std::floor(p.x() / kJoinToleranceMm)),
            static_cast<std::int64_t>(std::floor(p.y() / kJoinToleranceMm))};
  }
  static std::uint64_t pack(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ static_cast<std::uint32_t>(y);
  }
  static std::uint64_t key(const Vec2& p) {
    const auto [x, y] = cell(p);
    return pack(x, y);
  }
  const std::vector<Entity>& es_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

std::string describe(const Entity& e) {
  std::string s = std::string(entity_name(e.kind)) + " at DXF line " + std::to_string(e.line);
  if (!e.block.empty()) s += " (block " + e.block + ")";
  return s;
}

}  // namespace

std::string format_point(const Vec2& p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", p.x(), p.y());
  return buf;
}

Result<std::vector<Contour>> chain_contours(const Drawing& d) {
  const std::vector<Entity>& es = d.entities;
  const EndIndex index(es);
  std::vector<bool> used(es.size(), false);
  std::vector<Contour> out;

  // The ends at p other than `self` (an end id), unused entities only; a
  // branch error when more than one.
  auto others_at = [&](const Vec2& p, std::size_t self_entity, const Contour& c,
                       std::vector<std::size_t>& found) -> Status {
    found.clear();
    for (std::size_t id : index.near(p)) {
      if (id / 2 == self_entity || used[id / 2]) continue;
      found.push_back(id);
    }
    if (found.size() > 1) {
      std::string list;
      for (std::size_t id : found) list += (list.empty() ? "" : ", ") + describe(es[id / 2]);
      return make_error(ErrorCode::DxfOpenContour,
                        c.name() + " branches at " + format_point(p) + ": " + describe(es[self_entity]) +
                            " meets " + list + "; expected exactly two entity ends at every vertex",
                        d.file, es[found[0] / 2].line);
    }
    return {};
  };

  std::vector<std::size_t> found;
  for (std::size_t first = 0; first < es.size(); ++first) {
    if (used[first]) continue;
    Contour c;
    c.index = static_cast<std::uint32_t>(out.size() + 1);
    c.first_kind = es[first].kind;
    c.first_line = es[first].line;
    c.layer = es[first].layer;
    c.block = es[first].block;
    used[first] = true;
    c.edges = es[first].edges;
    const Vec2 start = es[first].start();
    std::size_t last = first;
    for (;;) {
      const Vec2 end = c.edges.back().b;
      if (Status s = others_at(end, last, c, found); !s) return s.error();
      if ((end - start).norm() <= kJoinToleranceMm) {
        if (!found.empty()) {  // a third end at the closing vertex
          return make_error(ErrorCode::DxfOpenContour,
                            c.name() + " branches at " + format_point(end) + ": " +
                                describe(es[found[0] / 2]) +
                                " also starts or ends there; expected exactly two entity "
                                "ends at every vertex",
                            d.file, es[found[0] / 2].line);
        }
        c.edges.back().b = start;  // close exactly
        break;
      }
      if (found.empty()) {
        return make_error(ErrorCode::DxfOpenContour,
                          c.name() + " is open: " + describe(es[last]) + " ends at " + format_point(end) +
                              " and no entity continues it (the contour "
                              "starts at " +
                              format_point(start) + ", " + std::to_string((end - start).norm()) +
                              " mm away); expected a closed contour (ends within " +
                              std::to_string(kJoinToleranceMm) + " mm)",
                          d.file, es[last].line);
      }
      const std::size_t next = found[0] / 2;
      const bool at_start = found[0] % 2 == 0;
      used[next] = true;
      const Vec2& join = end;
      if (at_start) {
        for (const Edge& e : es[next].edges) c.edges.push_back(e);
      } else {
        for (auto it = es[next].edges.rbegin(); it != es[next].edges.rend(); ++it) {
          c.edges.push_back(reversed(*it));
        }
      }
      // Snap the joint: the new entity starts exactly where the chain ended.
      const std::size_t first_new = c.edges.size() - es[next].edges.size();
      c.edges[first_new].a = join;
      last = next;
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace lcnc::dxf

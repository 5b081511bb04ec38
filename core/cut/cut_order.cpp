#include "cut/cut_order.h"

#include <limits>

namespace lcnc::cut {
namespace {

using Vec2 = Eigen::Vector2d;

struct Orderer {
  const Nesting& nest;
  const std::vector<std::vector<Vec2>>& paths;
  const CutStep& cut;
  std::vector<std::size_t> order;
  Vec2 at;

  [[nodiscard]] double distance(std::size_t i) const {
    double d = std::numeric_limits<double>::infinity();
    for (const Vec2& p : paths[i]) d = std::min(d, (p - at).squaredNorm());
    return d;
  }

  // Cuts the siblings `set` (and their subtrees), nearest first.
  void siblings(std::vector<std::size_t> set) {
    while (!set.empty()) {
      std::size_t best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < set.size(); ++k) {
        const double d = distance(set[k]);
        if (d < best_d) {
          best_d = d;
          best = k;
        }
      }
      const std::size_t i = set[best];
      set.erase(set.begin() + static_cast<long>(best));
      siblings(nest.children[i]);  // rule 1: what is inside i first
      at = cut(i, at);
      order.push_back(i);
    }
  }
};

}  // namespace

std::vector<std::size_t> cut_order(const Nesting& nest, const std::vector<std::vector<Vec2>>& paths,
                                   const Vec2& start, const CutStep& cut) {
  Orderer o{nest, paths, cut, {}, start};
  o.siblings(nest.roots);
  return std::move(o.order);
}

}  // namespace lcnc::cut

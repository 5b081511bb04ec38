// Look-ahead (docs/design.md §5.2, Chi, Wu and Cui (2020) §3 "forward–backward"), streaming.
//
// Per segment i: length L, top speed Vm (feed, per-axis and centripetal
// limits: plan/segment_limits.h), tangential acceleration a, and a junction
// limit Vj(i) on the speed where segment i ends and i+1 starts:
//   * 0 at program end, at G61/G61.1 blocks, dwells, rapid↔feed changes;
//   * 0 at a corner: a per-axis jump of the unit tangent over kMaxJunctionJump
//     (0.06°) — corners in G64 are blended first, so these are the corners
//     that could not be (arc–line, G61 neighbours, reversals);
//   * on near-tangent joins (CAM arcs rounded to 4 decimals) the velocity
//     jump per axis stays within a tenth of one period's acceleration:
//       Vj ≤ min_i  0.1·amax_i·T / |t_i(b, start) − t_i(a, end)|
//   * no limit but the segments' own on tangent joins (blends; the blender
//     marks its own, IndexedSegment::tangent_in, which are not looked at).
// Backward pass from the window's end, assumed a stop:
//   Ve(i) = min(Vj(i), Vs(i+1)),   Vs(i) = min(Vm(i), sqrt(Ve(i)² + 2aL))
// Forward pass from the speed the last released segment ends at:
//   Ve(i) = min(Ve(i), sqrt(Vs(i)² + 2aL)),   Vs(i+1) = Ve(i)
// On arcs a depends on the speed (less centripetal load when slower): a is
// taken at the speed reached, the highest on the way, so each step is safe —
// v'² = v² + 2L·a(v') solved exactly (SegmentLimits::reach_up/reach_down).
// The passes run on the squares (x = v², the phase plane), where a step is
// x' = x + 2L·a: a square root is taken only when a profile is fitted.
// Each segment then runs a trapezoid Vs → Vc → Ve (plan/trapezoid.h) with the
// highest Vc ≤ Vm whose acceleration a(Vc) still fits the segment.
//
// Only what changes is recomputed: the backward pass stops at the first
// segment (from the end) whose entry speed is what the previous plan found —
// nothing before it can change — and the forward pass covers the segments
// released; a profile is fitted when its segment is handed out.
//
// Streaming: the window holds segments until what follows the front is
// longer than the braking distance from the highest top speed in the window,
// so a stop assumed at the window's end cannot slow the segments released
// (none of them is faster than that). Memory is
// bounded by kMaxWindow segments whatever the program's length; a release is
// always safe (the assumed stop is conservative), only possibly slower.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "machine/machine_config.h"
#include "plan/path_blender.h"
#include "plan/planned_segment.h"
#include "plan/segment_limits.h"

namespace lcnc {

class Lookahead {
 public:
  static constexpr std::size_t kMaxWindow = 1 << 16;
  static constexpr std::size_t kInitialCapacity = 1 << 10;
  // The window is filled to this many braking lengths and planned; what lies
  // more than one braking length before its end is released. Each segment is
  // thus planned about kRefillDepth / (kRefillDepth − 1) times.
  static constexpr double kRefillDepth = 4.0;

  Lookahead(const MachineConfig& machine, IndexedSource source);
  // The next planned segment, valid until next() is called again (it stays
  // in the window's ring).
  [[nodiscard]] SourceStatus next(const PlannedSegment*& out);

  [[nodiscard]] std::size_t max_window_seen() const noexcept { return max_window_; }

  // The feed override to plan for (≥ 1; 1 at the start): feed moves at F·k
  // within the axes' limits (target_speed), rapids as ever. A raise re-plans
  // every segment not yet handed out, from the speed the last one handed out
  // ends at — it can only speed them up, so the plan stays feasible; a
  // segment already planned faster keeps its speed. A lower k applies to the
  // segments that come in from now on (the RT slows what is planned faster).
  void set_feed_scale(double k);
  [[nodiscard]] double feed_scale() const noexcept { return feed_scale_; }

 private:
  // What the passes read and write, kept apart from the planned segments
  // (some 600 bytes each, touched only when they come in and go out): the
  // passes sweep the window several times, and a compact one stays in cache.
  struct Node {
    // user-provided, so that the vector does not zero the whole node first
    // NOLINTNEXTLINE(modernize-use-equals-default)
    Node() {}
    // Speeds as their squares (x = v², the phase plane): the passes chain
    // reaches with no square root between segments.
    double length = 0.0;
    double x_max = 0.0;       // top speed on the segment
    double x_junction = 0.0;  // limit where this segment ends and the next starts
    // The same from the geometry alone (∞: none), before the two top speeds.
    double x_junction_geo = 0.0;
    // The backward pass's speeds, kept from one plan to the next: the pass
    // stops at the first segment whose entry speed comes out unchanged.
    double x_entry_back = 0.0, x_exit_back = 0.0;
    // The forward pass's, for released segments: the profile runs entry → exit.
    double x_entry = 0.0, x_exit = 0.0;
    bool dwell = false;
    bool planned_back = false;
    bool entry_by_reach = false;  // x_entry_back is the reach from x_exit_back (below x_max)
    // The profile's shape, when the passes already know it: speeding up or
    // slowing down over the whole segment (else it is fitted).
    enum class Shape : std::uint8_t { Fit, SpeedUp, SlowDown } shape = Shape::Fit;
    SegmentLimits lim;  // tangential acceleration as a function of speed
  };

  bool fill();  // pull until the window is deep enough; false when nothing is left
  void plan_and_release();
  // How far a stop from segment k's top speed reaches back (0 on a machine
  // with no axes): at the weakest axis' acceleration — or, on a curve piece,
  // at its own deceleration at half its top speed when that is less (a
  // joint curve near the pole slows far below any axis' limit; a window
  // too short for its stops would have each release plan one it need not).
  [[nodiscard]] double braking_length(std::size_t k) noexcept {
    const Node& n = node(k);
    double a = a_brake_;
    if (segment(k).geo.is_curve()) a = std::min(a, n.lim.at(0.5 * std::sqrt(n.x_max)).decel);
    return a > 0.0 ? n.x_max / (2.0 * a) : 0.0;
  }
  // The junction's limit from the geometry and the axes (∞ when none), to be
  // taken with the two segments' top speeds.
  [[nodiscard]] double junction_limit(const PlannedSegment& a, const PlannedSegment& b);
  void set_speed(std::size_t k, double k_plan);  // segment k's top speed at override k_plan

  const MachineConfig& machine_;
  IndexedSource source_;
  // The window, oldest first, as two rings of the same capacity (a power of
  // two, doubled when full): the passes' nodes and the segments, window
  // position k at slot (head_ + k) & mask_. [0, released_) are planned and
  // handed out in order (handed_ of them so far); then the head moves past
  // them: nothing is moved, and nothing allocated once the rings have grown.
  std::vector<Node> nodes_;
  std::vector<PlannedSegment> segments_;
  std::size_t head_ = 0, size_ = 0, mask_ = 0;
  std::size_t released_ = 0, handed_ = 0;
  [[nodiscard]] Node& node(std::size_t k) noexcept { return nodes_[(head_ + k) & mask_]; }
  [[nodiscard]] PlannedSegment& segment(std::size_t k) noexcept { return segments_[(head_ + k) & mask_]; }
  void grow();  // doubles the rings' capacity, the window kept in order
  // The unit tangent (dp/ds) where the window's last segment ends, when already known:
  // a line's is its start tangent, found for the junction before it.
  std::optional<Pose> back_end_tangent_;
  double tail_length_ = 0.0;  // length of the window behind its front segment
  // Braking length from the highest top speed in the window: what a stop
  // assumed at its end may reach back over.
  double braking_length_ = 0.0;
  double a_brake_ = 0.0;          // the weakest axis's acceleration (planned units)
  double x_start_ = 0.0;          // speed² the last released segment ends at
  double x_released_from_ = 0.0;  // speed² the released segments start at
  double feed_scale_ = 1.0;
  bool source_done_ = false;
  bool source_error_ = false;
  std::size_t max_window_ = 0;
};

}  // namespace lcnc

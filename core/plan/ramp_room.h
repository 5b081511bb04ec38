// Each position-buffer entry's room for a feed-override ramp (RampRoom in
// plan/period_increment.h), from the planned poses.
//
// The RT executes the plan with every period scaled to T/K (K ≤ 1): an axis
// then moves at K·v and accelerates at K²·a + v·dK/dt (rt/feed_override.h),
// with v and a the plan's. The plan uses the axes' full accelerations, so
// the RT may change K only as fast as the room each entry leaves:
//
//     K²·|a_i| + |dK/dt|·|v_i| ≤ amax_i      on an axis where the ramp adds
//                                            to the plan's acceleration,
//     |dK/dt|·|v_i| ≤ amax_i                 on one where it takes away.
//
// A falling K adds on an axis that brakes (a·v < 0), a rising K on one that
// speeds up (a·v > 0). Per axis the room is linear in u = K²,
//
//     room_i(u) = r_i·(1 − u·f_i),   r_i = amax_i/|v_i|,
//                                    f_i = |a_i|/amax_i on an axis that adds, else 0,
//
// and the room of the entry, min_i room_i, is concave in u: it lies above
// its chord between u = 0 and u = 1. The entry carries that chord,
//
//     |dK/dt| ≤ r0·(1 − K²·f),   r0 = min_i r_i,   f = 1 − min_i r_i·(1 − f_i) / r0,
//
// f = down for a falling K and up for a rising one: exact at K = 0 and
// K = 1, safe between. (r0 from one axis and f from another would be safe
// too, but a circle at its centripetal limit — one axis at full
// acceleration and nearly at rest, the other fast and unaccelerated — would
// then leave a hold no room at all.) Entry k's v is the larger of the
// planned velocities of periods k−1 and k (the RT sets the K
// of period k from entry k, and the step in speed into it carries period
// k−1's velocity), its a the second difference of the planned poses
// (p_k − 2·p_{k−1} + p_{k−2})/T², the change of speed into it. Exact poses,
// not steps: one step of rounding would read as a huge acceleration.
#pragma once

#include <array>

#include "geom/pose.h"
#include "machine/machine_config.h"
#include "plan/period_increment.h"

namespace lcnc {

class RampRoomMeter {
 public:
  RampRoomMeter(const MachineConfig& machine, const Pose& start);
  // The room of the entry that moves the machine to `pose` (the next
  // sample's), the planned poses before it taken into account.
  [[nodiscard]] RampRoom next(const Pose& pose) noexcept;

 private:
  std::array<double, kAxisCount> amax_{};
  std::array<bool, kAxisCount> present_{};
  double inv_period_ = 0.0;
  Pose p1_, p2_;  // the last two poses (p_{k−1}, p_{k−2})
};

}  // namespace lcnc

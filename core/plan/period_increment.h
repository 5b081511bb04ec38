// One entry of the position buffer (docs/design.md §5.3): what the RT thread executes
// in one period. Integer micro-steps per axis (signed: sign = direction),
// the laser power for the period and where it came from. Trivially copyable,
// fixed size: it lives in the lock-free ring and, later, in shared memory.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "geom/pose.h"
#include "path/segment.h"

namespace lcnc {

// How fast the RT may change the period scale K (≤ 1) while it executes an
// entry without an axis leaving its acceleration limit (rt/feed_override.h):
// |dK/dt| ≤ r0·max(0, 1 − K²·f), f = down while K falls, up while it rises.
// The planner sets it from the entry's planned axis speeds and
// accelerations (plan/ramp_room.h); an entry built by hand leaves the
// defaults, which put no bound but the ramp's own rate.
struct RampRoom {
  float r0 = std::numeric_limits<float>::infinity();  // 1/s
  float down = 0.0f;                                  // share of amax, 0 … 1
  float up = 0.0f;                                    // share of amax, 0 … 1
};

// What a period's entry carries besides its steps: the laser, the outputs,
// where in the program it is and what the RT does at it. The coarse
// interpolator's samples carry the same, and hand it on whole
// (StepQuantizer::emit).
struct EntrySignals {
  float power_pct = 0.0f;  // laser output for this period (at K = 1)
  // M4 (dynamic power): the programmed power S. The RT kernel scales the
  // output by the feed override K — power follows the actual speed — up to
  // this cap. 0 for M3 and laser off: their power does not follow speed.
  float power_cap_pct = 0.0f;
  // The feed override this entry was planned at (feed moves scaled by it
  // within the axes' limits; rapids and dwells 1). The RT runs it at
  // K = min(1, override / k_plan): faster than planned it never goes.
  float k_plan = 1.0f;
  std::uint32_t line = 0;                // source line executing
  std::uint32_t segment = 0;             // segment index executing (0-based)
  MotionKind kind = MotionKind::Linear;  // Dwell entries run at the nominal period whatever the override
  bool end_of_program = false;           // the last entry of the job
  // M0/M1/M60: after this entry (at rest, a dwell's) the RT holds the job
  // until the operator resumes it.
  bool pause = false;
  // The outputs while this entry runs: digital P0 … P7 (bits 0 … 7), assist
  // gas (kOutputMist, kOutputFlood), analog E0 … E3. The RT sets them only
  // while on the path; off otherwise.
  std::uint16_t outputs = 0;
  std::array<float, kAnalogOutputs> analog{};
  // M48 … M53 (Segment::feed_control): kFeedOverrideOff — the RT runs the
  // entry at K = 1 whatever the operator's override; kAdaptiveFeed — the
  // machine's adaptive-feed input (0 … 1) scales the override;
  // kFeedHoldInputOff — the machine's feed-hold input does not hold it.
  std::uint8_t feed_control = 0;
  // M66: after this entry (at rest, a dwell's) the RT holds the job until
  // the input does as asked (Segment::wait_*), or stops it at the timeout.
  std::int8_t wait_input = -1;
  std::uint8_t wait_mode = 0;
  float wait_timeout_s = 0.0f;
};

struct PeriodIncrement : EntrySignals {
  std::array<std::int32_t, kAxisCount> steps{};  // increment this period, per axis
  RampRoom ramp;
};
static_assert(std::is_trivially_copyable_v<PeriodIncrement>);

}  // namespace lcnc

// A motion segment: what the G-code front end hands to the planner. All in
// machine coordinates (work offsets and units already applied): mm and deg.
#pragma once

#include <array>
#include <cstdint>

#include "geom/pose.h"

namespace lcnc {

enum class MotionKind : std::uint8_t {
  Rapid,   // G0: each axis at its max velocity, path still a straight line
  Linear,  // G1
  Arc,     // G2/G3 (helix when the normal axis moves)
  Dwell,   // G4: stand still dwell_s seconds
};

// Plane of an arc, named by (first, second, normal) axis as RS274NGC does:
// G17 (X, Y, Z), G18 (Z, X, Y), G19 (Y, Z, X). Free: any plane through the
// centre with unit normal Segment::normal (the planner's corner blends).
enum class Plane : std::uint8_t { XY, ZX, YZ, Free };

enum class PathMode : std::uint8_t {
  ExactPath,  // G61: stop exactly at each programmed point
  ExactStop,  // G61.1
  Blend,      // G64 [P tol] [Q naive-cam tol]
};

// The laser is always off on rapids and at the end. On a dwell, M3 fires at
// constant power (percussion drilling) and M4 gives 0 (speed 0).
// The machine's general-purpose outputs a program sets (M62–M65 digital
// P0 … P7, M67/M68 analog E0 … E3), and where the assist gas (M7, M8)
// appears in the output word the RT hands its sink (bits above the digital
// outputs').
inline constexpr int kDigitalOutputs = 8;
inline constexpr int kAnalogOutputs = 4;
inline constexpr int kDigitalInputs = 8;  // M66 P0 … P7
inline constexpr std::uint16_t kOutputMist = 1u << kDigitalOutputs;
inline constexpr std::uint16_t kOutputFlood = 1u << (kDigitalOutputs + 1);

// How the operator's feed override and the machine's feed inputs act on a
// segment (Segment::feed_control, bits; M48–M53 set them). 0: the override
// acts, no adaptive feed, the feed-hold input stops the motion — the
// defaults.
inline constexpr std::uint8_t kFeedOverrideOff = 1u;   // M50 P0, M49: runs at 100 % whatever the override
inline constexpr std::uint8_t kAdaptiveFeed = 2u;      // M52 P1: the adaptive-feed input (0 … 1) scales it
inline constexpr std::uint8_t kFeedHoldInputOff = 4u;  // M53 P0: the feed-hold input does not stop it

enum class LaserMode : std::uint8_t {
  Off,       // M5
  Constant,  // M3: power = S
  Dynamic,   // M4: power = S · actual speed / programmed speed
};

struct Segment {
  MotionKind kind = MotionKind::Linear;
  Pose start = Pose::Zero();
  Pose end = Pose::Zero();

  // Arcs only. The arc lies in `plane`; centre is in machine coordinates of
  // the three linear axes; clockwise as seen looking from the positive end of
  // the normal axis toward the origin (RS274NGC); extra_turns full turns are
  // added (G2/G3 P n: extra_turns = n − 1). The normal axis and the rotary
  // axes move linearly with the arc angle (helix).
  Plane plane = Plane::XY;
  Vec3 center = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // Plane::Free only: counter-clockwise about it (a helix travels along it)
  bool clockwise = false;
  std::uint32_t extra_turns = 0;

  // Lines and rapids only: a piece of a smooth curve instead of a straight
  // line (tool-centre-point control: the joints' path of a move). It runs
  // from start to end as the cubic Hermite curve of σ ∈ [0, 1] whose
  // derivatives dp/dσ at the ends are curve_d_start and curve_d_end, σ =
  // s / curve_length: the path length is the curve's parameter scaled, not
  // its arc length (see SegmentGeometry). smooth_in: the segment before it
  // ends with the same dp/ds (a piece of the same curve): the join is no
  // corner.
  bool curve = false;
  bool smooth_in = false;
  double curve_length = 0.0;
  Pose curve_d_start = Pose::Zero();
  Pose curve_d_end = Pose::Zero();

  double feed_mm_s = 0.0;   // programmed path speed (mm/s, or deg/s for a pure rotary move); 0 on rapids
  double duration_s = 0.0;  // G93 inverse-time: the move takes this long; 0 otherwise
  double dwell_s = 0.0;     // Dwell only

  PathMode path_mode = PathMode::ExactPath;
  double blend_tolerance_mm = 0.0;      // G64 P (0 = as fast as possible within the machine default)
  double naive_cam_tolerance_mm = 0.0;  // G64 Q

  LaserMode laser = LaserMode::Off;
  double power_pct = 0.0;  // programmed laser power, % of rated (from S / s_max)
  bool mist = false;       // M7 (assist gas, low pressure)
  bool flood = false;      // M8 (assist gas, high pressure)
  // The digital outputs (bit n: P n) and analog outputs (E n) while this
  // segment runs: set from its first period on.
  std::uint8_t digital_out = 0;
  std::array<float, kAnalogOutputs> analog_out{};
  std::uint8_t feed_control = 0;  // kFeedOverrideOff | kAdaptiveFeed | kFeedHoldInputOff

  std::uint32_t line = 0;  // source line (1-based)
  // M0/M1/M60 (a Dwell of two periods, the beam off): once it has run the
  // machine waits, at rest, for the operator's resume.
  bool pause = false;
  // M66 (a Dwell of two periods, the beam off): once it has run the machine
  // waits, at rest, for digital input wait_input (0 … kDigitalInputs − 1)
  // — wait_mode 1 a rise, 2 a fall, 3 high, 4 low — for at most
  // wait_timeout_s; then the job stops with a fault. −1: no wait.
  std::int8_t wait_input = -1;
  std::uint8_t wait_mode = 0;
  float wait_timeout_s = 0.0f;
};

}  // namespace lcnc

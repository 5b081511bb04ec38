// Step 2 of reading a line: the interpreter. Runs one parsed Block against
// the modal state and turns it into at most two Segments (a G4 dwell and a
// move), in machine coordinates: mm and degrees, work offset applied.
//
// Order within a block (RS274NGC, LinuxCNC execute_block): feed mode
// (G93/G94), F, S, M3/M4/M5, M7/M8/M9, G4 dwell, plane, units, coordinate
// system and distance modes, path control (these four are independent),
// motion, stop (M2/M30). A dwell thus carries the modes from before its
// block's G17-G64 codes, the move those after them.
//
// Every segment carries the modal laser mode and power, assist gas, path
// mode and tolerances, and its source line — except that rapids and dwells
// always carry LaserMode::Off (path/segment.h), keeping the programmed power.
// A move that does not change the position is checked but produces nothing.
//
// Coordinates: machine = program + work offset (G54..G59) for G90; machine =
// current + increment for G91. Lengths are × 25.4 in G20 (X Y Z I J K R, F,
// G64 P Q); A B C stay degrees. All words of a block — F too — are read in the
// units in effect after that block's G20/G21. A feed, once set, keeps its
// physical speed when the units change later.
//
// Feed (G94): feed_mm_s = F/60 in mm/min, or in deg/min for a move with no
// X Y Z motion but rotary motion. Inverse time (G93): F on every G1/G2/G3
// block, duration_s = 60/F, feed_mm_s = length / duration_s. Switching
// between G93 and G94 forgets the F in effect (its meaning changed); in G93 an
// F on a block without a feed move is ignored, as LinuxCNC does.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "gcode/block_parser.h"
#include "machine/machine_config.h"
#include "path/segment.h"

namespace lcnc::gcode {

// What one block produced: at most a dwell and a move.
class SegmentBuffer {
 public:
  [[nodiscard]] bool empty() const noexcept { return next_ == count_; }
  void clear() noexcept { count_ = next_ = 0; }
  Segment& push() noexcept { return items_[count_++]; }
  [[nodiscard]] const Segment& pop() noexcept { return items_[next_++]; }

 private:
  std::array<Segment, 2> items_{};
  int count_ = 0;
  int next_ = 0;
};

enum class MotionMode : std::uint8_t { None, Rapid, Linear, ArcCw, ArcCcw };

class Interpreter {
 public:
  Interpreter(const MachineConfig& machine, const Pose& start);

  // Runs a block; its segments are pushed to `out`. false on error (fault()),
  // and then the state is undefined: reading stops.
  [[nodiscard]] bool execute(const Block& block, const LineText& text, std::uint32_t line,
                             SegmentBuffer& out);

  [[nodiscard]] bool ended() const noexcept { return ended_; }  // M2 or M30 ran
  [[nodiscard]] const Fault& fault() const noexcept { return fault_; }
  [[nodiscard]] const Pose& position() const noexcept { return pos_; }

 private:
  bool resolve_motion();
  bool check_word_use();
  bool set_feed_and_power();
  bool dwell(SegmentBuffer& out);
  void set_modes();
  bool set_path_control();
  bool move(SegmentBuffer& out);
  bool arc(const Pose& end_in, SegmentBuffer& out);
  bool check_feed();
  bool check_duration(double linear_mm, double rotary_deg);
  bool fail_duration(double linear_mm, double rotary_deg);
  bool check_magnitude(const Pose& end);
  bool check_travel(const Pose& lo, const Pose& hi, const Pose& end);
  void fill_modal(Segment& s) const;
  void set_segment_feed(Segment& s, double linear_mm, double rotary_deg) const;

  bool fail(ErrorCode code, Span at, std::string message);
  bool fail_at(ErrorCode code, std::uint32_t byte_pos, std::string message);
  [[nodiscard]] std::string quoted(Span s) const;
  [[nodiscard]] std::string quoted_block() const;
  [[nodiscard]] double length_scale() const noexcept;  // mm per program length unit
  [[nodiscard]] const char* feed_unit() const noexcept;
  [[nodiscard]] std::string tolerance_unit() const;

  const MachineConfig& machine_;
  Pose pos_;  // machine coordinates
  // bit index(Axis) for each axis check_travel does not bound: continuous
  // rotary axes, and X Y Z under tool-centre-point control
  std::uint8_t untraveled_axes_ = 0;
  std::uint8_t wrapping_axes_ = 0;    // continuous rotary axes: G90 takes the shorter turn

  // Modal state (initially G17 G21 G90 G91.1 G94 G54 G61 M5 M9, F unset, S0).
  MotionMode motion_ = MotionMode::None;
  Plane plane_ = Plane::XY;
  bool inch_ = false;
  bool absolute_ = true;
  bool arc_absolute_ = false;
  bool inverse_time_ = false;
  int work_offset_ = 0;  // 0 = G54 .. 5 = G59
  PathMode path_mode_ = PathMode::ExactPath;
  double blend_tolerance_mm_ = 0.0;
  double naive_cam_tolerance_mm_ = 0.0;
  bool feed_set_ = false;
  double feed_mm_min_ = 0.0;  // F converted to mm/min when it was read
  double feed_raw_ = 0.0;     // F as written: deg/min for pure rotary moves
  LaserMode laser_ = LaserMode::Off;
  double power_pct_ = 0.0;
  bool mist_ = false;
  bool flood_ = false;
  bool ended_ = false;

  // The block being run.
  const Block* b_ = nullptr;
  const LineText* t_ = nullptr;
  std::uint32_t line_ = 0;
  MotionMode block_motion_ = MotionMode::None;
  Span motion_word_{};       // the G0..G3 word, or the first axis word
  bool block_has_f_ = false;  // G93: this block's F
  double block_f_ = 0.0;

  Fault fault_;
};

}  // namespace lcnc::gcode

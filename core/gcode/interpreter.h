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
// Coordinates (LinuxCNC's): machine = program + work offset (G54 … G59.3,
// set by G10 L2/L20) + axis offset (G92, G52) + tool offset (G43) for G90;
// machine = current + increment for G91; G53 names machine coordinates for
// its block. The offsets live in the numbered parameters (#5211 …,
// #5221 …: gcode/parameter_file.h), where programs read them and the
// parameter file keeps them; G28/G30 go to the positions #5161/#5181 hold.
// Tools: T selects one of the machine's tool table, M6 or M61 puts it in the
// spindle, G43 applies its offset; a tool not in the table is an error at
// its T, H, P or Q word. Lengths are × 25.4 in G20 (X Y Z I J K R, F,
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
#include <string_view>
#include <vector>

#include "gcode/block_parser.h"
#include "gcode/comp_gouge.h"
#include "gcode/gcode_tolerances.h"
#include "gcode/parameter_file.h"
#include "machine/machine_config.h"
#include "path/segment.h"

namespace lcnc::gcode {

// What one block produced: a dwell and a move, or a canned cycle's moves
// (at most kMaxBlockSegments). Storage is kept from block to block.
class SegmentBuffer {
 public:
  [[nodiscard]] bool empty() const noexcept { return next_ == count_; }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  void clear() noexcept { count_ = next_ = 0; }
  // A slot to fill (fill_modal resets it): reused, grown only past the
  // most a block has needed so far.
  Segment& push() {
    if (count_ == items_.size()) items_.emplace_back();
    return items_[count_++];
  }
  [[nodiscard]] const Segment& pop() noexcept { return items_[next_++]; }

 private:
  std::vector<Segment> items_;
  std::size_t count_ = 0;
  std::size_t next_ = 0;
};

// Motion modes: G0 G1 G2 G3 and the canned cycles G73 G81 G82 G83 G85 G89.
// Words that only some codes use (check_word_use): P Q H L I J K R D E.
inline constexpr std::uint32_t kDataLetters = [] {
  std::uint32_t m = 0;
  for (const char c : {'P', 'Q', 'H', 'L', 'I', 'J', 'K', 'R', 'D', 'E'}) m |= 1u << letter_index(c);
  return m;
}();

enum class MotionMode : std::uint8_t {
  None,
  Rapid,
  Linear,
  ArcCw,
  ArcCcw,
  Cycle73,
  Cycle81,
  Cycle82,
  Cycle83,
  Cycle85,
  Cycle86,
  Cycle89
};
[[nodiscard]] constexpr bool is_cycle(MotionMode m) noexcept { return m >= MotionMode::Cycle73; }

// Numbers for messages: num() up to 4 decimals, trailing zeros dropped;
// gnum() 6 significant digits (a bound, or a value of any size).
[[nodiscard]] std::string num(double v);
[[nodiscard]] std::string gnum(double v);

class Interpreter {
 public:
  // `numbered`: the program's parameters, indexed by number (#0 unused),
  // kept by the caller; the offsets are read from them by load_offsets().
  Interpreter(const MachineConfig& machine, const Pose& start, std::vector<double>& numbered);

  // Takes the coordinate system, the G92 offset (#5210 … #5220) and the
  // tool table (`tools`: the machine's, with the parameter file's changes,
  // whose numbers are `changed`) as a job starts.
  void load_offsets(std::vector<ToolConfig> tools, std::vector<int> changed);
  // The tools set by G10 L1/L10/L11, now or in an earlier job (from the
  // parameter file): what the parameter file keeps.
  [[nodiscard]] std::vector<ToolConfig> changed_tools() const;
  // A predefined named parameter (#<_x>, #<_current_tool>, …): false when
  // `name` (lower-cased, with its '_') is none of them.
  [[nodiscard]] bool predefined(std::string_view name, double& out) const;
  // #5420 + axis: the position in program coordinates and units (read when
  // a program asks, not written every block).
  [[nodiscard]] double position_param(int axis) const;

  // Runs a block; its segments are pushed to `out`. false on error (fault()),
  // and then the state is undefined: reading stops. Under cutter
  // compensation a move is held until the next shows where it ends: its
  // segments come out with a later block's, or from finish().
  [[nodiscard]] bool execute(const Block& block, const LineText& text, std::uint32_t line,
                             SegmentBuffer& out);
  // The program's end (the file's, or '%'): the moves compensation still
  // holds, as they stand, to `out`. false on error (fault()).
  [[nodiscard]] bool finish(SegmentBuffer& out);
  // A subroutine call begins / returns (the reader says): the modal state
  // M70/M73 save is kept per call level, and an M73's comes back on return.
  void enter_call();
  void leave_call();

  [[nodiscard]] bool ended() const noexcept { return ended_; }  // M2 or M30 ran
  [[nodiscard]] const Fault& fault() const noexcept { return fault_; }
  [[nodiscard]] const Pose& position() const noexcept { return pos_; }
  // machine = program + offsets(): the work system's origin, the G92 offset
  // and the tool offset in effect (mm, deg).
  [[nodiscard]] const Pose& offsets() const noexcept { return offsets_; }
  [[nodiscard]] int coord_system() const noexcept { return modal_.coord_system; }  // 0 = G54
  [[nodiscard]] bool inch() const noexcept { return modal_.inch; }
  // The modes a later reading starts in to go on where this one stands
  // (MDI: one command after the other), as one block: plane, units,
  // distance and arc-distance modes, feed mode, work system, path mode,
  // F, S and G0/G1. Not the beam (off between commands), tool, cutter
  // compensation, arcs or canned cycles: a command needs its own.
  [[nodiscard]] std::string modes_block() const;

 private:
  bool resolve_motion();
  void set_motion_mode(MotionMode m);
  bool check_word_use();
  bool set_feed_and_power();
  bool dwell(SegmentBuffer& out);
  void set_modes();
  bool set_path_control();
  // Tools (tool_offsets.cpp): T, M6, M61; G43 G43.1 G43.2 G49; G10 L1/L10.
  bool change_tool();
  bool set_tool_length();
  bool set_tool_data();
  [[nodiscard]] const ToolConfig* find_tool(int number) const;
  bool tool_number(char letter, int& out);
  // Coordinate systems (coordinate_systems.cpp): G54 … G59.3, G10 L2/L20,
  // G92 G92.1 G92.2 G92.3 G52, G28 G28.1 G30 G30.1.
  void select_coord_system(int index);
  bool run_non_modal(SegmentBuffer& out);
  bool set_coord_system_data();
  bool set_axis_offsets();
  bool go_home(int first_param, SegmentBuffer& out);
  // offsets_ = their sum, after whatever changes one of them.
  void update_offsets() { offsets_ = origin_ + axis_offset_ + modal_.tool_offset; }
  // A block's axis word in mm / deg.
  [[nodiscard]] double axis_value(int axis) const {
    return (*b_)[kAxisLetters[axis]] * (axis < 3 ? length_scale() : 1.0);
  }
  // A straight move from where the machine is: G0, or G1 at the feed in effect.
  bool rapid_to(const Pose& end, SegmentBuffer& out);
  bool line_to(const Pose& end, SegmentBuffer& out);
  bool pause(SegmentBuffer& out);
  Segment& hold_segment(SegmentBuffer& out);
  // A polar block's X Y (@ ^ about the program's origin; G91: added to the
  // radius and angle of `from`), written into `to` in machine coordinates.
  bool polar_target(const Pose& from, Pose& to);
  // Canned cycles (canned_cycles.cpp).
  bool canned_cycle(SegmentBuffer& out);
  bool cycle_words(double& r, double& z, double& p, double& q);
  void dwell_for(double seconds, SegmentBuffer& out);
  bool move(SegmentBuffer& out);
  bool arc(const Pose& end_in, SegmentBuffer& out);
  // The block's arc from `from` to `end` (R or I J K words, checked): its
  // centre `c` (normal coordinate: `from`'s) and extra turns; `end` made
  // exact for a full circle.
  bool arc_centre(const Pose& from, Pose& end, Vec3& c, std::uint32_t& extra_turns);
  // An arc from where the machine is to `end` about `c`, checked (travel,
  // length, time).
  bool arc_to(const Pose& end, const Vec3& c, bool cw, std::uint32_t extra_turns, SegmentBuffer& out);
  // M62 … M65 digital and M67/M68 analog outputs; the synchronized ones
  // (M62 M63 M67) wait for the next move (take_synced_outputs).
  bool set_outputs();
  bool wait_input(SegmentBuffer& out);
  bool set_override_switches();  // M48 … M53
  void take_synced_outputs();
  // M70 M71 M72 M73 (LinuxCNC): save, forget, restore the modal state.
  bool run_context();
  // The modes M70 saves and M72 restores, as one value (modal_): saving is
  // a copy, restoring an assignment and the offsets made anew.
  struct ModalState {
    Plane plane = Plane::XY;
    bool inch = false;
    bool absolute = true;
    bool arc_absolute = false;
    bool inverse_time = false;
    int coord_system = 0;             // 0 = G54 … 8 = G59.3
    Pose tool_offset = Pose::Zero();  // G43
    bool tool_length_on = false;      // G43 / G43.1 / G43.2 in effect
    bool retract_old_z = false;       // G98 (true) / G99
    PathMode path_mode = PathMode::ExactPath;
    double blend_tolerance_mm = 0.0;
    double naive_cam_tolerance_mm = 0.0;
    bool feed_set = false;
    double feed_mm_min = 0.0;  // F converted to mm/min when it was read
    double feed_raw = 0.0;     // F as written: deg/min for pure rotary moves
    LaserMode laser = LaserMode::Off;
    double power_pct = 0.0;
    bool mist = false;
    bool flood = false;
    std::uint8_t feed_control = 0;  // M48 … M53: Segment::feed_control
    bool speed_override = true;     // M48 M49 M51: kept for #<_speed_override>
  };
  void restore_modal(const ModalState& m);
  // The offsets and #5401 … #5409 after the tool offset or the system changed.
  void apply_tool_offset();
  // Where a new segment goes: to `out`, or held by cutter compensation.
  Segment& push_segment(SegmentBuffer& out);
  // Cutter (kerf) compensation (cutter_comp.cpp): G40 G41 G42 G41.1 G42.1.
  // What the gouge check needs of a held move: whether it is the entry (it
  // leaves the programmed start) and the programmed points it belongs to
  // (comp_gouge.h PlanePiece::anchor).
  struct HeldTag {
    bool entry = false;
    Eigen::Vector2d anchor[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    int anchors = 0;
    static HeldTag entry_move() { return {true, {}, 0}; }
    static HeldTag at(const Eigen::Vector2d& p) { return {false, {p, Eigen::Vector2d::Zero()}, 1}; }
    static HeldTag between(const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return {false, {p, q}, 2}; }
  };
  bool check_comp_conflicts();
  bool set_cutter_comp(SegmentBuffer& out);
  [[nodiscard]] bool comp_active() const noexcept { return comp_side_ != 0 && comp_radius_mm_ > 0.0; }
  bool comp_straight(const Pose& end, SegmentBuffer& out);
  bool comp_arc(const Pose& end, SegmentBuffer& out);
  bool comp_round_corner(double mx, double my, const Pose& end, bool rapid, SegmentBuffer& out);
  bool comp_held_straight(const Pose& end, double dx, double dy, SegmentBuffer& out, const HeldTag& tag);
  bool comp_held_arc(const Pose& end, const Vec3& c, int turn, double turns, SegmentBuffer& out,
                     const HeldTag& tag);
  bool comp_move_endpoint_and_flush(double x, double y, SegmentBuffer& out);
  bool comp_dequeue(SegmentBuffer& out);
  void comp_set_endpoint(double x, double y) {
    comp_endpoint_[0] = x;
    comp_endpoint_[1] = y;
    comp_endpoint_valid_ = true;
  }
  bool comp_fail(std::string message);
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
  // mm per program length unit
  [[nodiscard]] double length_scale() const noexcept { return modal_.inch ? kMmPerInch : 1.0; }
  [[nodiscard]] const char* feed_unit() const noexcept;
  [[nodiscard]] std::string tolerance_unit() const;

  const MachineConfig& machine_;
  Pose pos_;  // machine coordinates
  // bit index(Axis) for each axis check_travel does not bound: continuous
  // rotary axes, and X Y Z under tool-centre-point control
  std::uint8_t untraveled_axes_ = 0;
  std::uint8_t wrapping_axes_ = 0;  // continuous rotary axes: G90 takes the shorter turn

  // Modal state (initially G17 G21 G90 G91.1 G94 G54 G61 M5 M9, F unset, S0).
  MotionMode motion_ = MotionMode::None;
  ModalState modal_;
  std::vector<double>& numbered_;
  Pose origin_ = Pose::Zero();       // the coordinate system's offset
  Pose axis_offset_ = Pose::Zero();  // G92 / G52
  Pose offsets_ = Pose::Zero();      // their sum: machine = program + offsets_
  std::vector<ToolConfig> tools_;
  std::vector<int> changed_tools_;  // numbers of the tools G10 set
  int selected_tool_ = 0;           // T
  int current_tool_ = 0;            // in the spindle: M6, M61
  // Canned cycles (G98/G99: modal_.retract_old_z): the sticky R, Z, P, Q of the cycle in effect (mm, s), valid while
  // its mode lasts (a new cycle mode needs R and Z again).
  bool cycle_sticky_ = false;
  bool cycle_series_ = false;     // cycle blocks in a row: cycle_initial_z_ is set
  double cycle_initial_z_ = 0.0;  // where Z stood before the first of them
  double cycle_r_ = 0.0, cycle_z_ = 0.0, cycle_p_ = 0.0, cycle_q_ = 0.0;
  std::uint8_t digital_out_ = 0;                             // M62 … M65
  std::array<float, kAnalogOutputs> analog_out_{};           // M67 M68
  std::uint8_t synced_on_ = 0, synced_off_ = 0;              // M62 / M63 for the next move
  std::uint8_t synced_analog_ = 0;                           // M67 for the next move: which E …
  std::array<float, kAnalogOutputs> synced_analog_value_{};  // … to what
  bool ended_ = false;

  // Cutter compensation: the side (+1 left G41, -1 right G42, 0 off) and
  // radius (mm, from the tool's diameter or G41.1/G42.1 D); the next move
  // is the entry move; the programmed point (machine coordinates; pos_ is
  // the compensated one); after G40 the next move starts from the
  // programmed point and must be straight. Held moves wait for the next to
  // fix their end (LinuxCNC's interp_queue: one end point for all of them).
  struct HeldMove {
    Segment s;
    double dx = 0.0, dy = 0.0;  // straights: the direction programmed
    double turns = 0.0;         // arcs: the sweep programmed (rad; 0 for corner arcs)
    HeldTag tag;
  };
  int comp_side_ = 0;
  double comp_radius_mm_ = 0.0;
  bool comp_first_move_ = true;
  bool comp_exited_ = false;
  Pose programmed_ = Pose::Zero();
  std::vector<HeldMove> held_;
  bool holding_ = false;  // comp's moves: every new segment is held
  double comp_endpoint_[2] = {0.0, 0.0};
  bool comp_endpoint_valid_ = false;
  int comp_a_ = 0, comp_b_ = 1;  // the plane's two axes (X Y in G17, Z X in G18)
  GougeWindow gouge_;            // the run's programmed and cut moves (comp_gouge.h)
  bool comp_check_programmed(const PlanePiece& p);
  bool comp_check_cut(const HeldMove& h);
  bool comp_gouge_fail(const GougeWindow::Gouge& g);

  // M70/M73 saves, one per call level ([0]: the program's).
  struct Context {
    bool valid = false;
    bool restore_on_return = false;  // M73
    ModalState state;
  };
  std::vector<Context> contexts_ = std::vector<Context>(1);

  // The block being run.
  const Block* b_ = nullptr;
  const LineText* t_ = nullptr;
  std::uint32_t line_ = 0;
  MotionMode block_motion_ = MotionMode::None;
  Span motion_word_{};        // the G0..G3 word, or the first axis word
  bool block_has_f_ = false;  // G93: this block's F
  double block_f_ = 0.0;

  Fault fault_;
};

}  // namespace lcnc::gcode

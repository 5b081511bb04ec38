// The gouge check of cutter compensation: the tool (the beam, kerf/2 in
// radius) must never come nearer to the programmed path than its radius —
// nearer, it cuts into the part. A corner check between neighbouring moves
// cannot see it when the moves are split (a notch's end drawn as two
// collinear moves) or when the walls that come too close are moves apart (a
// slot whose mouth is narrower than the tool). So every compensated move
// the beam cuts is measured against every programmed move of the
// compensation run within a window of the latest kGougeWindow, and each
// new programmed move against the compensated moves already cut — all but
// the programmed moves that meet a compensated move's own at a corner: the
// corner rules (LinuxCNC's) decide those, and a straight move cut short
// into one is checked for running backwards instead.
//
// Distances are exact between lines, and between a line and an arc; arc to
// arc, the compensated arc is taken as chords within a quarter of the
// tolerance of it.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lcnc::gcode {

// How many of the latest programmed moves and compensated moves are kept
// to measure against each other.
inline constexpr std::size_t kGougeWindow = 256;

// A move in the compensation plane: a line a → b, or an arc from a about c
// by `sweep` rad (counter-clockwise positive; beyond ±2π for full turns).
struct PlanePiece {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  bool arc = false;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double radius = 0.0, start = 0.0, sweep = 0.0;
  std::uint32_t line = 0;   // the program line the move comes from
  Eigen::AlignedBox2d box;  // contains the piece
  // A compensated move: the programmed points it belongs to (its programmed
  // move's ends; a corner arc's corner). Programmed moves that end at one of
  // them meet it at a corner, which the corner rules judge, not this check.
  Eigen::Vector2d anchor[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  int anchors = 0;
  [[nodiscard]] bool meets(const PlanePiece& programmed) const {
    for (int i = 0; i < anchors; ++i)
      if (programmed.a == anchor[i] || programmed.b == anchor[i]) return true;
    return false;
  }

  static PlanePiece straight(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::uint32_t line);
  static PlanePiece circular(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                             double sweep, std::uint32_t line);
};

// The least distance between two pieces (chord_tol: how far chords of an arc
// may stand inside it when both are arcs).
[[nodiscard]] double piece_distance(const PlanePiece& p, const PlanePiece& q, double chord_tol);

// The programmed and compensated moves of one compensation run.
class GougeWindow {
 public:
  void clear() {
    programmed_.clear();
    cut_.clear();
  }
  // A nearer pair than `min_distance`: the two pieces and their distance.
  struct Gouge {
    PlanePiece cut, programmed;
    double distance = 0.0;
  };
  [[nodiscard]] std::optional<Gouge> add_programmed(const PlanePiece& p, double min_distance,
                                                    double chord_tol) {
    return add(p, false, min_distance, chord_tol);
  }
  [[nodiscard]] std::optional<Gouge> add_cut(const PlanePiece& p, double min_distance, double chord_tol) {
    return add(p, true, min_distance, chord_tol);
  }

 private:
  std::optional<Gouge> add(const PlanePiece& p, bool cut, double min_distance, double chord_tol);
  std::deque<PlanePiece> programmed_, cut_;
};

}  // namespace lcnc::gcode

// The 3D-measurement workflow (six-point positioning, docs/design.md §7, Shao (2022)
// §4): the workpiece is located on the machine by probing its three datum
// faces — 3 points on the primary (the top, z = 0 of the drawing), 2 on the
// secondary (the front, y = 0), 1 on the tertiary (the left, x = 0) — and
// solving the 3-2-1 frame (core/measure/workpiece_frame.h). The points are
// planned on the drawing's block at the operator's nominal placement; the
// machine takes each through lasercncd — up to a clearance plane, over, down
// to the stand-off with the tool axis along the face's outward normal (A =
// ±90° for a side face) — and the probe, on the head, measures along the
// axis into the face. The result is the work → machine transform with its
// residuals; the screen applies it to the holes after the operator
// confirms (ProcessDatabase::set_positions, all or none). Qt-free.
#pragma once

#include <chrono>

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/result.h"
#include "drivers/serial/probe_client.h"
#include "geom/pose.h"
#include "hmi/machine_mover.h"
#include "hmi/process_db.h"
#include "measure/workpiece_frame.h"

namespace lcnc::hmi {

// A point probe: the surface point it finds from where it stands (machine).
class PointProbe {
 public:
  virtual ~PointProbe() = default;
  [[nodiscard]] virtual Result<Vec3> measure() = 0;
};

// The 3D probe over its RS-232 line protocol (drivers/serial/probe_client.h).
class SerialPointProbe final : public PointProbe {
 public:
  // A probe answers within its latency; a loaded PC may take its time to
  // read the answer: by default the workflow waits a second for each of four
  // attempts. `answer_timeout` bounds a failure only: an answer is taken the
  // moment it comes.
  static constexpr std::chrono::milliseconds kAnswerTimeout{1000};
  static Result<std::unique_ptr<SerialPointProbe>> open(
      const std::string& device, std::chrono::milliseconds answer_timeout = kAnswerTimeout);
  [[nodiscard]] Result<Vec3> measure() override;

 private:
  explicit SerialPointProbe(std::unique_ptr<drivers::ProbeClient> c) : client_(std::move(c)) {}
  std::unique_ptr<drivers::ProbeClient> client_;
};

struct MeasurePlan {
  Vec3 block_mm = Vec3(200.0, 100.0, 40.0);  // the drawing's block: L, W, H
  // Where the operator believes the block's datum corner is and how it is
  // turned (a few mm and degrees off is what the probing is for).
  Eigen::Isometry3d nominal = Eigen::Isometry3d::Identity();
  double standoff_mm = 5.0;    // from the face, along its normal (within the probe's reach)
  double clearance_mm = 20.0;  // above the block's top for the moves between points
  // Four more points (one on the top, one on the front, two on the left, at
  // other heights) and the best fit on faces over all ten
  // (workpiece_frame.h fit_faces) instead of the 3-2-1 alone.
  bool best_fit = false;
};

struct ProbePoint {
  std::string face;                  // "primary 1" …
  Vec3 planned_work = Vec3::Zero();  // on the face, drawing frame
  Vec3 normal_work = Vec3::UnitZ();  // the face's outward normal, drawing frame
  Pose approach = Pose::Zero();      // where the machine stands to probe it
  std::optional<Vec3> measured;      // machine frame
  std::optional<double> residual_mm;
  std::string error;
};

// The six points and their approach poses (3 primary, 2 secondary, 1
// tertiary; with best_fit four more), or an error when a face cannot be
// reached by the tool axis.
[[nodiscard]] Result<std::vector<ProbePoint>> plan_321(const MeasurePlan& plan);

struct MeasureOutcome {
  std::vector<ProbePoint> points;
  std::optional<FrameFit> fit;  // when all six were measured
  std::string error;            // why not
};

// Probes the planned points in turn (progress(done, total) after each,
// cancel checked between), then fits: 3-2-1, and with best_fit the fit on
// faces over every point from it. Any point not measured ends the run.
[[nodiscard]] MeasureOutcome run_measurement(const MeasurePlan& plan, MachineMover& mover, PointProbe& probe,
                                             const std::function<void(int, int)>& progress = {},
                                             const std::atomic<bool>* cancel = nullptr);

// The holes moved by the fit (their stored X Y Z A C read as drawing
// coordinates), for ProcessDatabase::set_positions; an error names the hole.
[[nodiscard]] Result<std::vector<std::pair<std::uint32_t, Pose>>> placed_holes(
    const std::vector<HoleRecord>& holes, const Eigen::Isometry3d& work_to_machine);

}  // namespace lcnc::hmi

// Moves the machine for the HMI's workflows (focal length, 3D measurement)
// through lasercncd, over the shared-memory interface alone: a one-move
// program (G0 to the point) is written, loaded and started, and the move is
// over when the daemon says the job ended. Its own MachineLink, so a
// workflow on a worker thread never shares one with the screens. Qt-free.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>

#include "common/result.h"
#include "geom/pose.h"
#include "hmi/machine_link.h"

namespace lcnc::hmi {

class MachineMover {
 public:
  // `dir`: where the move programs are written (created if needed).
  MachineMover(std::string shm_name, std::filesystem::path dir);

  // Moves at rapid to `target` (machine coordinates) and waits until the
  // machine is at rest there. Fails when the daemon refuses (the reason is
  // its answer: a point beyond the travel, the machine busy), the move ends
  // in a fault, the link is lost or the time is up; a timeout stops the
  // machine first.
  [[nodiscard]] Status move_to(const Pose& target,
                               std::chrono::milliseconds timeout = std::chrono::seconds(60));
  // Where the machine is (its DRO), or an error when not linked.
  [[nodiscard]] Result<Pose> position();

 private:
  [[nodiscard]] Result<shm::JobStatus> command(shm::CommandType type, const std::string& text,
                                               std::chrono::steady_clock::time_point deadline);
  [[nodiscard]] bool wait_link(std::chrono::steady_clock::time_point deadline);

  MachineLink link_;
  std::filesystem::path dir_;
  unsigned moves_ = 0;
};

}  // namespace lcnc::hmi

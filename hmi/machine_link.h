// The HMI's link to lasercncd, through the shared-memory interface alone
// (rt/shm_interface.h, docs/design.md §2): the kernel's status read under its
// seqlock, the daemon's answers, commands into the command ring. Qt-free.
// The link is lost when the daemon's heartbeat stops or its process is gone
// (a daemon killed with SIGKILL shows within kLostAfter), and is taken up
// again when a daemon publishes the segment anew.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "rt/shm_interface.h"

namespace lcnc::hmi {

class MachineLink {
 public:
  static constexpr std::chrono::milliseconds kLostAfter{500};
  // How long a read waits out a daemon preempted in the middle of a write.
  static constexpr std::chrono::milliseconds kReadPatience{100};

  explicit MachineLink(std::string shm_name = shm::kDefaultName);

  // Call periodically (the screens' timer): (re)connects, watches the
  // heartbeat. True while linked.
  bool poll();
  [[nodiscard]] bool linked() const noexcept { return client_.has_value() && alive_; }
  // The latest status and job status (empty while not linked).
  [[nodiscard]] std::optional<shm::Status> status() const;
  [[nodiscard]] std::optional<shm::JobStatus> job() const;
  // Sends a command; its sequence number, or 0 when not linked or the ring
  // is full.
  std::uint32_t send(shm::CommandType type, double value = 0.0, std::uint8_t axis = 0,
                     const std::string& text = {});
  // The daemon's answer to command `seq` (send()'s number), once written:
  // each command has its own, so concurrent senders never take another's.
  [[nodiscard]] std::optional<shm::Answer> answer(std::uint32_t seq) const;
  // The next of the kernel's events (faults, state changes, the daemon's
  // news), oldest first; false when there is none. The event ring has one
  // consumer: the machine screen's link (a workflow's link must not take
  // them).
  bool next_event(shm::Event& out);
  // Why not linked, for the operator.
  [[nodiscard]] const std::string& why() const noexcept { return why_; }

 private:
  std::string name_;
  std::optional<shm::ShmClient> client_;
  std::uint64_t last_beat_ = 0;
  std::chrono::steady_clock::time_point beat_seen_{};
  bool alive_ = false;
  std::string why_ = "not connected";
  std::chrono::steady_clock::time_point next_try_{};
};

}  // namespace lcnc::hmi

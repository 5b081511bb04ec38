// The second shared-memory segment of `lasercncd --hal`: what the daemon's
// control side and the kernel in the HAL component (drivers/hal/, loaded
// into LinuxCNC's rtapi_app) share — the kernel's port, the position
// buffer, the trace and the log. Named after the daemon's segment with
// ".hal" appended. The daemon creates it and writes the header; the
// component maps it, checks magic, version and size, builds its kernel on
// it and says so in `attached`.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <type_traits>

#include <string>

#include <sys/types.h>

#include "common/result.h"

#include "rt/kernel_port.h"
#include "rt/rt_kernel.h"
#include "rt/rt_log.h"

namespace lcnc::shm {

inline constexpr std::uint32_t kHalMagic = 0x4C48414C;  // "LHAL"
inline constexpr std::uint32_t kHalVersion =
    5;  // 2: outputs in PeriodIncrement, 3: feed_control, 4: its signals first (EntrySignals), 5: commands counted

struct HalHeader {
  std::uint32_t magic = 0;
  std::uint32_t version = 0;
  std::uint64_t size = 0;  // sizeof(HalBlock) of the writer
  pid_t owner_pid = 0;
  char machine_path[512] = {};  // the machine TOML the daemon runs (absolute)
  std::array<std::int64_t, kAxisCount> start_steps{};
  std::atomic<pid_t> attached{0};  // the component's process once its kernel runs
};

struct HalBlock {
  HalHeader header;
  rt::KernelPort port;
  rt::PositionBuffer buffer;
  rt::TraceRing trace;
  rt::RtLogRing log;
};

// "/lasercnc" → "/lasercnc.hal"
[[nodiscard]] inline std::string hal_segment_name(const std::string& main) { return main + ".hal"; }

// The daemon's side: creates the segment (one left by a daemon that died
// is replaced — the main segment's owner check has made sure none lives),
// builds the block in it and writes the header; unmaps and unlinks it on
// destruction.
class HalSegment {
 public:
  [[nodiscard]] static Result<HalSegment> create(const std::string& main_name,
                                                 const std::string& machine_path,
                                                 const std::array<std::int64_t, kAxisCount>& start_steps);
  HalSegment(HalSegment&&) noexcept;
  HalSegment& operator=(HalSegment&&) = delete;
  ~HalSegment();
  [[nodiscard]] HalBlock& block() noexcept { return *block_; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  // The component's process, once its kernel runs on this block and while
  // that process lives; 0 otherwise.
  [[nodiscard]] pid_t attached() const noexcept;

 private:
  HalSegment(std::string name, HalBlock* block) : name_(std::move(name)), block_(block) {}
  std::string name_;
  HalBlock* block_ = nullptr;
};

}  // namespace lcnc::shm

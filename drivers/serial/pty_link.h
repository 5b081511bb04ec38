// A null-modem cable made of two pseudo-terminals and a relay thread, with a
// fault injector: the RTU tests put the Modbus master on a_path() and the
// slave on b_path(), so every frame crosses real ttys with real libmodbus
// RTU framing and CRC, and the cable can corrupt a byte or be "pulled".
//
//   master ── a_path ═ pty A ═╗ relay (this) ╔═ pty B ═ b_path ── slave
//                             ╚──── A→B ─────╝  (requests)
//                             ╚──── B→A ─────╝  (responses)
//
// Faults: corrupt_next(dir, k) flips the low bit of the k-th byte (0-based)
// relayed in `dir` from now on — with k = 3 that is inside the PDU of the
// next frame, so the receiver's CRC check fails; set_connected(false) drops
// every byte both ways until set to true again (a pulled cable or a device
// switched off). The relay never blocks on a full side: bytes that do not fit
// are dropped, as on a real line without a listener.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "common/result.h"
#include "drivers/serial/serial_port.h"

namespace lcnc::drivers {

enum class LinkDirection : std::uint8_t { AtoB, BtoA };

class PtyLink {
 public:
  PtyLink() = default;
  ~PtyLink();
  PtyLink(const PtyLink&) = delete;
  PtyLink& operator=(const PtyLink&) = delete;

  [[nodiscard]] Status start();
  void stop() noexcept;  // prompt: wakes the relay through an eventfd

  [[nodiscard]] const std::string& a_path() const noexcept { return a_.path; }
  [[nodiscard]] const std::string& b_path() const noexcept { return b_.path; }

  void corrupt_next(LinkDirection dir, std::size_t byte_offset = 3);
  void set_connected(bool connected) noexcept;
  [[nodiscard]] std::uint64_t corruptions() const noexcept { return corruptions_.load(); }
  [[nodiscard]] std::uint64_t bytes_relayed(LinkDirection dir) const noexcept;

 private:
  void run() noexcept;
  void relay(int from, int to, LinkDirection dir) noexcept;

  Pty a_, b_;
  int wake_fd_ = -1;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> connected_{true};  // relaxed: a fault switch, no data rides on it
  std::mutex fault_mutex_;             // guards armed_ (relay thread ↔ test thread)
  long long armed_[2] = {-1, -1};      // bytes to skip before the flip; −1 disarmed
  std::atomic<std::uint64_t> corruptions_{0};
  std::atomic<std::uint64_t> relayed_[2] = {0, 0};
};

}  // namespace lcnc::drivers

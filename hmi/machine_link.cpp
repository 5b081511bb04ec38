#include "hmi/machine_link.h"

#include <cstdio>

namespace lcnc::hmi {

MachineLink::MachineLink(std::string shm_name) : name_(std::move(shm_name)) {}

bool MachineLink::poll() {
  const auto now = std::chrono::steady_clock::now();
  if (!client_) {
    if (now < next_try_) return false;
    next_try_ = now + std::chrono::milliseconds(250);
    Result<shm::ShmClient> c = shm::ShmClient::open(name_);
    if (!c) {
      why_ = c.error().message;
      return false;
    }
    client_.emplace(std::move(c).value());
    last_beat_ = client_->block().header.heartbeat.load(std::memory_order_relaxed);
    beat_seen_ = now;
    alive_ = true;
  }
  // relaxed: a counter the daemon bumps; only its change matters
  const std::uint64_t beat = client_->block().header.heartbeat.load(std::memory_order_relaxed);
  if (beat != last_beat_) {
    last_beat_ = beat;
    beat_seen_ = now;
  }
  const bool fresh = now - beat_seen_ <= kLostAfter;
  if (!fresh || !client_->owner_alive()) {
    why_ = client_->owner_alive() ? "the daemon does not answer (heartbeat stopped)" : "the daemon is gone";
    alive_ = false;
    client_.reset();  // try afresh: a restarted daemon makes a new segment
    return false;
  }
  alive_ = true;
  why_.clear();
  return true;
}

std::optional<shm::Status> MachineLink::status() const {
  if (!linked()) return std::nullopt;
  shm::Status s;
  if (!const_cast<shm::ShmClient&>(*client_).block().status.load_patiently(s, kReadPatience))
    return std::nullopt;
  shm::sanitize(s);
  return s;
}

std::optional<shm::JobStatus> MachineLink::job() const {
  if (!linked()) return std::nullopt;
  shm::JobStatus j;
  if (!const_cast<shm::ShmClient&>(*client_).block().job.load_patiently(j, kReadPatience))
    return std::nullopt;
  shm::sanitize(j);
  return j;
}

std::optional<shm::Answer> MachineLink::answer(std::uint32_t seq) const {
  shm::Answer a;
  if (!linked() || !client_->answer(seq, a)) return std::nullopt;
  return a;
}

bool MachineLink::next_event(shm::Event& out) {
  if (!linked() || !client_->block().events.try_pop(out)) return false;
  shm::sanitize(out);
  return true;
}

std::uint32_t MachineLink::send(shm::CommandType type, double value, std::uint8_t axis,
                                const std::string& text) {
  if (!linked()) return 0;
  shm::Command c;
  c.type = type;
  c.axis = axis;
  c.value = value;
  std::snprintf(c.text, sizeof c.text, "%s", text.c_str());
  return client_->send(c);
}

}  // namespace lcnc::hmi

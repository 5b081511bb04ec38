// The daemon's requests executed lately, by their sender's id: a sender
// that sends one again (a retry after it saw no answer) gets the first
// answer, and the request is not executed twice. A fixed ring of the last
// kCapacity ids; id 0 is a sender that does not ask for this.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "app/cnc_modbus_host.h"

namespace lcnc::app {

class RecentRequests {
 public:
  static constexpr std::size_t kCapacity = 256;

  // The answer given to request `id`: kept unless it is kept already.
  void remember(std::uint64_t id, const Ack& a) {
    if (id == 0 || find(id) != nullptr) return;
    recent_[next_] = Entry{id, a};
    next_ = (next_ + 1) % kCapacity;
  }
  // The answer request `id` had, if it is among the last kCapacity.
  [[nodiscard]] const Ack* find(std::uint64_t id) const {
    if (id == 0) return nullptr;
    for (const Entry& r : recent_)
      if (r.id == id) return &r.ack;
    return nullptr;
  }

 private:
  struct Entry {
    std::uint64_t id = 0;
    Ack ack;
  };
  std::array<Entry, kCapacity> recent_{};
  std::size_t next_ = 0;
};

}  // namespace lcnc::app

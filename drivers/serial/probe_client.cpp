#include "drivers/serial/probe_client.h"

#include <variant>

namespace lcnc::drivers {

ProbeClient::ProbeClient(DeviceMap map, ProbeClientConfig config)
    : map_(std::move(map)), cfg_(std::move(config)) {}

Status ProbeClient::open() {
  std::lock_guard lock(mutex_);
  return port_.open(cfg_.device, cfg_.baud);
}

void ProbeClient::close() noexcept {
  std::lock_guard lock(mutex_);
  port_.close();
}

ProbeCounters ProbeClient::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

Result<probe::Message> ProbeClient::transact(const probe::Message& request, std::uint16_t id) {
  const std::string who = "probe_3d (" + cfg_.device + ")";
  const int attempts = 1 + std::max(0, cfg_.retries);
  Diagnostic last = make_error(ErrorCode::PeripheralTimeout, who + ": no answer");
  for (int attempt = 0; attempt < attempts; ++attempt) {
    ++counters_.requests;
    port_.flush_input();
    if (Status s = port_.write_all(probe::encode(request)); !s)
      return make_error(s.error().code, "probe_3d: " + s.error().message);
    const auto deadline = std::chrono::steady_clock::now() + cfg_.timeout;
    for (;;) {  // read answers until ours, a bad one, or the deadline
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      auto line = port_.read_line(std::max(left, std::chrono::milliseconds(0)), probe::kMaxSentence + 16);
      if (!line) {
        if (line.error().code == ErrorCode::PeripheralTimeout) {
          ++counters_.timeouts;
          last = make_error(ErrorCode::PeripheralTimeout,
                            who + ": no answer within " + std::to_string(cfg_.timeout.count()) + " ms");
        } else {
          ++counters_.syntax_errors;
          last = make_error(line.error().code, "probe_3d: " + line.error().message);
        }
        break;
      }
      auto msg = probe::decode(line.value(), cfg_.device);
      if (!msg) {
        ++(msg.error().code == ErrorCode::SerialChecksum ? counters_.checksum_errors
                                                         : counters_.syntax_errors);
        last = make_error(msg.error().code, who + ": answer rejected: " + msg.error().message);
        break;  // ask again
      }
      const probe::Message& m = msg.value();
      if (const auto* p = std::get_if<probe::PointReply>(&m); p && p->id != id) {
        ++counters_.stale;
        continue;
      }
      if (const auto* e = std::get_if<probe::ErrorReply>(&m); e && e->id != id && e->id != 0) {
        ++counters_.stale;
        continue;
      }
      return msg.value();
    }
  }
  return make_error(last.code, last.message + " (" + std::to_string(attempts) + " attempt" +
                                   (attempts > 1 ? "s" : "") + ")");
}

Result<probe::PointReply> ProbeClient::measure() {
  std::lock_guard lock(mutex_);
  const std::string who = "probe_3d (" + cfg_.device + ")";
  const std::uint16_t id = next_id_;
  next_id_ = static_cast<std::uint16_t>(next_id_ == 65535 ? 1 : next_id_ + 1);
  auto answer = transact(probe::MeasureRequest{id}, id);
  if (!answer) return answer.error();
  if (const auto* e = std::get_if<probe::ErrorReply>(&answer.value())) {
    ++counters_.device_errors;
    return make_error(ErrorCode::PeripheralException,
                      who + ": measurement " + std::to_string(id) + ": " +
                          std::string(probe::probe_error_text(e->code)) + " (code " +
                          std::to_string(static_cast<int>(e->code)) + ": " + e->text + ")");
  }
  const auto* p = std::get_if<probe::PointReply>(&answer.value());
  if (p == nullptr)
    return make_error(ErrorCode::PeripheralProtocol,
                      who + ": measurement " + std::to_string(id) + ": answer is not $POS or $ERR");
  const double xyz[3] = {p->x_mm, p->y_mm, p->z_mm};
  const char* names[3] = {"x_mm", "y_mm", "z_mm"};
  for (int i = 0; i < 3; ++i) {
    auto reg = map_.lookup(names[i]);
    if (!reg) return reg.error();
    if (!reg.value()->in_range(xyz[i]))
      return make_error(ErrorCode::PeripheralValueOutOfRange,
                        who + ": measurement " + std::to_string(id) + ": " + names[i] + " = " +
                            format_number(xyz[i]) + " outside " + reg.value()->describe(map_.name));
  }
  ++counters_.points;
  return *p;
}

std::future<Result<probe::PointReply>> ProbeClient::measure_async() {
  return std::async(std::launch::async, [this] { return measure(); });
}

Result<probe::PongReply> ProbeClient::ping() {
  std::lock_guard lock(mutex_);
  auto answer = transact(probe::PingRequest{}, 0);
  if (!answer) return answer.error();
  if (const auto* p = std::get_if<probe::PongReply>(&answer.value())) return *p;
  return make_error(ErrorCode::PeripheralProtocol,
                    "probe_3d (" + cfg_.device + "): answer to $PING is not $PONG");
}

}  // namespace lcnc::drivers

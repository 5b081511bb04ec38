#include "app/cnc_modbus_host.h"

#include <algorithm>

#include "drivers/modbus/register_map.h"
#include "rt/rt_kernel.h"

namespace lcnc::app {

Status check_hole_block(const drivers::HoleParameters& p) {
  HoleProcessParams h = p;
  // The polygon of a free shape is a process-database matter: check the
  // rest of the block as the circle scan's (same fields, same ranges).
  if (h.process == HoleProcessId::FreeShape) h.process = HoleProcessId::Circle;
  return validate(h);
}

drivers::CncStatusSnapshot to_snapshot(const shm::Status& st, std::uint32_t axes_mask) {
  drivers::CncStatusSnapshot s;
  s.state = static_cast<std::uint16_t>(st.state);
  s.fault_code = std::min<std::uint16_t>(st.fault, 999);
  // X Y Z A C of the X Y Z A B C poses; clamped to the map's range so that
  // a far-off rotary count never blocks the rest of the status
  constexpr int kAxes[5] = {0, 1, 2, 3, 5};
  for (int i = 0; i < 5; ++i) s.position[i] = std::clamp(st.pos[kAxes[i]], -10000.0, 10000.0);
  s.feed_override_pct = std::clamp(st.feed_override * 100.0, 0.0, 100.0 * 10.0);
  s.job_line = st.line;
  s.buffer_fill_pct =
      std::clamp(100.0 * st.buffer_fill / static_cast<double>(rt::kPositionBufferCapacity), 0.0, 100.0);
  s.underruns = static_cast<std::uint32_t>(std::min<std::uint64_t>(st.underruns, 4'000'000'000u));
  s.estop = st.state == shm::MachineState::EStop;
  s.homed = axes_mask != 0 && (st.homed_mask & axes_mask) == axes_mask;
  s.laser_on = st.power_pct > 0.0f;
  s.fault = st.fault != 0;
  return s;
}

Result<std::unique_ptr<CncModbusHost>> CncModbusHost::start(const drivers::Endpoint& endpoint,
                                                            std::shared_ptr<spdlog::logger> log) {
  Result<drivers::DeviceMap> map = drivers::shipped_device("cnc");
  if (!map) return map.error();
  drivers::SlaveConfig config;
  config.endpoint = endpoint;
  Result<std::unique_ptr<drivers::CncSlave>> slave = drivers::CncSlave::create(*map, config);
  if (!slave) return slave.error();
  std::unique_ptr<CncModbusHost> host(new CncModbusHost());
  host->log_ = std::move(log);
  host->slave_ = std::move(slave).value();
  CncModbusHost* h = host.get();
  host->slave_->on_command([h](drivers::CncCommand c, double v) { return h->on_command(c, v); });
  host->slave_->on_parameters([h](const drivers::HoleParameters& p) { return h->on_parameters(p); });
  if (Status s = host->slave_->start(); !s.ok()) return s.error();
  return host;
}

CncModbusHost::~CncModbusHost() {
  if (slave_) slave_->stop();
  // a command still queued gets its answer (the master's exception 04)
  std::lock_guard lock(mutex_);
  for (auto& p : inbox_)
    p->answer.set_value(Ack{false, ErrorCode::RtRefused, "the controller is shutting down"});
  inbox_.clear();
}

Status CncModbusHost::on_command(drivers::CncCommand command, double value) {
  shm::Command c;
  switch (command) {
    case drivers::CncCommand::Start: c.type = shm::CommandType::Start; break;
    case drivers::CncCommand::Hold: c.type = shm::CommandType::Hold; break;
    case drivers::CncCommand::Resume: c.type = shm::CommandType::Resume; break;
    case drivers::CncCommand::Stop: c.type = shm::CommandType::Stop; break;
    case drivers::CncCommand::Reset: c.type = shm::CommandType::Reset; break;
    case drivers::CncCommand::SetOverride:
      c.type = shm::CommandType::Override;
      c.value = value / 100.0;  // the register is in %, the command in K
      break;
  }
  auto pending = std::make_shared<Pending>();
  pending->command = c;
  std::future<Ack> answer = pending->answer.get_future();
  {
    std::lock_guard lock(mutex_);
    inbox_.push_back(pending);
  }
  if (answer.wait_for(kCommandWait) != std::future_status::ready) {
    // withdrawn, unless the control thread took it meanwhile
    std::lock_guard lock(mutex_);
    const auto it = std::find(inbox_.begin(), inbox_.end(), pending);
    if (it != inbox_.end()) {
      inbox_.erase(it);
      return make_error(ErrorCode::RtRefused, "the controller did not take the command in time");
    }
  }
  const Ack a = answer.get();
  if (a.ok) return {};
  return make_error(a.code, a.message);
}

Status CncModbusHost::on_parameters(const drivers::HoleParameters& p) {
  if (Status s = check_hole_block(p); !s.ok()) {
    log_->warn("modbus: hole parameter block refused: {}", s.error().message);
    return s;
  }
  std::lock_guard lock(mutex_);
  block_ = p;
  ++blocks_;
  return {};
}

bool CncModbusHost::publish(const shm::Status& st) {
  // Never wait for the bank: a master's command may hold it while its
  // handler waits for this thread to take the command (drain()).
  const std::optional<Status> published = slave_->try_publish(to_snapshot(st, st.axes_mask));
  if (!published) return false;
  const Status& s = *published;
  std::lock_guard lock(mutex_);
  const std::string err = s.ok() ? std::string() : s.error().message;
  if (err != last_publish_error_ && !err.empty()) log_->warn("modbus: status not published: {}", err);
  last_publish_error_ = err;
  return true;
}

void CncModbusHost::drain(const CommandExecutor& execute) {
  for (;;) {
    std::shared_ptr<Pending> p;
    {
      std::lock_guard lock(mutex_);
      if (inbox_.empty()) return;
      p = inbox_.front();
      inbox_.pop_front();
    }
    p->answer.set_value(execute(p->command));
  }
}

drivers::HoleParameters CncModbusHost::parameters() const {
  std::lock_guard lock(mutex_);
  return block_;
}

std::uint64_t CncModbusHost::blocks_accepted() const {
  std::lock_guard lock(mutex_);
  return blocks_;
}

}  // namespace lcnc::app

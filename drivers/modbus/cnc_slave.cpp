#include "drivers/modbus/cnc_slave.h"

#include "holes/hole_fields.h"

#include <string_view>
#include <vector>

namespace lcnc::drivers {

namespace {

// The hole parameter block: the record's fields by register name.
void load_block(HoleParameters& p, const RegisterBank& b) {
  for (const HoleField& f : kHoleFields) f.set(p, b.value(b.def(f.register_name)));
}

struct CommandCoil {
  std::string_view name;
  CncCommand command;
};
constexpr CommandCoil kCommands[] = {{"cmd_start", CncCommand::Start},
                                     {"cmd_hold", CncCommand::Hold},
                                     {"cmd_resume", CncCommand::Resume},
                                     {"cmd_stop", CncCommand::Stop},
                                     {"cmd_reset", CncCommand::Reset}};

constexpr std::string_view kStatusRegisters[] = {
    "state",    "fault_code",      "x_mm",      "y_mm",
    "z_mm",     "a_deg",           "c_deg",     "feed_override_pct",
    "job_line", "buffer_fill_pct", "underruns", "estop",
    "homed",    "laser_on",        "fault",     "feed_override_set_pct"};

}  // namespace

Result<std::unique_ptr<CncSlave>> CncSlave::create(DeviceMap map, SlaveConfig config) {
  if (map.name != "cnc")
    return make_error(ErrorCode::RegisterMapInvalid,
                      "the CNC slave was given the map of device '" + map.name + "'");
  auto need = [&](std::string_view n) -> Status {
    if (auto r = map.lookup(n); !r)
      return make_error(ErrorCode::RegisterMapInvalid,
                        "the CNC slave needs register '" + std::string(n) + "': " + r.error().message);
    return {};
  };
  for (const HoleField& f : kHoleFields)
    if (Status s = need(f.register_name); !s) return s.error();
  for (const CommandCoil& c : kCommands)
    if (Status s = need(c.name); !s) return s.error();
  for (std::string_view n : kStatusRegisters)
    if (Status s = need(n); !s) return s.error();
  if (config.tick_period.count() <= 0) config.tick_period = std::chrono::milliseconds(10);
  return std::unique_ptr<CncSlave>(new CncSlave(std::move(map), std::move(config)));
}

CncSlave::CncSlave(DeviceMap map, SlaveConfig config)
    : slave_(std::make_unique<ModbusSlave>(std::move(map), std::move(config))) {
  slave_->set_write_hook(
      [this](std::span<const RegisterWrite> w, RegisterBank& b) { return on_write(w, b); });
  // Command coils read 1 until taken: clear them every tick.
  slave_->set_tick_hook([](double, RegisterBank& b) {
    for (const CommandCoil& c : kCommands) b.set_clamped(b.def(c.name), 0);
  });
}

CncSlave::~CncSlave() { stop(); }

void CncSlave::on_command(CncCommandHandler handler) { command_handler_ = std::move(handler); }
void CncSlave::on_parameters(HoleParametersHandler handler) { parameters_handler_ = std::move(handler); }
Status CncSlave::start() { return slave_->start(); }
void CncSlave::stop() noexcept { slave_->stop(); }

ModbusException CncSlave::on_write(std::span<const RegisterWrite> writes, RegisterBank& b) {
  // Parameters first: the whole block with the new values merged in.
  bool block_touched = false;
  HoleParameters p;
  load_block(p, b);
  for (const RegisterWrite& w : writes)
    if (const auto k = hole_field_by_register(w.reg->name)) {
      kHoleFields[*k].set(p, w.value);
      block_touched = true;
    }
  if (block_touched && parameters_handler_ && !parameters_handler_(p).ok())
    return ModbusException::DeviceFailure;
  if (!command_handler_) return ModbusException::None;
  for (const RegisterWrite& w : writes) {
    if (w.reg->name == "feed_override_set_pct") {
      if (!command_handler_(CncCommand::SetOverride, w.value).ok()) return ModbusException::DeviceFailure;
      continue;
    }
    if (w.value == 0) continue;  // a command coil written 0 is no command
    for (const CommandCoil& c : kCommands)
      if (w.reg->name == c.name && !command_handler_(c.command, 0.0).ok())
        return ModbusException::DeviceFailure;
  }
  return ModbusException::None;
}

namespace {

Status write_status(const CncStatusSnapshot& s, RegisterBank& b) {
  Status result;
  [&] {
    const std::pair<std::string_view, double> values[] = {
        {"state", s.state},         {"fault_code", s.fault_code},
        {"x_mm", s.position[0]},    {"y_mm", s.position[1]},
        {"z_mm", s.position[2]},    {"a_deg", s.position[3]},
        {"c_deg", s.position[4]},   {"feed_override_pct", s.feed_override_pct},
        {"job_line", s.job_line},   {"buffer_fill_pct", s.buffer_fill_pct},
        {"underruns", s.underruns}, {"estop", s.estop ? 1 : 0},
        {"homed", s.homed ? 1 : 0}, {"laser_on", s.laser_on ? 1 : 0},
        {"fault", s.fault ? 1 : 0}};
    // Check everything first: a snapshot is published whole or not at all.
    for (const auto& [name, v] : values)
      if (!b.def(name).in_range(v)) {
        result = make_error(ErrorCode::PeripheralValueOutOfRange,
                            "cnc status not published: " + std::string(name) + " = " + format_number(v) +
                                " outside " + b.def(name).describe("cnc"));
        return;
      }
    for (const auto& [name, v] : values) (void)b.set(b.def(name), v);
  }();
  return result;
}

}  // namespace

Status CncSlave::publish(const CncStatusSnapshot& s) {
  Status result;
  slave_->with_bank([&](RegisterBank& b) { result = write_status(s, b); });
  return result;
}

std::optional<Status> CncSlave::try_publish(const CncStatusSnapshot& s) {
  Status result;
  if (!slave_->try_with_bank([&](RegisterBank& b) { result = write_status(s, b); })) return std::nullopt;
  return result;
}

HoleParameters CncSlave::parameters() const {
  HoleParameters p;
  slave_->with_bank([&](RegisterBank& b) { load_block(p, b); });
  return p;
}

}  // namespace lcnc::drivers

// The CNC's own Modbus slave (register map device "cnc"): what lasercncd
// exposes to a PLC or an MES (docs/design.md §8, Shao (2022) §4 fig. 15 — "reading CNC
// system parameters and providing CNC system commands"). A thin, typed layer
// over ModbusSlave, so the daemon deals in its own terms:
//
//   * publish(status) — the machine's state, positions, override, job line,
//     buffer fill, underruns, e-stop/homed/laser/fault bits into the input
//     registers and discrete inputs, all under one lock (a master never
//     reads half an update);
//   * commands — a coil cmd_* written 1, or feed_override_set_pct written,
//     is handed to the command handler at once (on the slave's thread: it
//     must only queue the command, e.g. into the daemon's command ring). A
//     handler that refuses gets the master exception 04 and the coil stays
//     0; an accepted command's coil reads 1 until the next tick (10 ms)
//     clears it — "taken";
//   * the hole parameter block (holding 0–24, docs/design.md §6 fields 1–18; the
//     registers named by holes/hole_fields.h) — ranges are checked by the map (exception 03, nothing stored); a valid
//     write, whole or partial, is handed to the parameter handler as the
//     complete block with the new values merged in; a refusal is
//     exception 04 and nothing is stored.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "common/result.h"
#include "drivers/modbus/modbus_slave.h"
#include "holes/hole_processes.h"

namespace lcnc::drivers {

// The CNC's status as the register map publishes it.
struct CncStatusSnapshot {
  std::uint16_t state = 0;       // 0 idle, 1 running, 2 feed hold, 3 stopping, 4 e-stop, 5 jog, 6 homing
  std::uint16_t fault_code = 0;  // share/errors.def number, 0 none
  std::array<double, 5> position = {};  // X Y Z (mm), A C (deg)
  double feed_override_pct = 100.0;
  std::uint32_t job_line = 0;
  double buffer_fill_pct = 0.0;
  std::uint32_t underruns = 0;
  bool estop = false, homed = false, laser_on = false, fault = false;
};

enum class CncCommand : std::uint8_t { Start, Hold, Resume, Stop, Reset, SetOverride };

// docs/design.md §6 fields 1–18 (the process database row of one hole): the
// parameter block's registers are the fields' register names of
// holes/hole_fields.h. A block from Modbus has no free-shape polygon.
using HoleParameters = HoleProcessParams;

// `value` is the override in % for SetOverride, else 0. Return a failed
// Status to refuse (the master gets exception 04).
using CncCommandHandler = std::function<Status(CncCommand command, double value)>;
using HoleParametersHandler = std::function<Status(const HoleParameters&)>;

class CncSlave {
 public:
  // `map` is the register map's "cnc" device.
  [[nodiscard]] static Result<std::unique_ptr<CncSlave>> create(DeviceMap map, SlaveConfig config = {});
  ~CncSlave();

  // Handlers are set before start(); unset ones accept everything.
  void on_command(CncCommandHandler handler);
  void on_parameters(HoleParametersHandler handler);

  [[nodiscard]] Status start();
  void stop() noexcept;
  [[nodiscard]] Endpoint endpoint() const { return slave_->endpoint(); }
  [[nodiscard]] ModbusSlave& slave() noexcept { return *slave_; }

  // Out-of-range values are not published; the error names the register.
  [[nodiscard]] Status publish(const CncStatusSnapshot& status);
  // The same unless a request is being served right now (nullopt: nothing
  // published, try again). The write hook runs while a request is served,
  // and an owner whose command handler waits for its own thread must
  // publish with this, or the two would wait for each other.
  [[nodiscard]] std::optional<Status> try_publish(const CncStatusSnapshot& status);
  // The block as stored now (what a master reads back with FC3).
  [[nodiscard]] HoleParameters parameters() const;

 private:
  explicit CncSlave(DeviceMap map, SlaveConfig config);
  ModbusException on_write(std::span<const RegisterWrite> writes, RegisterBank& bank);

  std::unique_ptr<ModbusSlave> slave_;
  CncCommandHandler command_handler_;
  HoleParametersHandler parameters_handler_;
};

}  // namespace lcnc::drivers

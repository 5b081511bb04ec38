// The focal-length workflow (docs/design.md §7, Shao (2022) §4): for the holes chosen,
// the machine goes over each with the point-laser displacement sensor (on
// the Z carriage, beam down −Z, coaxial with the tool) at the stand-off from
// the hole's Z, the sensor reads, and the hole's focus offset is
//   offset = stand-off − distance   (the surface's height above the hole's Z)
// A hole the sensor cannot see (out of range), or the machine cannot reach,
// has an error and no offset; the others are measured. Nothing is stored
// here: the operator saves the offsets (ProcessDatabase::set_focus_offsets,
// all or none), and a drilling run then takes Z + offset from the database.
// Qt-free; runs on a worker thread.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/result.h"
#include "drivers/modbus/modbus_master.h"
#include "hmi/machine_mover.h"
#include "hmi/process_db.h"

namespace lcnc::hmi {

// The sensor: one fresh reading, in mm (an error when out of range).
class DistanceSensor {
 public:
  virtual ~DistanceSensor() = default;
  [[nodiscard]] virtual Result<double> read() = 0;
};

// The register map's displacement_sensor over Modbus: sets the averaging,
// waits for a reading newer than the call (sample_counter moves), then reads
// in_range and distance_mm.
class ModbusDistanceSensor final : public DistanceSensor {
 public:
  static Result<std::unique_ptr<ModbusDistanceSensor>> connect(const drivers::Endpoint& at, int averaging);
  [[nodiscard]] Result<double> read() override;

 private:
  explicit ModbusDistanceSensor(std::unique_ptr<drivers::ModbusMaster> m) : master_(std::move(m)) {}
  std::unique_ptr<drivers::ModbusMaster> master_;
};

struct FocalConfig {
  double standoff_mm = 50.0;  // sensor to surface at the hole's Z: the middle of its 30–70 mm
  std::chrono::milliseconds move_timeout{60000};
};

struct FocalReading {
  std::uint32_t hole = 0;
  Pose at = Pose::Zero();             // where the sensor read (machine)
  std::optional<double> distance_mm;  // what it read
  std::optional<double> offset_mm;    // the focus offset, when measured
  std::string error;                  // why not, when not
};

// Measures each hole in turn; `progress(done, total)` after each (any
// thread), `cancel` checked between holes. A lost link or a machine fault
// ends the run (the rest have that error); a hole out of the sensor's range
// is one error and the run goes on.
[[nodiscard]] std::vector<FocalReading> run_focal(const std::vector<HoleRecord>& holes, MachineMover& mover,
                                                  DistanceSensor& sensor, const FocalConfig& config,
                                                  const std::function<void(int, int)>& progress = {},
                                                  const std::atomic<bool>* cancel = nullptr);

// The offsets to store: every measured reading, checked against the
// database's range (kMaxFocusOffsetMm).
[[nodiscard]] std::vector<std::pair<std::uint32_t, double>> offsets_to_save(
    const std::vector<FocalReading>& readings);

}  // namespace lcnc::hmi

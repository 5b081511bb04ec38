// The values of one device's registers, laid out as the Modbus tables of its
// DeviceMap: what a slave serves and what a virtual device's model updates.
// Not thread-safe by itself: ModbusSlave guards it with its mutex and hands
// it to hooks under that lock.
//
// Every register starts at the value of its range nearest to 0 (so a
// register with min = 1 starts at 1, never at an out-of-range 0).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "common/result.h"
#include "drivers/modbus/register_map.h"

namespace lcnc::drivers {

class RegisterBank {
 public:
  explicit RegisterBank(DeviceMap map);

  [[nodiscard]] const DeviceMap& map() const noexcept { return map_; }

  // By name: unknown names and out-of-range values are errors naming them.
  [[nodiscard]] Result<double> get(std::string_view name) const;
  [[nodiscard]] Status set(std::string_view name, double value);
  // By definition (a pointer into map()): for models that cache them.
  [[nodiscard]] double value(const RegisterDef& reg) const noexcept;
  [[nodiscard]] Status set(const RegisterDef& reg, double value);
  // The model's convenience: set, clamping into the register's range (a
  // simulated reading never goes out of its own range).
  void set_clamped(const RegisterDef& reg, double value) noexcept;
  // The register named `name`; the model's lookups are by names the map was
  // checked to contain, so a miss is a programming error: it aborts with a
  // message naming the device and register.
  [[nodiscard]] const RegisterDef& def(std::string_view name) const;

  // Raw tables (one uint8 per bit, one uint16 per word), sized table_size().
  [[nodiscard]] std::vector<std::uint8_t>& bits(Table t) noexcept;
  [[nodiscard]] std::vector<std::uint16_t>& words(Table t) noexcept;

 private:
  DeviceMap map_;
  std::array<std::vector<std::uint8_t>, 2> bits_;    // coil, discrete
  std::array<std::vector<std::uint16_t>, 2> words_;  // holding, input
};

}  // namespace lcnc::drivers

#include "hmi/focal_workflow.h"

#include <cmath>
#include <cstdio>
#include <thread>

#include "drivers/modbus/register_map.h"

namespace lcnc::hmi {
namespace {

constexpr auto kReadingTimeout = std::chrono::seconds(3);

}  // namespace

Result<std::unique_ptr<ModbusDistanceSensor>> ModbusDistanceSensor::connect(const drivers::Endpoint& at,
                                                                            int averaging) {
  Result<drivers::DeviceMap> map = drivers::shipped_device("displacement_sensor");
  if (!map) return map.error();
  drivers::MasterConfig c;
  c.endpoint = at;
  auto m = std::make_unique<drivers::ModbusMaster>(*map, c);
  if (Status s = m->start(); !s) return s.error();
  if (Status s = m->write("averaging", averaging).get(); !s) return s.error();
  return std::unique_ptr<ModbusDistanceSensor>(new ModbusDistanceSensor(std::move(m)));
}

Result<double> ModbusDistanceSensor::read() {
  // a reading taken after this call: the machine has come to rest by now
  Result<double> first = master_->read("sample_counter").get();
  if (!first) return first.error();
  const auto until = std::chrono::steady_clock::now() + kReadingTimeout;
  for (int fresh = 0; fresh < 2;) {  // two moves of the counter: a whole reading since
    Result<double> c = master_->read("sample_counter").get();
    if (!c) return c.error();
    if (*c != *first) {
      ++fresh;
      first = c;
      continue;
    }
    if (std::chrono::steady_clock::now() > until)
      return make_error(ErrorCode::PeripheralTimeout, "displacement sensor: no new reading in 3 s");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  Result<std::vector<double>> r = master_->read_block({"distance_mm", "sample_counter"}).get();
  if (!r) return r.error();
  Result<double> in_range = master_->read("in_range").get();
  if (!in_range) return in_range.error();
  if (*in_range == 0.0)
    return make_error(ErrorCode::MeasureOutOfRange, "displacement sensor: no surface in its range");
  return (*r)[0];
}

std::vector<FocalReading> run_focal(const std::vector<HoleRecord>& holes, MachineMover& mover,
                                    DistanceSensor& sensor, const FocalConfig& config,
                                    const std::function<void(int, int)>& progress,
                                    const std::atomic<bool>* cancel) {
  std::vector<FocalReading> out;
  std::string fatal;
  const int total = static_cast<int>(holes.size());
  for (const HoleRecord& h : holes) {
    FocalReading r;
    r.hole = h.params.hole_number;
    r.at = h.params.position;
    r.at[2] = h.params.position[2] + config.standoff_mm;
    r.at[3] = 0.0;  // the sensor looks straight down
    if (cancel != nullptr && cancel->load()) fatal = "cancelled";
    if (!fatal.empty()) {
      r.error = fatal;
    } else if (Status s = mover.move_to(r.at, config.move_timeout); !s) {
      char where[96];
      std::snprintf(where, sizeof where, "the sensor's point X%.3f Y%.3f Z%.3f: ", r.at[0], r.at[1], r.at[2]);
      r.error = (s.error().code == ErrorCode::GcodeBeyondTravel
                     ? std::string(where) + "beyond the machine's travel ("
                     : std::string()) +
                s.error().message + (s.error().code == ErrorCode::GcodeBeyondTravel ? ")" : "");
      // a refused point (beyond the travel) is this hole's; anything else ends the run
      if (s.error().code != ErrorCode::GcodeBeyondTravel) fatal = "not measured: " + r.error;
    } else if (Result<double> d = sensor.read(); !d) {
      r.error = d.error().message;
      if (d.error().code != ErrorCode::MeasureOutOfRange) fatal = "not measured: " + r.error;
    } else {
      r.distance_mm = *d;
      r.offset_mm = config.standoff_mm - *d;
    }
    out.push_back(r);
    if (progress) progress(static_cast<int>(out.size()), total);
  }
  return out;
}

std::vector<std::pair<std::uint32_t, double>> offsets_to_save(const std::vector<FocalReading>& readings) {
  std::vector<std::pair<std::uint32_t, double>> out;
  for (const FocalReading& r : readings)
    if (r.offset_mm && std::abs(*r.offset_mm) <= kMaxFocusOffsetMm) out.emplace_back(r.hole, *r.offset_mm);
  return out;
}

}  // namespace lcnc::hmi

// The fuzz targets: every parser of outside input, fed any bytes. Each
// returns normally whatever the input (a clear error is a normal return);
// a crash, a hang, an out-of-bounds access or a sanitizer report is a
// finding. Built two ways (tests/fuzz/CMakeLists.txt): with clang's libFuzzer
// for the long runs (RELIABILITY.md), and with the replay-and-mutate driver
// (fuzz_driver.cpp) as the CI's smoke under ASan+UBSan.
#include "tests/fuzz/fuzz_targets.h"

#include <string>
#include <string_view>

#include "dxf/dxf_reader.h"
#include "drivers/modbus/register_map.h"
#include "drivers/serial/probe_protocol.h"
#include "gcode/program_reader.h"
#include "holes/hole_table.h"
#include "machine/machine_config.h"

namespace lcnc::fuzz {
namespace {

std::string_view text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

const MachineConfig& machine() {
  static const MachineConfig m = [] {
    Result<MachineConfig> c = load_machine_config(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
    return c ? *c : MachineConfig{};
  }();
  return m;
}

int gcode(const std::uint8_t* data, std::size_t size) {
  auto reader = ProgramReader::from_string(std::string(text(data, size)), "fuzz.ngc", machine());
  Segment s;
  // every program ends: at its end, at an error, or at the line budget
  for (int n = 0; n < 100000 && reader->next(s) == ProgramReader::Next::Segment; ++n) {
  }
  return 0;
}

int dxf(const std::uint8_t* data, std::size_t size) {
  (void)dxf::read_dxf_text(text(data, size), "fuzz.dxf");
  return 0;
}

int machine_config(const std::uint8_t* data, std::size_t size) {
  (void)parse_machine_config(text(data, size), "fuzz.toml");
  return 0;
}

int hole_table(const std::uint8_t* data, std::size_t size) {
  (void)parse_hole_table(text(data, size), "fuzz.csv");
  return 0;
}

int probe_sentence(const std::uint8_t* data, std::size_t size) {
  (void)drivers::probe::parse_sentence(text(data, size), "fuzz");
  return 0;
}

int register_map(const std::uint8_t* data, std::size_t size) {
  (void)drivers::parse_register_map(text(data, size), "fuzz.toml");
  return 0;
}

}  // namespace

const Target* find_target(std::string_view name) {
  static const Target targets[] = {
      {"gcode", gcode},           {"dxf", dxf},
      {"machine_config", machine_config}, {"hole_table", hole_table},
      {"probe_sentence", probe_sentence}, {"register_map", register_map},
  };
  for (const Target& t : targets)
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace lcnc::fuzz

// The fuzz targets: every parser of outside input, fed any bytes. Each
// returns normally whatever the input (a clear error is a normal return);
// a crash, a hang, an out-of-bounds access or a sanitizer report is a
// finding. Built two ways (tests/fuzz/CMakeLists.txt): with clang's libFuzzer
// for the long runs (RELIABILITY.md), and with the replay-and-mutate driver
// (fuzz_driver.cpp) as the CI's smoke under ASan+UBSan.
#include "tests/fuzz/fuzz_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/control_client.h"
#include "drivers/modbus/register_map.h"
#include "drivers/modbus/slave_request.h"
#include "drivers/serial/probe_protocol.h"
#include "dxf/dxf_reader.h"
#include "gcode/program_reader.h"
#include "holes/hole_table.h"
#include "machine/machine_config.h"
#include "rt/shm_command.h"
#include "rt/shm_interface.h"

namespace lcnc::fuzz {
namespace {

std::string_view text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

const MachineConfig& machine() {
  static const MachineConfig m = [] {
    Result<MachineConfig> c =
        load_machine_config(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
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

// A broken invariant is a finding: say which and abort (the fuzzer keeps
// the input).
[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::abort();
}

// The slave's request handling with raw frames: the cnc device of the
// shipped map (what lasercncd exposes to a PLC), each input delivered
// through libmodbus's receive and reply over a socket pair. The first byte
// picks the framing: TCP as given, RTU as given, or RTU with the CRC
// appended by the harness (so that mutations reach the request's body).
// Invariants: no request writes a read-only register or a value outside a
// register's range (the defaults before any write may be); a request
// taken gets an answer; an exception answer echoes the function code.
struct ModbusHarness {
  drivers::SlaveRequestHandler handler;
  std::unique_ptr<drivers::RawFrameLoop> tcp, rtu;
  std::uint8_t unit;

  static ModbusHarness& get() {
    static ModbusHarness h = [] {
      Result<drivers::DeviceMap> map = drivers::shipped_device("cnc");
      if (!map) finding("the shipped map: " + map.error().to_string());
      return ModbusHarness(std::move(map).value());
    }();
    return h;
  }
  explicit ModbusHarness(drivers::DeviceMap map)
      : handler(std::move(map)), unit(handler.bank().map().unit_id) {
    auto t = drivers::RawFrameLoop::open(drivers::Transport::Tcp, unit);
    auto r = drivers::RawFrameLoop::open(drivers::Transport::Rtu, unit);
    if (!t || !r) finding("cannot open the frame loops");
    tcp = std::move(t).value();
    rtu = std::move(r).value();
  }
  ModbusHarness(ModbusHarness&&) = delete;
};

std::string hex(std::span<const std::uint8_t> b) {
  std::string s;
  char h[4];
  for (std::uint8_t c : b) {
    std::snprintf(h, sizeof h, "%02x ", c);
    s += h;
  }
  return s;
}

int modbus_request(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  ModbusHarness& h = ModbusHarness::get();
  const int mode = data[0] % 3;
  const std::span<const std::uint8_t> rest(data + 1, size - 1);
  std::vector<std::uint8_t> frame(rest.begin(), rest.end());
  if (mode == 2) frame = drivers::RawFrameLoop::rtu_frame(h.unit, rest);
  drivers::RawFrameLoop& loop = mode == 0 ? *h.tcp : *h.rtu;
  const drivers::RegisterBank& bank = h.handler.bank();
  const std::vector<drivers::RegisterDef>& regs = bank.map().registers;
  std::vector<double> before(regs.size());
  for (std::size_t i = 0; i < regs.size(); ++i) before[i] = bank.value(regs[i]);
  const drivers::RawFrameLoop::Exchange x = loop.deliver(h.handler, frame);
  for (std::size_t i = 0; i < regs.size(); ++i) {
    const double v = bank.value(regs[i]);
    if (!regs[i].writable() && v != before[i]) finding("read-only register " + regs[i].name + " written");
    if (v != before[i] && !regs[i].in_range(v))
      finding("register " + regs[i].name + " written " + std::to_string(v) + ", outside its range");
  }
  if (x.received.kind == drivers::Received::Kind::Answered) {
    const bool broadcast = mode != 0 && !frame.empty() && frame[0] == 0;
    const std::size_t fc_at = mode == 0 ? 7 : 1;
    if (!broadcast && x.reply.size() <= fc_at) finding("a request taken got no answer");
    if (!broadcast && x.received.exception != drivers::ModbusException::None &&
        x.reply[fc_at] != (frame[fc_at] | 0x80))
      finding("an exception answer without the function code's echo: " + hex(frame) + " → " + hex(x.reply));
  }
  return 0;
}

// The daemon's command ring as another process may leave it: the input
// laid over the ring's bytes (indices and slots), then drained as the
// daemon drains it, each frame checked. Invariants: the drain ends within
// two rings' worth; a frame that passes the check is one the daemon can act
// on without reading past a field (type known, axis present, value finite
// and in range, path terminated).
int shm_commands(const std::uint8_t* data, std::size_t size) {
  using Ring = decltype(shm::ShmBlock::commands);
  static_assert(std::is_trivially_destructible_v<Ring>);
  alignas(Ring) static unsigned char storage[sizeof(Ring)];
  std::memset(storage, 0, sizeof storage);
  Ring* ring = new (storage) Ring();
  std::memcpy(storage, data, std::min(size, sizeof storage));  // what a sender wrote
  shm::CommandLimits limits;
  limits.axes_mask = 0b101111;  // X Y Z A C
  limits.max_override = 1.5;
  shm::Command c;
  std::size_t taken = 0;
  for (; taken <= 2 * Ring::kCapacity && ring->try_pop(c); ++taken) {
    if (!shm::check_command_frame(c, limits)) continue;
    if (static_cast<std::uint8_t>(c.type) >= static_cast<std::uint8_t>(shm::CommandType::Count))
      finding("an unknown command type passed");
    if (c.type == shm::CommandType::Load && std::memchr(c.text, 0, sizeof c.text) == nullptr)
      finding("an unterminated path passed");
    if ((c.type == shm::CommandType::Jog || c.type == shm::CommandType::Home) &&
        (c.axis >= kAxisCount || !((limits.axes_mask >> c.axis) & 1u)))
      finding("a missing axis passed");
    if (c.type == shm::CommandType::Override && !(c.value >= 0.0 && c.value <= limits.max_override))
      finding("an override out of range passed");
    if (c.type == shm::CommandType::Jog && !(std::abs(c.value) <= limits.max_jog))
      finding("a jog out of range passed");
  }
  // At most what the consumer's cached tail promised plus one ring's worth
  // after it reads the real tail: anything more is a ring handing out
  // garbage (before the check in try_pop: 2^64 items, a hung daemon).
  if (taken > 2 * Ring::kCapacity) finding("the ring served more than it can hold");
  return 0;
}

// The status blocks as any process of the group may leave them: the input
// laid over the kernel's Status, the daemon's JobStatus and an Event, each
// sanitized as a reader does (shm::sanitize), then printed as `lasercnc
// status` prints them. Invariants: the texts end inside their fields, and
// the JSON printed is valid JSON (any bytes in a text, any number).
int shm_status(const std::uint8_t* data, std::size_t size) {
  shm::Status st;
  shm::JobStatus job;
  shm::Event ev;
  static_assert(std::is_trivially_copyable_v<shm::Status> && std::is_trivially_copyable_v<shm::JobStatus> &&
                std::is_trivially_copyable_v<shm::Event>);
  std::size_t at = 0;
  const auto lay = [&](auto& block) {  // what a writer left
    const std::size_t n = std::min(sizeof block, size - at);
    std::memcpy(static_cast<void*>(&block), data + at, n);
    at += n;
  };
  lay(st);
  lay(job);
  lay(ev);
  shm::sanitize(st);
  shm::sanitize(job);
  shm::sanitize(ev);
  if (std::memchr(job.message, 0, sizeof job.message) == nullptr ||
      std::memchr(job.program, 0, sizeof job.program) == nullptr ||
      std::memchr(ev.text, 0, sizeof ev.text) == nullptr)
    finding("a text runs past its field");
  (void)app::format_status(st, job, false);
  if (!nlohmann::json::accept(app::format_status(st, job, true)))
    finding("lasercnc status --json printed invalid JSON");
  return 0;
}

}  // namespace

const Target* find_target(std::string_view name) {
  static const Target targets[] = {
      {"gcode", gcode},
      {"dxf", dxf},
      {"machine_config", machine_config},
      {"hole_table", hole_table},
      {"probe_sentence", probe_sentence},
      {"register_map", register_map},
      {"modbus_request", modbus_request},
      {"shm_commands", shm_commands},
      {"shm_status", shm_status},
  };
  for (const Target& t : targets)
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace lcnc::fuzz

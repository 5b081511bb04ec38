// The register map: the shipped file loads and is consistent; every kind of
// mistake in a map is an error naming file:line:col, the device, the entry
// and what was expected; values convert to raw words and back exactly.
#include "drivers/modbus/register_map.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "drivers/modbus/register_bank.h"
#include "holes/hole_fields.h"

namespace lcnc::drivers {
namespace {

TEST(RegisterMap, ShippedMapLoadsWithEveryDevice) {
  auto m = load_register_map(default_register_map_path());
  ASSERT_TRUE(m.ok()) << m.error().to_string();
  for (const char* d :
       {"cnc", "laser_source", "power_meter", "scan_head", "displacement_sensor", "probe_3d"}) {
    const DeviceMap* dev = m->device(d);
    ASSERT_NE(dev, nullptr) << d;
    EXPECT_FALSE(dev->registers.empty()) << d;
  }
  // The CNC's hole parameter block (docs/design.md §6 fields 1–18) is one contiguous
  // run of holding registers, so one FC16 writes it.
  const DeviceMap& cnc = *m->device("cnc");
  EXPECT_EQ(cnc.find("hole_number")->address, 0);
  EXPECT_EQ(cnc.find("process_id")->address, 24);
  for (std::uint16_t a = 0; a < 25; ++a) EXPECT_NE(cnc.at(Table::Holding, a), nullptr) << a;
  EXPECT_DOUBLE_EQ(cnc.find("hole_c_deg")->max, 359.999);
}

TEST(RegisterMap, EncodeDecodeRoundTrips) {
  RegisterDef r;
  r.name = "x_mm";
  r.type = ValueType::I32;
  r.scale = 1000;
  r.min = -10000;
  r.max = 10000;
  std::uint16_t raw[2];
  ASSERT_TRUE(r.encode(-1234.567, raw).ok());
  EXPECT_EQ(raw[0], 0xFFED);  // −1234567 = 0xFFED2979, high word first
  EXPECT_EQ(raw[1], 0x2979);
  EXPECT_DOUBLE_EQ(r.decode(raw), -1234.567);
  const Status s = r.encode(10000.001, raw);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::PeripheralValueOutOfRange);
  r.type = ValueType::U32;
  r.min = 0;
  r.max = 4000000;
  ASSERT_TRUE(r.encode(4000000, raw).ok());
  EXPECT_DOUBLE_EQ(r.decode(raw), 4000000);
}

TEST(RegisterBank, StartsInRangeAndRefusesOutOfRange) {
  auto cnc = shipped_device("cnc");
  ASSERT_TRUE(cnc.ok());
  RegisterBank b(cnc.value());
  EXPECT_EQ(b.get("hole_number").value(), 1.0);  // min 1: never an out-of-range 0
  EXPECT_EQ(b.get("scan_radius_turns").value(), 1.0);
  const Status s = b.set("hole_a_deg", -95.5);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("cnc.hole_a_deg = -95.5 deg is outside -95 … 95 deg"), std::string::npos)
      << s.error().message;
  EXPECT_FALSE(b.get("nope").ok());
}

// Each bad map yields an error at the right line, naming device and entry.
struct BadMap {
  const char* what;
  const char* registers;  // the registers array of device "dev"
  const char* expect;     // substring of the message
  std::uint32_t line;     // expected line (the map text starts at line 1)
};

std::string map_text(const char* registers) {
  return std::string("version = 1\n[devices.dev]\nunit_id = 7\nregisters = [\n") + registers + "\n]\n";
}

class RegisterMapErrors : public ::testing::TestWithParam<BadMap> {};

TEST_P(RegisterMapErrors, NamesFileLineDeviceAndEntry) {
  const BadMap& c = GetParam();
  auto m = parse_register_map(map_text(c.registers), "bad.toml");
  ASSERT_FALSE(m.ok()) << c.what;
  const Diagnostic& d = m.error();
  EXPECT_EQ(d.code, ErrorCode::RegisterMapInvalid) << d.to_string();
  EXPECT_EQ(d.file, "bad.toml");
  EXPECT_EQ(d.line, c.line) << d.to_string();
  EXPECT_NE(d.message.find(c.expect), std::string::npos) << c.what << ": " << d.to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RegisterMapErrors,
    ::testing::Values(
        BadMap{"overlap",
               "{ name = \"a\", table = \"holding\", address = 0, type = \"u32\", unit = \"\", scale = 1, "
               "min = 0, max = 1, access = \"rw\" },\n"
               "{ name = \"b\", table = \"holding\", address = 1, type = \"u16\", unit = \"\", scale = 1, "
               "min = 0, max = 1, access = \"rw\" },",
               "devices.dev.b: holding 1 overlaps a (line 5)", 6},
        BadMap{"duplicate name",
               "{ name = \"a\", table = \"coil\", address = 0, type = \"bool\", access = \"rw\" },\n"
               "{ name = \"a\", table = \"coil\", address = 1, type = \"bool\", access = \"rw\" },",
               "devices.dev.a: name already used on line 5", 6},
        BadMap{"range does not fit the type",
               "{ name = \"p\", table = \"holding\", address = 0, type = \"u16\", unit = \"%\", scale = "
               "1000, min = 0, max = 100, access = \"rw\" },",
               "dev.p: range 0 … 100 at scale 1000 needs raw 0 … 100000, which a u16 cannot hold", 5},
        BadMap{"bool in a word table",
               "{ name = \"p\", table = \"input\", address = 0, type = \"bool\", access = \"r\" },",
               "dev.p: type bool in table input", 5},
        BadMap{"writable input",
               "{ name = \"p\", table = \"input\", address = 0, type = \"u16\", unit = \"\", scale = 1, min "
               "= 0, max = 1, access = \"rw\" },",
               "access = 'rw' in table input", 5},
        BadMap{"unknown key",
               "{ name = \"p\", table = \"coil\", address = 0, type = \"bool\", access = \"rw\", units = "
               "\"x\" },",
               "dev.registers[0]: unknown key 'units'", 5},
        BadMap{"unknown table",
               "{ name = \"p\", table = \"holdings\", address = 0, type = \"u16\", unit = \"\", scale = 1, "
               "min = 0, max = 1, access = \"rw\" },",
               "dev.p: table = 'holdings'; expected one of: coil, discrete, holding, input", 5},
        BadMap{"min above max",
               "{ name = \"p\", table = \"holding\", address = 0, type = \"i16\", unit = \"mm\", scale = 1, "
               "min = 5, max = 1, access = \"rw\" },",
               "dev.p: min = 5 > max = 1", 5},
        BadMap{"missing scale",
               "{ name = \"p\", table = \"holding\", address = 0, type = \"i16\", unit = \"mm\", min = 0, "
               "max = 1, access = \"rw\" },",
               "dev.p: missing key 'scale'", 5},
        BadMap{"address beyond 65535 for a u32",
               "{ name = \"p\", table = \"holding\", address = 65535, type = \"u32\", unit = \"\", scale = "
               "1, min = 0, max = 1, access = \"rw\" },",
               "dev.p: address = 65535; expected an integer 0 … 65534", 5},
        BadMap{"bad name",
               "{ name = \"Power W\", table = \"coil\", address = 0, type = \"bool\", access = \"rw\" },",
               "name must be non-empty snake_case", 5}));

TEST(RegisterMap, SyntaxErrorHasLineAndColumn) {
  auto m = parse_register_map("version = 1\n[devices.dev\nunit_id = 1\n", "broken.toml");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, ErrorCode::RegisterMapSyntax);
  EXPECT_EQ(m.error().line, 2u);
  EXPECT_GT(m.error().col, 0u);
  EXPECT_NE(m.error().to_string().find("broken.toml:2:"), std::string::npos) << m.error().to_string();
}

TEST(RegisterMap, DuplicateUnitIdAndMissingFileAreErrors) {
  auto m = parse_register_map(
      "version = 1\n"
      "[devices.a]\nunit_id = 3\nregisters = [{ name = \"x\", table = \"coil\", address = 0, type = "
      "\"bool\", access = \"rw\" }]\n"
      "[devices.b]\nunit_id = 3\nregisters = [{ name = \"x\", table = \"coil\", address = 0, type = "
      "\"bool\", access = \"rw\" }]\n",
      "dup.toml");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("unit_id 3 already used by a"), std::string::npos)
      << m.error().to_string();
  EXPECT_EQ(m.error().line, 6u);
  auto missing = load_register_map("/nonexistent/map.toml");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::FileNotFound);
  auto v2 = parse_register_map("version = 2\n", "v2.toml");
  ASSERT_FALSE(v2.ok());
  EXPECT_NE(v2.error().message.find("this build reads version 1"), std::string::npos);
}

TEST(RegisterMap, UnknownDeviceAndRegisterListWhatExists) {
  auto d = shipped_device("plasma_torch");
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("has no device 'plasma_torch'; it has: cnc, laser_source"),
            std::string::npos)
      << d.error().message;
  auto laser = shipped_device("laser_source");
  ASSERT_TRUE(laser.ok());
  auto r = laser->lookup("power");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("no register 'power'; it has: enable, alarm_reset"), std::string::npos)
      << r.error().message;
}

// The hole record's registers against its field table (holes/hole_fields.h):
// a register documented "field N" is field N, with the table's unit and
// range, a scale that carries it, and nothing missing on either side.
int field_of(const RegisterDef& r) {
  if (r.doc.rfind("field ", 0) != 0) return 0;
  return std::atoi(r.doc.c_str() + 6);
}

void expect_agrees(std::string_view device, const RegisterDef& r, const HoleField& f) {
  SCOPED_TRACE(std::string(device) + "." + r.name + " ~ field " + std::to_string(f.number) + " " +
               std::string(f.column));
  EXPECT_EQ(r.table, Table::Holding);
  EXPECT_TRUE(r.writable());
  EXPECT_EQ(r.unit, f.unit);
  EXPECT_EQ(r.min, f.lo);
  EXPECT_EQ(r.max, f.hi);
  if (f.type != HoleFieldType::Real) {
    EXPECT_EQ(r.scale, 1.0);  // whole numbers on the wire
    EXPECT_TRUE(r.type == ValueType::U16 || r.type == ValueType::U32);
  }
  if (f.lo < 0) {
    EXPECT_TRUE(r.type == ValueType::I16 || r.type == ValueType::I32);
  }
  std::uint16_t raw[2];
  EXPECT_TRUE(r.encode(f.lo, raw).ok()) << "the table's lower end does not fit the register";
  EXPECT_TRUE(r.encode(f.hi, raw).ok()) << "the table's upper end does not fit the register";
}

TEST(RegisterMap, CncParameterBlockAgreesWithTheHoleFieldTable) {
  auto m = load_register_map(default_register_map_path());
  ASSERT_TRUE(m.ok()) << m.error().to_string();
  const DeviceMap& cnc = *m->device("cnc");
  for (const HoleField& f : kHoleFields) {
    const RegisterDef* r = cnc.find(f.register_name);
    ASSERT_NE(r, nullptr) << "the map lacks field " << f.number << " (" << f.register_name << ")";
    EXPECT_EQ(field_of(*r), f.number) << r->name << ": doc '" << r->doc << "'";
    expect_agrees("cnc", *r, f);
  }
  for (const RegisterDef& r : cnc.registers) {
    if (field_of(r) == 0) continue;
    const auto k = hole_field_by_register(r.name);
    ASSERT_TRUE(k.has_value()) << "cnc." << r.name << " (" << r.doc << ") is no field of the table";
    EXPECT_EQ(kHoleFields[*k].number, field_of(r)) << r.name;
  }
}

TEST(RegisterMap, ScanHeadBlockAgreesWithTheHoleFieldTable) {
  auto m = load_register_map(default_register_map_path());
  ASSERT_TRUE(m.ok()) << m.error().to_string();
  const DeviceMap& head = *m->device("scan_head");
  std::set<int> fields;
  for (const RegisterDef& r : head.registers) {
    const int n = field_of(r);
    if (n == 0) continue;
    ASSERT_GE(n, 1);
    ASSERT_LE(n, static_cast<int>(kHoleFields.size()));
    EXPECT_TRUE(fields.insert(n).second) << "field " << n << " twice";
    expect_agrees("scan_head", r, kHoleFields[static_cast<std::size_t>(n - 1)]);
  }
  EXPECT_EQ(fields, (std::set<int>{12, 13, 14, 15, 16, 17, 18}));  // the head's parameter block
}

}  // namespace
}  // namespace lcnc::drivers

// Words shared by the Modbus master and slave: transports, function codes,
// exception codes and the endpoint description used in every message.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace lcnc::drivers {

enum class Transport : std::uint8_t { Rtu, Tcp };

// The function codes both sides implement (Modbus Application Protocol 1.1b3).
enum class Function : std::uint8_t {
  ReadCoils = 1,
  ReadDiscreteInputs = 2,
  ReadHoldingRegisters = 3,
  ReadInputRegisters = 4,
  WriteSingleCoil = 5,
  WriteSingleRegister = 6,
  WriteMultipleCoils = 15,
  WriteMultipleRegisters = 16,
};

// Exception codes a slave answers with (and a write hook may return).
enum class ModbusException : std::uint8_t {
  None = 0,
  IllegalFunction = 1,
  IllegalDataAddress = 2,
  IllegalDataValue = 3,
  DeviceFailure = 4,
  DeviceBusy = 6,
};

[[nodiscard]] constexpr std::string_view exception_name(std::uint8_t code) noexcept {
  switch (code) {
    case 1: return "illegal function";
    case 2: return "illegal data address";
    case 3: return "illegal data value";
    case 4: return "server device failure";
    case 5: return "acknowledge";
    case 6: return "server device busy";
    case 8: return "memory parity error";
    case 10: return "gateway path unavailable";
    case 11: return "gateway target failed to respond";
    default: return "unknown exception";
  }
}

// Where a device is: the transport, and host:port or the serial device path.
struct Endpoint {
  Transport transport = Transport::Tcp;
  std::string host = "127.0.0.1";  // TCP
  std::uint16_t port = 0;          // TCP; 0 = any free port (slave only)
  std::string device;              // RTU: /dev/ttyS0, /dev/pts/N
  int baud = 115200;               // RTU
  char parity = 'N';               // RTU: N, E or O (8 data bits, 1 stop bit)

  [[nodiscard]] std::string to_string() const {
    return transport == Transport::Tcp ? "tcp " + host + ":" + std::to_string(port)
                                       : "rtu " + device + " @" + std::to_string(baud);
  }
};

}  // namespace lcnc::drivers

#include "machine/pulse_sink.h"

#include <gtest/gtest.h>

namespace lcnc {
namespace {

// A sink that only takes pulses, as the GHDL co-simulation does.
class PulsesOnly final : public PulseSink {
 public:
  void send(const PulseFrame&) noexcept override {}
};

TEST(PulseSink, DefaultHasNoActiveInputs) {
  PulsesOnly sink;
  PulseSink& s = sink;
  const MachineInputs in = s.read_inputs();
  for (int i = 0; i < kAxisCount; ++i) {
    EXPECT_FALSE(in.home[i]) << i;
    EXPECT_FALSE(in.limit_min[i]) << i;
    EXPECT_FALSE(in.limit_max[i]) << i;
  }
  EXPECT_FALSE(in.estop);
  static_assert(noexcept(s.read_inputs()), "read_inputs runs on the RT thread");
}

}  // namespace
}  // namespace lcnc

#include "app/framing.h"

#include <algorithm>
#include <cstdio>

namespace lcnc::app {

Framing framing_program(const ProgramSummary& sum, const std::string& name, const Pose& here,
                        const MachineConfig& machine) {
  Framing f;
  const bool cuts = sum.feed_min[0] <= sum.feed_max[0];
  f.lo = cuts ? sum.feed_min : sum.min;
  f.hi = cuts ? sum.feed_max : sum.max;
  const double feed_mm_min = 30.0 * std::min(machine.axes[0].max_velocity, machine.axes[1].max_velocity);
  char text[512];
  std::snprintf(text, sizeof text,
                "(framing %s: X %.4f … %.4f, Y %.4f … %.4f)\n"
                "G90 G21 G61 M5\n"
                "G53 G0 X%.6f Y%.6f\n"
                "G53 G1 X%.6f F%.3f\n"
                "G53 G1 Y%.6f\n"
                "G53 G1 X%.6f\n"
                "G53 G1 Y%.6f\n"
                "G53 G0 X%.6f Y%.6f\n",
                name.c_str(), f.lo[0], f.hi[0], f.lo[1], f.hi[1], f.lo[0], f.lo[1], f.hi[0], feed_mm_min,
                f.hi[1], f.lo[0], f.lo[1], here[0], here[1]);
  f.program = text;
  return f;
}

}  // namespace lcnc::app

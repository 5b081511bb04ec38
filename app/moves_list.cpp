#include "app/moves_list.h"

#include "common/output_file.h"
#include "gcode/program_reader.h"

namespace lcnc::app {

Status write_moves(const std::string& program, const MachineConfig& machine, const std::string& out_path,
                   const std::vector<std::string>& inputs) {
  auto reader = ProgramReader::open(program, machine);
  if (!reader) return reader.error();
  auto out = OutputFile::open(out_path, inputs);
  if (!out) return out.error();
  Segment s;
  for (;;) {
    const ProgramReader::Next n = (*reader)->next(s);
    if (n == ProgramReader::Next::Error) return (*reader)->error();
    if (n == ProgramReader::Next::End) break;
    if (s.pause) {  // M0/M1/M60: the canonical program stop (its dwell holds the RT)
      out->printf("%u pause\n", s.line);
      continue;
    }
    if (s.kind == MotionKind::Dwell) {
      out->printf("%u dwell %.17g\n", s.line, s.dwell_s);
      continue;
    }
    const char* kind = s.kind == MotionKind::Rapid ? "rapid" : s.kind == MotionKind::Arc ? "arc" : "feed";
    out->printf("%u %s %.17g %.17g %.17g %.17g %.17g %.17g", s.line, kind, s.end[0], s.end[1], s.end[2],
                s.end[3], s.end[4], s.end[5]);
    if (s.kind == MotionKind::Arc) {
      const char* plane = s.plane == Plane::XY   ? "XY"
                          : s.plane == Plane::ZX ? "ZX"
                          : s.plane == Plane::YZ ? "YZ"
                                                 : "free";
      const long turns = static_cast<long>(s.extra_turns) + 1;
      out->printf(" %.17g %.17g %.17g %s %ld", s.center[0], s.center[1], s.center[2], plane,
                  s.clockwise ? -turns : turns);
    }
    out->write("\n");
  }
  return out->commit();
}

}  // namespace lcnc::app

// Where the interpreter keeps its offsets among the numbered parameters, and
// the parameter file that carries them from one job to the next.
//
// As LinuxCNC (its "Numbered Parameters" and PARAMETER_FILE), the work
// offsets, the G92 offset and the G28/G30 positions live in parameters
// #5161 … #5390; a program may read them (#5221 is G54's X), and G10, G92,
// G28.1 and G30.1 write them. Axis k of a block of nine is X Y Z A B C U V W
// (LinuxCNC's order; U V W are always 0 here). Values are mm and degrees,
// machine coordinates: the machine's units, whatever G20/G21 a program is in.
//
// The file: one parameter a line, "<index> <value>" (LinuxCNC's .var
// format), then the tools G10 L1/L10/L11 changed, one a line in LinuxCNC's
// tool table format "T<n> X<x> Y<y> Z<z> D<diameter> ;description". It is
// replaced whole (written beside, then renamed), so a job killed while
// saving leaves the previous file, never half of one.
#pragma once

#include <string>
#include <vector>

#include "common/result.h"
#include "machine/machine_config.h"

namespace lcnc::gcode {

inline constexpr int kParamAxes = 9;            // X Y Z A B C U V W
inline constexpr int kParamG28 = 5161;          // #5161 … #5169: G28 position (G28.1)
inline constexpr int kParamG30 = 5181;          // #5181 … #5189: G30 position (G30.1)
inline constexpr int kParamG92On = 5210;        // 1 while the G92 offset applies
inline constexpr int kParamG92 = 5211;          // #5211 … #5219: the G92 / G52 offset
inline constexpr int kParamCoordSystem = 5220;  // 1 … 9: G54 … G59.3 in effect
inline constexpr int kParamCoordFirst = 5221;   // G54's X; system n (0-based) at +20·n
inline constexpr int kParamCoordStride = 20;
inline constexpr int kParamCoordRotation = 9;   // +9 in a system's block: its XY rotation (R)
inline constexpr int kParamInputResult = 5399;  // M66: the input's value
inline constexpr int kParamTool = 5400;         // the tool in the spindle (M6, M61)
inline constexpr int kParamToolOffset = 5401;   // #5401 … #5409: the tool offset in effect (G43)
inline constexpr int kParamToolDiameter = 5410;
inline constexpr int kParamToolLast = 5413;  // … #5411 – #5413: its angles and orientation (lathes)
inline constexpr int kParamPosition = 5420;  // #5420 … #5428: the position, program coordinates
// Kept in the file (LinuxCNC's required set).
inline constexpr int kParamPersistentFirst = 5161;
inline constexpr int kParamPersistentLast = 5390;

// First parameter of work coordinate system `index` (0 = G54 … 8 = G59.3).
[[nodiscard]] constexpr int coord_param(int index) noexcept {
  return kParamCoordFirst + kParamCoordStride * index;
}

struct ParameterFileData {
  std::vector<std::pair<int, double>> params;  // index, value: persistent ones only
  std::vector<ToolConfig> tools;               // tools set by a program (replace the config's)
};

// Reads a parameter file. A file that does not exist is empty (the first
// job); a line that is neither a persistent parameter nor a tool is an
// error at its line and column.
[[nodiscard]] Result<ParameterFileData> read_parameter_file(const std::string& path);

// Writes #5161 … #5390 of `numbered` (indexed by parameter number) and
// `tools`, replacing the file whole.
[[nodiscard]] Status write_parameter_file(const std::string& path, const std::vector<double>& numbered,
                                          const std::vector<ToolConfig>& tools);

}  // namespace lcnc::gcode

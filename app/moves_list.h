// `lasercnc check PROGRAM --moves FILE`: the program's canonical moves, what
// the G-code front end hands the planner, one line each, so they can be read
// or compared with another interpreter's (tests/e2e/linuxcnc_canon.py prints
// LinuxCNC's in the same form). Machine coordinates, mm and degrees, every
// number in full double precision (%.17g):
//
//   LINE rapid X Y Z A B C
//   LINE feed  X Y Z A B C
//   LINE arc   X Y Z A B C  CX CY CZ  PLANE  TURNS
//   LINE dwell SECONDS
//
// X … C are the end point; CX CY CZ the arc's centre; PLANE XY, ZX or YZ;
// TURNS counts the revolutions begun, signed + counter-clockwise and −
// clockwise (LinuxCNC's canonical "rotation": 1 is an arc of less than a
// turn; G2 … P2 gives −2). Zero-length moves are not motion and not listed.
#pragma once

#include <string>
#include <vector>

#include "common/result.h"
#include "machine/machine_config.h"

namespace lcnc::app {

// `inputs`: every file the program's reading reads (app/run_job.h
// job_inputs), which the list must not be written over.
[[nodiscard]] Status write_moves(const std::string& program, const MachineConfig& machine,
                                 const std::string& out_path, const std::vector<std::string>& inputs);

}  // namespace lcnc::app

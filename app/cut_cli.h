// `lasercnc cut PART.dxf -o PART.ngc ...` — laser cutting from a DXF part as
// a 2D laser cutter's operator expects it (CypCut-style): contours nested
// into parts and holes, holes cut first, kerf compensated, pierced off the
// part with lead-ins from the scrap side, power and speed per layer; writes
// the G-code our interpreter runs, prints a summary and draws the plan
// (--svg). The algorithm is core/cut/ (cut_program.h).
//
// Exit codes as `lasercnc run`: 0 done, 1 bad input (drawing, process
// table, units, a hole too small for the kerf), 2 bad command line (an
// output that is an input or another output, too). Outputs are written
// through common/output_file.h: a refused command leaves them as they were.
#pragma once

namespace lcnc::app {

// argv[0] is "cut" (the sub-command).
int cut_main(int argc, char** argv);

}  // namespace lcnc::app

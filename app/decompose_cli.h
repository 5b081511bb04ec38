// `lasercnc decompose PART.dxf ...` — main + auxiliary axes decomposition of a
// DXF part (docs/design.md §5.7): reads the drawing, checks every contour
// closed and free of crossings, decomposes each one (synchronous mode by
// default, the paper's with --mode seed), prints a report and writes the
// kinematics table (CSV) and pictures (SVG) when asked.
//
// Exit codes as `lasercnc run`: 0 done, 1 bad input (drawing, or a contour
// speed the limits do not allow — the message gives the highest that works),
// 2 bad command line (an output that is an input or another output, too).
// The outputs (--csv, --svg, --accel-svg, --run-svg) are written through
// common/output_file.h: they replace their files only once the command has done
// its work, and a refused command leaves them as they were.
#pragma once

namespace lcnc::app {

// argv[0] is "decompose" (the sub-command), argv[1] the drawing.
int decompose_main(int argc, char** argv);

}  // namespace lcnc::app

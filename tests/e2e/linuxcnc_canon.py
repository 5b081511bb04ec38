#!/usr/bin/python3
"""LinuxCNC's own interpreter (rs274ngc, through the `gcode` module of
linuxcnc-uspace, which its AXIS preview uses) on a G-code program: prints the
canonical moves in the form of `lasercnc check --moves` (app/moves_list.h),
full double precision, mm and degrees.

    linuxcnc_canon.py PROGRAM [--units G21|G20]

Exit 0 with the moves on stdout; 1 when LinuxCNC refuses the program (its
message on stderr); 2 when its only complaint is that the file ends with no
M2, M30 or closing '%' (LinuxCNC wants one; LaserCNC ends at the file's end),
the moves read until then on stdout. No INI file and a fresh parameter file: every offset 0,
the machine at 0, block delete on; subroutine files are looked for in the
program's folder (the working folder is set to it).
"""
import os
import sys
import tempfile

import gcode

INCH = 25.4


class Canon:
    use_move_batches = False

    def __init__(self, parameter_file):
        self.parameter_file = parameter_file
        self.plane = 1
        self.line = 0
        self.last = (0.0,) * 6  # the machine starts at 0
        self.out = []

    # what rs274ngc asks of its canon
    def check_abort(self): return False
    def next_line(self, st): self.line = st.sequence_number
    def get_external_angular_units(self): return 1.0
    def get_external_length_units(self): return 1.0 / INCH
    def get_axis_mask(self): return 0x3F  # X Y Z A B C
    def get_block_delete(self): return True
    def get_tool(self, n): return (n,) + (0.0,) * 12 + (0,)
    def set_plane(self, plane): self.plane = plane
    def __getattr__(self, name):  # feeds, spindle, coolant, comments: not motion
        if name.startswith("__"):
            raise AttributeError(name)
        return lambda *args: None

    def _end(self, kind, x, y, z, a, b, c, extra=""):
        end = (x * INCH, y * INCH, z * INCH, a, b, c)
        if kind != "arc" and end == self.last:
            return  # a zero-length move is not motion
        self.last = end
        self.out.append("%d %s %s%s" % (self.line, kind, " ".join("%.17g" % v for v in end), extra))

    def straight_traverse(self, x, y, z, a, b, c, *uvw): self._end("rapid", x, y, z, a, b, c)
    def straight_feed(self, x, y, z, a, b, c, *uvw): self._end("feed", x, y, z, a, b, c)

    def arc_feed(self, first_end, second_end, first_axis, second_axis, rotation, axis_end,
                 a, b, c, *uvw):
        # LinuxCNC's planes: 1 XY (first X, second Y), 2 YZ (Y, Z), 3 XZ (Z, X)
        if self.plane == 1:
            x, y, z, cx, cy, cz, name = first_end, second_end, axis_end, first_axis, second_axis, 0.0, "XY"
        elif self.plane == 2:
            y, z, x, cy, cz, cx, name = first_end, second_end, axis_end, first_axis, second_axis, 0.0, "YZ"
        else:
            z, x, y, cz, cx, cy, name = first_end, second_end, axis_end, first_axis, second_axis, 0.0, "ZX"
        centre = " ".join("%.17g" % (v * INCH) for v in (cx, cy, cz))
        self._end("arc", x, y, z, a, b, c, " %s %s %d" % (centre, name, rotation))

    def dwell(self, seconds):
        self.out.append("%d dwell %.17g" % (self.line, seconds))


def main():
    args = sys.argv[1:]
    units = "G21"
    if "--units" in args:
        i = args.index("--units")
        units = args[i + 1]
        del args[i:i + 2]
    if len(args) != 1:
        sys.exit(__doc__)
    program = os.path.abspath(args[0])
    with tempfile.TemporaryDirectory() as tmp:
        var = os.path.join(tmp, "linuxcnc.var")
        open(var, "w").close()
        os.chdir(os.path.dirname(program))
        canon = Canon(var)
        # its chatter on stdout goes to stderr: stdout is the moves alone
        saved = os.dup(1)
        os.dup2(2, 1)
        try:
            result, seq = gcode.parse(program, canon, units, "")
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
    moves = "".join(line + "\n" for line in canon.out)
    if result > gcode.MIN_ERROR:
        message = gcode.strerror(result)
        sys.stderr.write("%s:%d: LinuxCNC: %s\n" % (program, seq, message))
        if "File ended with no percent sign or program end" in message:
            sys.stdout.write(moves)
            return 2
        return 1
    sys.stdout.write(moves)
    return 0


if __name__ == "__main__":
    sys.exit(main())

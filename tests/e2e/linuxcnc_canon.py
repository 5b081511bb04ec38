#!/usr/bin/python3
"""LinuxCNC's own interpreter (rs274ngc, through the `gcode` module of
linuxcnc-uspace, which its AXIS preview uses) on a G-code program: prints the
canonical moves in the form of `lasercnc check --moves` (app/moves_list.h),
full double precision, mm and degrees.

    linuxcnc_canon.py PROGRAM [--units G21|G20] [--tool-table FILE]

Exit 0 with the moves on stdout; 1 when LinuxCNC refuses the program (its
message on stderr); 2 when its only complaint is that the file ends with no
M2, M30 or closing '%' (LinuxCNC wants one; LaserCNC ends at the file's end),
the moves read until then on stdout; 3 when the moves stop at a tool change
that follows an arc (the `gcode` module, unlike LinuxCNC's canon, reads back
a stale position there), the moves until then on stdout. No INI file and a fresh parameter file: every offset 0,
the machine at 0, block delete on; the tool table is FILE (LinuxCNC's format),
else empty; subroutine files are looked for in the
program's folder (the working folder is set to it).
"""
import ctypes
import math
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
        # The interpreter hands its canon program coordinates and the offsets
        # apart (as LinuxCNC's own canon, emccanon, takes them): machine =
        # rotate_xy(program + G92) + G5x + tool offset.
        self.g5x = [0.0] * 6
        self.g92 = [0.0] * 6
        self.tool = [0.0] * 6
        self.rotation = 0.0

    # what rs274ngc asks of its canon
    def check_abort(self): return False
    def next_line(self, st): self.line = st.sequence_number
    def get_external_angular_units(self): return 1.0
    # A metric machine, as LaserCNC's: the tool table and the offsets in
    # #5161 … #5390 are mm. (The canon's calls are in inches whatever this
    # says: the `gcode` module's own units.)
    def get_external_length_units(self): return 1.0
    def get_axis_mask(self): return 0x3F  # X Y Z A B C
    def get_block_delete(self): return True
    # The tool in a pocket: its number and diameter (what G41/G42 reads);
    # offsets 0, as LinuxCNC's interpreter reads a loaded table's alone.
    # Pocket 0 is the spindle: the tool M6 put there.
    diameters = {}  # pocket: (tool, diameter mm), from the --tool-table file
    spindle = 0     # the pocket whose tool is in the spindle
    # The `gcode` module keeps the position its interpreter reads back after
    # a tool change from straight moves alone: after an arc, that position
    # is stale, and so is every move from there (LinuxCNC's own canon keeps
    # it right). The moves are cut off there.
    stale_from = None  # the line of such a tool change
    def change_tool(self, pocket):
        self.spindle = pocket
        if self.out and self.out[-1].split()[1] == "arc" and self.stale_from is None:
            self.stale_from = self.line
    def get_tool(self, n):
        if n == 0:
            tool, diameter = self.diameters.get(self.spindle, (0, 0.0))
        else:
            tool, diameter = self.diameters.get(n, (n, 0.0))
        return (tool,) + (0.0,) * 9 + (diameter, 0.0, 0.0, 0)
    def set_plane(self, plane): self.plane = plane
    def set_g5x_offset(self, index, x, y, z, a, b, c, *uvw): self.g5x = [x, y, z, a, b, c]
    def set_g92_offset(self, x, y, z, a, b, c, *uvw): self.g92 = [x, y, z, a, b, c]
    def set_xy_rotation(self, theta): self.rotation = theta
    def tool_offset(self, x, y, z, a, b, c, *uvw): self.tool = [x, y, z, a, b, c]

    def machine(self, p):
        p = [v + o for v, o in zip(p, self.g92)]
        if self.rotation:
            t = math.radians(self.rotation)
            p[0], p[1] = (p[0] * math.cos(t) - p[1] * math.sin(t),
                          p[0] * math.sin(t) + p[1] * math.cos(t))
        return [v + o + l for v, o, l in zip(p, self.g5x, self.tool)]
    def __getattr__(self, name):  # feeds, spindle, coolant, comments: not motion
        if name.startswith("__"):
            raise AttributeError(name)
        return lambda *args: None

    def _end(self, kind, x, y, z, a, b, c, extra=""):
        if self.stale_from is not None:
            return
        m = self.machine([x, y, z, a, b, c])
        end = (m[0] * INCH, m[1] * INCH, m[2] * INCH, m[3], m[4], m[5])
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
        # the centre through the same offsets (its normal coordinate: 0, unused)
        m = self.machine([cx, cy, cz, 0.0, 0.0, 0.0])
        centre = " ".join("%.17g" % (v * INCH) for v in m[:3])
        self._end("arc", x, y, z, a, b, c, " %s %s %d" % (centre, name, rotation))

    def dwell(self, seconds):
        if self.stale_from is not None:
            return
        self.out.append("%d dwell %.17g" % (self.line, seconds))


def load_tool_table(path):
    """rs274ngc finds a T word's tool in LinuxCNC's tool data, which its task
    process maps in; alone, as here, the interpreter would read an unmapped
    table (a segfault at the first T). Map one in this process and load
    `path` (LinuxCNC's tool table format) into it, or leave it empty. (A
    table's offsets do not reach this interpreter's G43: it reads them as
    0, and G10 L1 values as written. Its diameters reach G41/G42 through
    the canon's get_tool.)"""
    lib = ctypes.CDLL("libtooldata.so.0")
    global _tool_stat  # the map's status block, kept for the process's life
    _tool_stat = ctypes.create_string_buffer(1 << 20)
    lib._Z17tool_mmap_creatorPK13EMC_TOOL_STATi(_tool_stat, 0)
    lib._Z13tooldata_initb(0)
    if path is None:
        return
    if lib._Z13tooldata_loadPKcPPc(path.encode(), None) != 0:
        sys.exit("cannot load the tool table " + path)
    for row in open(path):
        words = {w[0].upper(): w[1:] for w in row.split(";")[0].split() if len(w) > 1}
        if "T" in words and "P" in words:
            Canon.diameters[int(words["P"])] = (int(words["T"]), float(words.get("D", 0.0)))


def main():
    args = sys.argv[1:]
    units = "G21"
    if "--units" in args:
        i = args.index("--units")
        units = args[i + 1]
        del args[i:i + 2]
    table = None
    if "--tool-table" in args:
        i = args.index("--tool-table")
        table = os.path.abspath(args[i + 1])
        del args[i:i + 2]
    if len(args) != 1:
        sys.exit(__doc__)
    program = os.path.abspath(args[0])
    load_tool_table(table)
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
    if canon.stale_from is not None:
        sys.stderr.write("%s:%d: the gcode module's position is stale after this tool change "
                         "(an arc before it): moves cut off here\n" % (program, canon.stale_from))
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Runs G-code programs through LaserCNC (`lasercnc check --moves -`) and
through LinuxCNC's own interpreter (linuxcnc_canon.py) and compares their
canonical moves: the same moves in the same order, each of the same kind
(rapid, feed, arc, dwell), end points within 1e-6 mm (1e-6 deg on A B C),
arcs with the same plane, centre (within 1e-6 mm) and signed turns, dwells
of the same time.

    compare_with_linuxcnc.py LASERCNC MACHINE.toml PROGRAM... [--at-least N]
                             [--table FILE.md] [--tool-table FILE.tbl]

Every program both accept is compared; one that only one of them accepts is
listed (a program LaserCNC accepts and LinuxCNC refuses is a failure: it
would run something LinuxCNC calls wrong), except a file LinuxCNC refuses
only for ending without M2, M30 or '%': LaserCNC ends there, and the moves
read up to it are compared, and one whose LinuxCNC moves stop at a tool
change after an arc (linuxcnc_canon.py exit 3) is compared up to there.
Exit 0 when every comparison
agrees and at least N programs were compared; 1 otherwise. The table (one
row a program) goes to --table, or to stdout. --tool-table is LinuxCNC's
tool table for the machine's [tools] (the same numbers; offsets 0, as
LinuxCNC's interpreter reads a loaded table's alone).
"""
import os
import subprocess
import sys

TOL = 1e-6
HERE = os.path.dirname(os.path.abspath(__file__))
NCFILES = "/usr/share/linuxcnc/ncfiles"  # LinuxCNC's samples: named from there


def parse_moves(text):
    moves = []
    for row in text.splitlines():
        f = row.split()
        if f[1] == "dwell":
            moves.append((int(f[0]), "dwell", [float(f[2])], None))
            continue
        if f[1] == "pause":  # M0 M1 M60: LinuxCNC's `gcode` module hands its canon no program stop
            continue
        end = [float(v) for v in f[2:8]]
        arc = None
        if f[1] == "arc":
            arc = ([float(v) for v in f[8:11]], f[11], int(f[12]))
        moves.append((int(f[0]), f[1], end, arc))
    return moves


def in_plane(centre, plane):
    x, y, z = centre
    return {"XY": (x, y), "ZX": (z, x), "YZ": (y, z)}.get(plane, (x, y, z))


def compare(ours, theirs):
    """(None, worst deviation) when they agree, else (reason, worst)."""
    worst = 0.0
    if len(ours) != len(theirs):
        n = min(len(ours), len(theirs))
        for i in range(n):
            if ours[i][1] != theirs[i][1]:
                n = i
                break
        return ("%d moves against LinuxCNC's %d (first difference at move %d, line %d)"
                % (len(ours), len(theirs), n + 1, theirs[n][0] if n < len(theirs) else ours[n][0]),
                worst)
    for i, (a, b) in enumerate(zip(ours, theirs)):
        where = "move %d (line %d)" % (i + 1, b[0])
        if a[1] != b[1]:
            return ("%s: %s against LinuxCNC's %s" % (where, a[1], b[1]), worst)
        d = max((abs(p - q) for p, q in zip(a[2], b[2])), default=0.0)
        worst = max(worst, d)
        if d > TOL:
            return ("%s: end %s against LinuxCNC's %s (%.3g apart)" % (where, a[2], b[2], d), worst)
        if a[3] is not None:
            (ca, pa, ta), (cb, pb, tb) = a[3], b[3]
            if pa != pb or ta != tb:
                return ("%s: arc in %s, %d turns against LinuxCNC's %s, %d" % (where, pa, ta, pb, tb),
                        worst)
            d = max(abs(p - q) for p, q in zip(in_plane(ca, pa), in_plane(cb, pb)))
            worst = max(worst, d)
            if d > TOL:
                return ("%s: arc centre %s against LinuxCNC's %s" % (where, ca, cb), worst)
    return (None, worst)


def main():
    args = sys.argv[1:]
    at_least, table = 0, None
    if "--at-least" in args:
        i = args.index("--at-least")
        at_least = int(args[i + 1])
        del args[i:i + 2]
    if "--table" in args:
        i = args.index("--table")
        table = args[i + 1]
        del args[i:i + 2]
    tool_table = []
    if "--tool-table" in args:
        i = args.index("--tool-table")
        tool_table = ["--tool-table", os.path.abspath(args[i + 1])]
        del args[i:i + 2]
    if len(args) < 3:
        sys.exit(__doc__)
    lasercnc, machine = os.path.abspath(args[0]), os.path.abspath(args[1])
    programs = [os.path.abspath(p) for p in args[2:]]
    rows, compared, failures = [], 0, 0
    for k, program in enumerate(programs):
        name = (os.path.relpath(program, NCFILES) if program.startswith(NCFILES + os.sep)
                else os.path.basename(program))
        sys.stderr.write("\r[%d/%d] %-40s" % (k + 1, len(programs), name[:40]))
        ours = subprocess.run([lasercnc, "check", program, "--machine", machine, "--moves", "-"],
                              capture_output=True, text=True, cwd=os.path.dirname(program) or ".")
        theirs = subprocess.run([sys.executable, os.path.join(HERE, "linuxcnc_canon.py"), program]
                                + tool_table,
                                capture_output=True, text=True)
        if ours.returncode != 0 and theirs.returncode != 0:
            rows.append((name, "-", "both refuse"))
            continue
        if ours.returncode != 0:
            rows.append((name, "-", "LaserCNC refuses: " + ours.stderr.strip().splitlines()[0].split(": ", 1)[-1][:90]))
            continue
        no_end = theirs.returncode == 2  # LinuxCNC wants an M2 at the end; the moves are whole
        cut = theirs.returncode == 3  # the gcode module's moves stop at a tool change after an arc
        if theirs.returncode != 0 and not no_end and not cut:
            failures += 1
            rows.append((name, "-", "**FAIL** LinuxCNC refuses what LaserCNC accepts: "
                         + theirs.stderr.strip().splitlines()[-1][:90]))
            continue
        a, b = parse_moves(ours.stdout), parse_moves(theirs.stdout)
        note = "; LinuxCNC also wants M2 at the end" if no_end else ""
        if cut:
            line = int(theirs.stderr.strip().splitlines()[-1].split(":")[1])
            note = ("; %d moves compared, up to the tool change on line %d (after it the "
                    "`gcode` module's position is stale)" % (len(b), line))
            a = a[:len(b)]
        why, worst = compare(a, b)
        compared += 1
        if why is None:
            rows.append((name, str(len(a)), "same (max difference %.1e)" % worst + note))
        else:
            failures += 1
            rows.append((name, str(len(a)), "**FAIL** " + why))
    sys.stderr.write("\n")
    out = ["| program | moves | LaserCNC against LinuxCNC |", "|---|---|---|"]
    out += ["| %s | %s | %s |" % (n, m, r.replace("|", "\\|")) for n, m, r in rows]
    out.append("")
    differ = sum(1 for r in rows if r[2].startswith("**FAIL**") and r[1] != "-")
    out.append("compared %d programs: %d agree, %d differ; %d refused by LinuxCNC alone"
               % (compared, compared - differ, differ, failures - differ))
    text = "\n".join(out) + "\n"
    if table:
        with open(table, "w") as f:
            f.write(text)
        print(out[-1])
    else:
        sys.stdout.write(text)
    if failures or compared < at_least:
        if compared < at_least:
            print("compared %d programs, fewer than the %d required" % (compared, at_least))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

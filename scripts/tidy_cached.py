#!/usr/bin/env python3
"""clang-tidy over sources of a build's compile_commands.json, two at a time,
with each clean verdict kept in ~/.cache/lasercnc/clang-tidy under a key made
of the source as preprocessed (so any header it includes counts), its flags,
clang-tidy's version and .clang-tidy, the checkout's path left out: a second
run, in this clone or another, checks only what changed.

A unity build's database (CMAKE_UNITY_BUILD) names the unity files only:
each source they include is checked alone, with its unity file's flags.

usage: tidy_cached.py BUILD_DIR SOURCE...   (exit 1 if any source has findings)
"""
import concurrent.futures
import hashlib
import json
import os
import shlex
import subprocess
import sys


def compiler_flags(entry):
    """The compiler and its flags of an entry, without its launcher (env
    VAR=VALUE ccache), input, output and dependency files."""
    args = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    while args and (os.path.basename(args[0]) in ("env", "ccache") or "=" in args[0]):
        args = args[1:]
    src = os.path.realpath(os.path.join(entry["directory"], entry["file"]))
    out, skip = [], False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-c", "-MD", "-MMD") or os.path.realpath(os.path.join(entry["directory"], a)) == src:
            continue
        out.append(a)
    return out


def preprocess_command(entry):
    """The entry's compile command turned into one that preprocesses to stdout."""
    return compiler_flags(entry) + [entry["file"], "-E", "-P", "-o", "-"]


def unity_sources(entry):
    """The sources a unity-build file includes (CMAKE_UNITY_BUILD), each with
    its own command: the unity file's, compiling that source instead."""
    unity = os.path.realpath(os.path.join(entry["directory"], entry["file"]))
    args = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    out = {}
    with open(unity) as f:
        for line in f:
            if line.startswith("#include \""):
                src = os.path.realpath(line.split("\"")[1])
                own = [src if os.path.realpath(os.path.join(entry["directory"], a)) == unity else a for a in args]
                out[src] = {"directory": entry["directory"], "file": src, "arguments": own}
    return out


def main():
    build, sources = sys.argv[1], sys.argv[2:]
    root = os.getcwd()
    with open(os.path.join(build, "compile_commands.json")) as f:
        entries = {}
        for e in json.load(f):
            path = os.path.realpath(os.path.join(e["directory"], e["file"]))
            entries.update(unity_sources(e) if "/Unity/unity_" in path else {path: e})
    cache = os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "lasercnc", "clang-tidy")
    os.makedirs(cache, exist_ok=True)
    version = subprocess.run(["clang-tidy", "--version"], capture_output=True, text=True).stdout
    with open(os.path.join(root, ".clang-tidy")) as f:
        rules = version + f.read()

    def check(src):
        entry = entries.get(os.path.realpath(src))
        if entry is None:
            return src, False, f"{src}: not in {build}/compile_commands.json (configure again)\n"
        pre = subprocess.run(preprocess_command(entry), cwd=entry["directory"], capture_output=True)
        key = None
        if pre.returncode == 0:
            h = hashlib.sha1()
            h.update(rules.encode())
            # the checkout's own path left out, as ccache's base_dir: another
            # clone of the same sources hits
            h.update(" ".join(compiler_flags(entry)).replace(root, "<checkout>").encode())
            h.update(pre.stdout.replace(root.encode(), b"<checkout>"))
            key = os.path.join(cache, h.hexdigest())
            if os.path.exists(key):
                return src, True, ""
        # the entry's own flags (a unity build's sources are not in the database)
        flags = compiler_flags(entry)[1:]
        r = subprocess.run(["clang-tidy", "--quiet", entry["file"], "--", "-Wno-unknown-warning-option", *flags],
                           capture_output=True, text=True, cwd=entry["directory"])
        ok = r.returncode == 0
        if ok and key:
            open(key, "w").close()
        return src, ok, "" if ok else r.stdout + r.stderr

    failed = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for n, (src, ok, text) in enumerate(pool.map(check, sources), 1):
            if not ok:
                failed += 1
                sys.stdout.write(text)
            if n % 20 == 0 or n == len(sources):
                print(f"lint: clang-tidy {n}/{len(sources)}", file=sys.stderr)
    if failed:
        print(f"lint: clang-tidy found something in {failed} sources (checks: .clang-tidy)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

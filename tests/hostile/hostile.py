#!/usr/bin/env python3
"""Hostile-input harness (issue 15): generates malformed and extreme inputs, extreme options,
output clashes and signals; runs the CLI on each with a timeout and an address-space cap; and
tallies crashes by signal, hangs, memory aborts, wrong exit codes or unclear messages, and
partial outputs left behind.

    tests/hostile/hostile.py --scansurf build/cli/scansurf [--work /tmp/hostile] [--cap-gib 6]

Prints one line per failure and a summary table (markdown). Exit status 1 when anything failed.
Standard library only; DICOM files are written byte by byte (implicit VR little endian).
"""
import argparse
import json
import math
import os
import random
import shutil
import signal
import struct
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data" / "rtstruct"
EXAMPLE = ROOT / "examples" / "phantom.json"


# ---------------------------------------------------------------------------------------------
# Inputs

def circle(r, n=24, cx=0.0, cy=0.0):
    return [[cx + r * math.cos(2 * math.pi * i / n), cy + r * math.sin(2 * math.pi * i / n)] for i in range(n)]


def contour_json(features):
    return json.dumps({"version": 1, "units": "mm", "features": features})


def feature(name, zs, contour):
    return {"name": name, "slices": [{"z": z, "contours": [contour]} for z in zs]}


def deep(depth, leaf="1"):
    return "[" * depth + leaf + "]" * depth


def json_cases():
    ok = feature("organ", [0, 2, 4], circle(10))
    base = lambda extra="": '{"version": 1, "units": "mm"' + extra + ', "features": [' + json.dumps(ok) + "]}"
    cases = {
        "deep-version": '{"version": ' + deep(200000) + ', "features": []}',
        "deep-order": base(', "order": ' + deep(200000)),
        "deep-point": '{"version": 1, "features": [{"name": "a", "slices": [{"z": 0, "contours": [[' + deep(200000, "0") + "]]}]}]}",
        "deep-object": '{"version": 1, "x": ' + '{"a":' * 100000 + "1" + "}" * 100000 + "}",
        "empty": "",
        "truncated": base()[: len(base()) // 2],
        "not-json": "hello world",
        "null": "null",
        "array-top": "[1, 2, 3]",
        "no-features": '{"version": 1}',
        "wrong-version": '{"version": 99, "features": []}',
        "string-coords": contour_json([feature("a", [0, 2], [["x", "y"], [1, 0], [0, 1]])]),
        "nan-token": base().replace("10.0", "NaN", 1),
        "inf-token": base().replace("10.0", "Infinity", 1),
        "coord-1e300": contour_json([feature("a", [0, 2], circle(1e300))]),
        "coord-1e-200": contour_json([feature("a", [0, 2], circle(1e-200))]),
        "z-1e308": contour_json([feature("a", [-1e308, 1e308], circle(10))]),
        "z-gap-1e12": contour_json([feature("a", [0, 0.002, 1e12], circle(10))]),
        "huge-number-literal": base().replace("10.0", "1" + "0" * 400, 1),
        "two-points": contour_json([feature("a", [0, 2], [[0, 0], [1, 1]])]),
        "collinear": contour_json([feature("a", [0, 2], [[0, 0], [1, 1], [2, 2], [3, 3]])]),
        "self-intersecting": contour_json([feature("a", [0, 2], [[0, 0], [10, 10], [10, 0], [0, 10]])]),
        "one-slice": contour_json([feature("a", [0], circle(10))]),
        "empty-name": contour_json([feature("", [0, 2], circle(10))]),
        "control-name": contour_json([feature("a\u001b[2J\r\nscansurf: error: forged", [0, 2], circle(10))]),
        "long-name": contour_json([feature("N" * 300, [0, 2], circle(10))]),
        "case-names": contour_json([feature("Body", [0, 2], circle(10)), feature("BODY", [0, 2], circle(10, cx=30))]),
        "slash-name": contour_json([feature("../../etc/passwd", [0, 2], circle(10))]),
        "duplicate-z": contour_json([feature("a", [0, 0, 2], circle(10))]),
        "million-point-contour": contour_json([feature("a", [0, 2], circle(40, 1000000))]),
        "many-features-5000": contour_json([feature("f%d" % i, [0, 2], [[3 * (i % 100), 3 * (i // 100)],
                                                                          [3 * (i % 100) + 2, 3 * (i // 100)],
                                                                          [3 * (i % 100) + 2, 3 * (i // 100) + 2],
                                                                          [3 * (i % 100), 3 * (i // 100) + 2]])
                                            for i in range(5000)]),
        "too-many-features-70000": contour_json([feature("f%d" % i, [0, 2], [[0, 0], [1, 0], [0, 1]]) for i in range(70000)]),
        "nested-3000": contour_json([feature("n%d" % i, [0, 2], circle(1 + 0.1 * i, 64)) for i in range(3000)]),
        "slices-20000": contour_json([feature("a", [0.5 * k for k in range(20000)], circle(10))]),
        "invalid-utf8-name": None,  # written as bytes below
    }
    return cases


def write_json_cases(work):
    paths = {}
    for name, text in json_cases().items():
        p = work / "in" / (name + ".json")
        if text is None:
            data = contour_json([feature("PLACEHOLDER", [0, 2], circle(10))]).encode().replace(b"PLACEHOLDER", b"bad\xff\xfe")
            p.write_bytes(data)
        else:
            p.write_text(text)
        paths[name] = p
    return paths


# DICOM (implicit VR little endian, no Part 10 header): a minimal RT Structure Set.
def element(group, elem, value):
    if len(value) % 2:
        value += b"\0" if group == 0x0008 and elem == 0x0016 else b" "
    return struct.pack("<HHI", group, elem, len(value)) + value


def sequence(group, elem, items):
    body = b"".join(struct.pack("<HHI", 0xFFFE, 0xE000, len(i)) + i for i in items)
    return struct.pack("<HHI", group, elem, len(body)) + body


def rtstruct(rois):
    """rois: list of (number, name, [contour point lists [(x,y,z),...]])"""
    header = element(0x0008, 0x0016, b"1.2.840.10008.5.1.4.1.1.481.3") + element(0x0008, 0x0060, b"RTSTRUCT")
    defs = [element(0x3006, 0x0022, str(n).encode()) + element(0x3006, 0x0026, name.encode()) for n, name, _ in rois]
    contours = []
    for n, _, polys in rois:
        items = []
        for pts in polys:
            data = "\\".join("%g" % c for p in pts for c in p).encode()
            items.append(element(0x3006, 0x0042, b"CLOSED_PLANAR") + element(0x3006, 0x0046, str(len(pts)).encode()) +
                         element(0x3006, 0x0050, data))
        contours.append(sequence(0x3006, 0x0040, items) + element(0x3006, 0x0084, str(n).encode()))
    return header + sequence(0x3006, 0x0020, defs) + sequence(0x3006, 0x0039, contours)


def nested_dicom(depth):
    out = element(0x0008, 0x0016, b"1.2.840.10008.5.1.4.1.1.481.3") + element(0x0008, 0x0060, b"RTSTRUCT")
    out += (struct.pack("<HHI", 0x3006, 0x0039, 0xFFFFFFFF) + struct.pack("<HHI", 0xFFFE, 0xE000, 0xFFFFFFFF)) * depth
    out += (struct.pack("<HHI", 0xFFFE, 0xE00D, 0) + struct.pack("<HHI", 0xFFFE, 0xE0DD, 0)) * depth
    return out


def square3(x, y, z, s=2.0):
    return [(x, y, z), (x + s, y, z), (x + s, y + s, z), (x, y + s, z)]


def write_dicom_cases(work, rng):
    paths = {}
    def put(name, data):
        p = work / "in" / (name + ".dcm")
        p.write_bytes(data)
        paths[name] = p
    put("dicom-nested-10000", nested_dicom(10000))
    put("dicom-nested-200000", nested_dicom(200000))
    circle_pts = lambda n, z: [(40 * math.cos(2 * math.pi * i / n), 40 * math.sin(2 * math.pi * i / n), z) for i in range(n)]
    put("dicom-contour-20000", rtstruct([(1, "big", [circle_pts(20000, 0), circle_pts(20000, 2)])]))
    put("dicom-contour-200000", rtstruct([(1, "big", [circle_pts(200000, 0), circle_pts(200000, 2)])]))
    put("dicom-contour-1000000", rtstruct([(1, "big", [circle_pts(1000000, 0), circle_pts(1000000, 2)])]))
    put("dicom-rois-10000", rtstruct([(i + 1, "R%d" % i, [square3(3 * (i % 100), 3 * (i // 100), 0)]) for i in range(10000)]))
    put("dicom-rois-70000", rtstruct([(i + 1, "R%d" % i, [square3(3 * (i % 300), 3 * (i // 300), 0)]) for i in range(70000)]))
    put("dicom-nan", rtstruct([(1, "a", [[(0, 0, 0), (float("nan"), 1, 0), (1, 1, 0)]])]))
    put("dicom-1e300", rtstruct([(1, "a", [square3(0, 0, 0, 1e300), square3(0, 0, 2, 1e300)])]))
    # Mutations of the public samples: flipped bytes, truncations, inserted garbage.
    for sample in sorted(SHARED.glob("**/*.dcm")):
        if sample.stat().st_size > 2_000_000 or "mim_phantom" in str(sample):
            continue
        data = sample.read_bytes()
        for k in range(60):
            b = bytearray(data)
            kind = k % 3
            if kind == 0:
                for _ in range(rng.randint(1, 8)):
                    b[rng.randrange(len(b))] = rng.randrange(256)
            elif kind == 1:
                b = b[: rng.randrange(len(b))]
            else:
                at = rng.randrange(len(b))
                b[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
            put("mut-%s-%02d" % (sample.stem, k), bytes(b))
    return paths


# ---------------------------------------------------------------------------------------------
# Running and judging

class Outcome:
    def __init__(self):
        self.rows = []  # (category, case, verdict, detail)

    def add(self, category, case, verdict, detail=""):
        self.rows.append((category, case, verdict, detail))
        if verdict != "ok":
            print("%-10s %-40s %-16s %s" % (category, case, verdict, detail[:300].replace("\n", " | ")), flush=True)


def snapshot(directory):
    if not directory.exists():
        return {}
    def state(p):
        st = p.lstat()
        return (st.st_size, st.st_mtime_ns, st.st_ino) if p.is_file() else None
    return {str(p.relative_to(directory)): state(p) for p in directory.rglob("*")}


def run(cmd, timeout, cap_bytes, send=None):
    """Runs cmd; send = (seconds, signal) interrupts it. Returns (code, output, seconds, timed_out)."""
    def limit():
        import resource
        resource.setrlimit(resource.RLIMIT_AS, (cap_bytes, cap_bytes))
    start = time.time()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, preexec_fn=limit)
    timed_out = False
    try:
        if send:
            try:
                out, _ = proc.communicate(timeout=send[0])
            except subprocess.TimeoutExpired:
                proc.send_signal(send[1])
                out, _ = proc.communicate(timeout=timeout)
        else:
            out, _ = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        proc.kill()
        out, _ = proc.communicate()
    return proc.returncode, out.decode("utf-8", "replace"), time.time() - start, timed_out


def judge(outcome, category, case, cmd, out_dir, expect, args, send=None, mention=None):
    """expect: set of acceptable exit codes. A failed run must leave out_dir as it was."""
    if out_dir.name == "out":  # the shared output directory: emptied, with one old file to protect
        shutil.rmtree(out_dir, ignore_errors=True)
        out_dir.mkdir(parents=True)
        (out_dir / "organ.ply").write_text("a previous result")
    before = snapshot(out_dir)
    code, text, seconds, timed_out = run(cmd, args.timeout, args.cap_gib << 30, send)
    after = snapshot(out_dir)
    if timed_out:
        return outcome.add(category, case, "hang", "over %d s" % args.timeout)
    if code < 0:
        return outcome.add(category, case, "crash", "signal %d: %s" % (-code, text[-300:]))
    if code == 8:
        return outcome.add(category, case, "memory abort", text[-300:])
    if code not in expect:
        return outcome.add(category, case, "wrong exit", "exit %d (expected %s): %s" % (code, sorted(expect), text[-300:]))
    if code != 0:
        errors = [l for l in text.splitlines() if l.startswith("scansurf: error:")]
        if not errors and code not in (2,) and not text.strip().startswith("scansurf: interrupted"):
            return outcome.add(category, case, "unclear message", text[-300:])
        if mention and mention not in text:
            return outcome.add(category, case, "unclear message", "does not name %r: %s" % (mention, text[-300:]))
        if before != after:
            changed = sorted(set(before) ^ set(after)) + [k for k in before if k in after and before[k] != after[k]]
            return outcome.add(category, case, "partial output", ", ".join(changed[:5]))
    if "\x1b" in text or "\r" in text:
        return outcome.add(category, case, "unclear message", "raw control character printed")
    outcome.add(category, case, "ok", "exit %d, %.1f s" % (code, seconds))


# ---------------------------------------------------------------------------------------------
# Second round (issue 32): the lock file, names in every format, precision, results that are
# silently wrong (judged by the report's volumes), memory outside the budget, unbounded inputs
# and paths.

def ball_json(path, units, zs, r, name="ball"):
    path.write_text(json.dumps({"version": 1, "units": units,
                                "features": [feature(name, zs, circle(r, 48))]}))
    return path


def judge_volumes(outcome, category, case, cmd, report, args, tolerance=0.05):
    """A run that must succeed with every surface's volume within tolerance of its contours'."""
    code, text, seconds, timed_out = run(cmd + ["--report", str(report)], args.timeout, args.cap_gib << 30)
    if timed_out or code != 0:
        return outcome.add(category, case, "hang" if timed_out else "wrong exit", "exit %s: %s" % (code, text[-300:]))
    rows = json.loads(report.read_text())["features"]
    for f in rows:
        want, got = f["contour_volume"], f["surface_volume"]
        if not (want > 0 and abs(got - want) <= tolerance * want):
            return outcome.add(category, case, "wrong result", "%s: surface %g, contours %g" % (f["name"], got, want))
    outcome.add(category, case, "ok", "exit 0, %.1f s, volumes within %g %%" % (seconds, 100 * tolerance))


def deflated_bomb(work):
    """A Part 10 RTSTRUCT in deflated explicit VR whose data set holds 4 GiB of zeros."""
    import zlib
    ts = b"1.2.840.10008.1.2.1.99\0"
    meta_body = struct.pack("<HH2sHI", 0x0002, 0x0001, b"OB", 0, 2) + b"\0\1"
    meta_body += struct.pack("<HH2sH", 0x0002, 0x0010, b"UI", len(ts)) + ts
    meta = struct.pack("<HH2sHI", 0x0002, 0x0000, b"UL", 4, len(meta_body)) + meta_body
    head = struct.pack("<HH2sH", 0x0008, 0x0060, b"CS", 8) + b"RTSTRUCT"
    head += struct.pack("<HH2sHI", 0x0009, 0x1010, b"OB", 0, 0xFFFFFFF0)  # a private value of zeros
    z = zlib.compressobj(9, zlib.DEFLATED, -15)
    parts = [z.compress(head)]
    zeros = bytes(1 << 24)
    for _ in range(0xFFFFFFF0 >> 24):
        parts.append(z.compress(zeros))
    parts.append(z.flush())
    p = work / "in" / "deflated-bomb.dcm"
    p.write_bytes(b"\0" * 128 + b"DICM" + meta + b"".join(parts))
    return p


def second_round(exe, work, outcome, args):
    r2 = work / "round2"
    r2.mkdir()
    ex = str(EXAMPLE)

    # Security: a lock file that is a link is never followed; names never become statements.
    victim = r2 / "victim"
    victim.write_text("keep me")
    for kind in ("link", "dangling"):
        d = r2 / ("lock-" + kind)
        d.mkdir()
        (d / ".scansurf.lock").symlink_to(victim if kind == "link" else r2 / "nowhere")
        code, text, _, _ = run([exe, ex, "-o", str(d), "-q"], args.timeout, args.cap_gib << 30)
        ok = victim.read_text() == "keep me" and not (r2 / "nowhere").exists() and code in (0, 4)
        outcome.add("security", "lock-file-" + kind, "ok" if ok else "wrong result", "exit %d: %s" % (code, text[-200:]))
    forged = ball_json(r2 / "forged.json", "mm", [0, 2, 4], 10, name='PTV "boost"\nmtllib /etc/passwd\nv 1 2 3')
    for fmt in ("obj", "ply", "stl", "glb", "nrrd"):
        d = r2 / ("names-" + fmt)
        what = ["--label-volume", str(d / "labels.nrrd")] if fmt == "nrrd" else ["--format", fmt]
        d.mkdir()
        code, text, _, _ = run([exe, str(forged), "-o", str(d)] + what + ["-q"], args.timeout, args.cap_gib << 30)
        raw = b"".join(p.read_bytes() for p in d.glob("*") if p.is_file()) if d.exists() else b""
        bad = code != 0 or b"\nmtllib /etc/passwd" in raw or b"\nv 1 2 3" in raw
        outcome.add("names", "newline-quote-name-" + fmt, "wrong result" if bad else "ok", "exit %d: %s" % (code, text[-200:]))

    # Precision: planes in any unit, coordinates far from the origin, duplicated contours.
    cases = {
        "nm-sections-in-metres": ("m", [5e-9 * k for k in range(12)], 4e-8),
        "mm-0.00005-slices": ("mm", [5e-5 * k for k in range(12)], 4e-4),
        "metres-0.5mm-slices": ("m", [5e-4 * k for k in range(20)], 0.02),
    }
    for name, (units, zs, r) in cases.items():
        judge_volumes(outcome, "precision", name, [exe, str(ball_json(r2 / (name + ".json"), units, zs, r)), "-o",
                                                   str(r2 / name), "-q"], r2 / (name + ".report.json"), args)
    pair = r2 / "slices-1e-9-apart.json"
    pair.write_text(json.dumps({"version": 1, "features": [feature("ball", [0, 1e-9, 2, 4, 6], circle(5, 48))]}))
    code, text, _, _ = run([exe, str(pair), "-o", str(r2 / "pair")], args.timeout, args.cap_gib << 30)
    outcome.add("precision", "slices-1e-9-apart-warned", "ok" if code == 0 and "merged into its plane" in text else "wrong result",
                "exit %d: %s" % (code, text[-200:]))
    far = r2 / "far-9.9e6.json"
    far.write_text(json.dumps({"version": 1, "features": [feature("f", [0, 2, 4], circle(10, 48, cx=9.9e6))]}))
    judge(outcome, "precision", "coordinates-9.9e6-voxel-0.25", [exe, str(far), "-o", str(r2 / "far"), "--voxel-size", "0.25", "-q"],
          r2 / "far", {0, 3}, args, mention="float32")
    dup = r2 / "duplicate-contour.json"
    f = feature("organ", [0, 2, 4], circle(10, 48))
    f["slices"][1]["contours"].append(f["slices"][1]["contours"][0])
    dup.write_text(json.dumps({"version": 1, "features": [f]}))
    judge_volumes(outcome, "precision", "duplicate-contour", [exe, str(dup), "-o", str(r2 / "dup"), "-q"],
                  r2 / "dup.report.json", args)

    # Memory outside the budget: smoothing of a self-crossing star, remeshing far off the grid.
    star = r2 / "star-1001.json"
    n, k = 1001, 500
    pts = [[50 * math.cos(2 * math.pi * (i * k % n) / n), 50 * math.sin(2 * math.pi * (i * k % n) / n)] for i in range(n)]
    star.write_text(json.dumps({"version": 1, "features": [{"name": "star", "slices": [{"z": z, "contours": [pts]}
                                                                                       for z in range(8)]}]}))
    judge(outcome, "memory", "star-1001-smoothing", [exe, str(star), "-o", str(r2 / "star"), "--grid", "256", "256", "-q"],
          r2 / "star", {0, 9}, args)
    for length in ("1e-6", "1e9"):
        judge(outcome, "memory", "edge-length-" + length, [exe, ex, "-o", str(r2 / "edge"), "--remesh", "--edge-length", length, "-q"],
              r2 / "edge", {2}, args, mention="--edge-length")

    # Unbounded inputs: named, refused before they are read.
    judge(outcome, "unbounded", "deflated-bomb", [exe, str(deflated_bomb(work)), "-o", str(r2 / "bomb"), "-q"], r2 / "bomb",
          {3, 9}, args, mention="deflated-bomb.dcm")
    zero = r2 / "zero.json"
    zero.symlink_to("/dev/zero")
    judge(outcome, "unbounded", "json-link-to-dev-zero", [exe, str(zero), "-o", str(r2 / "zero"), "-q"], r2 / "zero", {3}, args,
          mention="zero.json")
    fifo = r2 / "fifo.json"
    os.mkfifo(fifo)
    judge(outcome, "unbounded", "fifo-without-writer", [exe, str(fifo), "-o", str(r2 / "fifo"), "-q"], r2 / "fifo", {3}, args,
          mention="fifo.json")

    # Paths: long names, an output that is the input, SIGPIPE.
    longname = r2 / ("L" * 240 + ".json")
    shutil.copy(EXAMPLE, longname)
    judge(outcome, "paths", "file-name-240-characters", [exe, str(longname), "-o", str(r2 / ("O" * 240)), "-q"], r2, {0}, args)
    copy = r2 / "input-copy.json"
    shutil.copy(EXAMPLE, copy)
    code, text, _, _ = run([exe, str(copy), "-o", str(r2 / "same"), "--report", str(copy)], args.timeout, args.cap_gib << 30)
    intact = copy.read_bytes() == EXAMPLE.read_bytes()
    outcome.add("paths", "report-equals-input", "ok" if code == 2 and intact else "wrong result", "exit %d: %s" % (code, text[-200:]))
    pipe = r2 / "sigpipe"
    code, text, _, _ = run(["bash", "-c", "\"$0\" \"$@\" | head -c0; exit ${PIPESTATUS[0]}", exe, ex, "-o", str(pipe)],
                           args.timeout, args.cap_gib << 30)
    left = [p.name for p in pipe.iterdir() if p.name.startswith(".scansurf")] if pipe.exists() else []
    outcome.add("paths", "stdout-closed-early", "ok" if code in (0, 4) and not left else "partial output",
                "exit %d, left %s" % (code, left))


# ---------------------------------------------------------------------------------------------
# Third round (issue 55): the batches, the Python API, character sets and names, resources.

def third_round(exe, work, outcome, args):
    r3 = work / "round3"
    r3.mkdir()
    cap = args.cap_gib << 30
    python_dir = Path(args.python) if args.python else Path(exe).parent.parent / "python"
    env = dict(os.environ, PYTHONPATH=str(python_dir))

    def check(category, case, ok, detail):
        outcome.add(category, case, "ok" if ok else "wrong result", detail)

    def batch_inputs(name, count=2):
        folder = r3 / name
        folder.mkdir()
        for i in range(count):
            ball_json(folder / ("in%d.json" % i), "mm", [0, 2, 4], 5 + i)
        return folder

    # Batch: its own record, a damaged report, a pipe, an empty folder, two batches at once, a
    # link at the log, a file name that is not UTF-8.
    d = batch_inputs("own-output")
    codes = [run([exe, "batch", str(d), "-o", str(d), "-q"], args.timeout, cap)[0] for _ in range(2)]
    check("batch", "output-is-input-twice", codes == [0, 0] and not (d / "batch").exists(), "exits %s" % codes)
    d = batch_inputs("damaged-report", 1)
    run([exe, "batch", str(d), "-o", str(d / "out"), "-q"], args.timeout, cap)
    (d / "out" / "in0" / "report.json").write_text('{"cut')
    code, text, _, _ = run([exe, "batch", str(d), "-o", str(d / "out"), "-q"], args.timeout, cap)
    status = json.loads((d / "out" / "batch.json").read_text())["inputs"][0]["status"]
    check("batch", "damaged-report-rerun", code == 0 and status == "done", "exit %d, %s" % (code, status))
    os.mkfifo(r3 / "pipe.json")
    code, text, _, _ = run([exe, "batch", str(r3 / "pipe.json"), "-o", str(r3 / "pipe-out"), "-q"], args.timeout, cap)
    check("batch", "fifo-input", code == 4 and "not a regular file" in text, "exit %d: %s" % (code, text[-200:]))
    (r3 / "empty").mkdir()
    code, text, _, _ = run([exe, "batch", str(r3 / "empty"), "-o", str(r3 / "empty-out"), "-q"], args.timeout, cap)
    check("batch", "empty-folder", code == 2, "exit %d" % code)
    d = batch_inputs("at-once", 4)
    cmd = [exe, "batch", str(d), "-o", str(d / "out"), "-q", "--workers", "1"]
    first = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    code, text, _, _ = run(cmd, args.timeout, cap)
    statuses = {r["status"] for r in json.loads((d / "out" / "batch.json").read_text())["inputs"]}
    check("batch", "two-batches-at-once", first.wait() == 0 and code == 0 and statuses <= {"done", "skipped"},
          "exits %d, %d; %s" % (first.returncode, code, sorted(statuses)))
    d = batch_inputs("log-link", 1)
    victim = r3 / "precious.txt"
    victim.write_text("precious")
    (d / "out").mkdir()
    (d / "out" / ".scansurf-batch-in0.log").symlink_to(victim)
    run([exe, "batch", str(d), "-o", str(d / "out"), "-q"], args.timeout, cap)
    check("security", "batch-log-link", victim.read_text() == "precious", victim.read_text()[:40])
    d = batch_inputs("not-utf8", 0)
    shutil.copy(EXAMPLE, os.path.join(os.fsencode(d), b"caf\xe9.json"))
    code, _, _, _ = run([exe, "batch", str(d), "-o", str(d / "cli"), "-q"], args.timeout, cap)
    check("charsets", "not-utf8-file-name-cli", code == 0 and (d / "cli" / "caf_").is_dir(), "exit %d" % code)

    # Names and resources.
    nul = r3 / "nul.json"
    nul.write_text(json.dumps({"version": 1, "features": [feature("le\u0000ft", [0, 2], circle(5))]}))
    judge(outcome, "names", "nul-in-name", [exe, str(nul), "-o", str(r3 / "nul-out"), "--format", "vtp,seg.vtm", "-q"],
          r3 / "nul-out", {3}, args, mention="NUL")
    blocks = ball_json(r3 / "blocks.json", "mm", [0, 2, 4], 5, name="blocks.seg_0")
    code, text, _, _ = run([exe, str(blocks), "-o", str(r3 / "blocks"), "--format", "vtp,seg.vtm", "-q"], args.timeout, cap)
    check("names", "feature-named-as-a-segmentation-block", code == 0, "exit %d: %s" % (code, text[-200:]))
    judge(outcome, "options", "preview-8192-over-max-memory",
          [exe, str(EXAMPLE), "-o", str(r3 / "big-preview"), "--max-memory", "1G", "--preview", str(r3 / "big.png"),
           "--preview-size", "8192", "8192", "-q"], r3 / "big-preview", {9}, args, mention="preview")

    # The Python package: skipped, saying so, where it cannot be imported.
    probe = subprocess.run([sys.executable, "-c", "import scansurf"], env=env, capture_output=True)
    if probe.returncode != 0:
        outcome.add("python", "import", "ok", "skipped: scansurf not importable from %s" % python_dir)
        return
    script = r3 / "python_cases.py"
    script.write_text("""
import os, sys, json, scansurf
cs = scansurf.read(%r)
res = {}
for name, options in [("snap-off-stage", dict(smooth=False, snap=0.9)), ("iterations-huge", dict(smooth_iterations=10**7)),
                      ("threads-huge", dict(threads=100000)), ("interpolate-0", dict(interpolate=0)),
                      ("tolerance-0", dict(overlap_tolerance=0))]:
    try:
        scansurf.build(cs, voxel_size=2.0, **options); res[name] = "accepted"
    except scansurf.InvalidArgument:
        res[name] = "refused"
built = scansurf.build(cs, voxel_size=2.0)
try:
    built.write(%r, scene_name="../../x"); res["scene-name-path"] = "accepted"
except scansurf.InvalidArgument:
    res["scene-name-path"] = "refused"
print(json.dumps(res))
""" % (str(EXAMPLE), str(r3 / "py-out")))
    p = subprocess.run([sys.executable, str(script)], env=env, capture_output=True, text=True, timeout=args.timeout)
    try:
        results = json.loads(p.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        results = {}
        outcome.add("python", "options", "crash", p.stderr[-300:])
    for name, verdict in results.items():
        check("python", name, verdict == "refused", verdict)
    code = subprocess.run([sys.executable, "-m", "scansurf", "batch", str(r3 / "empty"), "-o", str(r3 / "py-empty"), "-q"],
                          env=env, capture_output=True).returncode
    check("python", "batch-empty-folder", code == 2, "exit %d" % code)
    d = r3 / "not-utf8"
    code = subprocess.run([sys.executable, "-m", "scansurf", "batch", str(d), "-o", str(d / "py"), "-q", "--serial"],
                          env=env, capture_output=True).returncode
    check("python", "batch-not-utf8-file-name", code == 0 and (d / "py" / "caf_").is_dir(), "exit %d" % code)
    unguarded = r3 / "unguarded.py"
    unguarded.write_text("import scansurf\nscansurf.batch(%r, %r)\n" % (str(EXAMPLE), str(r3 / "unguarded-out")))
    try:
        p = subprocess.run([sys.executable, str(unguarded)], env=env, capture_output=True, text=True, timeout=60)
        check("python", "batch-from-unguarded-script", p.returncode != 0 and "__main__" in p.stderr, "exit %d" % p.returncode)
    except subprocess.TimeoutExpired:
        outcome.add("python", "batch-from-unguarded-script", "hang", "over 60 s")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scansurf", required=True)
    ap.add_argument("--work", default="/tmp/scansurf-hostile")
    ap.add_argument("--timeout", type=int, default=120)
    ap.add_argument("--cap-gib", type=int, default=6)
    ap.add_argument("--quick", action="store_true", help="skip the slowest cases")
    ap.add_argument("--round2-only", action="store_true", help="only the second round's cases (issue 32)")
    ap.add_argument("--round3-only", action="store_true", help="only the third round's cases (issue 55)")
    ap.add_argument("--python", default=None, help="the Python package's folder (default: build/python beside the CLI)")
    args = ap.parse_args()
    exe = str(Path(args.scansurf).resolve())
    work = Path(args.work)
    shutil.rmtree(work, ignore_errors=True)
    (work / "in").mkdir(parents=True)
    rng = random.Random(15)
    outcome = Outcome()
    out = work / "out"

    # 1. Input files: valid ones must surface (exit 0); the rest exit 3 (or 9 when too big for
    # the memory cap), naming the file.
    for name, path in ({} if (args.round2_only or args.round3_only) else write_json_cases(work)).items():
        if args.quick and name in ("slices-20000", "nested-3000", "too-many-features-70000"):
            continue
        extra = ["--label-volume", str(out / "labels.nrrd")] if name == "z-gap-1e12" else []
        judge(outcome, "json", name, [exe, str(path), "-o", str(out), "-q"] + extra, out, {0, 3, 9}, args, mention=None)
    for name, path in ({} if (args.round2_only or args.round3_only) else write_dicom_cases(work, rng)).items():
        judge(outcome, "dicom", name + " --list-rois", [exe, str(path), "--list-rois"], out, {0, 3}, args)
        judge(outcome, "dicom", name, [exe, str(path), "-o", str(out), "-q"], out, {0, 3, 9}, args)

    # 2. Options on the bundled example.
    ex = str(EXAMPLE)
    option_cases = {
        "grid-16384": ["--grid", "16384", "16384"], "voxel-0.0078": ["--voxel-size", "0.0078"],
        "voxel-1e308": ["--voxel-size", "1e308"], "voxel-1e-300": ["--voxel-size", "1e-300"],
        "voxel-nan": ["--voxel-size", "nan"], "voxel-neg": ["--voxel-size", "-1"],
        "grid-0": ["--grid", "0", "0"], "grid-huge": ["--grid", "99999999999", "3"],
        "preview-2^31": ["--preview", str(out / "p.png"), "--preview-size", "2147483648", "2147483648"],
        "preview-16384": ["--preview", str(out / "p.png"), "--preview-size", "16384", "16384"],
        "threads-1000": ["--threads", "1000"], "threads-neg": ["--threads", "-5"],
        "device-huge": ["--device", "99999999999999999999"], "device-name": ["--device", "no-such-gpu"],
        "strength-nan": ["--smooth-strength", "nan"], "strength-0": ["--smooth-strength", "0"],
        "iterations-huge": ["--smooth-iterations", "99999999999"], "draco-bits-99": ["--format", "drc", "--draco-bits", "99"],
        "max-memory-1": ["--max-memory", "1"], "max-memory-junk": ["--max-memory", "lots"],
        "format-junk": ["--format", "xyz"], "label-volume-ext": ["--label-volume", str(out / "x.vol")],
        "dicom-seg-no-ref": ["--dicom-seg", str(out / "s.dcm")], "view-junk": ["--view", "sideways"],
        "tolerance-long-arg": ["--voxel-size", "1" * 5000],
    }
    for name, opts in ({} if (args.round2_only or args.round3_only) else option_cases).items():
        judge(outcome, "options", name, [exe, ex, "-o", str(out), "-q"] + opts, out, {0, 2, 3, 4, 5, 9}, args)

    if not (args.round2_only or args.round3_only):
        # 3. Output clashes: nothing may be replaced when any target cannot be written.
        clash = work / "clash"
        clash.mkdir()
        (clash / "BODY.ply").write_text("old body")
        (clash / "vertebra.ply").mkdir()  # a directory where a file goes
        judge(outcome, "outputs", "target-is-directory", [exe, ex, "-o", str(clash), "-q"], clash, {4}, args)
        ro = work / "readonly"
        ro.mkdir()
        (ro / "BODY.ply").write_text("old")
        ro.chmod(0o555)
        if os.geteuid() != 0:
            judge(outcome, "outputs", "read-only-dir", [exe, ex, "-o", str(ro), "-q"], ro, {4}, args)
        judge(outcome, "outputs", "output-is-file", [exe, ex, "-o", str(EXAMPLE) + "/x", "-q"], out, {4}, args)
        judge(outcome, "outputs", "report-equals-preview", [exe, ex, "-o", str(out), "--report", str(out / "a.png"),
                                                            "--preview", str(out / "a.png")], out, {2, 4}, args)
        fsz = work / "fsize"
        fsz.mkdir()
        judge(outcome, "outputs", "file-size-limit", ["bash", "-c", "ulimit -f 1024; exec \"$0\" \"$@\"", exe, ex, "-o", str(fsz), "-q"],
              fsz, {4}, args)
        lockd = work / "locked"
        lockd.mkdir()
        (lockd / ".scansurf.lock").write_text("")  # held by flock below, as another run would
        judge(outcome, "outputs", "locked-by-another-run", ["flock", str(lockd / ".scansurf.lock"), exe, ex, "-o", str(lockd), "-q"],
              lockd, {4}, args)

        # 4. Signals at several moments of a ~10 s run: exit 128 + signal, nothing left, old files kept.
        sig = work / "signals"
        sig.mkdir()
        (sig / "BODY.ply").write_text("previous")
        for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            for at in (0.3, 1.5, 3.0, 5.0, 7.0):
                judge(outcome, "signals", "%s@%.1fs" % (s.name, at),
                      [exe, ex, "-o", str(sig), "--voxel-size", "0.25", "--format", "ply,obj", "-q"], sig,
                      {0, 128 + s}, args, send=(at, s))
        # SIGKILL leaves staging behind, which the next run into the same place removes.
        for at in (1.5, 3.0, 5.0, 7.0):
            run([exe, ex, "-o", str(sig), "--voxel-size", "0.25", "--format", "ply,obj", "-q"], 60, args.cap_gib << 30,
                send=(at, signal.SIGKILL))
            code, text, _, _ = run([exe, ex, "-o", str(sig), "-q"], 60, args.cap_gib << 30)
            left = [p.name for p in sig.iterdir() if p.name.startswith(".scansurf")]
            outcome.add("signals", "SIGKILL@%.1fs then a run" % at, "ok" if code == 0 and not left else "partial output",
                        "exit %d, left %s" % (code, left))

    # 5. The second round's causes (issue 32); 6. the third round's (issue 55).
    if not args.round3_only:
        second_round(exe, work, outcome, args)
    third_round(exe, work, outcome, args)

    # Every row, for the record; then the summary.
    with open(work / "results.tsv", "w") as f:
        for row in outcome.rows:
            f.write("\t".join(row).replace("\n", " ") + "\n")
    print("every case: %s" % (work / "results.tsv"))
    cats = []
    for c, *_ in outcome.rows:
        if c not in cats:
            cats.append(c)
    verdicts = ["crash", "hang", "memory abort", "wrong exit", "unclear message", "partial output", "wrong result"]
    print("\n| category | inputs | " + " | ".join(verdicts) + " |")
    print("|---|---|" + "---|" * len(verdicts))
    total = [0] * (len(verdicts) + 1)
    for c in cats:
        rows = [r for r in outcome.rows if r[0] == c]
        counts = [sum(1 for r in rows if r[2] == v) for v in verdicts]
        total = [a + b for a, b in zip(total, [len(rows)] + counts)]
        print("| %s | %d | %s |" % (c, len(rows), " | ".join(map(str, counts))))
    print("| **all** | %d | %s |" % (total[0], " | ".join(map(str, total[1:]))))
    return 1 if any(total[1:]) else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Turns run_benchmarks.sh's results (one JSON object per set) into docs/benchmarks.md.

  make_table.py RESULTS.jsonl COMMIT [SCALING.jsonl]

SCALING.jsonl (optional): one object per run, {"set", "threads", "run", "ours"}, the whole run
at each thread count, interleaved; it adds the section on threads."""
import datetime
import json
import platform
import subprocess
import sys


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def median(values):
    v = sorted(values)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def raw_total(ours):
    """scansurf's total less the stages that shape the mesh after assembly."""
    return ours["total"] - sum(ours.get(s, 0.0) for s in ("smoothing", "triangle shape", "simplification"))


def by_set(runs):
    """Per set, in first-seen order: its runs, the run of median total (ours) and the ratios
    Slicer / scansurf pair by pair (each run's two routes ran back to back)."""
    sets = {}
    for r in runs:
        sets.setdefault(r["set"], []).append(r)
    rows = []
    for name, rs in sets.items():
        ordered = sorted(rs, key=lambda r: r["ours"]["total"])
        row = dict(ordered[(len(ordered) - 1) // 2])
        row["runs"] = len(rs)
        row["ratios"] = [r["slicer"]["total"] / r["ours"]["total"] for r in rs]
        row["ratios_raw"] = [r["slicer"]["total"] / raw_total(r["ours"]) for r in rs]
        row["slicer_totals"] = [r["slicer"]["total"] for r in rs]
        row["our_totals"] = [r["ours"]["total"] for r in rs]
        rows.append(row)
    return rows


AFTER_ASSEMBLY = ("feature surfaces", "smoothing", "triangle shape", "simplification", "audit", "write")
SCALED_STAGES = ("scan conversion", "classification", "assembly", "smoothing", "triangle shape", "simplification")


def scaling_section(runs):
    """The whole run and its stages at each thread count (medians of the runs), the speed-up
    over one thread, and the time after assembly per million output triangles per core."""
    sets = {}
    for r in runs:
        sets.setdefault(r["set"], {}).setdefault(r["threads"], []).append(r["ours"])
    if not sets:
        return []
    out = ["\n## Threads\n",
           "The whole run at each thread count (`SCANSURF_THREADS` for scansurf's CPU stages, `LP_NUM_THREADS` "
           "for lavapipe's), the thread counts interleaved run by run; medians of the runs. *after assembly*: "
           "every stage after assembly (feature surfaces, smoothing, triangle shape, simplification, audit, "
           "write), in seconds per million output triangles and per core (time × threads ÷ Mtriangles).\n"]
    head = "| set | threads | runs | " + " | ".join(SCALED_STAGES) + " | **total** | speed-up | after assembly s / Mtri / core |"
    out.append(head)
    out.append("|" + "---|" * (len(SCALED_STAGES) + 6))
    for name, by_threads in sets.items():
        base = median([o["total"] for o in by_threads.get(1, [])]) if 1 in by_threads else None
        for threads in sorted(by_threads):
            rs = by_threads[threads]
            total = median([o["total"] for o in rs])
            cells = ["%.3f" % median([o.get(s, 0.0) for o in rs]) for s in SCALED_STAGES]
            after = median([sum(o.get(s, 0.0) for s in AFTER_ASSEMBLY) * threads / (o["feature_triangles"] / 1e6)
                            for o in rs])
            speed = "%.2f×" % (base / total) if base else "–"
            out.append("| %s | %d | %d | %s | **%.2f** | %s | %.2f |" % (name, threads, len(rs), " | ".join(cells), total,
                                                                       speed, after))
    return out


def main():
    rows = by_set([json.loads(line) for line in open(sys.argv[1]) if line.strip()])
    commit = sys.argv[2]
    cores = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
    mem = subprocess.run(["free", "-g"], capture_output=True, text=True).stdout.split("\n")[1].split()[1]
    device = rows[0]["ours"].get("device", "?") if rows else "?"
    out = []
    out.append("# Benchmarks\n")
    out.append("Reproduce with one command: `tests/bench/run_benchmarks.sh` (installs plastimatch and "
               "python3-vtk9, builds, generates the sets, runs both routes, rewrites this file). "
               "`scansurf_bench run INPUT.json PIXELS [--no-smooth] [--interpolate auto|off|N] [--snap F] [--no-simplify] [--remesh]` times one input; "
               "`tests/bench/count_instructions.sh SCANSURF INPUT [OPTIONS...]` counts the instructions one run executes "
               "(valgrind's callgrind), a cost that does not drift with the machine's load; "
               "`tests/bench/cgal_reference.sh INPUT [OPTIONS...]` puts remeshing's time beside smoothing's and beside CGAL's "
               "isotropic remeshing of the same smoothed surfaces (it installs Debian's libcgal-dev). "
               "This page is the current table only: what changed and why is in CHANGELOG.md and in the commit "
               "messages, with their before and after figures.\n")
    out.append("- machine: %s, %s cores, %s GiB; Vulkan device: %s" % (cpu_name(), cores, mem, device))
    out.append("- date: %s; commit: %s\n" % (datetime.date.today().isoformat(), commit))
    out.append("Sets (generated by `scansurf_bench generate`, deterministic): `pelvis` ~30 structures, "
               "`head-neck` ~80 structures, `em-cells` ~2000 small branching objects over 300 sections. "
               "Both routes use the same grid: 512 square pixels along the longer side, the slices as layers, "
               "one background layer and pixel all around.\n")
    out.append("## Stage times (seconds) and memory\n")
    out.append("Each set's run of median total among %s; every run's two routes ran back to back, "
               "interleaved with the other runs.\n" % ", ".join("%d (%s)" % (r["runs"], r["set"]) for r in rows))
    stages = ["parse", "nesting", "grid", "scan conversion", "classification", "assembly", "feature surfaces",
              "smoothing", "triangle shape", "simplification", "write"]
    head = "| set | grid | " + " | ".join(stages) + " | **total** | floor copy | peak RSS MiB | volume+mesh MiB | triangles |"
    out.append(head)
    out.append("|" + "---|" * (len(stages) + 7))
    for r in rows:
        o = r["ours"]
        cells = [("%.3f" % o[s]) if s in o else "–" for s in stages]
        out.append("| %s | %dx%dx%d | %s | **%.2f** | %.4f | %.0f | %.0f | %d |" % (
            r["set"], o["nx"], o["ny"], o["nz"], " | ".join(cells), o["total"], o["floor_copy"],
            o["peak_rss_mib"], o["label_volume_mib"] + o["mesh_mib"], o["feature_triangles"]))
    out.append("\n## Against the 3D Slicer route and the floor\n")
    out.append("Slicer route: `plastimatch convert` to a label map, then per label `vtkDiscreteFlyingEdges3D` "
               "and `vtkWindowedSincPolyDataFilter` (Slicer's defaults) and normals.\n")
    out.append("Slicer ÷ scansurf: the median of the runs' ratios (each run's two routes back to back) and their "
               "range; the totals are each route's median.\n")
    out.append("| set | runs | scansurf s (without smoothing and simplification) | Slicer route s (rasterize / surfaces) | "
               "Slicer ÷ scansurf, median (range) | without smoothing and simplification | scan conv. + classif. s | floor s | (scan+classif) ÷ floor | "
               "peak RSS ÷ (volume+mesh) | peak RSS MiB ours / Slicer | triangles ours / Slicer |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        o, s = r["ours"], r["slicer"]
        sc = o["scan conversion"] + o["classification"]
        raw = raw_total(o)
        q = r["ratios"]
        out.append("| %s | %d | %.2f (%.2f) | %.2f (%.2f / %.2f) | **%.2f×** (%.2f–%.2f×) | %.2f× | %.3f | %.4f | %.0f× | %.2f× | %.0f / %.0f | %d / %d |" % (
            r["set"], r["runs"], median(r["our_totals"]), raw, median(r["slicer_totals"]), s["rasterize"], s["surfaces"],
            median(q), min(q), max(q), median(r["ratios_raw"]), sc, o["floor_copy"], sc / o["floor_copy"],
            o["peak_rss_mib"] / (o["label_volume_mib"] + o["mesh_mib"]), o["peak_rss_mib"], s["peak_rss_mib"],
            o["feature_triangles"], s["triangles"]))
    out.append("""
## Reading the table

- *floor*: one `memcpy` of a buffer the size of the label volume, the least any route must spend.
- On this machine the "GPU" stages (scan conversion, classification) run on lavapipe, Mesa's
  CPU implementation of Vulkan, sharing the same 2 cores; on a real GPU they are expected to
  shrink by orders of magnitude while the CPU stages stay.
- The separating surface is extracted over six tetrahedra per voxel cube (what makes it
  consistent between abutting labels, with no ambiguous cases), about three times flying
  edges' triangles; smoothing (150 sweeps' worth of constrained fairing, run as 35 Jacobi
  sweeps on the CPU) costs in proportion to them; simplification then merges them, to fewer
  than flying edges gives on pelvis and head-neck (em-cells, whose every layer is a contour
  plane whose vertices stay, keeps 2.5 times as many; docs/method.md, "Simplification").
- The scansurf runs use the defaults of the command-line tool: smoothing and simplification on, layers for
  overlapping structures, interpolation `auto` (off at these grids: the slices are 2-2.5 px
  apart), the labels kept on the device between scan conversion and classification, and
  freed memory kept for reuse (`keepFreedMemoryForReuse`, as the tool does at start).
- The Slicer route rasterizes and surfaces each structure on its own, so it grows with the
  number of structures; scansurf renders all structures of a slice at once and extracts every
  surface in one pass, so it grows with the surface area.""")
    if len(sys.argv) > 3:
        out += scaling_section([json.loads(line) for line in open(sys.argv[3]) if line.strip()])
    print("\n".join(out))


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The Python package's figures (issue 29), from a Release build with the package built
(README's build), run as:

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/python_bench.py [--build build] [--sets 40] [--runs 5]

1. Overhead of the Python layer on the bundled example: `scansurf examples/phantom.json -o DIR
   --report DIR/report.json -q` against a fresh `python3` process doing read, build and write of
   the same outputs (import included), each run --runs times, interleaved; medians and ratio.
2. Batch throughput on --sets generated structure sets (python/tests/cohort.py): serially in one
   process (the default threads: every core), on a Dask LocalCluster of 2 workers (cluster start
   included), and `scansurf batch --workers 1` and `--workers 2`; inputs per second and the
   speed-ups. The 2-worker outputs are compared with the serial ones byte for byte.
"""

import argparse
import filecmp
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python" / "tests"))

PYTHON_RUN = """
import scansurf, sys
scansurf.build(scansurf.read(sys.argv[1])).write(sys.argv[2], formats=["ply"], report="report.json")
"""


def timed(command, env=None):
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def overhead(cli, work, runs):
    example = str(ROOT / "examples" / "phantom.json")
    env = dict(os.environ)
    cli_times, py_times = [], []
    for i in range(runs):
        out = work / ("cli%d" % i)
        cli_times.append(timed([cli, example, "-o", str(out), "--report", str(out / "report.json"), "-q"]))
        py_times.append(timed([sys.executable, "-c", PYTHON_RUN, example, str(work / ("py%d" % i))], env))
    same = all(filecmp.cmp(work / "cli0" / f, work / "py0" / f, shallow=False)
               for f in os.listdir(work / "cli0") if f.endswith(".ply"))
    c, p = statistics.median(cli_times), statistics.median(py_times)
    print("bundled example, %d runs each: CLI median %.3f s (%.3f-%.3f), Python %.3f s (%.3f-%.3f): overhead %+.1f %%; "
          "surfaces identical: %s" % (runs, c, min(cli_times), max(cli_times), p, min(py_times), max(py_times),
                                      100 * (p / c - 1), same))


def batch_throughput(cli, work, count):
    import scansurf
    from cohort import write_cohort
    paths = write_cohort(str(work / "cohort"), count, scansurf)
    rates = {}
    start = time.perf_counter()
    scansurf.batch(paths, work / "serial", client="serial", progress=False)
    rates["python serial"] = count / (time.perf_counter() - start)
    start = time.perf_counter()
    summary = scansurf.batch(paths, work / "dask2", workers=2, progress=False)
    rates["python Dask, 2 workers"] = count / (time.perf_counter() - start)
    assert not summary.failed
    for workers in (1, 2):
        start = time.perf_counter()
        subprocess.run([cli, "batch", *paths, "-o", str(work / ("cli%d" % workers)), "--workers", str(workers), "-q"],
                       check=True)
        rates["CLI batch, %d worker(s)" % workers] = count / (time.perf_counter() - start)
    identical = True
    for p in paths:
        name = os.path.basename(p)[:-5]
        for f in os.listdir(work / "serial" / name):
            if f.endswith(".ply"):
                identical &= filecmp.cmp(work / "serial" / name / f, work / "dask2" / name / f, shallow=False)
                identical &= filecmp.cmp(work / "serial" / name / f, work / "cli2" / name / f, shallow=False)
    for k, v in rates.items():
        print("%-26s %6.3f inputs/s" % (k, v))
    print("Dask 2 workers / serial: %.2fx; CLI 2 workers / 1 worker: %.2fx; outputs identical to serial: %s" %
          (rates["python Dask, 2 workers"] / rates["python serial"],
           rates["CLI batch, 2 worker(s)"] / rates["CLI batch, 1 worker(s)"], identical))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default=str(ROOT / "build"))
    p.add_argument("--sets", type=int, default=40)
    p.add_argument("--runs", type=int, default=5)
    a = p.parse_args()
    cli = str(pathlib.Path(a.build) / "cli" / "scansurf")
    work = pathlib.Path(tempfile.mkdtemp(prefix="scansurf-python-bench-"))
    try:
        print("machine: %d cores; commit %s" % (os.cpu_count(), subprocess.run(
            ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()))
        overhead(cli, work, a.runs)
        batch_throughput(cli, work, a.sets)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

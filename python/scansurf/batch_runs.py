"""Whole cohorts: many contour sets surfaced on Dask, one output folder each, and a summary.

    import scansurf
    summary = scansurf.batch(["a/RS.dcm", "b/RS.dcm"], "out/")            # a local cluster
    summary = scansurf.batch(inputs, "out/", client=Client("tcp://sched:8786"))  # an existing one

Each input gets OUT/<name>/ with its surfaces and report.json, written all or nothing (the
report last, so a folder with a report is complete); OUT/summary.csv has one row per structure
and OUT/batch.json one entry per input. A rerun skips the inputs whose folder is complete, so a
batch killed half way finishes only the rest. Each worker process keeps one engine (one Vulkan
device) for all its inputs (scansurf.engine); a failing input is recorded with its error and
does not stop the others.
"""

import argparse
import csv
import json
import os
import sys
import tempfile
import time


SUMMARY_COLUMNS = ["input", "roi", "label", "volume_unit", "contour_volume", "voxel_volume", "surface_volume",
                   "triangles", "status", "seconds"]
INPUT_SUFFIXES = (".json", ".dcm", ".ser", ".mod")


class BatchSummary(list):
    """The summary rows (dicts with SUMMARY_COLUMNS), with the per-input records in .inputs."""

    def __init__(self, rows, inputs):
        super().__init__(rows)
        self.inputs = inputs

    @property
    def failed(self):
        return [i for i in self.inputs if i["status"] == "failed"]


def _task_of(item):
    """An input as a dict: {"input": path, "reference": CT folder or None, "rois": [...]}."""
    if isinstance(item, dict):
        task = dict(item)
    else:
        task = {"input": os.fspath(item)}
    task["input"] = os.fspath(task["input"])
    return task


def inputs_in(folder, out_dir=None):
    """The contour sets of a folder, sorted: .json, .dcm (RTSTRUCT), .ser, .mod files; not the
    batch's own record when the folder is also the output (out_dir/batch.json)."""
    names = sorted(os.listdir(folder))
    record = os.path.realpath(os.path.join(out_dir, "batch.json")) if out_dir is not None else None
    return [os.path.join(folder, n) for n in names if n.lower().endswith(INPUT_SUFFIXES)
            and os.path.isfile(os.path.join(folder, n)) and os.path.realpath(os.path.join(folder, n)) != record]


def _names(tasks):
    """Each input's folder name: its file name up to the first ".", made a safe file name and
    unique ignoring case, as the command-line batch names them."""
    from . import _scansurf
    # As bytes: a file name that is not UTF-8 (os.listdir's surrogate escapes) gets the
    # command line's name, byte for byte.
    stems = [os.fsencode(os.path.basename(t["input"])).split(b".")[0] or b"input" for t in tasks]
    return _scansurf._file_stems(stems)


def _volume(value):
    """A volume as the summary writes it: 7 significant digits (the CLI's %.7g)."""
    return format(value, ".7g") if isinstance(value, (int, float)) and not isinstance(value, bool) else ""


def _rows_of_report(input_path, report, status, seconds):
    """One row per structure; a skipped input's rows say so and took no time."""
    rows = []
    for f in report.get("features", []):
        rows.append({"input": input_path, "roi": f.get("name", ""), "label": f.get("label", ""),
                     "volume_unit": report.get("volume_unit", ""), "contour_volume": _volume(f.get("contour_volume")),
                     "voxel_volume": _volume(f.get("labelled_volume")), "surface_volume": _volume(f.get("surface_volume")),
                     "triangles": f.get("triangles", ""), "status": status,
                     "seconds": "" if status == "skipped" else round(seconds, 3)})
    return rows


def _report_of(folder):
    """The folder's report (written last, so the folder is complete), or None when it has none
    that reads as one: a report cut short or damaged since means the input is surfaced again."""
    try:
        with open(os.path.join(folder, "report.json"), encoding="utf-8", errors="surrogateescape") as f:
            report = json.load(f)
    except (OSError, ValueError):
        return None
    return report if isinstance(report, dict) and isinstance(report.get("features"), list) else None


def run_one(task, folder, formats, options):
    """Surfaces one input into `folder` on this process's engine; never raises for the input's
    own failure (it is returned as the record's error)."""
    from . import IoError, build, engine, read  # imported on the worker
    start = time.perf_counter()
    record = {"input": task["input"], "output": folder, "status": "done", "error": "", "rows": []}
    report = _report_of(folder)
    if report is not None:
        record["rows"] = _rows_of_report(task["input"], report, "skipped", 0.0)
        record["status"], record["seconds"] = "skipped", 0.0
        return record
    try:
        cs = read(task["input"], reference=task.get("reference"), rois=task.get("rois"), objects=task.get("objects"))
        result = build(cs, engine=engine(options.pop("device", None)), **options)
        while True:
            try:
                result.write(folder, formats=formats, report="report.json")
                break
            except IoError as e:  # another run (a second batch into this output) holds the folder: wait for it
                if "another scansurf run" not in str(e):
                    raise
                time.sleep(0.25)
                report = _report_of(folder)
                if report is not None:  # it completed the folder
                    record["rows"] = _rows_of_report(task["input"], report, "skipped", 0.0)
                    record["status"], record["seconds"] = "skipped", 0.0
                    return record
        seconds = time.perf_counter() - start
        with open(os.path.join(folder, "report.json"), encoding="utf-8", errors="surrogateescape") as f:
            record["rows"] = _rows_of_report(task["input"], json.load(f), "done", seconds)
    except Exception as e:  # the input's own failure (scansurf.Error), or its report unreadable
        record["status"], record["error"] = "failed", "%s: %s" % (type(e).__name__, e)
    record["seconds"] = time.perf_counter() - start
    return record


def _completed_elsewhere(records):
    """A run fails on a folder another run (a second batch into the same output) holds; runs are
    all or nothing, so a folder complete after such a failure was completed by the other run:
    the input is skipped, not failed."""
    for r in records:
        if r["status"] != "failed" or not r["error"].startswith("IoError"):
            continue
        report = _report_of(r["output"])
        if report is not None:
            r.update(status="skipped", error="", seconds=0.0, rows=_rows_of_report(r["input"], report, "skipped", 0.0))
    return records


def _write_atomically(path, write):
    folder = os.path.dirname(os.path.abspath(path))
    fd, staged = tempfile.mkstemp(prefix=".scansurf-", dir=folder)
    umask = os.umask(0)
    os.umask(umask)
    os.fchmod(fd, 0o666 & ~umask)  # as any file the user writes, not mkstemp's 0600
    try:
        # A file name that is not UTF-8 goes back out as the bytes it was (surrogate escapes).
        with os.fdopen(fd, "w", newline="", encoding="utf-8", errors="surrogateescape") as f:
            write(f)
        os.replace(staged, path)
    except BaseException:
        os.unlink(staged)
        raise


def write_summary(out_dir, records):
    """OUT/summary.csv (one row per structure; a failed input one row with its error) and
    OUT/batch.json (one entry per input)."""
    rows = []
    for r in records:
        if r["status"] == "failed":
            rows.append({"input": r["input"], "roi": "", "label": "", "volume_unit": "", "contour_volume": "",
                         "voxel_volume": "", "surface_volume": "", "triangles": "", "status": "failed: " + r["error"],
                         "seconds": round(r.get("seconds", 0), 3)})
        rows.extend(r["rows"])

    def csv_out(f):
        w = csv.DictWriter(f, fieldnames=SUMMARY_COLUMNS)
        w.writeheader()
        w.writerows(rows)

    _write_atomically(os.path.join(out_dir, "summary.csv"), csv_out)
    entries = [{k: r.get(k) for k in ("input", "output", "status", "error", "seconds")} for r in records]
    _write_atomically(os.path.join(out_dir, "batch.json"), lambda f: json.dump({"inputs": entries}, f, indent=2, ensure_ascii=False))
    return rows


class _Progress:
    def __init__(self, total, enabled):
        self.total, self.done, self.failed, self.enabled = total, 0, 0, enabled
        self.start = time.perf_counter()

    def step(self, record):
        self.done += 1
        self.failed += record["status"] == "failed"
        if not self.enabled:
            return
        width = 30
        filled = width * self.done // max(self.total, 1)
        elapsed = time.perf_counter() - self.start
        eta = elapsed / self.done * (self.total - self.done)
        sys.stderr.write("\r[%s%s] %d/%d inputs, %d failed, %.0f s left " %
                         ("#" * filled, " " * (width - filled), self.done, self.total, self.failed, eta))
        if self.done == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def _unguarded_script():
    """The running script's path when its top level would run again in every local worker.

    Dask starts local workers by spawning processes, and a spawned process imports the main
    script again: a batch() call at its top level, outside `if __name__ == "__main__":`, starts
    another cluster from every worker, which never ends. None when the script guards its entry
    point (or there is no script: an interactive session, python -c, a notebook).
    """
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if not path or not os.path.isfile(path) or getattr(main, "__spec__", None) is not None:
        return None  # no script, or run as a module (python -m), which spawn does not re-run
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            source = f.read()
    except OSError:
        return None
    return None if "__main__" in source else path


def _in_respawned_script():
    """Whether this call comes from the top level of the main script as a spawned process imports
    it again (see _unguarded_script); not from a worker's own code that calls batch()."""
    import multiprocessing
    main = sys.modules.get("__main__")
    if multiprocessing.parent_process() is None or getattr(main, "__name__", "") != "__mp_main__":
        return False
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_globals is vars(main) and frame.f_code.co_name == "<module>":
            return True
        frame = frame.f_back
    return False


def _local_client(workers):
    from distributed import Client, LocalCluster
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def batch(inputs, out_dir, client=None, workers=None, formats=("ply",), progress=True, **options):
    """Surfaces every input into OUT/<name>/ and writes OUT/summary.csv and OUT/batch.json.

    inputs: paths (or a folder: its .json, .dcm, .ser, .mod files), or dicts {"input": path,
        "reference": CT folder, "rois": [...], "objects": [...]}.
    client: a dask.distributed Client to run on (its workers need scansurf installed); None: a
        LocalCluster of `workers` processes (default: this machine's cores), closed at the end;
        "serial": one after another in this process.
    formats: as BuildResult.write; options: as scansurf.build (threads defaults to the cores
        divided among the local workers). Returns a BatchSummary.
    """
    if client is None:
        if _in_respawned_script():  # a worker importing an unguarded script: leave the batch to the parent
            return BatchSummary([], [])
        script = _unguarded_script()
        if script is not None:
            raise RuntimeError(
                "scansurf.batch on a local cluster runs its workers as new processes, which import %s again "
                "and would start the batch again each: put the call under `if __name__ == \"__main__\":` "
                "(or pass client=\"serial\" to run in this process)" % script)
    if isinstance(inputs, (str, os.PathLike)):  # one folder of inputs, or one input
        inputs = inputs_in(inputs, out_dir) if os.path.isdir(inputs) else [inputs]
    tasks = [_task_of(i) for i in inputs]
    os.makedirs(out_dir, exist_ok=True)
    folders = [os.path.join(os.fspath(out_dir), n) for n in _names(tasks)]
    formats = [formats] if isinstance(formats, str) else list(formats)
    bar = _Progress(len(tasks), progress)
    if client == "serial":
        records = []
        for task, folder in zip(tasks, folders):
            records.append(run_one(task, folder, formats, dict(options)))
            bar.step(records[-1])
        _completed_elsewhere(records)
        return BatchSummary(write_summary(out_dir, records), records)
    owned = None
    if client is None:
        workers = workers or os.cpu_count() or 1
        options.setdefault("threads", max(1, (os.cpu_count() or 1) // workers))
        client, owned = _local_client(workers)
    try:
        records = _run_on(client, tasks, folders, formats, options, bar)
    finally:
        if owned is not None:
            client.close()
            owned.close()
    _completed_elsewhere(records)
    return BatchSummary(write_summary(out_dir, records), records)


def _run_on(client, tasks, folders, formats, options, bar):
    from distributed import as_completed
    futures = {client.submit(run_one, t, f, formats, dict(options), pure=False): i
               for i, (t, f) in enumerate(zip(tasks, folders))}
    records = [None] * len(tasks)
    for future in as_completed(futures):
        i = futures[future]
        try:
            records[i] = future.result()
        except Exception as e:  # the worker itself died or could not import scansurf
            records[i] = {"input": tasks[i]["input"], "output": folders[i], "status": "failed",
                          "error": "%s: %s" % (type(e).__name__, e), "rows": [], "seconds": 0}
        bar.step(records[i])
    return records


_MEMORY_UNITS = {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}


def _option_value(name, text):
    """A run option's value from its command-line text, as build() takes it."""
    if name == "max_memory":  # 8G, 512M, 1.5GiB
        number = text.rstrip("iIbB")
        unit = number[-1:].upper() if number[-1:].isalpha() else ""
        if unit not in _MEMORY_UNITS:
            raise ValueError("'%s' is not a memory size such as 8G or 512M" % text)
        return int(float(number[:len(number) - len(unit)]) * _MEMORY_UNITS[unit])
    if name == "overlap_tolerance" and "," in text:  # DEPTH,PERCENT
        return tuple(float(t) for t in text.split(","))
    for convert in (int, float):
        try:
            return convert(text)
        except ValueError:
            pass
    return text  # auto, off, round, ...


def run_options(tokens):
    """The command line's run options (--interpolate off, --no-smooth, --grid 512 512, ...) as
    build() keywords; a name that is no run option raises ValueError naming it."""
    from . import _scansurf
    names = set(_scansurf._option_names())
    options, i = {}, 0
    while i < len(tokens):
        token = tokens[i]
        name, _, value = token[2:].partition("=") if token.startswith("--") else ("", "", "")
        name = name.replace("-", "_")
        i += 1
        if name.startswith("no_") and name[3:] in names and not value:
            options[name[3:]] = False
            continue
        if name not in names:
            raise ValueError("%s is not a run option (they are --%s, and --no-X for an on/off X)"
                             % (token, ", --".join(sorted(n.replace("_", "-") for n in names))))
        takes = 2 if name == "grid" else 1
        values = [value] if value else []
        while len(values) < takes and i < len(tokens) and not tokens[i].startswith("--"):
            values.append(tokens[i])
            i += 1
        if not values:
            options[name] = True  # an on/off option given alone: on
        elif len(values) < takes:
            raise ValueError("--%s takes %d values" % (token[2:], takes))
        else:
            converted = [_option_value(name, v) for v in values]
            options[name] = tuple(converted) if takes > 1 else converted[0]
    _scansurf._check_options(options)
    return options


_ON_OFF = {"smooth", "simplify", "remesh", "contour_fit", "junction_smoothing", "keep_volume", "curvature_sizing"}


def _split_run_options(argv):
    """argv's run options with their values, wherever they stand (before the inputs too), apart
    from the batch's own arguments."""
    from . import _scansurf
    names = set(_scansurf._option_names())
    own, run, i = [], [], 0
    while i < len(argv):
        name = argv[i][2:].partition("=")[0].replace("-", "_") if argv[i].startswith("--") else ""
        if name not in names and not (name.startswith("no_") and name[3:] in names):
            own.append(argv[i])
            i += 1
            continue
        takes = 0 if "=" in argv[i] or name.startswith("no_") or name in _ON_OFF else 2 if name == "grid" else 1
        run.extend(argv[i:i + 1 + takes])
        i += 1 + takes
    return own, run


def main(argv):
    """python3 -m scansurf batch INPUT... -o OUT [--workers N] [--serial] [--format F] [run options]"""
    p = argparse.ArgumentParser(prog="python3 -m scansurf batch", description="Surface many contour sets on Dask.")
    p.add_argument("command", choices=["batch"])
    p.add_argument("inputs", nargs="+", help="contour sets, or folders of them")
    p.add_argument("-o", "--output", required=True, help="output folder: OUT/<name>/, summary.csv, batch.json")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: the cores)")
    p.add_argument("--scheduler", default=None, help="address of an existing Dask scheduler (tcp://host:8786)")
    p.add_argument("--serial", action="store_true", help="one input after another in this process, no Dask")
    p.add_argument("--format", default="ply", help="comma-separated output formats (as scansurf --format)")
    p.add_argument("-q", "--quiet", action="store_true")
    p.epilog = "Any other --option is a run option, as scansurf --help lists them (e.g. --voxel-size 1 --no-smooth)."
    own, rest = _split_run_options(argv)
    a, unknown = p.parse_known_args(own)
    try:
        options = run_options(unknown + rest)
    except Exception as e:  # an unknown name, a bad value: a usage error, before any input
        sys.stderr.write("scansurf batch: error: %s\n" % e)
        return 2
    inputs = []
    for i in a.inputs:
        inputs.extend(inputs_in(i, a.output) if os.path.isdir(i) else [i])
    if not inputs:  # as the command line's batch: a usage error
        sys.stderr.write("scansurf batch: error: no contour set (.json, .dcm, .ser, .mod) among the inputs\n")
        return 2
    client = "serial" if a.serial else None
    if a.scheduler:
        from distributed import Client
        client = Client(a.scheduler)
    summary = batch(inputs, a.output, client=client, workers=a.workers, formats=a.format.split(","),
                    progress=not a.quiet, **options)
    for r in summary.failed:
        sys.stderr.write("scansurf batch: %s failed: %s\n" % (r["input"], r["error"]))
    return _exit_code(summary.failed)


def _exit_code(failed):
    """As the command line's batch: the first failed input's exit code (its error class's), 0
    when none failed; 1 for a failure that is no scansurf error (a worker that died)."""
    from . import _errors
    if not failed:
        return 0
    error = getattr(_errors, failed[0]["error"].split(":", 1)[0], None)
    return error.exit_code if isinstance(error, type) and issubclass(error, _errors.Error) else 1

"""Batch runs: on a Dask LocalCluster, serially, resumed after a kill, and the CLI's batch."""

import csv
import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

import scansurf
from cohort import write_cohort

pytest.importorskip("distributed", reason="dask.distributed is not installed (Debian: python3-distributed)")

OPTIONS = {"voxel_size": 1.5}


@pytest.fixture(scope="module")
def cohort(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cohort")
    paths = write_cohort(str(folder), 6, scansurf)
    (folder / "broken.json").write_text('{"version": 1, "features": [{"name": "x", "slices": []}]}')
    return paths, str(folder / "broken.json")


def surface_files(folder):
    return sorted(n for n in os.listdir(folder) if n.endswith(".ply"))


def test_a_local_cluster_gives_the_serial_results_byte_for_byte(tmp_path, cohort):
    paths, broken = cohort
    serial = scansurf.batch(paths + [broken], tmp_path / "serial", client="serial", progress=False, **OPTIONS)
    dask = scansurf.batch(paths + [broken], tmp_path / "dask", workers=2, progress=False, **OPTIONS)
    assert [r["status"] for r in dask.inputs] == ["done"] * 6 + ["failed"]
    for p in paths:
        name = os.path.basename(p)[:-5]
        a, b = tmp_path / "serial" / name, tmp_path / "dask" / name
        assert surface_files(a) == surface_files(b) and len(surface_files(a)) == 4
        for f in surface_files(a):
            assert filecmp.cmp(a / f, b / f, shallow=False), f
    # The failing input is recorded with its error and did not stop the others.
    failed = dask.failed[0]
    assert failed["input"] == broken and failed["error"].startswith("InvalidInput:") and "broken.json" in failed["error"]
    rows = list(csv.DictReader(open(tmp_path / "dask" / "summary.csv")))
    assert len(rows) == 6 * 3 + 1 and rows == [dict(r) for r in rows]
    assert {r["roi"] for r in rows if r["status"] == "done"} == {"Body", "Organ_A", "Organ_B"}
    assert [r for r in rows if r["status"].startswith("failed: InvalidInput")][0]["input"] == broken
    body = [r for r in rows if r["roi"] == "Body"][0]
    assert float(body["surface_volume"]) == pytest.approx(float(body["contour_volume"]), rel=0.02)
    assert json.load(open(tmp_path / "dask" / "batch.json"))["inputs"][-1]["status"] == "failed"
    assert [len(serial), len(dask)] == [len(rows), len(rows)]


def test_a_rerun_skips_what_is_complete(tmp_path, cohort):
    paths, _ = cohort
    scansurf.batch(paths[:2], tmp_path, client="serial", progress=False, **OPTIONS)
    again = scansurf.batch(paths, tmp_path, client="serial", progress=False, **OPTIONS)
    assert [r["status"] for r in again.inputs] == ["skipped"] * 2 + ["done"] * 4
    assert len(again) == 6 * 3  # the skipped inputs' rows come from their reports


def test_a_batch_killed_half_way_finishes_only_the_rest(tmp_path, cohort):
    paths, _ = cohort
    out = tmp_path / "out"
    command = [sys.executable, "-m", "scansurf", "batch", *paths, "-o", str(out), "--serial", "-q", "--voxel-size", "1.5"]
    run = subprocess.Popen(command, env=os.environ.copy())
    deadline = time.time() + 120
    while time.time() < deadline and sum((out / os.path.basename(p)[:-5] / "report.json").exists() for p in paths) < 2:
        time.sleep(0.05)
    run.send_signal(signal.SIGKILL)
    run.wait()
    finished = sum((out / os.path.basename(p)[:-5] / "report.json").exists() for p in paths)
    assert 2 <= finished < len(paths)
    subprocess.run(command, check=True, env=os.environ.copy())
    record = json.load(open(out / "batch.json"))["inputs"]
    assert [r["status"] for r in record].count("skipped") == finished
    assert [r["status"] for r in record].count("done") == len(paths) - finished
    for p in paths:  # nothing partial: each folder holds its whole output
        assert len(surface_files(out / os.path.basename(p)[:-5])) == 4


def test_the_command_line_batch_writes_the_same(tmp_path, cohort, cli):
    paths, broken = cohort
    python = scansurf.batch(paths[:3] + [broken], tmp_path / "py", client="serial", progress=False, **OPTIONS)
    run = subprocess.run([cli, "batch", *paths[:3], broken, "-o", str(tmp_path / "cli"), "--workers", "2", "-q",
                          "--voxel-size", "1.5"], capture_output=True, text=True)
    assert run.returncode == 3, run.stderr  # the failed input's exit code, after the others ran
    for p in paths[:3]:
        name = os.path.basename(p)[:-5]
        for f in surface_files(tmp_path / "py" / name):
            assert filecmp.cmp(tmp_path / "py" / name / f, tmp_path / "cli" / name / f, shallow=False)
    without_time = [{k: v for k, v in r.items() if k != "seconds"} for r in
                    csv.DictReader(open(tmp_path / "cli" / "summary.csv"))]
    expected = [{k: str(v) for k, v in r.items() if k != "seconds"} for r in python]
    assert without_time == expected
    again = subprocess.run([cli, "batch", *paths[:3], "-o", str(tmp_path / "cli")], capture_output=True, text=True)
    assert again.returncode == 0 and again.stdout.count(": skipped") == 3


def test_the_module_command_runs_on_an_existing_scheduler(tmp_path, cohort):
    from distributed import LocalCluster
    paths, _ = cohort
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as cluster:
        subprocess.run([sys.executable, "-m", "scansurf", "batch", *paths[:2], "-o", str(tmp_path), "-q",
                        "--scheduler", cluster.scheduler_address, "--voxel-size", "1.5"], check=True, env=os.environ.copy())
    assert [r["status"] for r in json.load(open(tmp_path / "batch.json"))["inputs"]] == ["done", "done"]


def test_a_folder_with_an_older_report_is_skipped_without_breaking_the_summary(tmp_path, cohort, cli):
    paths, _ = cohort
    (tmp_path / "patient00").mkdir()
    (tmp_path / "patient00" / "report.json").write_text('{"features": [{"name": "Body"}]}')  # fields of another version
    run = subprocess.run([cli, "batch", paths[0], "-o", str(tmp_path), "-q"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    rows = list(csv.DictReader(open(tmp_path / "summary.csv")))
    assert rows == [{"input": paths[0], "roi": "Body", "label": "", "volume_unit": "", "contour_volume": "",
                     "voxel_volume": "", "surface_volume": "", "triangles": "", "status": "skipped", "seconds": ""}]
    again = scansurf.batch(paths[:1], tmp_path, client="serial", progress=False)
    assert again.inputs[0]["status"] == "skipped" and again[0]["roi"] == "Body"


def test_the_command_line_batch_never_follows_a_link_at_its_log(tmp_path, cli):
    inputs, out = tmp_path / "in", tmp_path / "out"
    inputs.mkdir(), out.mkdir()
    (inputs / "a.json").write_text('{"version":1,"features":"x"}')
    victim = tmp_path / "v.txt"
    victim.write_text("precious")
    (out / ".scansurf-batch-a.log").symlink_to(victim)
    run = subprocess.run([cli, "batch", str(inputs), "-o", str(out), "-q"], capture_output=True, text=True)
    assert victim.read_text() == "precious"
    assert run.returncode != 0 and "a.json failed" in run.stderr  # quiet still names a failed input


def test_a_script_without_the_main_guard_is_refused_at_once(tmp_path, cohort):
    paths, _ = cohort
    script = tmp_path / "cohort_script.py"
    script.write_text("import scansurf\nscansurf.batch(%r, %r)\n" % (paths[0], str(tmp_path / "out")))
    run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=120,
                         env=os.environ.copy())
    assert run.returncode != 0
    assert 'if __name__ == "__main__":' in run.stderr
    assert not (tmp_path / "out").exists()


def test_a_batch_into_its_own_input_folder_never_takes_its_record_as_an_input(tmp_path, cohort, cli):
    paths, _ = cohort
    for runner in ("cli", "module"):
        folder = tmp_path / runner
        folder.mkdir()
        shutil.copy(paths[0], folder)
        for _ in range(2):  # the second run finds OUT/batch.json among the inputs
            if runner == "cli":
                command = [cli, "batch", str(folder), "-o", str(folder), "-q", "--voxel-size", "1.5"]
            else:
                command = [sys.executable, "-m", "scansurf", "batch", str(folder), "-o", str(folder), "-q", "--serial",
                           "--voxel-size", "1.5"]
            run = subprocess.run(command, capture_output=True, text=True, env=os.environ.copy())
            assert run.returncode == 0, run.stderr
        assert sorted(p.name for p in folder.iterdir() if p.is_dir()) == [os.path.basename(paths[0])[:-5]]


def test_an_empty_folder_is_a_usage_error_in_both_batches(tmp_path, cli):
    (tmp_path / "empty").mkdir()
    for command in ([cli, "batch", str(tmp_path / "empty"), "-o", str(tmp_path / "a"), "-q"],
                    [sys.executable, "-m", "scansurf", "batch", str(tmp_path / "empty"), "-o", str(tmp_path / "b"), "-q"]):
        run = subprocess.run(command, capture_output=True, text=True, env=os.environ.copy())
        assert run.returncode == 2 and "no contour set" in run.stderr, command


def test_a_file_name_that_is_not_utf8_gets_the_command_lines_folder(tmp_path, cohort, cli):
    paths, _ = cohort
    inputs = tmp_path / "inputs"
    inputs.mkdir()
    shutil.copy(paths[0], os.path.join(os.fsencode(inputs), b"caf\xe9.json"))
    summary = scansurf.batch(str(inputs), tmp_path / "py", client="serial", progress=False, **OPTIONS)
    assert not summary.failed
    subprocess.run([cli, "batch", str(inputs), "-o", str(tmp_path / "cli"), "-q", "--voxel-size", "1.5"], check=True)
    assert os.listdir(tmp_path / "py" / "caf_") and sorted(os.listdir(tmp_path / "py")) == sorted(os.listdir(tmp_path / "cli"))


def test_a_pipe_is_named_as_no_regular_file(tmp_path, cli):
    os.mkfifo(tmp_path / "pipe.json")
    run = subprocess.run([cli, "batch", str(tmp_path / "pipe.json"), "-o", str(tmp_path / "out"), "-q"],
                         capture_output=True, text=True)
    assert run.returncode == 4 and "not a regular file" in run.stderr


def test_a_damaged_report_means_the_input_is_surfaced_again(tmp_path, cohort, cli):
    paths, _ = cohort
    name = os.path.basename(paths[0])[:-5]
    for runner in ("cli", "serial"):
        out = tmp_path / runner
        for damaged in (False, True):
            if damaged:
                (out / name / "report.json").write_text('{"cut sho')
            if runner == "cli":
                subprocess.run([cli, "batch", paths[0], "-o", str(out), "-q", "--voxel-size", "1.5"], check=True)
            else:
                scansurf.batch([paths[0]], out, client="serial", progress=False, **OPTIONS)
        record = json.load(open(out / "batch.json"))["inputs"][0]
        assert record["status"] == "done", runner
        assert json.load(open(out / name / "report.json"))["features"]
        assert len(list(csv.DictReader(open(out / "summary.csv")))) == 3, runner


def test_the_module_command_passes_every_run_option_on(tmp_path, cohort, cli):
    paths, _ = cohort
    flags = ["--voxel-size", "1.5", "--interpolate", "off", "--no-smooth", "--overlap-tolerance", "1,2"]
    subprocess.run([sys.executable, "-m", "scansurf", "batch", paths[0], "-o", str(tmp_path / "py"), "-q", "--serial",
                    *flags], check=True, env=os.environ.copy())
    subprocess.run([cli, "batch", paths[0], "-o", str(tmp_path / "cli"), "-q", *flags], check=True)
    name = os.path.basename(paths[0])[:-5]
    py, cl = (json.load(open(tmp_path / d / name / "report.json")) for d in ("py", "cli"))
    assert py["parameters"]["interpolation"] == "off" and py["parameters"]["smoothing"] is False
    assert [f["surface_volume"] for f in py["features"]] == [f["surface_volume"] for f in cl["features"]]
    bad = subprocess.run([sys.executable, "-m", "scansurf", "batch", paths[0], "-o", str(tmp_path / "bad"), "--voxel-sise",
                          "1"], capture_output=True, text=True, env=os.environ.copy())
    assert bad.returncode == 2 and "--voxel-sise is not a run option" in bad.stderr and not (tmp_path / "bad").exists()


def test_two_batches_into_one_output_at_once_fail_nothing(tmp_path, cohort, cli):
    paths, _ = cohort
    out = tmp_path / "out"
    command = [cli, "batch", *paths[:4], "-o", str(out), "-q", "--workers", "1", "--voxel-size", "1.5"]
    first = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    second = subprocess.run([sys.executable, "-m", "scansurf", "batch", *paths[:4], "-o", str(out), "-q", "--serial",
                             "--voxel-size", "1.5"], capture_output=True, text=True, env=os.environ.copy())
    first_err = first.communicate()[1]
    assert first.returncode == 0, first_err
    assert second.returncode == 0, second.stderr
    assert {r["status"] for r in json.load(open(out / "batch.json"))["inputs"]} <= {"done", "skipped"}
    rows = list(csv.DictReader(open(out / "summary.csv")))
    assert len(rows) == 4 * 3 and not [r for r in rows if r["status"].startswith("failed")]


def test_an_interrupted_command_line_batch_says_what_it_kept(tmp_path, cohort, cli):
    paths, _ = cohort
    out = tmp_path / "out"
    run = subprocess.Popen([cli, "batch", *paths, "-o", str(out), "--workers", "1", "--voxel-size", "1.5"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while time.time() < deadline and not (out / os.path.basename(paths[0])[:-5] / "report.json").exists():
        time.sleep(0.05)
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate()
    assert run.returncode == 128 + signal.SIGINT
    assert ": started" in stdout  # progress before an input finishes
    assert "the inputs finished so far are kept, and a rerun skips them" in stderr
    assert "no output was written" not in stderr.split("scansurf batch: interrupted")[-1]


def test_both_batches_exit_with_the_failed_inputs_code(tmp_path, cohort, cli):
    paths, broken = cohort
    codes = []
    for command in ([cli, "batch", paths[0], broken, "-o", str(tmp_path / "cli"), "-q", "--voxel-size", "1.5"],
                    [sys.executable, "-m", "scansurf", "batch", paths[0], broken, "-o", str(tmp_path / "py"), "-q", "--serial",
                     "--voxel-size", "1.5"]):
        codes.append(subprocess.run(command, capture_output=True, env=os.environ.copy()).returncode)
    assert codes == [3, 3]  # invalid input, as a single run's exit


def test_the_command_line_batch_names_a_long_stage_while_an_input_runs(tmp_path, cli):
    from conftest import EXAMPLE
    run = subprocess.run([cli, "batch", EXAMPLE, "-o", str(tmp_path / "out")], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    stages = [line for line in lines if line.endswith(" s in)")]  # e.g. "[0/1] .../phantom.json: interpolation (2 s in)"
    assert stages, run.stdout  # the bundled example's interpolation alone runs for seconds on lavapipe
    assert lines.index(stages[0]) > 0 and ": started" in lines[0] and ": done" in lines[-1]

"""README's Python section runs as written (from a folder holding the repository's examples/)."""

import os
import re
import subprocess

import pytest

import scansurf
from conftest import ROOT
from cohort import write_cohort


def section_blocks(language):
    text = (ROOT / "README.md").read_text()
    section = text[text.index("\n## Python\n"):]
    section = section[:section.index("\n## ", 1)]
    return re.findall(r"```%s\n(.*?)```" % language, section, re.S)


@pytest.fixture
def here(tmp_path, monkeypatch):
    os.symlink(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_example_runs_as_written(here, capsys):
    exec(section_blocks("python")[0], {})
    printed = capsys.readouterr().out.split("\n")
    assert printed[0].startswith("(") and printed[1].endswith("auto")
    assert (here / "out" / "phantom-py" / "phantom.glb").exists() and (here / "out" / "phantom-py" / "rectum.ply").exists()


def test_the_batch_examples_run_as_written(here, cli):
    from distributed import Client, LocalCluster
    paths = write_cohort(str(here / "cohort"), 3, scansurf)
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, Client(cluster) as client:
        exec(section_blocks("python")[1], {"scansurf": scansurf, "paths": paths, "client": client})
    assert len(list(open(here / "out" / "cohort" / "summary.csv"))) == 1 + 3 * 3
    command = section_blocks("sh")[0].strip().replace("./build/cli/scansurf", cli)
    subprocess.run(command.split(), check=True, stdout=subprocess.DEVNULL)
    assert (here / "out" / "cohort" / "batch.json").exists()

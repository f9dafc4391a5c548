"""README's Python section runs as written (from a folder holding the repository's examples/)."""

import os
import re
import subprocess
import sys

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
    pytest.importorskip("distributed", reason="dask.distributed is not installed (Debian: python3-distributed)")
    write_cohort(str(here / "cohort"), 3, scansurf)
    (here / "cohort_example.py").write_text(section_blocks("python")[1])  # a script of its own, as a user runs it
    package = os.path.dirname(os.path.dirname(os.path.abspath(scansurf.__file__)))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [package, os.environ.get("PYTHONPATH")])))
    run = subprocess.run([sys.executable, "cohort_example.py"], capture_output=True, text=True, timeout=300, env=env)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "9 structures, 0 inputs failed"
    assert len(list(open(here / "out" / "cohort" / "summary.csv"))) == 1 + 3 * 3
    command = section_blocks("sh")[0].strip().replace("./build/cli/scansurf", cli)
    subprocess.run(command.split(), check=True, stdout=subprocess.DEVNULL)
    assert (here / "out" / "cohort" / "batch.json").exists()


def test_the_contours_snippet_of_the_python_page_runs_as_written(capsys):
    page = (ROOT / "docs" / "python.md").read_text()
    block = [b for b in re.findall(r"```python\n(.*?)```", page, re.S) if "scansurf.contours(" in b][0]
    exec(block, {})
    assert capsys.readouterr().out.strip() == "['ball', 'ring'] ['ball']"


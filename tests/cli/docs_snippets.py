#!/usr/bin/env python3
"""Every Python snippet of README.md and docs/python.md, README's batch command line, and the
C++ snippets that are whole programs but for main() (README's, the library page's first), run
(README's C++ built only: it reads an RS.dcm) as written from an installed prefix, in a scratch folder outside the source tree: the example
data copied from where the install puts it, the package found on PYTHONPATH (as README says for
a custom prefix), the command line from the prefix's bin/.

    docs_snippets.py --root SOURCE_DIR --prefix PREFIX --python-dir lib/python3/dist-packages --work DIR

Exit status 1 naming the snippet whose run failed or whose output is not what the page shows.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path


def blocks(page, language):
    return re.findall(r"```%s\n(.*?)```" % language, page.read_text(), re.S)


def run(what, command, env, cwd, timeout=600):
    done = subprocess.run(command, capture_output=True, text=True, env=env, cwd=cwd, timeout=timeout)
    if done.returncode != 0:
        sys.exit("%s failed (%d):\n%s\n%s" % (what, done.returncode, done.stdout, done.stderr))
    return done.stdout


def expect(what, condition, detail):
    if not condition:
        sys.exit("%s: %s" % (what, detail))


def cpp_program(block):
    """A C++ snippet as a program: its #include lines on top, its statements in main(), where
    `path` is the first argument (the input, as the library page names it)."""
    lines = block.splitlines()
    includes = [line for line in lines if line.startswith("#include")]
    body = [line for line in lines if not line.startswith("#include")]
    return "\n".join(includes + ["", "int main(int argc, char** argv) {",
                                  "  const char* path = argc > 1 ? argv[1] : \"examples/phantom.json\";",
                                  "  (void)path;"] + ["  " + line for line in body] + ["  return 0;", "}", ""])


def cpp_snippets(a, env):
    """README's C++ snippet and the library page's first, each built as a program against the
    installed package; the library page's run on the example (it reads `path`, writes a GLB)."""
    project = a.work / "cpp"
    project.mkdir()
    programs = {"readme_snippet": blocks(a.root / "README.md", "cpp")[0],
                "library_snippet": blocks(a.root / "docs" / "library.md", "cpp")[0]}
    for name, block in programs.items():
        (project / (name + ".cpp")).write_text(cpp_program(block))
    (project / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.25)\nproject(snippets LANGUAGES CXX)\nfind_package(scansurf REQUIRED)\n" +
        "".join("add_executable(%s %s.cpp)\ntarget_link_libraries(%s PRIVATE scansurf::scansurf)\n" % (n, n, n)
                for n in programs))
    run("configure the C++ snippets", [a.cmake, "-S", str(project), "-B", str(project / "build"), "-G", a.generator,
                                       "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + str(a.prefix)], env, a.work)
    run("build the C++ snippets", [a.cmake, "--build", str(project / "build")], env, a.work)
    run("the library page's snippet", [str(project / "build" / "library_snippet"), "examples/phantom.json"], env, a.work)
    expect("the library page's snippet", (a.work / "surfaces.glb").exists(), "no surfaces.glb")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--root", type=Path, required=True)
    p.add_argument("--prefix", type=Path, required=True)
    p.add_argument("--python-dir", required=True)
    p.add_argument("--work", type=Path, required=True)
    p.add_argument("--cmake", default="cmake")
    p.add_argument("--generator", default="Ninja")
    a = p.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    a.work.mkdir(parents=True)
    shutil.copytree(a.prefix / "share" / "doc" / "scansurf" / "examples", a.work / "examples")
    os.environ["PYTHONPATH"] = str(a.prefix / a.python_dir)  # for this process's Dask workers too
    env = dict(os.environ)
    scansurf_cli = str(a.prefix / "bin" / "scansurf")
    readme, python_page = a.root / "README.md", a.root / "docs" / "python.md"
    snippets = {}
    for page in (readme, python_page):
        for i, block in enumerate(blocks(page, "python")):
            name = "%s-%d.py" % (page.stem.lower(), i)
            (a.work / name).write_text(block)
            snippets[name] = block

    # README's example: prints a surface's shape and volumes, then the grid and the interpolation.
    out = run("README's Python example", [sys.executable, "readme-0.py"], env, a.work)
    lines = out.splitlines()
    expect("README's Python example", len(lines) == 2 and lines[0].startswith("(") and lines[1].endswith("auto"), out)
    expect("README's Python example", (a.work / "out" / "phantom-py" / "phantom.glb").exists(), "no out/phantom-py/phantom.glb")

    cpp_snippets(a, env)
    try:
        import distributed  # noqa: F401
    except ImportError:
        print("README's batch snippets and the cluster snippet skipped: dask.distributed is not installed "
              "(Debian: python3-distributed)")
        distributed = None
    out = run("the contours snippet", [sys.executable, "python-0.py"], env, a.work)
    expect("the contours snippet", out.strip() == "['ball', 'ring'] ['ball']", out)
    if distributed is None:
        return

    # README's batch script and command line, on a generated cohort.
    sys.path.insert(0, str(a.root / "python" / "tests"))
    from cohort import write_cohort
    sys.path.insert(0, env["PYTHONPATH"])
    import scansurf
    expect("the installed package", str(Path(scansurf.__file__)).startswith(str(a.prefix)), scansurf.__file__)
    paths = write_cohort(str(a.work / "cohort"), 3, scansurf)
    out = run("README's batch script", [sys.executable, "readme-1.py"], env, a.work)
    expect("README's batch script", out.strip() == "9 structures, 0 inputs failed", out)
    command = blocks(readme, "sh")
    command = [c for c in command if " batch " in c][0].strip().replace("./build/cli/scansurf", scansurf_cli)
    out = run("README's batch command line", command.split(), env, a.work)
    expect("README's batch command line", out.count(": skipped") == 3, out)  # the script did them

    # docs/python.md: a batch on an existing scheduler.
    from distributed import LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        out = run("the cluster snippet", [sys.executable, "python-1.py", cluster.scheduler_address, *paths], env, a.work)
    expect("the cluster snippet", out.strip() == "9 structures, 0 inputs failed", out)
    expect("every snippet", len(snippets) == 4, "%d Python snippets; this script runs 4: add the new one" % len(snippets))
    print("%d Python snippets, README's batch command and 2 C++ snippets ran as written from %s" % (len(snippets), a.prefix))


if __name__ == "__main__":
    main()

"""Every shell example (```sh blocks) of README.md and docs/ runs as pasted, from a scratch copy
of the checkout's layout (scenes/, scripts/, bench/, docs/ and the build beside ../shared), as the
user running the tests, with the environment the docs tell a reader to set.

What is not run, and why, is said where it is decided:
- commands that set up or build the checkout (`bash scripts/setup.sh`, `render.sh`, `test.sh`,
  `bench.sh`, `cmake ...`): CI runs the setup and the build itself (.ci/run), and this test is
  part of that run;
- a block after `<!-- shell: not run: REASON -->` in the doc, which gives its reason.
A block after `<!-- shell: after the Python example above -->` runs that ```python block first
(in the same folder), as a reader following the page would.

A command that takes more than a few seconds says so in its comment (`# ~40 s`, `# ~3 min`; a
command spread over lines with a backslash, on one of them). Such a command runs at a smaller
size unless RAYLANE_DOCS_FULL=1 is set: raylane renders at 160 pixels wide, two frames of an
animation, report sweeps of two points against a small reference, benchmarks with one short
repetition, 50,000 rays of a Python ray query; a job script (a block that starts with
`#!/bin/bash` and `#SBATCH` lines), given to the stand-in sbatch, runs two of its tasks. A block's commands run with `set -e`: the
first that fails fails the test, with its output.
"""
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import RAYLANE_EXE, SOURCE_DIR

DOCS = ["README.md"] + sorted(
    os.path.join("docs", f) for f in os.listdir(os.path.join(SOURCE_DIR, "docs"))
    if f.endswith(".md"))
FULL = os.environ.get("RAYLANE_DOCS_FULL") == "1"

# commands that set up or build the checkout: CI runs them itself
BUILDS = re.compile(r"^\s*(bash scripts/(setup|render|test|bench)\.sh\b|cmake\b)")
# a run time in a command's comment: "~40 s", "~3 min", "(~10 min)"
RUN_TIME = re.compile(r"#.*~\s*(\d+(?:\.\d+)?)\s*(s|min)\b")


def blocks():
    """(doc, line, text, marker, python block before it) of every ```sh block."""
    found = []
    for doc in DOCS:
        with open(os.path.join(SOURCE_DIR, doc), encoding="utf-8") as f:
            text = f.read()
        for m in re.finditer(r"^```sh\n(.*?)^```", text, re.S | re.M):
            line = text.count("\n", 0, m.start()) + 1
            before = text[:m.start()].rstrip("\n").splitlines()
            marker = re.match(r"<!-- shell: (.*?) -->", before[-1]).group(1) \
                if before and before[-1].startswith("<!-- shell:") else ""
            python = re.findall(r"^```python\n(.*?)^```", text[:m.start()], re.S | re.M)
            found.append((doc, line, m.group(1), marker, python[-1] if python else ""))
    return found


def seconds(comment_time):
    value, unit = comment_time
    return float(value) * (60 if unit == "min" else 1)


def logical_lines(script):
    """The block's lines with their continuations joined (for reading comments and commands)."""
    return re.sub(r"\\\n\s*", " ", script).splitlines()


def is_slow(line):
    return any(seconds(m) > 5 for m in RUN_TIME.findall(line))


def shrink(line):
    """A command at the smaller size (see the module's docstring)."""
    if re.search(r"\braylane (render|compare|report)\b", line) and "assemble" not in line:
        if re.search(r"--width \d+", line):
            line = re.sub(r"--width \d+", "--width 160", line)
            line = re.sub(r"--height \d+", "--height 90", line)
        else:
            line = re.sub(r"\braylane (render|compare|report)\b", r"raylane \1 --width 160", line,
                          count=1)
        line = re.sub(r"--frames (all|0\.\.71)", "--frames 0..1", line)
        line = re.sub(r"--spp-list [\d,]+", "--spp-list 1,2", line)
        line = re.sub(r"--reference-spp \d+", "--reference-spp 16", line)
        if "raylane report" in line and "--reference-spp" not in line:
            line = line.replace("raylane report", "raylane report --reference-spp 16", 1)
    line = re.sub(r"--benchmark_min_time=[\d.]+", "--benchmark_min_time=0.01", line)
    line = re.sub(r"--benchmark_repetitions=\d+", "--benchmark_repetitions=1", line)
    if re.search(r"bench/bench_\w+", line) and "--benchmark_min_time" not in line:
        line = re.sub(r"(bench/bench_\w+)", r"\1 --benchmark_min_time=0.01", line, count=1)
    line = re.sub(r"--rounds \d+", "--rounds 1", line)
    if "ray_queries.py" in line:
        line = line.replace("ray_queries.py", "ray_queries.py --rays 50000 --min-time 0.01", 1)
    line = re.sub(r"\bseq 0 71\b", "seq 0 1", line)
    line = re.sub(r"--array=0-71\b", "--array=0-1", line)
    return line


def prepared(script):
    """The block as it runs: build commands left out (each says so), slow ones shrunk."""
    out = []
    for line in logical_lines(script):
        if BUILDS.match(line):
            out.append("true  # not run here, it sets up or builds the checkout: " + line)
        else:
            out.append(shrink(line) if is_slow(line) and not FULL else line)
    return "\n".join(out) + "\n"


SBATCH = r'''#!/usr/bin/env python3
"""A stand-in for SLURM's sbatch: runs the job at once, every task of an array in turn (the
first SBATCH_MAX_TASKS of them, when set). Takes options on its command line or in the job
script's #SBATCH lines."""
import os, subprocess, sys
args, wrap, script, tasks = sys.argv[1:], None, None, [None]
for a in list(args):
    if not a.startswith("--") and os.path.isfile(a):
        args += [l.split()[1] for l in open(a) if l.startswith("#SBATCH ")]
i = 0
while i < len(args):
    a = args[i]
    if a == "--wrap":
        wrap = args[i + 1]; i += 1
    elif a.startswith("--array="):
        lo, hi = a.split("=")[1].split("-"); tasks = range(int(lo), int(hi) + 1)
    elif a.startswith("--cpus-per-task="):
        os.environ["SLURM_CPUS_PER_TASK"] = a.split("=")[1]
    elif not a.startswith("--"):
        script = a
    i += 1
if tasks != [None] and "SBATCH_MAX_TASKS" in os.environ:
    tasks = list(tasks)[: int(os.environ["SBATCH_MAX_TASKS"])]
for t in tasks:
    env = dict(os.environ)
    if t is not None:
        env["SLURM_ARRAY_TASK_ID"] = str(t)
    cmd = ["bash", "-c", wrap] if wrap is not None else ["bash", script]
    if subprocess.run(cmd, env=env).returncode != 0:
        sys.exit(1)
if "--parsable" in args:
    print(1)
'''


def scratch(tmp_path):
    """A checkout's layout in tmp_path/raylane beside tmp_path/shared: links to the sources and
    the build, a copy of docs/ (a command may rewrite a page), a bin/ with sbatch."""
    root = tmp_path / "raylane"
    root.mkdir()
    for name in ["scenes", "scripts", "bench", "python", "src", "README.md"]:
        os.symlink(os.path.join(SOURCE_DIR, name), root / name)
    shutil.copytree(os.path.join(SOURCE_DIR, "docs"), root / "docs")
    (root / "build").mkdir()
    os.symlink(os.path.dirname(RAYLANE_EXE), root / "build" / "release")
    shared = os.path.normpath(os.path.join(SOURCE_DIR, "..", "shared"))
    if os.path.isdir(shared):
        os.symlink(shared, tmp_path / "shared")
    home = tmp_path / "home"
    (home / "bin").mkdir(parents=True)
    (home / "bin" / "sbatch").write_text(SBATCH)
    (home / "bin" / "sbatch").chmod(0o755)
    if os.path.isdir(shared):
        os.symlink(os.path.join(shared, "models"), home / "models")
    return root, home


def environment(root, home):
    env = {k: v for k, v in os.environ.items() if k not in ("RAYLANE_MODEL_PATH", "PYTHONPATH")}
    env["HOME"] = str(home)
    # `raylane` alone (docs/distributed.md) is the one on PATH: the build's
    env["PATH"] = os.pathsep.join([str(home / "bin"), str(root / "build" / "release"),
                                   env.get("PATH", "")])
    if os.geteuid() == 0:  # what the README's comment tells root to set for Open MPI
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    # what README.md and docs/python.md tell a reader to export first
    shared = root.parent / "shared"
    env["RAYLANE_MODEL_PATH"] = f"{shared}/models:{shared}/textures"
    env["PYTHONPATH"] = str(root / "build" / "release" / "python")
    return env


def test_the_docs_have_shell_examples():
    assert len(blocks()) >= 15


def test_every_run_time_comment_reads_as_one():
    # a "~N s" the pattern misses would leave a slow command at full size
    for doc, line, script, _, _ in blocks():
        for text in logical_lines(script):
            if "~" in text.split("#", 1)[-1] and "#" in text:
                assert RUN_TIME.search(text), f"{doc}:{line}: {text}"


@pytest.mark.parametrize("index", range(len(blocks())),
                         ids=[f"{b[0]}:{b[1]}" for b in blocks()])
def test_shell_example_runs_as_pasted(tmp_path, index):
    if not RAYLANE_EXE:
        pytest.skip("RAYLANE_EXE is not set")
    doc, line, script, marker, python = blocks()[index]
    if marker.startswith("not run:"):
        pytest.skip(f"{doc}:{line}: {marker}")
    root, home = scratch(tmp_path)
    env = environment(root, home)
    if marker == "after the Python example above":
        p = subprocess.run([sys.executable, "-c", python], cwd=root, env=env,
                           capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
    else:
        assert marker == "", f"{doc}:{line}: unknown marker {marker!r}"
    if script.startswith("#!/bin/bash\n#SBATCH"):  # a job script: given to sbatch
        (root / "job.sh").write_text(script)
        script = "sbatch job.sh\n"
        if not FULL:  # a frame a task: two of them
            env["SBATCH_MAX_TASKS"] = "2"
    p = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", prepared(script)], cwd=root,
                       env=env, capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, (f"{doc}:{line} failed ({p.returncode}):\n{prepared(script)}\n"
                               f"--- stdout\n{p.stdout[-3000:]}\n--- stderr\n{p.stderr[-3000:]}")

"""Every Python example in docs/python.md runs as written, from a folder that holds the
checkout's scenes/ (as the checkout itself does), and prints what its comments say it prints."""
import os
import re
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR, model_or_skip

DOC = os.path.join(SOURCE_DIR, "docs", "python.md")


def examples():
    with open(DOC, encoding="utf-8") as f:
        return re.findall(r"```python\n(.*?)```", f.read(), re.S)


def test_the_doc_has_examples():
    assert len(examples()) >= 6


@pytest.mark.parametrize("index", range(len(examples())))
def test_example_runs_as_written(tmp_path, index):
    model_or_skip("bunny.ply")
    model_or_skip("dragon.ply")
    code = examples()[index]
    os.symlink(os.path.join(SOURCE_DIR, "scenes"), tmp_path / "scenes")
    p = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True,
                       env={**os.environ, "MPLBACKEND": "Agg"})
    assert p.returncode == 0, p.stderr
    # the comment of a print call ("print(x)  # [ 0 -1]") is what it printed
    shown = [m.group(1).strip() for m in re.finditer(r"^\s*print\(.*\)\s+# (.*)$", code, re.M)]
    printed = [line.strip() for line in p.stdout.splitlines()]
    for line in shown:
        assert line in printed, f"{line!r} not printed; got {printed}"

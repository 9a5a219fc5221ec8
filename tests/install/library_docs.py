#!/usr/bin/env python3
"""docs/library.md against an install of the build, as a reader would use it.

- Every ```cpp block is a complete program: it compiles as C++17 with warnings as errors
  (-Wall -Wextra -Wpedantic -Wshadow -Wconversion) against the installed headers and
  libraylane.so (the flags of the install's raylane.pc), runs from a folder that holds the
  checkout's scenes/ with RAYLANE_MODEL_PATH as ctest sets it, exits 0, and prints every line a
  `// prints: TEXT` comment of it gives. When clang-format is installed, each is formatted as
  the repository's .clang-format says, as CI wants every .cpp file.
- Every ```sh block marked `<!-- shell: not run: tests/install/library_docs.py ... -->` (the
  build commands, which tests/python/test_shell_docs.py leaves out) runs as pasted with
  `bash -e`, in a folder holding the page's first.cpp (the ```cpp block that starts with
  `// first.cpp`) and its ```cmake block as CMakeLists.txt, with HOME set so that
  $HOME/raylane is the install. A `cmake --install` line is left out: the install is there.

Without bunny.ply or dragon.ply on RAYLANE_MODEL_PATH the test is skipped (exit 77), or fails
when RAYLANE_REQUIRE_MODELS=1.

Usage: library_docs.py PREFIX SOURCE_DIR WORK_DIR [CXX]
"""
import concurrent.futures
import os
import re
import shlex
import shutil
import subprocess
import sys

MARK = "tests/install/library_docs.py"
WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Wshadow", "-Wconversion", "-Werror"]


def blocks(page):
    """(kind, line, text, marker) of every fenced block of the page, in order."""
    with open(page, encoding="utf-8") as f:
        text = f.read()
    found = []
    for m in re.finditer(r"^```(\w+)\n(.*?)^```", text, re.S | re.M):
        line = text.count("\n", 0, m.start()) + 1
        before = text[:m.start()].rstrip("\n").splitlines()
        marker = before[-1] if before and before[-1].startswith("<!-- shell:") else ""
        found.append((m.group(1), line, m.group(2), marker))
    return found


def model_folders():
    return [d for d in os.environ.get("RAYLANE_MODEL_PATH", "").split(":") if d]


def check_models():
    for name in ("bunny.ply", "dragon.ply"):
        if not any(os.path.isfile(os.path.join(d, name)) for d in model_folders()):
            why = f"{name} is not on RAYLANE_MODEL_PATH (put ../shared/models beside the checkout)"
            if os.environ.get("RAYLANE_REQUIRE_MODELS") == "1":
                sys.exit(f"library_docs: {why} and RAYLANE_REQUIRE_MODELS=1")
            print(f"skipped: {why}")
            sys.exit(77)


def pkg_config(prefix, *args):
    env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(prefix, "lib", "pkgconfig"))
    p = subprocess.run(["pkg-config", *args, "raylane"], capture_output=True, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"library_docs: pkg-config {' '.join(args)} raylane failed: {p.stderr}")
    return shlex.split(p.stdout)


def compile_block(cxx, flags, source, program):
    p = subprocess.run([cxx, "-std=c++17", *WARNINGS, source, "-o", program, *flags],
                       capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def format_problems(source_dir, source):
    """clang-format's complaints about a block's file ("" when it is formatted, or when
    clang-format is not installed)."""
    if shutil.which("clang-format") is None:
        return ""
    style = "--style=file:" + os.path.join(source_dir, ".clang-format")
    p = subprocess.run(["clang-format", style, "--dry-run", "--Werror", source],
                       capture_output=True, text=True)
    return p.stderr if p.returncode != 0 else ""


def run_program(program, cwd):
    p = subprocess.run([program], cwd=cwd, capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


def expected_lines(code):
    """The TEXT of each `// prints: TEXT` comment."""
    return [m.group(1).strip() for m in re.finditer(r"//\s*prints:\s*(.*)$", code, re.M)]


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    prefix, source_dir, work = (os.path.abspath(a) for a in sys.argv[1:4])
    cxx = sys.argv[4] if len(sys.argv) == 5 else os.environ.get("CXX", "c++")
    page = os.path.join(source_dir, "docs", "library.md")
    check_models()
    if shutil.which("pkg-config") is None:
        sys.exit("library_docs: pkg-config is not installed (scripts/setup.sh installs it)")

    found = blocks(page)
    cpp = [b for b in found if b[0] == "cpp"]
    cmake = [b for b in found if b[0] == "cmake"]
    shell = [b for b in found if b[0] == "sh" and MARK in b[3]]
    if len(cpp) < 10 or len(cmake) != 1 or len(shell) < 2:
        sys.exit(f"library_docs: {page} has {len(cpp)} cpp blocks (at least 10 expected), "
                 f"{len(cmake)} cmake blocks (1) and {len(shell)} sh blocks marked for this "
                 "test (at least 2)")
    first = [b for b in cpp if b[2].startswith("// first.cpp")]
    if len(first) != 1:
        sys.exit("library_docs: no ```cpp block starts with `// first.cpp`")

    shutil.rmtree(work, ignore_errors=True)
    run_dir = os.path.join(work, "run")  # where the programs run: the checkout's scenes/
    os.makedirs(run_dir)
    os.symlink(os.path.join(source_dir, "scenes"), os.path.join(run_dir, "scenes"))
    flags = pkg_config(prefix, "--cflags", "--libs")
    flags.append("-Wl,-rpath," + pkg_config(prefix, "--variable=libdir")[0])

    failures = []
    jobs = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        for _, line, code, _ in cpp:
            source = os.path.join(work, f"library_md_{line}.cpp")
            with open(source, "w", encoding="utf-8") as f:
                f.write(code)
            jobs[line] = pool.submit(compile_block, cxx, flags, source, source[:-4])
    for _, line, code, _ in cpp:
        where = f"docs/library.md:{line}"
        status, messages = jobs[line].result()
        if status != 0:
            failures.append(f"{where}: does not compile:\n{messages}")
            continue
        unformatted = format_problems(source_dir, os.path.join(work, f"library_md_{line}.cpp"))
        if unformatted:
            failures.append(f"{where}: not formatted as .clang-format says:\n{unformatted}")
        status, out, err = run_program(os.path.join(work, f"library_md_{line}"), run_dir)
        printed = [text.strip() for text in out.splitlines()]
        missing = [text for text in expected_lines(code) if text not in printed]
        if status != 0 or missing:
            failures.append(f"{where}: exit status {status}" +
                            "".join(f", did not print {text!r}" for text in missing) +
                            f"\n--- stdout\n{out[-2000:]}\n--- stderr\n{err[-2000:]}")
        elif not unformatted:
            print(f"{where}: compiles, runs, prints its {len(expected_lines(code))} lines")

    # the build commands, as pasted, beside first.cpp and CMakeLists.txt; $HOME/raylane: the install
    home = os.path.join(work, "home")
    os.makedirs(home)
    os.symlink(prefix, os.path.join(home, "raylane"))
    env = {k: v for k, v in os.environ.items() if k not in ("PKG_CONFIG_PATH", "CMAKE_PREFIX_PATH")}
    env.update(HOME=home, CXX=cxx)
    if shutil.which("ninja"):
        env["CMAKE_GENERATOR"] = "Ninja"
    for index, (_, line, script, _) in enumerate(shell):
        where = f"docs/library.md:{line}"
        project = os.path.join(work, f"project_{index}")
        os.makedirs(project)
        with open(os.path.join(project, "first.cpp"), "w", encoding="utf-8") as f:
            f.write(first[0][2])
        with open(os.path.join(project, "CMakeLists.txt"), "w", encoding="utf-8") as f:
            f.write(cmake[0][2])
        script = "\n".join(l for l in re.sub(r"\\\n", "", script).splitlines()
                           if not re.match(r"\s*cmake --install\b", l))
        p = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", script], cwd=project, env=env,
                           capture_output=True, text=True, timeout=600)
        missing = [text for text in expected_lines(first[0][2])
                   if text not in [l.strip() for l in p.stdout.splitlines()]]
        if p.returncode != 0 or missing:
            failures.append(f"{where}: exit status {p.returncode}" +
                            "".join(f", first did not print {text!r}" for text in missing) +
                            f"\n{script}\n--- stdout\n{p.stdout[-3000:]}\n"
                            f"--- stderr\n{p.stderr[-3000:]}")
        else:
            print(f"{where}: the build commands run as pasted and first runs")

    if failures:
        print("\n\n".join(failures), file=sys.stderr)
        sys.exit(f"library_docs: {len(failures)} of {len(cpp) + len(shell)} blocks failed")
    print(f"library_docs: {len(cpp)} programs and {len(shell)} build blocks of docs/library.md "
          "work against the install")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Links: every relative link in README.md and docs/ leads somewhere, and every repository path
written in backticks exists.

- Markdown links `[text](target)`, images `![alt](target)` and reference definitions
  `[name]: target` in README.md and docs/**/*.md: the target exists (relative to the file);
  a `#anchor` names a heading of the target Markdown file (or of the same file), slugged as
  GitHub does: lower case, punctuation other than - and _ dropped, spaces to hyphens, -1, -2, ...
  for repeated headings. Web and mail links are not followed.
- Backticked paths in README.md, docs/**/*.md and the text files of src/, simd/, python/,
  bench/, tests/ and scripts/ (comments, docstrings, help text): every word that starts with a
  top-level folder of the repository (src/, docs/, scenes/, ...) or is a top-level file
  (README.md, CMakeLists.txt, ...) exists. A word ending in / must be a folder; one with * is a
  glob that must match something; <placeholder> and ... stand for any name (tests/<folder>/ is
  tests/*/); {a,b} lists alternatives, each of which must exist; a :LINE suffix and a trailing
  (), comma or full stop are ignored. A word starting with ../shared/ is looked up in the shared
  folder beside the checkout.

Usage: python3 scripts/check_links.py   (from anywhere; exit status 1 when something is missing)
"""
import glob
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
FOLDERS = ["src", "simd", "docs", "scripts", "tests", "bench", "python", "scenes", "cmake"]
CODE_FOLDERS = ["src", "simd", "python", "bench", "tests", "scripts"]
SKIPPED = ("tests/fuzz/corpus/", "tests/fuzz/regressions/")

FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REF_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s+<?(\S+?)>?(\s|$)")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
HTML_ANCHOR = re.compile(r"<a\s+(?:name|id)=\"([^\"]+)\"")
BACKTICKS = re.compile(r"(`+)(.+?)\1")


def tracked_files():
    out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True)
    return [f for f in out.stdout.decode().split("\0") if f]


def is_text(path):
    try:
        with open(path, "rb") as f:
            return b"\0" not in f.read(8192)
    except OSError:
        return False


def read_lines(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read().splitlines()


def outside_fences(lines):
    """(line number, line) of the lines outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(lines, 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def slug(heading):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links: their text
    text = re.sub(r"<[^>]+>", "", text)  # inline HTML
    text = text.replace("`", "")
    text = re.sub(r"(\*\*|__|\*)", "", text)
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)  # \w keeps letters of every script, digits and _
    return text.replace(" ", "-")


_anchors = {}


def anchors(path):
    """The anchors a Markdown file defines: its headings' slugs and <a name/id> anchors."""
    if path not in _anchors:
        found, seen = set(), {}
        for _, line in outside_fences(read_lines(path)):
            found.update(HTML_ANCHOR.findall(line))
            m = HEADING.match(line)
            if not m:
                continue
            base = slug(m.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
        _anchors[path] = found
    return _anchors[path]


def check_link(source, target):
    """None when the link from `source` (a repository path) to `target` resolves, else why not."""
    if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("//"):
        return None  # http:, https:, mailto:, ...
    path, _, anchor = target.partition("#")
    full = os.path.join(ROOT, source) if not path else os.path.join(
        os.path.dirname(os.path.join(ROOT, source)), path)
    full = os.path.normpath(full)
    if not os.path.exists(full):
        return f"link to {target}: {path} does not exist"
    if path.endswith("/") and not os.path.isdir(full):
        return f"link to {target}: {path} is not a folder"
    if anchor and full.endswith(".md") and not re.fullmatch(r"L\d+(-L\d+)?", anchor):
        if anchor not in anchors(full):
            return f"link to {target}: no heading with the anchor #{anchor} in {path or source}"
    return None


def expand_braces(word):
    """src/a.{h,cpp} -> [src/a.h, src/a.cpp] (every {..,..} group, nested ones included)."""
    m = re.search(r"\{([^{}]*,[^{}]*)\}", word)
    if not m:
        return [word]
    out = []
    for alternative in m.group(1).split(","):
        out.extend(expand_braces(word[:m.start()] + alternative + word[m.end():]))
    return out


def path_words(code, top_files):
    """The words of a backticked text that are repository paths."""
    for word in code.split():
        word = word.strip("\"'")
        word = re.sub(r"[,.;:)]+$", "", word) if not word.endswith("/") else word
        word = re.sub(r"\(\)$", "", word)
        word = re.sub(r":\d+(-\d+)?$", "", word)  # file:line
        if word.startswith("../shared/"):
            yield word
            continue
        first = word.split("/", 1)[0]
        if ("/" in word and first in FOLDERS) or word in top_files:
            yield word


def check_path(word):
    """None when a backticked repository path exists, else why not."""
    if word.startswith("../shared/"):
        base, rel = SHARED, word[len("../shared/"):]
    else:
        base, rel = ROOT, word
    for alternative in expand_braces(rel):
        pattern = re.sub(r"<[^<>]*>", "*", alternative)
        pattern = pattern.replace("...", "*").replace("…", "*")
        want_dir = pattern.endswith("/")
        full = os.path.join(base, pattern)
        if "*" in pattern or "?" in pattern or "[" in pattern:
            matches = glob.glob(full.rstrip("/"))
            if want_dir:
                matches = [m for m in matches if os.path.isdir(m)]
            if not matches:
                return f"`{word}`: nothing matches {alternative}"
        elif not os.path.exists(full.rstrip("/") or base):
            return f"`{word}`: {alternative} does not exist"
        elif want_dir and not os.path.isdir(full):
            return f"`{word}`: {alternative} is not a folder"
    return None


def main():
    files = tracked_files()
    top_files = {f for f in files if "/" not in f}
    docs = [f for f in files if f == "README.md" or (f.startswith("docs/") and f.endswith(".md"))]
    code = [f for f in files
            if f.split("/", 1)[0] in CODE_FOLDERS and not f.startswith(SKIPPED)
            and not f.endswith(".md") and is_text(os.path.join(ROOT, f))]
    code += [f for f in files if f.split("/", 1)[0] in CODE_FOLDERS and f.endswith(".md")
             and not f.startswith(SKIPPED)]
    problems = []
    for source in docs:
        lines = read_lines(os.path.join(ROOT, source))
        for number, line in outside_fences(lines):
            targets = INLINE_LINK.findall(BACKTICKS.sub("", line))
            m = REF_DEF.match(line)
            if m:
                targets.append(m.group(1))
            for target in targets:
                why = check_link(source, target)
                if why:
                    problems.append(f"{source}:{number}: {why}")
    for source in docs + code:
        lines = read_lines(os.path.join(ROOT, source))
        numbered = outside_fences(lines) if source.endswith(".md") else enumerate(lines, 1)
        for number, line in numbered:
            for _, text in BACKTICKS.findall(line):
                for word in path_words(text, top_files):
                    why = check_path(word)
                    if why:
                        problems.append(f"{source}:{number}: {why}")
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print("links: the links and paths above lead nowhere; point them at what exists",
              file=sys.stderr)
        return 1
    print(f"links: every link and backticked path of {len(docs)} docs and {len(code)} code files "
          "exists", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())

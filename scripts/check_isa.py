#!/usr/bin/env python3
"""No instruction outside its set: disassembles linked files (the raylane binary, the Python
module) and checks every function against the instruction set its code was compiled for.

A function belongs to a set when its symbol is in the set's namespace (raylane::isa_avx2::...,
mangled "8isa_avx2") or carries the set's prefix (isa_avx2._ZNSt6vector..., the set's own copies
of library templates, named so by cmake/isa_object.sh). Every other function is baseline code,
which runs on every CPU from x86-64-v2 up. The rules:

- AVX-512 (a zmm or mask register, or an EVEX-encoded instruction) only in avx512 code;
- AVX (any VEX- or EVEX-encoded instruction: a ymm register, or a v-prefixed mnemonic on xmm)
  only in avx2 and avx512 code.

    scripts/check_isa.py FILE...     exit 1 and a line per offending function when a rule fails
"""
import re
import subprocess
import sys

SETS = (("avx512", "10isa_avx512"), ("avx2", "8isa_avx2"), ("sse4.2", "9isa_sse42"))
FUNCTION = re.compile(r"^[0-9a-f]+ <(.+)>:$")
INSTRUCTION = re.compile(r"^\s+[0-9a-f]+:\t((?:[0-9a-f]{2} )+)\s*\t(\S+)\s*(.*)$")
AVX512_REGISTER = re.compile(r"%zmm|%k[0-7]\b|%[xy]mm(1[6-9]|2[0-9]|3[01])\b|\{%k")


def owner(symbol):
    """The set whose code the function is ('baseline' for the rest)."""
    for name, mangled in SETS:
        namespace = mangled.lstrip("0123456789")  # isa_avx2
        if mangled in symbol or symbol.startswith(namespace + "."):
            return name
    return "baseline"


def evex(raw_bytes):
    """Whether the instruction's encoding starts with an EVEX prefix (0x62 in 64-bit mode),
    after an optional address-size or segment prefix."""
    b = raw_bytes.split()
    while b and b[0] in ("67", "2e", "3e", "26", "64", "65", "36"):
        b = b[1:]
    return bool(b) and b[0] == "62"


def check(path):
    bad = {}
    dump = subprocess.Popen(["objdump", "-d", "-w", path],
                            stdout=subprocess.PIPE, text=True, errors="replace")
    function, kind = None, "baseline"
    for line in dump.stdout:
        m = FUNCTION.match(line)
        if m:
            function, kind = m.group(1), owner(m.group(1))
            continue
        if function is None or kind == "avx512":
            continue
        m = INSTRUCTION.match(line)
        if not m:
            continue
        raw, mnemonic, operands = m.groups()
        problem = None
        if evex(raw) or AVX512_REGISTER.search(operands):
            problem = "AVX-512"
        elif kind in ("baseline", "sse4.2") and (mnemonic.startswith("v") or "%ymm" in operands):
            problem = "AVX"
        if problem:
            bad.setdefault((function, kind, problem), f"{mnemonic} {operands}".strip())
    if dump.wait() != 0:
        sys.exit(f"check_isa: objdump failed on {path}")
    for (function, kind, problem), example in sorted(bad.items()):
        print(f"{path}: {problem} instruction in {kind} code: {function}: {example}",
              file=sys.stderr)
    return not bad


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    ok = all([check(path) for path in sys.argv[1:]])
    if ok:
        print("check_isa: every AVX and AVX-512 instruction is in its set's code: "
              + ", ".join(sys.argv[1:]), file=sys.stderr)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()

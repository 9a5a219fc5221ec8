#!/bin/sh
# One instruction set's objects as one relocatable object in which only the set's namespace
# (raylane::isa_avx2, ...) stays global. The inline functions and templates the set's code
# instantiates (the standard library's, GLM's, oneTBB's, xsimd's) are compiled with the set's
# flags; were they left global, the linker could keep the AVX-512 copy of std::vector<float>'s
# growth for a caller compiled for the baseline. Made local, each set keeps its own copies, and
# they are renamed "<ns>.<symbol>" (isa_avx2._ZNSt6vector...), so that a disassembly says which
# set each function belongs to (scripts/check_isa.py).
#
#   isa_object.sh LD OBJCOPY NM OBJDUMP NAMESPACE no-init|allow-init OUT OBJECT...
#
# no-init: the objects must not run code at start-up (a static initialiser runs on every CPU,
# before any instruction set is chosen).
set -eu
ld=$1 objcopy=$2 nm=$3 objdump=$4 ns=$5 init_rule=$6 out=$7
shift 7
tmp="$out.partial"
# one object; COMDAT groups dissolved, so that the set's copies are its own sections
"$ld" -r --force-group-allocation -o "$tmp" "$@"
# every defined global symbol outside the set's namespace (mangled "7raylane<length><ns>")
mangled="7raylane${#ns}${ns}"
"$nm" -g --defined-only "$tmp" | awk '{ print $NF }' | grep -v -e "$mangled" >"$out.local" || true
"$objcopy" --localize-symbols="$out.local" "$tmp" "$tmp.local"
# every defined symbol outside the namespace, global before or local (static functions of
# headers), gets the set's prefix
"$nm" --defined-only "$tmp.local" | awk -v ns="$ns" -v m="$mangled" \
    '$2 != "a" && $2 != "N" && index($NF, m) == 0 && index($NF, ns ".") != 1 { print $NF, ns "." $NF }' |
    sort -u >"$out.rename"
"$objcopy" --redefine-syms="$out.rename" "$tmp.local" "$out"
rm -f "$tmp" "$tmp.local"
if [ "$init_rule" = no-init ]; then
    if "$objdump" -h "$out" | grep -q -e '\.init_array' -e '\.ctors'; then
        echo "isa_object.sh: $ns: code runs at start-up (a static initialiser; look for" \
             "_GLOBAL__sub_I_ in: $nm $out | grep _GLOBAL__sub_I_): make it constant or move it" \
             "to a file compiled for the baseline" >&2
        rm -f "$out"
        exit 1
    fi
fi

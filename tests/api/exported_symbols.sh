#!/bin/sh
# libraylane.so exports the public API of include/raylane/ and nothing else: its soname carries
# the major version, and every defined dynamic symbol is a member of raylane::Error, Scene or
# Mesh, one of the API's free functions, or Error's type information.
set -eu
lib="$1"
soname=$(objdump -p "$lib" | awk '$1 == "SONAME" { print $2 }')
case "$soname" in
    libraylane.so.[0-9]*) ;;
    *) echo "soname '$soname', expected libraylane.so.MAJOR" >&2; exit 1 ;;
esac
api='^raylane::((Error|Scene|Mesh)::|(version|find_model|compiled_instruction_sets|cpu_instruction_sets|instruction_set|packet_width|use_instruction_set)(\[abi:cxx11\])?\()'
others=$(nm -D --defined-only -C "$lib" | cut -d' ' -f3- | sed 's/@@*RAYLANE_0$//' |
    grep -v -E -e "$api" -e '^(typeinfo|typeinfo name|vtable) for raylane::Error$' -e '^RAYLANE_0$' || true)
if [ -n "$others" ]; then
    echo "$lib exports symbols outside the API:" >&2
    echo "$others" | head -20 >&2
    exit 1
fi
count=$(nm -D --defined-only "$lib" | grep -c ' T ')
[ "$count" -ge 20 ] || { echo "only $count functions exported" >&2; exit 1; }
echo "$lib ($soname): $count functions, all of the API"

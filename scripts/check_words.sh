#!/usr/bin/env bash
# Words: the repository describes the product, not its own development. Fails on a tracked text
# file (docs, comments, program output, scripts) that narrates how the code came to be (numbered
# work periods or tasks, where they were tracked) or the machine it was written on; the history
# lives in git. In docs/, src/, simd/, python/, bench/, tests/ and scripts/ it also refuses dates
# (YYYY-MM-DD) and words that look like commit hashes: 7 to 40 lower-case hex digits with at
# least one digit and one letter, standing alone (not after 0x, #, a dot or another letter, so
# hex constants, colours and float literals such as 6.2831853f pass). The fuzz corpora and
# binary files are not read. An allowed use is listed below as FILE:REGEX (a line of FILE
# matching REGEX is not reported).
set -euo pipefail
cd "$(dirname "$0")/.."

pattern='\bsessions?\b|\bissues?\b|\btracker\b|\bVM\b|virtual machine|work periods?|#[0-9]{1,3}\b'
allowed=(
    'scripts/check_words.sh:.'  # the patterns themselves
    # the hex digits in order, as a lookup table
    'src/io/read_file.cpp:"0123456789abcdef"'
    'src/io/text_form.cpp:"0123456789abcdef"'
    'tests/distribute/scene_hash_test.cpp:"0123456789abcdef"'
    'tests/image/exr_test.cpp:"0123456789abcdef"'
    'tests/support/sha256.h:"0123456789abcdef"'
)
# dates and commit-hash-like words (Perl regexes), and where they are looked for
date_pattern='(?<![0-9])(19|20)[0-9]{2}-(0[1-9]|1[0-2])-(0[1-9]|[12][0-9]|3[01])(?![0-9])'
hash_pattern='(?<![0-9A-Za-z_#.])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![0-9A-Za-z_])'
dated=(docs src simd python bench tests scripts)

bad=0
while IFS= read -r hit; do
    file="${hit%%:*}"
    rest="${hit#*:}"
    text="${rest#*:}"
    skip=0
    for entry in "${allowed[@]}"; do
        if [[ "$file" == "${entry%%:*}" ]] && grep -qE -- "${entry#*:}" <<<"$text"; then
            skip=1
            break
        fi
    done
    [[ $skip == 1 ]] && continue
    echo "$hit" >&2
    bad=1
done < <(
    git ls-files -z -- ':!tests/fuzz/corpus' ':!tests/fuzz/regressions' |
        xargs -0 grep -nIiE -- "$pattern" 2>/dev/null || true
    git ls-files -z -- "${dated[@]}" ':!tests/fuzz/corpus' ':!tests/fuzz/regressions' |
        xargs -0 grep -nIP -- "$date_pattern|$hash_pattern" 2>/dev/null || true
)

if [[ $bad == 1 ]]; then
    echo "words: the lines above speak of the project's history or of one machine, or hold a" \
         "date or a commit hash; say what the code does and what was measured, with the command" >&2
    exit 1
fi
echo "words: no history, dates or commit hashes in docs, comments or output" >&2

#!/usr/bin/env bash
# Words: the repository describes the product, not its own development. Fails on a tracked text
# file (docs, comments, program output, scripts) that narrates how the code came to be (numbered
# work periods or tasks, where they were tracked) or the machine it was written on; the history
# lives in git. An allowed use is listed below as FILE:REGEX (a line of FILE matching REGEX is
# not reported).
set -euo pipefail
cd "$(dirname "$0")/.."

pattern='\bsessions?\b|\bissues?\b|\btracker\b|\bVM\b|virtual machine|work periods?|#[0-9]{1,3}\b'
allowed=(
    'scripts/check_words.sh:.'  # the patterns themselves
)

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
done < <(git ls-files -z -- ':!tests/fuzz/corpus' ':!tests/fuzz/regressions' |
         xargs -0 grep -nIiE -- "$pattern" 2>/dev/null || true)

if [[ $bad == 1 ]]; then
    echo "words: the lines above speak of the project's history or of one machine;" \
         "say what the code does and what was measured, with the command" >&2
    exit 1
fi
echo "words: no history in docs, comments or output" >&2

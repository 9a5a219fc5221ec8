# bash completion for raylane(1): the commands, each command's options, the values of options
# that take one of a fixed set, and file names by kind (scenes and models, images, EXR parts).
# Installed as bash-completion/completions/raylane; needs bash alone, not the bash-completion
# package's helpers. tests/python/test_packaging.py keeps the lists in step with the program.

# _raylane_files EXTENSION...: file names with one of the extensions (any case), and folders
_raylane_files() {
    local entry lower ext
    local -a entries
    mapfile -t entries < <(compgen -f -- "$cur")
    for entry in "${entries[@]}"; do
        if [[ -d $entry ]]; then
            COMPREPLY+=("$entry")
            continue
        fi
        lower=${entry,,}
        for ext in "$@"; do
            if [[ $lower == *."$ext" ]]; then
                COMPREPLY+=("$entry")
                break
            fi
        done
    done
}

# _raylane_values PREFIX VALUE...: the values that start with cur, after PREFIX (the items
# before the last comma of a comma-separated list)
_raylane_values() {
    local prefix=$1
    shift
    local value
    for value in "$@"; do
        [[ $prefix$value == "$cur"* ]] && COMPREPLY+=("$prefix$value")
    done
}

_raylane() {
    local cur=${COMP_WORDS[COMP_CWORD]}
    local prev="" cword=$COMP_CWORD
    ((cword > 0)) && prev=${COMP_WORDS[cword - 1]}
    COMPREPLY=()

    local -a commands=(render info compare report scene assemble)
    local -a help_options=(-h --help --help-all)
    # the options of each command, besides help_options
    local -A options=(
        [render]="-o --output --exr-float --spp --threads --width --height --aov --seed --path
                  --bvh --frames --crop --tile -q --quiet --strict --isa"
        [info]="--bvh --isa"
        [compare]="--spp --threads --width --height --bvh --tolerance --id-allowance --repeats
                   -q --quiet --isa"
        [report]="--out-dir --reference-spp --reference-path --spp-list --paths --repeats
                  --threads --width --height --fresh-reference -q --quiet --isa"
        [scene]="--isa"
        [assemble]="-o --output --exr-float --threads --isa"
    )
    # the options that take a value (the next word, or the text after '=')
    local -A takes_value=()
    local option
    for option in -o --output --spp --threads --width --height --aov --seed --path --bvh --frames \
        --crop --tile --isa --tolerance --id-allowance --repeats --out-dir --reference-spp \
        --reference-path --spp-list --paths; do
        takes_value[$option]=1
    done

    # the command: the first word after raylane
    if ((cword <= 1)); then
        if [[ $cur == -* ]]; then
            _raylane_values "" "${help_options[@]}" --version
        else
            _raylane_values "" "${commands[@]}"
        fi
        return 0
    fi
    local command=${COMP_WORDS[1]}
    [[ -n ${options[$command]+set} ]] || return 0
    local -a command_options
    read -d '' -ra command_options <<<"${options[$command]}"

    # --option=value: bash splits the word at '=' (COMP_WORDBREAKS)
    if [[ $cur == "=" ]]; then
        cur=""
    elif [[ $prev == "=" ]] && ((cword >= 2)); then
        prev=${COMP_WORDS[cword - 2]}
    fi

    # --crop takes four numbers
    local i
    for ((i = cword - 1; i >= 2 && i >= cword - 4; i--)); do
        [[ ${COMP_WORDS[i]} == --crop ]] && return 0
        [[ ${COMP_WORDS[i]} == -* ]] && break
    done

    # the word after an option of this command that takes a value
    local value_of=""
    for option in "${command_options[@]}"; do
        [[ $option == "$prev" && -n ${takes_value[$option]+set} ]] && value_of=$option
    done
    if [[ -n $value_of ]]; then
        case $value_of in
            --isa) _raylane_values "" sse4.2 avx2 avx512 ;;
            --aov) _raylane_values "" color normal depth bvh-cost all ;;
            --path | --reference-path) _raylane_values "" packet scalar ;;
            --paths)
                local before=""
                [[ $cur == *,* ]] && before=${cur%,*},
                _raylane_values "$before" packet scalar
                ;;
            --bvh) _raylane_values "" median sah ;;
            --frames) _raylane_values "" all ;;
            -o | --output)
                compopt -o filenames 2>/dev/null
                _raylane_files png pfm exr
                ;;
            --out-dir)
                compopt -o filenames 2>/dev/null
                mapfile -t COMPREPLY < <(compgen -d -- "$cur")
                ;;
        esac
        return 0
    fi

    if [[ $cur == -* ]]; then
        _raylane_values "" "${command_options[@]}" "${help_options[@]}"
        return 0
    fi

    # the command's files: scenes and models, a model, or parts of a frame
    compopt -o filenames 2>/dev/null
    case $command in
        render | info | compare | report) _raylane_files json obj ply gz ;;
        scene) _raylane_files obj ply gz ;;
        assemble) _raylane_files exr ;;
    esac
    return 0
}

complete -F _raylane raylane

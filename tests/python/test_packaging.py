"""The man page (packaging/raylane.1) and the bash completion (packaging/raylane.bash) against the
program: every command `raylane --help` lists and every option `raylane COMMAND --help` lists is
in the man page's subsection of that command (as an item of its option list) and among the words
the completion offers for that command, and every option either of them lists is one the program
takes, so an option added or removed on one side fails here. The man page formats without groff
warnings; the completion completes commands, options, the fixed values of options and file names
by kind."""
import os
import re
import shutil
import subprocess

import pytest

from conftest import SOURCE_DIR, run_cli

MAN_PAGE = os.path.join(SOURCE_DIR, "packaging", "raylane.1")
COMPLETION = os.path.join(SOURCE_DIR, "packaging", "raylane.bash")

# an option word: -o, --output (not the hyphen inside a word such as bvh-cost)
OPTION = re.compile(r"(?<![\w-])(--?[a-z][a-z0-9-]*)")
LONG_OPTION = re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*)")


# --- the program's help (CLI11's layout: "Title:" lines, then two-space indented entries) ---

def help_sections(*command):
    """{section title: its lines} of `raylane COMMAND --help`."""
    code, out, err = run_cli(*command, "--help")
    assert code == 0, err
    sections, title = {}, None
    for line in out.splitlines():
        m = re.match(r"^(\w[\w ]*):$", line)
        if m:
            title = m.group(1)
            sections[title] = []
        elif title and line.strip():
            sections[title].append(line)
    return sections


def program_commands():
    return [re.match(r"^  (\S+)", line).group(1)
            for line in help_sections()["Subcommands"] if re.match(r"^  \S", line)]


def program_options(*command):
    """{option name: the first line of its entry} of `raylane COMMAND --help`, short and long
    names alike (-o and --output both map to the entry of -o,--output)."""
    options = {}
    for line in help_sections(*command)["Options"]:
        m = re.match(r"^  (-\S+)", line)
        if m:
            for name in m.group(1).split(","):
                options[name] = line
    return options


def fixed_values(entry):
    """The values of an option whose help names a fixed set (TEXT:{a,b,c}), else None."""
    m = re.search(r"\{([^}]*)\}", entry)
    return set(m.group(1).split(",")) if m else None


def compiled_instruction_sets():
    code, out, err = run_cli("--version")
    assert code == 0, err
    m = re.search(r"instruction sets: (.*?) \(compiled\)", out)
    assert m, out
    return set(m.group(1).split())


# --- the man page ---

def man_text():
    with open(MAN_PAGE, encoding="utf-8") as f:
        return f.read().replace("\\-", "-").replace("\\%", "")


def man_sections():
    """{.SH title: {.SS title or "": its lines}}, comments left out."""
    sections, sh, ss = {}, None, ""
    for line in man_text().splitlines():
        if line.startswith('.\\"'):
            continue
        if line.startswith(".SH "):
            sh, ss = line[4:].strip().strip('"'), ""
            sections[sh] = {"": []}
        elif line.startswith(".SS ") and sh:
            ss = line[4:].strip().strip('"')
            sections[sh][ss] = []
        elif sh:
            sections[sh][ss].append(line)
    return sections


def listed_options(lines):
    """The option names in the heads of the .TP items of a part of the man page."""
    names = set()
    for i, line in enumerate(lines[:-1]):
        if line.startswith(".TP"):
            names.update(OPTION.findall(lines[i + 1]))
    return names


# --- the completion ---

def complete(*words, cwd=None):
    """The words the completion offers for a command line whose last word is being completed."""
    if shutil.which("bash") is None:
        pytest.skip("bash is not installed")
    script = ('source "$0" && COMP_WORDS=("$@") && COMP_CWORD=$((${#COMP_WORDS[@]} - 1)) && '
              '_raylane && printf "%s\\n" "${COMPREPLY[@]}"')
    p = subprocess.run(["bash", "--norc", "--noprofile", "-c", script, COMPLETION, *words],
                       capture_output=True, text=True, cwd=cwd)
    assert p.returncode == 0 and p.stderr == "", p.stderr
    return [w for w in p.stdout.split("\n") if w]


def differences(what, program, listed):
    """Lines naming what the program has that the list lacks, and the other way round."""
    out = []
    if set(program) - set(listed):
        out.append(f"{what}: missing {sorted(set(program) - set(listed))}")
    if set(listed) - set(program):
        out.append(f"{what}: not in the program {sorted(set(listed) - set(program))}")
    return out


# --- the tests ---

def test_the_man_page_names_every_command_in_its_synopsis_and_subsections():
    commands = program_commands()
    sections = man_sections()
    synopsis = {m.group(1) for line in sections["SYNOPSIS"][""]
                for m in [re.match(r"^\.B raylane (\w+)", line)] if m}
    assert synopsis == set(commands), differences("SYNOPSIS", commands, synopsis)
    subsections = [name for name in sections["COMMANDS"] if name]
    assert subsections == commands, "COMMANDS' subsections, in the order of raylane --help"


def test_the_man_page_lists_every_option_of_each_command_and_no_other():
    sections = man_sections()
    problems = differences("OPTIONS (raylane alone)", program_options(),
                           listed_options(sections["OPTIONS"][""]))
    for command in program_commands():
        lines = sections["COMMANDS"].get(command, [])
        problems += differences(f"{command}", program_options(command), listed_options(lines))
    assert not problems, "\n".join(problems)


def test_every_option_the_man_page_mentions_exists():
    known = set(program_options())
    for command in program_commands():
        known |= set(program_options(command))
    mentioned = set(LONG_OPTION.findall(man_text()))
    assert mentioned <= known, f"not options of raylane: {sorted(mentioned - known)}"


def test_the_man_page_formats_without_groff_warnings():
    if shutil.which("groff") is None:
        pytest.skip("groff is not installed (Debian's groff-base; scripts/setup.sh installs it)")
    p = subprocess.run(["groff", "-man", "-Tutf8", "-ww", "-z", MAN_PAGE], capture_output=True,
                       text=True)
    assert p.returncode == 0 and p.stderr == "", p.stderr


def test_the_completion_offers_every_command_and_option_and_no_other():
    problems = differences("commands", program_commands(), complete("raylane", ""))
    problems += differences("raylane -", program_options(), complete("raylane", "-"))
    for command in program_commands():
        problems += differences(f"raylane {command} -", program_options(command),
                                complete("raylane", command, "-"))
    assert not problems, "\n".join(problems)


def test_the_completion_offers_the_values_of_options_with_a_fixed_set():
    problems = []
    for command in program_commands():
        for name, entry in program_options(command).items():
            values = compiled_instruction_sets() if name == "--isa" else fixed_values(entry)
            if values is not None:
                problems += differences(f"raylane {command} {name}", values,
                                        complete("raylane", command, name, ""))
    assert not problems, "\n".join(problems)


def test_the_completion_knows_which_options_take_a_value(tmp_path):
    # after a flag comes what the command takes alone; after an option's value type in the help
    # (--spp INT, --aov TEXT:{...}) comes its value: no scene or part, an image for -o
    (tmp_path / "a.json").write_text("")
    (tmp_path / "b.exr").write_text("")
    problems = []
    for command in program_commands():
        alone = complete("raylane", command, "", cwd=tmp_path)
        for name, entry in program_options(command).items():
            offered = complete("raylane", command, name, "", cwd=tmp_path)
            if re.match(r"^  -\S+ \S", entry):
                files = {"a.json"} if name in ("-o", "--output") else {"a.json", "b.exr"}
                if files & set(offered):
                    problems.append(f"raylane {command} {name} takes a value, offered {offered}")
            elif offered != alone:
                problems.append(f"raylane {command} {name} is a flag, offered {offered}")
    assert not problems, "\n".join(problems)


def test_the_completion_completes_a_word_begun():
    assert complete("raylane", "re") == ["render", "report"]
    assert complete("raylane", "render", "--is") == ["--isa"]
    assert complete("raylane", "render", "--aov", "=", "de") == ["depth"]
    assert complete("raylane", "report", "--paths", "packet,s") == ["packet,scalar"]
    assert complete("raylane", "render", "--crop", "0", "0", "") == []


def test_the_completion_offers_files_by_kind(tmp_path):
    names = ["a.json", "b.OBJ", "c.ply", "d.ply.gz", "e.png", "f.pfm", "g.EXR", "h.txt"]
    for name in names:
        (tmp_path / name).write_text("")
    (tmp_path / "folder").mkdir()
    expected = {
        ("render", ""): {"a.json", "b.OBJ", "c.ply", "d.ply.gz", "folder"},
        ("report", "a.json", ""): {"a.json", "b.OBJ", "c.ply", "d.ply.gz", "folder"},
        ("scene", ""): {"b.OBJ", "c.ply", "d.ply.gz", "folder"},
        ("assemble", ""): {"g.EXR", "folder"},
        ("render", "-o", ""): {"e.png", "f.pfm", "g.EXR", "folder"},
        ("assemble", "--output", ""): {"e.png", "f.pfm", "g.EXR", "folder"},
    }
    for words, files in expected.items():
        assert set(complete("raylane", *words, cwd=tmp_path)) == files, words

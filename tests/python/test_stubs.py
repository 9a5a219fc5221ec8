"""python/raylane.pyi against the module: every public name of the module (classes, functions,
methods, properties, attributes) has a stub of the same kind and every stub names something the
module has; each function's and method's parameters in the stub are those of the runtime
signature (pybind11 writes it as the first line of __doc__): names, order, keyword-only and
defaulted or not; every public function and method says more than its signature; and the stubs
lie beside the module, where editors look for them."""
import ast
import filecmp
import inspect
import os
import re

import pytest

import raylane
from conftest import SOURCE_DIR

STUBS = os.path.join(SOURCE_DIR, "python", "raylane.pyi")
# dunder names that are part of the public surface: the version and the constructors
PUBLIC_DUNDERS = {"__version__", "__init__"}


def public(name):
    return not name.startswith("_") or name in PUBLIC_DUNDERS


# --- the stubs, read with ast


def stub_params(node):
    """[(name, kind, has default)] of a def in the stub; kind: positional, keyword, * or **."""
    a = node.args
    positional = a.posonlyargs + a.args
    defaults = [False] * (len(positional) - len(a.defaults)) + [True] * len(a.defaults)
    params = [(p.arg, "positional", d) for p, d in zip(positional, defaults)]
    if a.vararg:
        params.append((a.vararg.arg, "*", False))
    params += [(p.arg, "keyword", d is not None) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    if a.kwarg:
        params.append((a.kwarg.arg, "**", False))
    return params


def decorators(node):
    return {d.id if isinstance(d, ast.Name) else getattr(d, "attr", "")
            for d in node.decorator_list}


def read_stubs():
    """{name: (kind, detail)} of the module's stubs: kind 'function', 'class' or 'attribute';
    a class's detail is {name: (kind, detail)} of its members ('method', 'property',
    'attribute'); a function's or method's, the list of its overloads' parameter lists."""
    with open(STUBS, encoding="utf-8") as f:
        tree = ast.parse(f.read(), STUBS)

    def members(body, function_kind):
        found = {}
        for node in body:
            if isinstance(node, ast.FunctionDef):
                if "property" in decorators(node):
                    found[node.name] = ("property", None)
                else:
                    kind, overloads = found.get(node.name, (function_kind, []))
                    found[node.name] = (function_kind, overloads + [stub_params(node)])
            elif isinstance(node, ast.ClassDef):
                found[node.name] = ("class", members(node.body, "method"))
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
                found[node.target.id] = ("attribute", None)
            elif isinstance(node, ast.Assign):
                for target in node.targets:
                    if isinstance(target, ast.Name):
                        found[target.id] = ("attribute", None)
        return {name: v for name, v in found.items() if public(name)}

    return members(tree.body, "function")


# --- the module, and pybind11's signature lines


def split_top_level(text):
    """Splits at commas outside brackets and quotes."""
    parts, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            if c == quote and text[i - 1] != "\\":
                quote = None
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    if text[start:].strip():
        parts.append(text[start:])
    return [p.strip() for p in parts]


def signature_params(line, name):
    """[(name, kind, has default)] of one pybind11 signature line `name(a: T, b: T = x, *, ...)
    -> R`, without `self`."""
    m = re.match(re.escape(name) + r"\((.*)\) -> .*$", line.strip())
    assert m, f"{name}: no signature in {line!r}"
    params, kind = [], "positional"
    for part in split_top_level(m.group(1)):
        if part == "*":
            kind = "keyword"
        elif part == "/":
            continue
        elif part.startswith("**"):
            params.append((part[2:].split(":")[0].strip(), "**", False))
        elif part.startswith("*"):
            params.append((part[1:].split(":")[0].strip(), "*", False))
            kind = "keyword"
        else:
            head = split_default(part)
            params.append((head[0].split(":")[0].strip(), kind, head[1]))
    return params


def split_default(part):
    """(name: annotation, whether ` = default` follows) of one parameter."""
    depth, quote = 0, None
    for i, c in enumerate(part):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "=" and depth == 0:
            return part[:i].strip(), True
    return part.strip(), False


def runtime_signatures(obj, name):
    """Each overload's parameter list, from the signature lines pybind11 writes in __doc__."""
    doc = obj.__doc__ or ""
    lines = doc.splitlines()
    assert lines, f"{name}: no __doc__, so no signature"
    if len(lines) > 2 and lines[2].strip() == "Overloaded function.":
        found = [re.sub(r"^\d+\. ", "", l) for l in lines if re.match(r"^\d+\. " + name + r"\(", l)]
    else:
        found = [lines[0]]
    signatures = []
    for line in found:
        params = signature_params(line, name)
        if params and params[0][0] == "self":
            params = params[1:]
        signatures.append(params)
    return signatures


def signature_text(params):
    """`a, b=..., *, c=...`: names, order, keyword-only or not, defaulted or not."""
    parts, keyword_only = [], False
    for name, kind, has_default in params:
        if kind == "keyword" and not keyword_only:
            parts.append("*")
        keyword_only = keyword_only or kind in ("keyword", "*")
        prefix = {"*": "*", "**": "**"}.get(kind, "")
        parts.append(prefix + name + ("=..." if has_default else ""))
    return ", ".join(parts)


def is_pybind_function(obj):
    """A function or method pybind11 made (its __doc__ opens with the signature)."""
    return callable(obj) and not isinstance(obj, type) and (obj.__doc__ or "").startswith(
        getattr(obj, "__name__", "?") + "(")


def runtime_kind(obj, in_class):
    if isinstance(obj, type):
        return "class"
    if isinstance(obj, property):
        return "property"
    if callable(obj):
        return "method" if in_class else "function"
    return "attribute"


def runtime_members(obj, in_class):
    """{name: (kind, object)} of the module's or a class's own public names."""
    names = vars(obj)
    found = {}
    for name in names:
        if not public(name) or (name == "__version__" and in_class):
            continue
        member = names[name]
        if name == "__init__" and not is_pybind_function(member):
            continue  # no constructor of its own (Scene: raylane.load_scene makes them)
        found[name] = (runtime_kind(member, in_class), member)
    return found


def module_and_stubs():
    """[(qualified name, runtime (kind, object) or None, stub (kind, detail) or None)] of every
    public name in either."""
    stubs = read_stubs()
    module = runtime_members(raylane, in_class=False)
    rows = []
    for name in sorted(set(stubs) | set(module)):
        rows.append((name, module.get(name), stubs.get(name)))
        if name in module and name in stubs and module[name][0] == stubs[name][0] == "class":
            cls_members = runtime_members(module[name][1], in_class=True)
            cls_stubs = stubs[name][1]
            for member in sorted(set(cls_members) | set(cls_stubs)):
                rows.append((f"{name}.{member}", cls_members.get(member), cls_stubs.get(member)))
    return rows


ROWS = module_and_stubs()
IDS = [row[0] for row in ROWS]
FUNCTIONS = [row for row in ROWS if row[1] and row[1][0] in ("function", "method")]


def test_the_module_and_the_stubs_name_the_same_things():
    only_module = [name for name, runtime, stub in ROWS if stub is None]
    only_stubs = [name for name, runtime, stub in ROWS if runtime is None]
    assert not only_module, f"in the module without a stub in python/raylane.pyi: {only_module}"
    assert not only_stubs, f"in python/raylane.pyi but not in the module: {only_stubs}"
    assert {"Mesh", "Scene", "Error", "load_scene", "load_mesh", "Mesh.intersect",
            "Mesh.occluded", "Scene.render", "__version__"} <= set(IDS)


@pytest.mark.parametrize("row", ROWS, ids=IDS)
def test_each_stub_is_of_the_kind_of_its_name(row):
    name, runtime, stub = row
    if runtime is None or stub is None:
        pytest.skip("named on one side only (test_the_module_and_the_stubs_name_the_same_things)")
    assert stub[0] == runtime[0], f"{name}: a {runtime[0]} in the module, a {stub[0]} in the stubs"


@pytest.mark.parametrize("row", FUNCTIONS, ids=[row[0] for row in FUNCTIONS])
def test_each_stub_has_the_parameters_of_the_runtime_signature(row):
    name, (kind, obj), stub = row
    if stub is None or stub[0] != kind:
        pytest.skip("no stub of this kind (the tests above report it)")
    runtime = runtime_signatures(obj, name.split(".")[-1])
    stubbed = [params[1:] if kind == "method" else params for params in stub[1]]
    if kind == "method":
        assert all(params[:1] == [("self", "positional", False)] for params in stub[1]), \
            f"{name}: a method's stub takes self first"
    stub_text = sorted(signature_text(params) for params in stubbed)
    runtime_text = sorted(signature_text(params) for params in runtime)
    assert stub_text == runtime_text, \
        f"{name}: the stub takes ({' | '.join(stub_text)}), the module " \
        f"({' | '.join(runtime_text)})"


@pytest.mark.parametrize("row", FUNCTIONS, ids=[row[0] for row in FUNCTIONS])
def test_each_function_and_method_says_more_than_its_signature(row):
    name, (kind, obj), stub = row
    doc = inspect.cleandoc(obj.__doc__ or "")
    base = name.split(".")[-1]
    text = [line for line in doc.splitlines()
            if line.strip() and not re.match(r"^(\d+\. )?" + re.escape(base) + r"\(", line)
            and line.strip() != "Overloaded function."]
    assert text, f"{name}: help() shows only the signature; give it a docstring"


def test_the_stubs_lie_beside_the_module():
    beside = os.path.join(os.path.dirname(raylane.__file__), "raylane.pyi")
    assert os.path.isfile(beside), f"no {beside}: editors would not find the stubs"
    assert filecmp.cmp(beside, STUBS, shallow=False), f"{beside} is not python/raylane.pyi"

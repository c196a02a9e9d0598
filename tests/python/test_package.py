"""The package itself: its stubs match the extension, every public name is documented, and
`cmake --install` gives an importable package."""

import ast
import inspect
import os
import subprocess
import sys
from pathlib import Path

import pytest


def stub_names(path):
    tree = ast.parse(Path(path).read_text())
    names, members = set(), {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names.add(node.name)
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
            # the result classes' fields and the enums' members are annotations and assignments
            members[node.name] |= {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
            members[node.name] |= {t.id for n in node.body if isinstance(n, ast.Assign)
                                   for t in n.targets}
        elif isinstance(node, ast.FunctionDef):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return names, members


def public(names):
    return {n for n in names if not n.startswith("_") or n == "__version__"}


def test_the_stubs_name_everything_the_extension_has(gs):
    core = gs._core
    names, members = stub_names(Path(core.__file__).with_name("_core.pyi"))
    names -= {"ArrayLike", "FloatArray", "Int8Array", "PathLike"}
    assert public(names) == public(set(dir(core)) - {"__doc__", "__file__", "__loader__",
                                                      "__name__", "__package__", "__spec__"})
    for cls, stubbed in members.items():
        actual = {n for n in vars(getattr(core, cls)) if not n.startswith("_")}
        if hasattr(getattr(core, cls), "__members__"):
            actual -= {"name", "value"}  # an enum's own, as enum.Enum's
        stubbed = {n for n in stubbed if not n.startswith("_")}
        assert stubbed == actual, cls


def stub_method(path, cls, name):
    tree = ast.parse(Path(path).read_text())
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name == cls:
            for f in node.body:
                if isinstance(f, ast.FunctionDef) and f.name == name:
                    return f
    raise AssertionError(f"{cls}.{name} is not in {path}")


def test_the_stub_of_synthesize_has_the_options_of_the_request(gs):
    # Synthesizer.synthesize's keyword arguments are made from the C++ description of the
    # options (request_options); the stub, written for type checkers, must say the same.
    f = stub_method(Path(gs._core.__file__).with_name("_core.pyi"), "Synthesizer", "synthesize")
    stubbed = [(a.arg, ast.literal_eval(d)) for a, d in zip(f.args.kwonlyargs, f.args.kw_defaults)]
    runtime = inspect.signature(gs.Synthesizer.synthesize).parameters.values()
    options = [(p.name, p.default) for p in runtime
               if p.kind is inspect.Parameter.KEYWORD_ONLY]
    assert stubbed == options
    assert [a.arg for a in f.args.args] == ["self", "theta"]
    described = {o["name"]: o for o in gs.request_options("synthesize")}
    assert set(described) == {"theta"} | {name for name, _ in options}
    assert described["theta"]["required"]


@pytest.mark.parametrize("function, request_name", [
    ("generalize", "generalize"), ("run", "run"), ("select_representatives", "select")])
def test_a_study_functions_keywords_are_the_options_of_its_request(gs, function, request_name):
    # run, select_representatives and generalize take their options as explicit keyword
    # arguments made from the one C++ description, with its defaults, after their own.
    parameters = inspect.signature(getattr(gs, function)).parameters
    options = [p for p in parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY
               and p.name not in ("robot", "scene")]
    described = gs.request_options(request_name)
    assert [p.name for p in options] == [o["name"] for o in described]
    for p, o in zip(options, described):
        assert p.default == o["default"], p.name
        assert o["help"] in getattr(gs, function).__doc__
    with pytest.raises(TypeError):
        getattr(gs, function)(no_such_option=1)


@pytest.mark.parametrize("name, functions, methods", [
    ("simulate", ["simulate"], ["trial"]),
    ("robustness", ["robustness"], ["robustness"]),
    ("analyze", ["analyze_demonstrations"], []),
    ("segment", ["segment"], []),
    ("fit_wrist_line", ["fit_wrist_line"], []),
])
def test_functions_list_the_options_of_their_request(gs, name, functions, methods):
    # simulate, robustness, Simulation's methods and analyze_demonstrations take the options
    # of one C++ description each, as explicit keyword arguments with its defaults; the stubs say the same.
    described = [(o["name"], o["default"]) for o in gs.request_options(name)]
    stub = Path(gs._core.__file__).with_name("_core.pyi")
    callables = [getattr(gs, f) for f in functions]
    callables += [getattr(gs.Simulation, m) for m in methods]
    for function in callables:
        options = [(p.name, p.default) for p in inspect.signature(function).parameters.values()
                   if p.kind is inspect.Parameter.KEYWORD_ONLY and p.name not in ("robot", "scene")]
        assert options == described, function.__name__
    for m in methods:
        f = stub_method(stub, "Simulation", m)
        stubbed = [(a.arg, ast.literal_eval(d))
                   for a, d in zip(f.args.kwonlyargs, f.args.kw_defaults)]
        assert stubbed == described, m


def test_a_simulation_option_out_of_range_names_the_option(gs, repo):
    example = gs.Trajectory.load(str(repo / "examples" / "grasp_60deg.json"))
    with pytest.raises(gs.InputError, match="fidelity: 'exact' is not one of"):
        gs.simulate(example, fidelity="exact")
    with pytest.raises(gs.InputError, match="trials: must be >= 1"):
        gs.robustness(example, trials=0)
    with pytest.raises(gs.InputError, match="threads: must be"):
        gs.Simulation().robustness(example, threads=-1)
    with pytest.raises(TypeError, match="nois_scale"):
        gs.Simulation().robustness(example, nois_scale=1.0)


def extension_signature(function):
    """(name, default text or None) of each parameter but self, from pybind11's docstring."""
    line = function.__doc__.splitlines()[0]
    inner = line[line.index("(") + 1:line.rindex(") ->")]
    from graspsynth import _split_parameters  # the package's own splitter

    params = []
    for part in _split_parameters(inner):
        name = part.split(":")[0].strip()
        default = part.split(" = ", 1)[1] if " = " in part else None
        if name != "self":
            params.append((name, default))
    return params


def stub_signature(node):
    args = [a for a in node.args.args if a.arg != "self"]
    defaults = [None] * (len(args) - len(node.args.defaults)) + list(node.args.defaults)
    return [(a.arg, d) for a, d in zip(args, defaults)]


def test_the_stubs_give_the_extensions_signatures(gs):
    core = gs._core
    tree = ast.parse(Path(core.__file__).with_name("_core.pyi").read_text())
    checked = 0
    for node in tree.body:
        owner = core
        functions = [node]
        if isinstance(node, ast.ClassDef):
            owner = getattr(core, node.name)
            functions = [n for n in node.body if isinstance(n, ast.FunctionDef)
                         and not any(getattr(d, "id", "") == "property"
                                     or getattr(d, "attr", "") == "setter"
                                     for d in n.decorator_list)
                         and n.name not in ("__len__",)]
        for f in functions:
            if not isinstance(f, ast.FunctionDef):
                continue
            # the package checks the keywords of the extension's functions in a wrapper
            # (__wrapped__: the extension's own)
            function = inspect.unwrap(getattr(owner, f.name))
            if inspect.isfunction(function):
                continue  # added in Python (Synthesizer.synthesize: checked above)
            actual = extension_signature(function)
            stub = stub_signature(f)
            where = f"{getattr(owner, '__name__', '')}.{f.name}"
            assert [n for n, _ in stub] == [n for n, _ in actual], where
            for (name, stub_default), (_, default) in zip(stub, actual):
                assert (stub_default is None) == (default is None), f"{where}: {name}"
                if isinstance(stub_default, ast.Constant) and stub_default.value is not Ellipsis:
                    assert repr(stub_default.value) == default, f"{where}: {name}"
            checked += 1
    assert checked >= 30  # every function and method of the stubs


def test_every_public_name_has_a_docstring(gs):
    for name in gs.__all__:
        obj = getattr(gs, name)
        if not callable(obj):
            continue
        doc = inspect.getdoc(obj) or ""
        # pybind11 writes a signature line for every function: a docstring says more.
        text = [line for line in doc.splitlines()[1:] if line.strip()] if doc.startswith(
            name + "(") else doc.splitlines()
        assert text, name
    assert "names the file" in gs.InputError.__doc__


def test_the_installed_package_imports_and_computes(tmp_path):
    build = os.environ.get("GRASPSYNTH_BUILD_DIR")
    if not build:
        pytest.skip("GRASPSYNTH_BUILD_DIR is not set (CTest sets it)")
    subprocess.run(["cmake", "--install", build, "--prefix", str(tmp_path)], check=True,
                   capture_output=True)
    site = next(tmp_path.glob("lib/python3*/dist-packages"))
    code = ("import graspsynth, numpy; X = graspsynth.fk(numpy.zeros((2, 7)));"
            "print(graspsynth.__file__, X.shape)")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True).stdout
    assert out.startswith(str(site)) and "(2, 4, 4)" in out
    assert (tmp_path / "bin" / "graspsynth").exists()

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
        stubbed = {n for n in stubbed if not n.startswith("_")}
        assert stubbed == actual, cls


def test_every_public_name_has_a_docstring(gs):
    for name in gs.__all__:
        obj = getattr(gs, name)
        if callable(obj):
            assert inspect.getdoc(obj), name


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

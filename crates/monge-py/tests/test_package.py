"""The package itself: its names, their docstrings, and the type stubs."""

import ast
import pathlib

import monge
import monge._monge as native

STUB = pathlib.Path(__file__).resolve().parents[1] / "python" / "monge" / "_monge.pyi"


def public(names):
    return {n for n in names if not n.startswith("_")}


def test_the_stubs_declare_exactly_the_native_names():
    tree = ast.parse(STUB.read_text())
    declared = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    assert declared == public(dir(native))
    for cls in (monge.Design, monge.Mesh):
        stub = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls.__name__)
        members = {n.name for n in stub.body if isinstance(n, ast.FunctionDef)}
        members |= {n.target.id for n in stub.body if isinstance(n, ast.AnnAssign)}
        assert members == public(vars(cls)), cls


def test_every_name_is_exported_and_documented():
    assert set(monge.__all__) - {"__version__"} == public(dir(native))
    for name in public(dir(native)):
        assert getattr(monge, name).__doc__, name
    assert monge.__version__.count(".") == 2


def test_the_readme_example_runs(monkeypatch, capsys):
    readme = (STUB.parents[4] / "README.md").read_text()
    code = readme.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(STUB.parents[4])
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "'folded_faces': 0" in out and "characteristic" in out and "is singular" in out

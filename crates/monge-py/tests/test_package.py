"""The package itself: its names, their docstrings, and the type stubs."""

import ast
import doctest
import inspect
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

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


def test_the_package_doctest_runs(monkeypatch):
    # It once expected (21, 21, 3) for a (41, 33, 3) mesh, and nothing ran it.
    monkeypatch.chdir(STUB.parents[4])
    result = doctest.testmod(monge, verbose=False, report=False)
    assert result.attempted >= 3 and result.failed == 0, result


def test_signatures_show_the_real_defaults(cli):
    # help() once showed grid=Ellipsis, layers=Ellipsis.
    for f in (monge.approximate, monge.fabricate, monge.smooth, monge.scan, monge.check, monge.generate,
              monge.optimise_panels):
        assert "Ellipsis" not in str(inspect.signature(f)), f
    assert inspect.signature(monge.approximate).parameters["grid"].default == (40, 40)
    assert inspect.signature(monge.fabricate).parameters["layers"].default == [0.0]
    assert inspect.signature(monge.smooth).parameters["max_bytes"].default == 8e9
    assert inspect.signature(monge.generate).parameters["max_vertices"].default == 25_000_000
    # The core's own default, as the command writes it in its help.
    assert "[default: 25000000]" in cli("generate", "--help").stdout


def test_numpy_arrays_are_accepted_where_the_stubs_say_array_like():
    design = monge.Design.from_file(str(STUB.parents[4] / "examples" / "fig12-dupin-theta30.json"))
    assert list(monge.scan(design, np.array([10.0, 20.0]))["status"]) == ["fair", "fair"]
    assert len(monge.fabricate(design, layers=np.array([0.0, 0.1]))["layer_vertices"]) == 2


def test_the_stubs_pass_stubtest(tmp_path):
    # mypy's stubtest compares the stubs with the module at run time: the stub's
    # own aliases (Kind, PathLike, Array) and an empty __all__ once failed it.
    pytest.importorskip("mypy")
    config = tmp_path / "mypy.ini"
    config.write_text("[mypy]\nignore_missing_imports = True\n")
    p = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "monge", "--mypy-config-file", str(config)],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert p.returncode == 0, p.stdout + p.stderr


def test_the_test_wheel_is_not_where_the_release_wheel_goes():
    # scripts/pytest.sh once built its debug wheel into target/wheels, under the
    # release wheel's name, after emptying that folder.
    if "MONGE_BIN" not in os.environ:
        pytest.skip("run by scripts/pytest.sh only")
    wheel = pathlib.Path(os.environ.get("MONGE_TEST_WHEEL", ""))
    assert wheel.parent.name == "wheels-test", wheel
    assert wheel.name.startswith("monge-") and "-cp39-abi3-" in wheel.name

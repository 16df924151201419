"""Fixtures of the Python package's tests: the examples and the `monge` command.

The tests compare the package with the `monge` binary built by cargo (path in
the MONGE_BIN environment variable, set by scripts/pytest.sh) and measure its
output independently with numpy.
"""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "examples"


def example(name):
    """The path of an example design, as a string."""
    return str(EXAMPLES / name)


@pytest.fixture(scope="session")
def monge_bin():
    path = os.environ.get("MONGE_BIN") or str(ROOT / "target" / "debug" / "monge")
    if not os.path.exists(path):
        pytest.fail(
            f"the monge binary {path} does not exist: run `cargo build -p monge-cli` "
            "or set MONGE_BIN (scripts/pytest.sh does both)"
        )
    return path


@pytest.fixture
def cli(monge_bin):
    """Runs `monge ARGS…`; returns the completed process (text output)."""

    def run(*args, check=True):
        p = subprocess.run([monge_bin, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"monge {' '.join(map(str, args))}: {p.stderr}")
        return p

    return run


@pytest.fixture
def cli_mesh(cli, tmp_path):
    """`monge generate DESIGN -o mesh.json` as its JSON object, vertices as (rows, cols, 3)."""

    def run(design, *args):
        out = tmp_path / "mesh.json"
        cli("generate", design, "-o", out, *args)
        data = json.loads(out.read_text())
        shape = (data["rows"], data["cols"], 3)
        data["vertices"] = np.array(data["vertices"], dtype=float).reshape(shape)
        if data.get("normals"):
            data["normals"] = np.array(data["normals"], dtype=float).reshape(shape)
        return data

    return run


@pytest.fixture
def cli_error(cli):
    """The message of `monge ARGS…`, which must fail with status 2, without `error: `."""

    def run(*args):
        p = cli(*args, check=False)
        assert p.returncode == 2, (p.returncode, p.stderr)
        assert p.stderr.startswith("error: "), p.stderr
        return p.stderr[len("error: ") :].rstrip("\n")

    return run


def torus_patch_brep():
    """A curved rhino3dm surface sent as Grasshopper sends it, a Brep: a surface of
    revolution (a circular profile from x = 10 to 14, rising 3, turned 1.2 radians
    about the z axis), a torus patch, which has planar curvature lines (§4.1.1), so
    that one patch fits it at once."""
    import rhino3dm

    arc = rhino3dm.Arc(rhino3dm.Point3d(10, 0, 0), rhino3dm.Point3d(12.5, 0, 3), rhino3dm.Point3d(14, 0, 0))
    axis = rhino3dm.Line(rhino3dm.Point3d(0, 0, 0), rhino3dm.Point3d(0, 0, 1))
    surface = rhino3dm.RevSurface.Create(arc.ToNurbsCurve(), axis, 0.0, 1.2)
    return rhino3dm.Brep.CreateFromRevSurface(surface, False, False)


@pytest.fixture(scope="session")
def trimmed_result():
    """`monge.approximate`'s result for the shipped paraboloid's vertices, trimmed to
    its outline (trim=True; a quick search on an 8 × 8 grid)."""
    import monge

    points = np.array(
        [[float(x) for x in line.split()[1:4]] for line in open(example("targets/paraboloid.obj")) if line.startswith("v ")]
    )
    return monge.approximate(points, grid=(8, 8), starts=1, max_evaluations=60, trim=True)

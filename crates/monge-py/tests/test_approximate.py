"""monge.approximate with patches and a tolerance, compared with the `monge
approximate --patches/--tolerance` report and files (both call the same core), and
its node types at a designer's tolerance measured independently with numpy."""

import json
import re

import numpy as np
import pytest

import monge
from conftest import example

PARABOLOID = example("targets/paraboloid.obj")
# Small and fast: 8 × 8 faces, one start, a short search.
SEARCH = dict(grid=(8, 8), starts=1, max_evaluations=60)
SEARCH_ARGS = ["--grid", "8x8", "--starts", "1", "--max-evaluations", "60"]


def paraboloid_points():
    return np.array(
        [[float(x) for x in line.split()[1:4]] for line in open(PARABOLOID) if line.startswith("v ")]
    )


def number(text, pattern):
    """The number the regular expression `pattern` captures in `text`."""
    m = re.search(pattern, text)
    assert m, (pattern, text)
    return float(m.group(1))


def test_approximate_tolerance_equals_the_command(cli, tmp_path):
    """tolerance= and max_patches= give the command's design (the same file, byte
    for byte), and its report: tolerance, patches tried, node types, each patch,
    not met and why."""
    out = tmp_path / "cli.json"
    p = cli("approximate", PARABOLOID, "-o", out, *SEARCH_ARGS, "--tolerance", "5mm",
            "--max-patches", "2", check=False)
    assert p.returncode == 1, p.stderr  # not within 5 mm
    text = p.stdout
    r = monge.approximate(paraboloid_points(), **SEARCH, tolerance="5mm", max_patches=2)
    mine = tmp_path / "py.json"
    r["design"].to_file(mine)
    assert mine.read_bytes() == out.read_bytes()
    assert r["tolerance"] == pytest.approx(0.005, rel=1e-12)
    assert r["tolerance_relative"] * r["after"]["size"] == pytest.approx(0.005, rel=1e-12)
    assert number(text, r"tolerance ([0-9.e-]+) model units") == pytest.approx(r["tolerance"], rel=1e-5)
    assert not r["met"] and r["stop"] == "max_patches"
    assert "2 patches tried (max_patches=2)" in r["why"]
    # The last layout (here the only one, two patches) no nearer than a tenth of one
    # patch's largest distance: said, not "allow more".
    def nearest(several):
        d = [s["deviation"] for s in r["steps"] if (s["patches"] > 1) == several]
        return min((max(x["mesh_to_target_max"], x["target_to_mesh_max"]) for x in d if x),
                   default=float("inf"))
    stalled = nearest(True) >= 0.9 * nearest(False)
    assert ("the last layout (2 patches) not 10% nearer than fewer patches" in r["why"]) == stalled
    assert ("not 10% nearer than fewer patches" in text) == stalled
    assert "2 patches tried (--max-patches 2)" in text
    assert [s["patches"] for s in r["steps"]] == [
        int(m)
        for m in re.findall(
            r"^(\d+) patch(?:es \(§4\.7\))?(?:, trimmed to the target's outline)?: largest", text, re.M
        )
    ]
    chosen = re.search(r"^result: (.*)$", text, re.M).group(1)
    assert chosen == {"one_patch": "1 patch", "patches": f"{r['patches']} patches (§4.7)"}.get(
        r["chosen"], chosen
    )
    panels, types, tol = re.search(
        r"panels (\d+), distinct node types (\d+) \(beam angles within ([0-9.e-]+)°", text
    ).groups()
    # A trimmed result's panels are its polygons, as the command counts them.
    if r["trimmed"] is not None:
        assert r["panels"] == len(r["trimmed"]["faces"])
    assert (r["chosen"] in ("trimmed", "trimmed_patches")) == (r["trimmed"] is not None)
    assert (r["panels"], r["node_types"]) == (int(panels), int(types))
    assert r["node_angle_tol_deg"] == float(tol) == 0.5
    lines = re.findall(r"^patch (\d+) \(block (\d+) × (\d+)\): θ ([-0-9.e]+)°.*\((RMS [0-9.e-]+, )?(\d+) points\)",
                       text, re.M)
    assert len(lines) == len(r["per_patch"]) == r["patches"]
    for (k, a, b, theta, _, points), patch in zip(lines, r["per_patch"]):
        assert (int(a) - 1, int(b) - 1) == tuple(patch["block"])
        assert float(theta) == pytest.approx(patch["theta_deg"], rel=1e-5, abs=1e-9)
        assert int(points) == patch["target_points"]
    assert number(text, r"(\d+) meshes generated") == r["evaluations"]
    largest = number(text, r"nearest design found is ([0-9.e-]+) model units")
    assert largest == pytest.approx(r["max_deviation"], rel=1e-5)
    assert number(text, r"exactness of the result \(generated, measured\): ([0-9.e-]+)") == pytest.approx(
        r["max_error"], rel=1e-5
    )
    # The merged mesh: its faces index its vertices, one face a panel (a trimmed
    # result's panels are its polygons, above).
    rows, cols = r["vertices"].shape[:2]
    assert r["faces"].shape == ((rows - 1) * (cols - 1), 4) and r["faces"].max() < rows * cols
    assert r["trimmed"] is not None or r["panels"] == len(r["faces"])


def test_approximate_patches_equals_the_command(cli, tmp_path):
    """patches= gives the command's design file byte for byte (a multi-patch design
    when the patches follow the target closer), each patch's θ and the
    exactness of the patches as it prints them."""
    out = tmp_path / "cli.json"
    text = cli("approximate", PARABOLOID, "-o", out, *SEARCH_ARGS, "--patches", "2x1").stdout
    r = monge.approximate(paraboloid_points(), **SEARCH, patches="2x1")
    assert monge.approximate(paraboloid_points(), **SEARCH, patches=(2, 1))["design"] == r["design"]
    mine = tmp_path / "py.json"
    r["design"].to_file(mine)
    assert mine.read_bytes() == out.read_bytes()
    fit = r["patch_fit"]
    assert fit["closer"] == ("DESIGN is a multi-patch design" in text)
    assert isinstance(r["design"], monge.PatchesDesign if fit["closer"] else monge.Design)
    thetas = re.search(r"θ of the patches: (.*)°; (\d+) meshes generated", text)
    assert [float(t) for t in thetas.group(1).split("°, ")] == pytest.approx(fit["design"].theta_deg, rel=1e-5)
    assert int(thetas.group(2)) == fit["evaluations"]
    assert number(text, r"exactness of the patches \(generated, measured\): ([0-9.e-]+)") == pytest.approx(
        fit["max_error"], rel=1e-5, abs=1e-300
    )
    # The patches' design reads back as `monge fit` reads it.
    assert json.loads(out.read_text()) == r["design"].to_dict() or not fit["closer"]


def test_approximate_tolerance_and_patches_refuse_what_the_command_refuses(cli_error):
    """The tolerance and the layout are parsed by the command's own parsers: the
    same messages."""
    points = paraboloid_points()
    for text in ["0.05parsecs", "-1", "2"]:
        with pytest.raises(monge.OptimiseError) as e:
            monge.approximate(points, tolerance=text)
        message = str(e.value).removeprefix("tolerance: ")
        assert message in cli_error("approximate", PARABOLOID, "-o", "x.json", "--tolerance", text)
    with pytest.raises(monge.OptimiseError, match="relative tolerance of 2"):
        monge.approximate(points, tolerance=2.0)
    with pytest.raises(monge.OptimiseError) as e:
        monge.approximate(points, patches="2y3")
    assert str(e.value).split(": ", 1)[1] in cli_error("approximate", PARABOLOID, "-o", "x.json", "--patches", "2y3")
    with pytest.raises(monge.OptimiseError, match="give one"):
        monge.approximate(points, patches=2, tolerance=5e-3)
    with pytest.raises(monge.OptimiseError, match="give tolerance too"):
        monge.approximate(points, max_patches=3)
    with pytest.raises(monge.OptimiseError, match="max_patches = 0"):
        monge.approximate(points, tolerance=5e-3, max_patches=0)
    with pytest.raises(monge.OptimiseError, match="angle_tol_deg = -1"):
        monge.approximate(points, angle_tol_deg=-1)
    with pytest.raises(monge.OptimiseError, match="trim fits a mesh that covers"):
        monge.approximate(points, trim=True, keep_boundary=True)
    assert "cannot be used with" in cli_error(
        "approximate", PARABOLOID, "-o", "x.json", "--trim", "x.obj", "--keep-boundary"
    )


def angles(vertices, normals):
    """Every node's beam angles (between consecutive present edges, in the order
    +i, +j, -i, -j) and axis angles (each edge with the node axis), in degrees, and
    which directions it has: computed here with numpy from the mesh."""
    rows, cols, _ = vertices.shape
    nodes = []
    for i in range(rows):
        for j in range(cols):
            edges = []
            present = []
            for k, (di, dj) in enumerate([(1, 0), (0, 1), (-1, 0), (0, -1)]):
                a, b = i + di, j + dj
                if 0 <= a < rows and 0 <= b < cols:
                    edges.append(vertices[a, b] - vertices[i, j])
                    present.append(k)
            angle = lambda u, v: np.degrees(np.arccos(np.clip(u @ v / np.linalg.norm(u) / np.linalg.norm(v), -1, 1)))
            pairs = 1 if len(edges) == 2 else len(edges)
            beam = [angle(edges[k], edges[(k + 1) % len(edges)]) for k in range(pairs)]
            axis = [angle(e, normals[i, j]) for e in edges]
            nodes.append((tuple(present), np.array(beam + axis)))
    return nodes


def test_approximate_node_types_group_nodes_within_the_designers_tolerance(cli, tmp_path):
    """A gently curved roof: its nodes' angles differ by less than the tolerance
    (measured here with numpy), so they group into one type per set of beam
    directions (9: 4 corners, 4 sides, the inside), where the exact types
    (fabricate's 1e-4°) tell nearly every node apart; the command counts the same."""
    x, y = np.meshgrid(np.linspace(0, 10, 21), np.linspace(0, 8, 17))
    points = np.stack([x, y, 0.004 * x**2 + 0.002 * y**2], axis=-1).reshape(-1, 3)
    r = monge.approximate(points, **SEARCH, tolerance=0.5)
    nodes = angles(r["vertices"], r["normals"])
    classes = {}
    for present, a in nodes:
        classes.setdefault(present, []).append(a)
    spread = max(np.ptp(np.array(a), axis=0).max() for a in classes.values())
    assert 1e-3 < spread < 0.5, spread  # within the tolerance, far above the exact one
    assert len(classes) == 9
    assert r["node_types"] == 9 and r["node_angle_tol_deg"] == 0.5
    exact = monge.approximate(points, **SEARCH, tolerance=0.5, angle_tol_deg=1e-4)
    assert exact["node_types"] > 9 * 4
    target = tmp_path / "roof.json"
    target.write_text(json.dumps({"points": points.tolist()}))
    text = cli("approximate", target, "-o", tmp_path / "fit.json", *SEARCH_ARGS, "--tolerance", "0.5").stdout
    assert "distinct node types 9 (beam angles within 0.5°" in text
    text = cli("approximate", target, "-o", tmp_path / "fit.json", *SEARCH_ARGS, "--tolerance", "0.5",
               "--angle-tol", "1e-4").stdout
    assert f"distinct node types {exact['node_types']} (beam angles within 0.0001°" in text


def assert_trimmed_design(design, out, mesh, tmp_path):
    """`design` is the command's trimmed design `out` to the bit (the design before
    trimming, its key `design`, and the target's outline, `trim`), read back equal, and
    its mesh is the command's trimmed mesh `mesh` (the OBJ's vertices and faces)."""
    assert isinstance(design, monge.TrimmedDesign)
    mine = tmp_path / "py.json"
    design.to_file(mine)
    assert mine.read_bytes() == out.read_bytes()
    assert monge.TrimmedDesign.from_file(out) == design
    theirs = json.loads(out.read_text())
    assert json.loads(json.dumps(design.design.to_dict())) == theirs["design"]
    assert design.outline.shape == (len(theirs["trim"]["polygon"]), 3)
    lines = mesh.read_text().splitlines()
    vertices = np.array([[float(x) for x in l.split()[1:]] for l in lines if l.startswith("v ")])
    faces = [[int(x) - 1 for x in l.split()[1:]] for l in lines if l.startswith("f ")]
    m = design.mesh()
    assert np.array_equal(m["vertices"], vertices) and m["faces"] == faces


def test_approximate_trim_equals_the_command_and_its_panels_are_planar(cli, tmp_path):
    """trim=True gives the command's design and trimmed mesh (--trim), and the trimmed
    panels, measured with numpy, are planar and lie over the target: within its
    outline, near the paraboloid z = 0.04 x² + 0.1 y² over [0, 10]²."""
    out, mesh = tmp_path / "cli.json", tmp_path / "cli.obj"
    cli("approximate", PARABOLOID, "-o", out, *SEARCH_ARGS, "--trim", mesh)
    r = monge.approximate(paraboloid_points(), **SEARCH, trim=True)
    assert_trimmed_design(r["design"], out, mesh, tmp_path)
    t = r["trimmed"]
    lines = mesh.read_text().splitlines()
    vertices = np.array([[float(x) for x in l.split()[1:]] for l in lines if l.startswith("v ")])
    faces = [[int(x) - 1 for x in l.split()[1:]] for l in lines if l.startswith("f ")]
    assert np.array_equal(vertices, t["vertices"]) and faces == t["faces"]
    assert 0 < sum(t["cut"]) < len(faces)
    size = np.linalg.norm(paraboloid_points().max(0) - paraboloid_points().min(0))
    for f in faces:
        p = vertices[f] - vertices[f].mean(0)
        assert np.linalg.svd(p, compute_uv=False)[-1] <= 1e-12 * size
    # Each vertex's distance to the surface, by brute force on a fine sampling of it.
    u = np.linspace(0.0, 10.0, 401)
    x, y = np.meshgrid(u, u)
    surface = np.stack([x.ravel(), y.ravel(), (0.04 * x * x + 0.1 * y * y).ravel()], 1)
    far = max(np.min(np.linalg.norm(surface - v, axis=1)) for v in vertices)
    assert far <= 0.05 * size, far / size


def test_approximate_trimmed_patches_equal_the_command(cli, tmp_path):
    """trim=True with patches gives the command's multi-patch design and trimmed mesh
    (--trim with --patches), bit for bit."""
    out, mesh = tmp_path / "cli.json", tmp_path / "cli.obj"
    cli("approximate", PARABOLOID, "-o", out, *SEARCH_ARGS, "--trim", mesh, "--patches", "2x2")
    r = monge.approximate(paraboloid_points(), **SEARCH, trim=True, patches="2x2")
    assert r["patches"] == 4
    assert_trimmed_design(r["design"], out, mesh, tmp_path)
    assert isinstance(r["design"].design, monge.PatchesDesign)
    lines = mesh.read_text().splitlines()
    vertices = np.array([[float(x) for x in l.split()[1:]] for l in lines if l.startswith("v ")])
    faces = [[int(x) - 1 for x in l.split()[1:]] for l in lines if l.startswith("f ")]
    t = r["trimmed"]
    assert np.array_equal(vertices, t["vertices"]) and faces == t["faces"]
    assert r["panels"] == len(faces)


def torus_scan(count=2000):
    """`count` random points of a torus patch (radii 10 and 4), from the generator of
    the command's own test of a scan to a tolerance (xorshift), so the same points."""
    mask, state = (1 << 64) - 1, 0x9E3779B97F4A7C15
    points = []
    for _ in range(count):
        uv = []
        for _ in range(2):
            state ^= (state << 13) & mask
            state ^= state >> 7
            state ^= (state << 17) & mask
            uv.append((state >> 11) / float(1 << 53))
        u, v = 0.9 * uv[0], -0.6 + 1.5 * uv[1]
        rho = 10.0 + 4.0 * np.cos(v)
        points.append([rho * np.cos(u), rho * np.sin(u), 4.0 * np.sin(v)])
    return np.array(points)


def test_approximate_tolerance_on_a_scan_stops_at_its_edge_as_the_command_does(cli, tmp_path):
    """A scan within the tolerance but at its edge: the command's design and reason,
    and each fit's largest distance as far as the scan's points tell its edge, below
    its full reading; the mesh within the tolerance of the torus (closed form)."""
    points = torus_scan()
    scan = tmp_path / "torus.obj"
    scan.write_text("".join(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in points))
    out = tmp_path / "cli.json"
    p = cli("approximate", scan, "-o", out, "--tolerance", "5e-3", check=False)
    assert p.returncode == 1, p.stderr
    r = monge.approximate(points, tolerance=5e-3)
    mine = tmp_path / "py.json"
    r["design"].to_file(mine)
    assert mine.read_bytes() == out.read_bytes()
    assert not r["met"] and r["stop"] == "scan_edge" and r["chosen"] == "one_patch"
    assert "the target is a scan" in r["why"] and "the target is a scan" in p.stdout
    step = r["steps"][0]
    full = max(step["deviation"]["mesh_to_target_max"], step["deviation"]["target_to_mesh_max"])
    assert step["resolved_max"] < full
    assert step["resolved_max"] <= 5e-3 < full
    vertices = np.asarray(monge.generate(r["design"]).vertices).reshape(-1, 3)
    across = np.abs(np.hypot(np.hypot(vertices[:, 0], vertices[:, 1]) - 10.0, vertices[:, 2]) - 4.0)
    assert across.max() <= 5e-3 * r["after"]["size"]

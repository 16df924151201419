"""Errors: every exception class of monge, raised with the message that the
`monge` command prints for the same input (after its `error: `)."""

import json
import math
import warnings

import numpy as np
import pytest

import monge
from conftest import example

DUPIN = example("fig12-dupin-theta30.json")
FREEFORM = example("fig13-freeform.json")  # 61 × 41 vertices, 60 × 40 faces


def dupin(**changes):
    d = json.loads(open(DUPIN).read())
    d.update(changes)
    return d


def write(tmp_path, name, data):
    path = tmp_path / name
    path.write_text(data if isinstance(data, str) else json.dumps(data, indent=2))
    return str(path)


def test_hierarchy():
    for cls in [monge.FileError, monge.DesignError, monge.DegenerateError, monge.MeshError,
                monge.SmoothError, monge.FabricationError, monge.ScanError, monge.OptimiseError]:
        assert issubclass(cls, monge.MongeError)
    assert issubclass(monge.ThetaError, monge.DesignError)
    assert issubclass(monge.MongeError, Exception)


def test_missing_file_is_a_file_error(tmp_path, cli_error):
    path = str(tmp_path / "missing.json")
    with pytest.raises(monge.FileError) as e:
        monge.Design.from_file(path)
    assert str(e.value) == cli_error("info", path)


def test_unknown_key_is_a_design_error_located_like_the_command(tmp_path, cli_error):
    path = write(tmp_path, "typo.json", '{"thetadeg": 30,\n "guide_u": {}, "guide_v": {}}\n')
    with pytest.raises(monge.DesignError) as e:
        monge.Design.from_file(path)
    assert str(e.value) == cli_error("info", path)
    assert "unknown field `thetadeg`" in str(e.value) and ":1:" in str(e.value)


def test_unknown_extension_is_a_design_error(tmp_path, cli_error):
    path = write(tmp_path, "design.yaml", "theta_deg: 30\n")
    with pytest.raises(monge.DesignError) as e:
        monge.Design.from_file(path)
    assert str(e.value) == cli_error("info", path)


def test_from_dict_errors_name_the_key():
    with pytest.raises(monge.DesignError, match="unknown field `thetadeg`"):
        monge.Design.from_dict({"thetadeg": 30})
    with pytest.raises(monge.DesignError, match="not JSON-like .* at `theta_deg`"):
        monge.Design.from_dict(dupin(theta_deg=object()))


def freeform(change):
    with open(FREEFORM) as f:
        d = json.load(f)
    change(d)
    return d


@pytest.mark.parametrize(
    "change, message",
    [
        # They once named `<input>:63:1`, a line of a JSON text the caller never saw.
        (lambda d: d["guide_u"]["bspline"].update(foo=1),
         "at `guide_u.bspline.foo`: unknown field `foo`, expected one of"),
        (lambda d: d["guide_u"]["bspline"].pop("samples"), "at `guide_u.bspline`: missing field `samples`"),
        (lambda d: d.update(mesh="hex"), "at `mesh`: unknown variant `hex`, expected `circular` or `conical`"),
        (lambda d: d["guide_u"]["bspline"].update(samples="x"),
         'guide_u.bspline.samples must be a whole number ≥ 0, got the string "x"'),
        (lambda d: d.pop("guide_v"), "missing field `guide_v`"),
        # NaN and infinities (which JSON has not) are named where they are.
        (lambda d: d.update(theta_deg=float("nan")), "a number is not finite at `theta_deg` (nan): give a finite number"),
        (lambda d: d["guide_u"]["bspline"]["control_points"][1].__setitem__(0, float("-inf")),
         "a number is not finite at `guide_u.bspline.control_points[1][0]` (-inf): give a finite number"),
        (lambda d: d["guide_v"]["bspline"].update(control_points=np.array([[0, 0, 0], [0, np.nan, 1.0]])),
         "a number is not finite at `guide_v.bspline.control_points[1][1]` (nan): give a finite number"),
        (lambda d: d.update(patches=[]), "the dict is a multi-patch design (§4.7), not a design"),
    ],
)
def test_from_dict_errors_name_the_key_path_not_a_line(change, message):
    with pytest.raises(monge.DesignError) as e:
        monge.Design.from_dict(freeform(change))
    assert str(e.value).startswith("Design.from_dict: ")
    assert str(e.value).split("\n")[0].startswith("Design.from_dict: " + message), str(e.value)
    assert "<input>" not in str(e.value) and "\n" not in str(e.value)


def test_from_dict_takes_a_dict_and_numpy_values():
    with pytest.raises(monge.DesignError, match=r"^Design.from_dict: give a dict with the keys of the file, got list \[1, 2\]$"):
        monge.Design.from_dict([1, 2])
    d = freeform(lambda d: d.update(theta_deg=np.float32(-30.0)))
    d["guide_u"]["bspline"]["samples"] = np.int64(61)
    d["guide_u"]["bspline"]["control_points"] = np.array(d["guide_u"]["bspline"]["control_points"])
    assert monge.Design.from_dict(d) == monge.Design.from_file(FREEFORM)
    p = json.loads(open(example("fig20-piecewise.patches.json")).read())
    p["patches"][0]["theta_deg"] = "x"
    with pytest.raises(monge.DesignError, match=r'^fit: patches\[0\]\.theta_deg must be a number, got the string "x"$'):
        monge.fit(p)


def test_invalid_guides_are_design_errors_with_the_commands_message(tmp_path, cli_error):
    d = dupin()
    d["guide_v"]["arc"]["normal"] = [-1, 0.2, 0]  # start tangents no longer at 90°
    path = write(tmp_path, "skew.json", d)
    with pytest.raises(monge.DesignError) as e:
        monge.generate(monge.Design.from_file(path))
    assert type(e.value) is monge.DesignError
    assert str(e.value) == cli_error("generate", path, "-o", tmp_path / "out.obj")
    assert str(e.value).startswith(path + ": the guides must meet at 90°")
    with pytest.raises(monge.DesignError) as e:
        monge.info(monge.Design.from_file(path))
    assert str(e.value) == cli_error("info", path)
    assert not (tmp_path / "out.obj").exists()


def arbitrary(theta_deg):
    d = json.loads(open(example("fig10-arbitrary.json")).read())
    d["theta_deg"] = theta_deg
    return d


def normal_still():
    # guide_v leaves guide_u's plane (y = 0) by 3e-7 rad: that plane is nearly the
    # tangent plane, and the normal barely turns along guide_u.
    def arc(center, normal, angle_deg, samples):
        return {"arc": {"center": center, "start": [0, 0, 0], "normal": normal,
                        "angle_deg": angle_deg, "samples": samples}}
    return {"theta_deg": 66, "guide_u": arc([0, 0, -10], [0, 1, 0], 120, 41),
            "guide_v": arc([0, 10, -3e-6], [-1, 0, 0], 80, 33)}


@pytest.mark.parametrize(
    "design, error, fragment",
    [
        (dupin(theta_deg=90), monge.ThetaError, "is singular"),
        (normal_still(), monge.DegenerateError, "turns by only 5.2e-7 rad along guide_u"),
        # fig10 is in the arbitrary mode (§3.2): θ = 1° is below its admissible range
        (arbitrary(1), monge.ThetaError, "is not admissible"),
        (dupin(theta_deg=180), monge.DegenerateError, "cannot be built past face"),
    ],
)
def test_generation_errors_have_the_commands_message(design, error, fragment, tmp_path, cli_error):
    path = write(tmp_path, "design.json", design)
    with pytest.raises(error) as e:
        monge.generate(monge.Design.from_file(path))
    assert str(e.value) == cli_error("generate", path, "-o", tmp_path / "out.obj")
    assert fragment in str(e.value)


def test_info_refuses_guides_along_which_the_normal_barely_turns(tmp_path, cli_error):
    # A property of the guides, not of θ: `info` refuses it as `generate` does.
    path = write(tmp_path, "design.json", normal_still())
    with pytest.raises(monge.DegenerateError) as e:
        monge.info(monge.Design.from_file(path))
    assert str(e.value) == cli_error("info", path)
    assert "turns by only 5.2e-7 rad along guide_u" in str(e.value)


def test_bad_arrays_and_mesh_files_are_mesh_errors(tmp_path, cli_error):
    with pytest.raises(monge.MeshError, match=r"shape \(rows, cols, 3\), got \(3, 3, 2\)"):
        monge.check(np.zeros((3, 3, 2)))
    with pytest.raises(monge.MeshError, match=r"shape \(rows, cols, 3\), got \(9,\)"):
        monge.check(np.zeros(9))
    v = np.zeros((2, 2, 3))
    v[1, 0, 2] = np.inf
    with pytest.raises(monge.MeshError, match=r"vertices\[1, 0\] = .* is not finite"):
        monge.check(v)
    with pytest.raises(monge.MeshError, match=r"normals have shape \(2, 3, 3\)"):
        monge.check(np.zeros((2, 2, 3)), normals=np.zeros((2, 3, 3)))
    path = write(tmp_path, "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 x\n")
    with pytest.raises(monge.MeshError) as e:
        monge.check(path)
    assert str(e.value) == cli_error("check", path)


def test_offsets_must_be_finite():
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    with pytest.raises(monge.DesignError, match="finite"):
        mesh.offset(float("inf"))


@pytest.mark.parametrize("name", ["fig13-freeform.json", "fig13-conical.json"])
def test_offsets_whose_size_overflows_are_refused_before_measuring(name, capfd):
    # 1.5e308 once raised a PanicException ("Singular value was NaN", with a
    # hundred panic traces on stderr); 5e307 gave max_error NaN.
    mesh = monge.generate(monge.Design.from_file(example(name)))
    for d in (1.5e308, -1.5e308, 5e307, 1e160):
        with pytest.raises(monge.MeshError) as e:
            mesh.offset(d)
        assert str(e.value).startswith(f"offset(d={d!r}): ")
        # The size to 6 significant digits, as Python writes that number.
        v = np.asarray(mesh.vertices).reshape(-1, 3)
        size = float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))
        assert f"give a smaller |d| (this mesh's own size is {float(f'{size:.5e}')!r};" in str(e.value)
    assert "is not finite in f64, its coordinates reaching 5.0e307" in str(
        pytest.raises(monge.MeshError, mesh.offset, 5e307).value
    )
    assert "panicked" not in capfd.readouterr().err
    far = mesh.offset(1e6)
    assert math.isfinite(far.report["max_error"]) and far.offset_distance == 1e6


def test_smooth_errors(tmp_path, cli_error):
    # θ = −150° folds this design (§5.2): the cyclidic net refuses folded quads
    path = write(tmp_path, "folded.json", dupin(theta_deg=-150))
    with pytest.raises(monge.SmoothError) as e:
        monge.smooth(monge.Design.from_file(path))
    assert str(e.value) == cli_error("smooth", path, "-o", tmp_path / "net.json")
    with pytest.raises(monge.SmoothError, match="samples = 1"):
        monge.smooth(monge.Design.from_file(DUPIN), samples=1)
    conical = monge.generate(monge.Design.from_file(DUPIN), kind="conical")
    with pytest.raises(monge.SmoothError, match="not on a conical mesh"):
        monge.smooth(conical)


def test_smooth_refuses_a_conical_design_as_the_command_does(tmp_path, cli_error):
    # It once built the net of the design's circular mesh without a word.
    path = example("fig13-conical.json")
    design = monge.Design.from_file(path)
    with pytest.raises(monge.SmoothError) as e:
        monge.smooth(design)
    expected = cli_error("smooth", path, "-o", tmp_path / "net.json")
    assert str(e.value) == expected + (
        '; or keep it and pass its circular mesh, smooth(generate(design, kind="circular"))'
    )
    assert str(e.value).startswith(path + ': the design asks for a conical mesh')
    with pytest.raises(monge.SmoothError, match=r'^the design asks for a conical mesh'):
        monge.smooth(monge.Design.from_dict(design.to_dict()))
    # its circular mesh has a net
    s = monge.smooth(monge.generate(design, kind="circular"), samples=3)
    assert s["patches"].shape[2:] == (3, 3, 3)


def test_fabrication_errors():
    design = monge.Design.from_file(DUPIN)
    with pytest.raises(monge.FabricationError, match=r"^.*fig12-dupin-theta30.json: no layer"):
        monge.fabricate(design, layers=[])
    with pytest.raises(monge.FabricationError, match="tolerance `tol` is -1"):
        monge.fabricate(design, tol=-1.0)


def test_scan_errors(tmp_path, cli_error):
    design = monge.Design.from_file(DUPIN)
    with pytest.raises(monge.ScanError) as e:
        monge.scan(design, [0.0, 1.0], param="guide_u.spline.degree")
    expected = cli_error("scan", DUPIN, "--param", "guide_u.spline.degree", "--range", "0:1:1",
                         "-o", tmp_path / "scan.csv")
    assert str(e.value) == expected
    assert not (tmp_path / "scan.csv").exists()


def test_optimise_errors(tmp_path, cli_error):
    with pytest.raises(monge.OptimiseError) as e:
        monge.optimise_panels(monge.Design.from_file(DUPIN))
    assert str(e.value) == cli_error("optimise-panels", DUPIN, "-o", tmp_path / "o.json")
    assert "neither guide is a `bspline`" in str(e.value)
    patches = json.loads(open(example("fig20-piecewise.patches.json")).read())
    patches.pop("fit", None)
    path = write(tmp_path, "nofit.patches.json", patches)
    with pytest.raises(monge.OptimiseError) as e:
        monge.fit(path)
    assert str(e.value) == cli_error("fit", path, "-o", tmp_path / "f.json")
    with pytest.raises(monge.OptimiseError):
        monge.fit(patches)



def test_smooth_refuses_a_result_above_max_bytes_before_building_it():
    design = monge.Design.from_file(FREEFORM)
    # 60 × 40 patches of 1000 × 1000 points: 57.6 GB of patches alone
    with pytest.raises(monge.SmoothError) as e:
        monge.smooth(design, samples=1000)
    assert str(e.value).startswith(
        "smooth would take about 57.6 GB of memory (60 × 40 patches of 1000 × 1000 points, "
    )
    assert "above max_bytes = 8e9 (8.0 GB): lower samples (K × K points a patch) or use " \
        "fewer guide samples, or raise max_bytes" in str(e.value)
    # The estimate counts at least the patches returned.
    s = monge.smooth(design, samples=4)
    with pytest.raises(monge.SmoothError, match=r"above max_bytes = .*: lower samples"):
        monge.smooth(design, samples=4, max_bytes=s["patches"].nbytes)
    # On a mesh, the advice is a coarser mesh.
    with pytest.raises(monge.SmoothError, match="lower samples .* or pass a coarser mesh"):
        monge.smooth(monge.generate(design), samples=300, max_bytes=1e9)
    assert monge.smooth(design, samples=4, max_bytes=float("inf"))["patches"].shape == (60, 40, 4, 4, 3)
    for bad in (float("nan"), 0, -1.0):
        with pytest.raises(monge.SmoothError, match=r"max_bytes = .*: give a positive number of bytes"):
            monge.smooth(design, samples=4, max_bytes=bad)


def test_fabricate_refuses_a_result_above_max_bytes_before_building_it():
    design = monge.Design.from_file(FREEFORM)
    with pytest.raises(monge.FabricationError) as e:
        monge.fabricate(design, layers=[i * 0.01 for i in range(3000)])
    assert str(e.value) == (
        "fabricate would take about 64.8 GB of memory (the panels, beams and nodes of 60 × 40 "
        "faces and 3000 layer(s)), above max_bytes = 8e9 (8.0 GB): use fewer layers or fewer "
        "guide samples, or raise max_bytes if the machine has the memory"
    )
    with pytest.raises(monge.FabricationError, match=r"about 29 MB .* above max_bytes = 1e7 \(10 MB\)"):
        monge.fabricate(design, layers=[0.0], max_bytes=1e7)
    assert len(monge.fabricate(design, layers=[0.0, 0.1], max_bytes=1e8)["layer_vertices"]) == 2
    with pytest.raises(monge.FabricationError, match="max_bytes = nan"):
        monge.fabricate(design, max_bytes=float("nan"))


def shifted(path, by):
    """The design at `path` with both guides moved by `by` along x, y and z."""
    with open(path) as f:
        d = json.load(f)
    for g in ("guide_u", "guide_v"):
        spec = d[g]["bspline"]
        spec["control_points"] = [[c + by for c in p] for p in spec["control_points"]]
    return d


def test_far_from_origin_warns_as_the_command_does(tmp_path, cli):
    # 1e10 away, the mesh is generated with max_error 2e-7: it was silent.
    path = write(tmp_path, "far.json", shifted(FREEFORM, 1e10))
    design = monge.Design.from_file(path)
    stderr = cli("generate", path, "-o", tmp_path / "far.obj").stderr
    lines = [line.split("warning: ", 1)[1] for line in stderr.splitlines() if "warning: " in line]
    command = next(line for line in lines if line.startswith("the coordinates"))
    with pytest.warns(UserWarning) as all_warnings:
        mesh = monge.generate(design)
    w = [x for x in all_warnings if x.category is monge.FarFromOriginWarning]
    assert len(w) == 1 and issubclass(monge.FarFromOriginWarning, UserWarning)
    # the measured error over 1e-9 is told too (InexactWarning)
    assert [x.category for x in all_warnings].count(monge.InexactWarning) == 1
    message = str(w[0].message)
    # the command's words (one function of monge-io for both)
    assert message == command
    assert message.startswith("the coordinates are up to 5.1e8 times the design's size away")
    assert "(beyond 1.1e3 times)" in message
    assert '`--base-point start` (Python: `base_point="start"`)' in message
    assert w[0].filename == __file__  # the caller's line, not monge's
    with pytest.warns(monge.FarFromOriginWarning):
        monge.info(design)
    with pytest.warns(monge.FarFromOriginWarning):
        monge.check(mesh)
    # as errors (-W error), a warning is raised
    with warnings.catch_warnings():
        warnings.simplefilter("error", monge.FarFromOriginWarning)
        with pytest.raises(monge.FarFromOriginWarning):
            monge.generate(design)
    # near the origin, no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", monge.FarFromOriginWarning)
        monge.check(monge.generate(monge.Design.from_file(FREEFORM)))
        monge.info(monge.Design.from_dict(shifted(FREEFORM, 1e4)))


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda d: monge.smooth(d, samples=-1), monge.SmoothError,
         "samples = -1: give K in 2..=1000 (K × K points a patch)"),
        (lambda d: monge.smooth(d, samples=np.int64(-3)), monge.SmoothError,
         "samples = -3: give K in 2..=1000 (K × K points a patch)"),
        (lambda d: monge.smooth(d, samples=10**30), monge.SmoothError,
         f"samples = {10**30}: give K in 2..=1000 (K × K points a patch)"),
        (lambda d: monge.approximate(np.zeros((9, 3)), grid=(-1, 5)), monge.OptimiseError,
         "grid = (-1, 5): give (faces along guide_u, faces along guide_v), whole numbers, e.g. (40, 40)"),
        (lambda d: monge.approximate(np.zeros((9, 3)), starts=-2), monge.OptimiseError,
         "starts = -2: give a whole number of starts (default 4)"),
        (lambda d: monge.approximate(np.zeros((9, 3)), max_evaluations=-5), monge.OptimiseError,
         "max_evaluations = -5: give a whole number of mesh generations for each optimiser run "
         "(default 1500)"),
        (lambda d: monge.optimise_panels(d, max_evaluations=-1), monge.OptimiseError,
         "max_evaluations = -1: give a whole number of evaluations, or None for the optimiser's "
         "own budget"),
        (lambda d: monge.generate(d, max_vertices=-1), monge.DesignError,
         "max_vertices = -1: give a whole number of vertices (default 25000000)"),
    ],
)
def test_negative_whole_numbers_are_refused_naming_the_argument(call, error, message):
    # They once raised a bare "OverflowError: can't convert negative int to unsigned".
    with pytest.raises(error) as e:
        call(monge.Design.from_file(DUPIN))
    assert str(e.value) == message


def test_other_types_are_type_errors_naming_the_argument():
    design = monge.Design.from_file(DUPIN)
    with pytest.raises(TypeError, match="samples"):
        monge.smooth(design, samples=9.0)
    with pytest.raises(TypeError, match="grid"):
        monge.approximate(np.zeros((9, 3)), grid=5)
    assert monge.smooth(design, samples=np.int64(3))["patches"].shape[2] == 3


def test_generate_takes_a_vertex_limit_in_pythons_words(tmp_path):
    design = monge.Design.from_file(DUPIN)  # 41 × 33 = 1353 vertices
    with pytest.raises(monge.DesignError) as e:
        monge.generate(design, max_vertices=1000)
    assert str(e.value) == (
        f"{DUPIN}: the grid would have 41 × 33 = 1353 vertices, more than the limit of 1000: lower "
        "the `samples` of the guides, or raise the limit with generate(design, max_vertices=N) if the "
        "machine has the memory (48 bytes a vertex)"
    )
    assert "--max-vertices" not in str(e.value) and "GenerateOptions" not in str(e.value)
    assert monge.generate(design, max_vertices=1353).vertices.shape == (41, 33, 3)
    d = dupin()
    d["guide_u"]["arc"]["samples"] = 10**5
    d["guide_v"]["arc"]["samples"] = 10**5
    with pytest.raises(monge.DesignError, match="100000 × 100000 = 10000000000 vertices, more than the limit of 25000000"):
        monge.generate(monge.Design.from_dict(d))


def test_to_file_into_a_missing_folder_says_so_in_pythons_words(tmp_path):
    # It once said "choose another -o".
    path = tmp_path / "missing" / "d.json"
    with pytest.raises(monge.FileError) as e:
        monge.Design.from_file(DUPIN).to_file(path)
    assert str(e.value) == (
        f"cannot write `{path}`: the folder `{tmp_path / 'missing'}` does not exist: create it first "
        "(e.g. os.makedirs), or give a path in a folder that exists"
    )
    assert not path.parent.exists()


# A conical mesh whose faces turn over (4 folded faces, conical error 2.0),
# found by a sweep of random designs: once silent in Python and in the command.
TURNED = {
    "theta_deg": -161.88466388622183,
    "mesh": "conical",
    "guide_u": {"bspline": {"degree": 3, "samples": 7, "control_points": [
        [0, 0, 0], [1, 0, 0], [2.2330790589699796, 0, -0.5541680285794847],
        [2.8675485424895477, 0, -2.155466699292466], [3.4849537934883603, 0, 1.7232772800102358]]}},
    "guide_v": {"bspline": {"degree": 3, "samples": 11, "control_points": [
        [0, 0, 0], [0, 1, 0], [-0.007441484123705624, 1.9927520724723893, -0.0996294952040866],
        [6.193939782998956e-5, 3.0061583164315824, 0.0008292688442872063]]}},
}


def test_an_error_above_the_tolerance_warns_as_the_command_does(tmp_path, cli):
    path = write(tmp_path, "turned.json", TURNED)
    stderr = cli("generate", path, "-o", tmp_path / "m.obj").stderr
    command = next(line for line in stderr.splitlines() if "measures an error" in line)
    with pytest.warns(monge.InexactWarning) as w:
        mesh = monge.generate(monge.Design.from_file(path))
    assert issubclass(monge.InexactWarning, UserWarning)
    message = str(w[0].message)
    assert message.startswith("the mesh measures an error of 2.0e0 of its size")
    assert "likely cause: its 4 folded faces" in message
    # the command's words after the mesh's name (one function of monge-io for both)
    assert command.split(" measures ", 1)[1] == message.split(" measures ", 1)[1]
    assert w[0].filename == __file__
    assert mesh.report["folded_faces"] == 4 and mesh.report["max_error"] > 1.9
    # the conical faces turned over, measured here with numpy: the cross
    # product of each face's diagonals against its face normal
    v = mesh.vertices
    d1 = v[1:, 1:] - v[:-1, :-1]
    d2 = v[:-1, 1:] - v[1:, :-1]
    own = np.cross(d1, d2)
    cli("generate", path, "-o", tmp_path / "m.json")
    data = json.loads((tmp_path / "m.json").read_text())
    normals = np.array(data["face_normals"], dtype=float).reshape(own.shape)
    turned = int(((own * normals).sum(axis=2) < 0).sum())
    assert 0 < turned <= mesh.report["folded_faces"]
    # an exact mesh: no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", monge.InexactWarning)
        monge.generate(monge.Design.from_file(DUPIN))


def test_smooth_refuses_the_folded_mesh_that_check_finds_folded():
    # Dupin-family guides sampled from two arcs, θ = 30°: 144 folded faces
    # (48 bow-ties) for generate and check; smooth once built a net over them.
    def arc(n, angle_deg, along):
        t = np.radians(angle_deg) * np.arange(n) / (n - 1)
        return [along(np.sin(x), np.cos(x) - 1) for x in t]

    design = monge.Design.from_dict({
        "theta_deg": 30,
        "guide_u": {"points": arc(25, 120, lambda s, c: [s, 0, c])},
        "guide_v": {"points": arc(21, 300, lambda s, c: [0, s, c])},
    })
    mesh = monge.generate(design)
    assert monge.check(mesh)["folded_faces"] == {"value": 144, "at": (0, 0)}
    for source in (design, mesh):
        with pytest.raises(monge.SmoothError, match=r"face \(0, 0\) is folded"):
            monge.smooth(source, samples=2)
        assert monge.smooth(source, samples=2, allow_folded=True)["patches"].shape[:2] == (24, 20)


@pytest.mark.parametrize(
    "x", [0.0, -0.0, -1.0, -0.1, -1e-05, -123456.0, -1e16, -1.5e308, float("nan"), float("-inf")]
)
def test_numbers_in_messages_are_written_as_python_writes_them(x):
    # The refused value in the message is the value's own repr.
    design = monge.Design.from_file(FREEFORM)
    with pytest.raises(monge.SmoothError) as e:
        monge.smooth(design, samples=4, max_bytes=x)
    assert str(e.value).startswith(f"max_bytes = {x!r}: give a positive number of bytes"), str(e.value)

"""The checker of the cross-built wheels (scripts/check-wheels.py), and the wheels themselves.

The checker's own checks run on wheels made here from a real RECORD and WHEEL
and then damaged; the wheels of scripts/wheels.sh are checked only when that
script has built them (target/wheels-all; skipped otherwise: the cross builds
take minutes per platform and are not part of the suite).
"""

import base64
import hashlib
import importlib.util
import pathlib
import zipfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
WHEELS = ROOT / "target" / "wheels-all"

spec = importlib.util.spec_from_file_location("check_wheels", ROOT / "scripts" / "check-wheels.py")
check_wheels = importlib.util.module_from_spec(spec)
spec.loader.exec_module(check_wheels)

NAME = "monge-0.1.0-cp39-abi3-win_amd64.whl"


def digest(data):
    return "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()


def make_wheel(path, tags=("cp39-abi3-win_amd64",), tamper=None):
    """A wheel holding one module, with a WHEEL of the given tags and a RECORD (then `tamper`ed)."""
    files = {
        "monge/__init__.py": b"from ._monge import *\n",
        "monge-0.1.0.dist-info/WHEEL": (
            "Wheel-Version: 1.0\nGenerator: test\nRoot-Is-Purelib: false\n"
            + "".join(f"Tag: {t}\n" for t in tags)
        ).encode(),
    }
    record = "".join(f"{n},{digest(d)},{len(d)}\n" for n, d in files.items())
    record += "monge-0.1.0.dist-info/RECORD,,\n"
    files["monge-0.1.0.dist-info/RECORD"] = record.encode()
    if tamper:
        tamper(files)
    with zipfile.ZipFile(path, "w") as zf:
        for n, d in files.items():
            zf.writestr(n, d)
    return path


def run(check, path):
    with zipfile.ZipFile(path) as zf:
        return check(path.name, zf)


def test_a_sound_wheel_passes_the_tag_and_record_checks(tmp_path):
    wheel = make_wheel(tmp_path / NAME)
    platform, line = run(check_wheels.check_tags, wheel)
    assert platform.name == "Windows x86_64" and "win_amd64" in line
    assert run(check_wheels.check_record, wheel) == "RECORD: 2 files, sha256 and sizes match"


def test_a_file_changed_after_record_was_written_is_caught(tmp_path):
    def change(files):
        files["monge/__init__.py"] += b"# changed\n"

    with pytest.raises(check_wheels.CheckError, match="monge/__init__.py has sha256"):
        run(check_wheels.check_record, make_wheel(tmp_path / NAME, tamper=change))


def test_a_file_missing_from_record_is_caught(tmp_path):
    def add(files):
        files["monge/extra.py"] = b""

    with pytest.raises(check_wheels.CheckError, match="monge/extra.py"):
        run(check_wheels.check_record, make_wheel(tmp_path / NAME, tamper=add))


def test_tags_that_disagree_with_the_file_name_are_caught(tmp_path):
    wheel = make_wheel(tmp_path / NAME, tags=("cp39-abi3-macosx_11_0_arm64",))
    with pytest.raises(check_wheels.CheckError, match="the file name says"):
        run(check_wheels.check_tags, wheel)
    cp311 = make_wheel(tmp_path / "monge-0.1.0-cp311-cp311-win_amd64.whl", tags=("cp311-cp311-win_amd64",))
    with pytest.raises(check_wheels.CheckError, match="stable ABI"):
        run(check_wheels.check_tags, cp311)


def test_the_libraries_allowed_on_each_platform():
    windows, mac = (next(p for p in check_wheels.PLATFORMS if p.name == n) for n in ("Windows x86_64", "macOS arm64"))
    for dll in ("python3.dll", "KERNEL32.dll", "api-ms-win-core-synch-l1-2-0.dll", "ntdll.dll", "bcryptprimitives.dll"):
        assert windows.allows(dll), dll
    # The MinGW runtime DLLs are on no Windows machine; a versioned pythonXY.dll breaks abi3.
    for dll in ("libgcc_s_seh-1.dll", "libwinpthread-1.dll", "libstdc++-6.dll", "python311.dll"):
        assert not windows.allows(dll), dll
    assert mac.allows("/usr/lib/libSystem.B.dylib")
    assert not mac.allows("/opt/homebrew/lib/libgcc_s.1.dylib")
    assert not mac.allows("@rpath/libpython3.11.dylib")


@pytest.mark.skipif(not WHEELS.is_dir(), reason=f"no cross-built wheels in {WHEELS}: scripts/wheels.sh builds them")
@pytest.mark.parametrize("wheel", sorted(WHEELS.glob("*.whl")) if WHEELS.is_dir() else [], ids=lambda w: w.name)
def test_the_cross_built_wheel(wheel):
    for module in ("pefile", "macholib", "elftools", "auditwheel"):
        pytest.importorskip(module, reason=f"{module} checks the wheels (scripts/wheels.sh installs it)")
    lines = check_wheels.check_wheel(wheel)
    assert any(line.startswith("links only system libraries") for line in lines), lines

#!/usr/bin/env python3
"""Checks the cross-built wheels of scripts/wheels.sh as far as a Linux machine can.

    python scripts/check-wheels.py FOLDER [--monge BIN] [--no-run]

For every wheel in FOLDER: the tags of its file name and of its WHEEL file
(CPython >= 3.9 stable ABI, the platform the binary is built for), every file
hashed as RECORD says, the extension's binary format and architecture, that it
exports PyInit__monge, that it links only the system libraries of its platform
(and python3.dll, not a versioned pythonXY.dll, on Windows; no libpython on
Linux and macOS), and its size. The manylinux wheel is also checked by
`auditwheel show`, installed in a clean venv, and run: the README's Python
example, and the vertices of monge.generate compared with `monge generate`'s.
Prints one line per check; exits 1 if one fails.

Needs pefile, macholib, pyelftools and auditwheel (scripts/wheels.sh installs
them in its venv).
"""

import argparse
import base64
import csv
import hashlib
import io
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
# Largest wheel accepted: the wheels are 1-3 MB; a wheel with debug information
# or a statically linked C++ runtime would be several times larger.
MAX_WHEEL_BYTES = 8_000_000
INIT = "PyInit__monge"


class Platform:
    """What one platform's wheel must be: its tag, binary format, architecture, allowed libraries."""

    def __init__(self, name, tag, fmt, arch, allowed):
        self.name, self.tag, self.fmt, self.arch = name, re.compile(tag), fmt, arch
        self.allowed = [re.compile(a, re.IGNORECASE) for a in allowed]

    def allows(self, lib):
        return any(a.fullmatch(lib) for a in self.allowed)


# The system libraries each platform has on every machine. Windows: the stable
# ABI's python3.dll, the API sets, the kernel, the C runtime the system ships
# (msvcrt) or the universal CRT, and the system DLLs Rust's std calls (crypto
# random numbers, sockets, users). No libgcc_s/libstdc++/libwinpthread: a
# wheel needing them fails to import on a machine without MinGW.
WINDOWS_DLLS = [
    r"python3\.dll",
    r"api-ms-win-[a-z0-9-]+\.dll",
    r"kernel32\.dll",
    r"kernelbase\.dll",
    r"ntdll\.dll",
    r"msvcrt\.dll",
    r"ucrtbase\.dll",
    r"vcruntime140(_1)?\.dll",
    r"bcrypt\.dll",
    r"bcryptprimitives\.dll",
    r"advapi32\.dll",
    r"ws2_32\.dll",
    r"userenv\.dll",
    r"shell32\.dll",
    r"ole32\.dll",
    r"oleaut32\.dll",
    r"secur32\.dll",
    r"crypt32\.dll",
    r"user32\.dll",
]
PLATFORMS = [
    Platform(
        "Linux x86_64", r"(manylinux2014_x86_64\.)?manylinux_2_17_x86_64(\.manylinux2014_x86_64)?", "ELF", "x86_64",
        # The manylinux 2014 policy's libraries (checked again by auditwheel).
        [r"libc\.so\.6", r"libm\.so\.6", r"libdl\.so\.2", r"libpthread\.so\.0", r"librt\.so\.1",
         r"libgcc_s\.so\.1", r"ld-linux-x86-64\.so\.2"],
    ),
    Platform(
        "macOS x86_64", r"macosx_10_(1[2-5])_x86_64", "Mach-O", "x86_64",
        [r"/usr/lib/libSystem\.B\.dylib", r"/usr/lib/libiconv\.2\.dylib", r"/usr/lib/libcharset\.1\.dylib", r"/usr/lib/libresolv\.9\.dylib",
         r"/System/Library/Frameworks/(CoreFoundation|Security)\.framework/.*"],
    ),
    Platform(
        "macOS arm64", r"macosx_11_0_arm64", "Mach-O", "arm64",
        [r"/usr/lib/libSystem\.B\.dylib", r"/usr/lib/libiconv\.2\.dylib", r"/usr/lib/libcharset\.1\.dylib", r"/usr/lib/libresolv\.9\.dylib",
         r"/System/Library/Frameworks/(CoreFoundation|Security)\.framework/.*"],
    ),
    Platform("Windows x86_64", r"win_amd64", "PE", "x86_64", WINDOWS_DLLS),
]


def platform_of(tag):
    for p in PLATFORMS:
        if p.tag.fullmatch(tag):
            return p
    raise CheckError(f"platform tag {tag!r} is none of the platforms built ({', '.join(p.name for p in PLATFORMS)})")


class CheckError(Exception):
    pass


def parse_name(name):
    """(distribution, version, python, abi, platform) of a wheel's file name."""
    parts = name[: -len(".whl")].split("-")
    if len(parts) != 5:
        raise CheckError(f"{name}: not NAME-VERSION-PYTHON-ABI-PLATFORM.whl")
    return parts


def check_tags(name, zf):
    dist, version, py, abi, plat = parse_name(name)
    if (dist, py, abi) != ("monge", "cp39", "abi3"):
        raise CheckError(f"{name}: expected monge-VERSION-cp39-abi3-PLATFORM.whl (stable ABI, CPython >= 3.9)")
    wheel_file = f"{dist}-{version}.dist-info/WHEEL"
    meta = zf.read(wheel_file).decode()
    tags = {line.split(":", 1)[1].strip() for line in meta.splitlines() if line.startswith("Tag:")}
    expected = {f"{py}-{abi}-{p}" for p in plat.split(".")}
    if tags != expected:
        raise CheckError(f"{wheel_file}: tags {sorted(tags)}, the file name says {sorted(expected)}")
    if "Root-Is-Purelib: false" not in meta:
        raise CheckError(f"{wheel_file}: Root-Is-Purelib is not false (the wheel holds a binary)")
    return platform_of(plat), f"tags cp39-abi3-{plat} in the name and WHEEL"


def check_record(name, zf):
    dist, version = parse_name(name)[:2]
    record_name = f"{dist}-{version}.dist-info/RECORD"
    rows = list(csv.reader(io.StringIO(zf.read(record_name).decode())))
    listed = {r[0] for r in rows}
    files = {i.filename for i in zf.infolist() if not i.is_dir()}
    if listed != files:
        raise CheckError(f"{record_name}: lists {sorted(listed ^ files)} differently from the archive")
    for path, digest, size in rows:
        if path == record_name:
            continue
        data = zf.read(path)
        algo, _, expected = digest.partition("=")
        actual = base64.urlsafe_b64encode(hashlib.new(algo, data).digest()).rstrip(b"=").decode()
        if algo != "sha256" or actual != expected or int(size) != len(data):
            raise CheckError(f"{record_name}: {path} has {algo} {actual} and {len(data)} bytes, RECORD says {digest}, {size}")
    return f"RECORD: {len(rows) - 1} files, sha256 and sizes match"


def extension(zf):
    names = [n for n in zf.namelist() if re.fullmatch(r"monge/_monge(\.abi3\.so|\.pyd)", n)]
    if len(names) != 1:
        raise CheckError(f"expected one extension monge/_monge.abi3.so or monge/_monge.pyd, found {names}")
    return names[0], zf.read(names[0])


def inspect_elf(data):
    from elftools.elf.elffile import ELFFile

    elf = ELFFile(io.BytesIO(data))
    arch = {"EM_X86_64": "x86_64", "EM_AARCH64": "aarch64"}.get(elf["e_machine"], elf["e_machine"])
    dynamic = elf.get_section_by_name(".dynamic")
    libs = [t.needed for t in dynamic.iter_tags() if t.entry.d_tag == "DT_NEEDED"]
    dynsym = elf.get_section_by_name(".dynsym")
    exports = {s.name for s in dynsym.iter_symbols() if s["st_shndx"] != "SHN_UNDEF" and s["st_info"]["bind"] == "STB_GLOBAL"}
    return "ELF", arch, libs, exports


def inspect_macho(data):
    from macholib.mach_o import LC_LOAD_DYLIB, LC_LOAD_WEAK_DYLIB, LC_REEXPORT_DYLIB
    from macholib.MachO import MachO
    from macholib.SymbolTable import SymbolTable

    with tempfile.NamedTemporaryFile(suffix=".so") as f:
        f.write(data)
        f.flush()
        macho = MachO(f.name)
        if len(macho.headers) != 1:
            raise CheckError(f"a universal binary of {len(macho.headers)} architectures; one was built")
        header = macho.headers[0]
        arch = {0x01000007: "x86_64", 0x0100000C: "arm64"}.get(header.header.cputype, hex(header.header.cputype))
        libs = []
        for cmd, _, payload in header.commands:
            if cmd.cmd in (LC_LOAD_DYLIB, LC_LOAD_WEAK_DYLIB, LC_REEXPORT_DYLIB):
                libs.append(payload.rstrip(b"\0").decode())
        symbols = SymbolTable(macho, header)
        exports = {name.decode().removeprefix("_") for _, name in symbols.extdefsyms}
    return "Mach-O", arch, libs, exports


def inspect_pe(data):
    import pefile

    pe = pefile.PE(data=data)
    arch = {0x8664: "x86_64", 0xAA64: "aarch64"}.get(pe.FILE_HEADER.Machine, hex(pe.FILE_HEADER.Machine))
    libs = [e.dll.decode() for e in getattr(pe, "DIRECTORY_ENTRY_IMPORT", [])]
    libs += [e.dll.decode() for e in getattr(pe, "DIRECTORY_ENTRY_DELAY_IMPORT", [])]
    exports = {s.name.decode() for s in pe.DIRECTORY_ENTRY_EXPORT.symbols if s.name}
    return "PE", arch, libs, exports


def check_binary(platform, zf):
    path, data = extension(zf)
    magic = data[:4]
    if magic == b"\x7fELF":
        fmt, arch, libs, exports = inspect_elf(data)
    elif magic in (b"\xcf\xfa\xed\xfe", b"\xca\xfe\xba\xbe"):
        fmt, arch, libs, exports = inspect_macho(data)
    elif magic[:2] == b"MZ":
        fmt, arch, libs, exports = inspect_pe(data)
    else:
        raise CheckError(f"{path}: unknown binary format (first bytes {magic!r})")
    if (fmt, arch) != (platform.fmt, platform.arch):
        raise CheckError(f"{path}: a {fmt} {arch} binary in a {platform.name} wheel ({platform.fmt} {platform.arch} expected)")
    if INIT not in exports:
        raise CheckError(f"{path}: does not export {INIT} (Python cannot import monge._monge); exports {sorted(exports)[:10]}")
    foreign = [lib for lib in libs if not platform.allows(lib)]
    if foreign:
        raise CheckError(f"{path}: links {foreign}, not system libraries of {platform.name} (all: {libs})")
    return [f"{path}: {fmt} {arch}, exports {INIT}", f"links only system libraries: {', '.join(libs)}"]


def check_auditwheel(wheel):
    out = subprocess.run(
        [sys.executable, "-m", "auditwheel", "show", str(wheel)], capture_output=True, text=True
    )
    text = " ".join((out.stdout + out.stderr).split())
    if out.returncode != 0 or '"manylinux_2_17_x86_64"' not in text:
        raise CheckError(f"auditwheel show: {text}")
    return 'auditwheel show: consistent with "manylinux_2_17_x86_64"'


def readme_example():
    readme = (ROOT / "README.md").read_text()
    return readme.split("```python\n", 1)[1].split("```", 1)[0]


SMOKE = """
import json, sys, numpy as np, monge
cli = json.load(open(sys.argv[1]))
mesh = monge.generate(monge.Design.from_file("examples/fig12-dupin-theta30.json"))
v = np.array(cli["vertices"], dtype=float).reshape(cli["rows"], cli["cols"], 3)
assert mesh.vertices.shape == v.shape, (mesh.vertices.shape, v.shape)
print(json.dumps({"file": monge.__file__, "shape": v.shape, "diff": float(np.abs(mesh.vertices - v).max())}))
"""


def run_in_clean_venv(wheel, monge_bin):
    """Installs the wheel in a new venv and runs the README example and the comparison with the CLI."""
    with tempfile.TemporaryDirectory() as tmp:
        venv = pathlib.Path(tmp) / "venv"
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        py = str(venv / "bin" / "python")
        subprocess.run([py, "-m", "pip", "install", "--quiet", str(wheel)], check=True)
        cli_json = pathlib.Path(tmp) / "mesh.json"
        subprocess.run([monge_bin, "generate", "examples/fig12-dupin-theta30.json", "-o", str(cli_json)], check=True, cwd=ROOT)
        lines = []
        for what, code, args in (("README example", readme_example(), []), ("vertices vs monge generate", SMOKE, [str(cli_json)])):
            p = subprocess.run([py, "-c", code, *args], capture_output=True, text=True, cwd=ROOT)
            if p.returncode != 0:
                raise CheckError(f"{what} in a clean venv failed:\n{p.stderr}")
            lines.append(p.stdout)
        smoke = json.loads(lines[1])
        if not smoke["file"].startswith(str(venv)):
            raise CheckError(f"the smoke test imported monge from {smoke['file']}, not from the clean venv")
        if smoke["diff"] != 0.0:
            raise CheckError(f"the installed wheel's vertices differ from `monge generate`'s by {smoke['diff']}")
        return [
            "installed in a clean venv: the README example ran",
            f"vertices {tuple(smoke['shape'])} equal to `monge generate`'s (largest difference {smoke['diff']})",
        ]


def check_wheel(wheel, monge_bin=None):
    """The check lines of one wheel; raises CheckError at the first failure."""
    lines = []
    size = wheel.stat().st_size
    if size > MAX_WHEEL_BYTES:
        raise CheckError(f"{size} bytes, more than {MAX_WHEEL_BYTES} (debug information or a bundled runtime?)")
    lines.append(f"size {size} bytes")
    with zipfile.ZipFile(wheel) as zf:
        platform, line = check_tags(wheel.name, zf)
        lines += [f"{platform.name}", line, check_record(wheel.name, zf)]
        lines += check_binary(platform, zf)
    if platform.fmt == "ELF":
        lines.append(check_auditwheel(wheel))
        if monge_bin:
            lines += run_in_clean_venv(wheel, monge_bin)
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=pathlib.Path)
    parser.add_argument("--monge", help="the monge binary the Linux wheel is compared with (default: run nothing)")
    args = parser.parse_args()
    wheels = sorted(args.folder.glob("*.whl"))
    if not wheels:
        print(f"error: no wheel in {args.folder}: run scripts/wheels.sh", file=sys.stderr)
        return 1
    failed = 0
    seen = set()
    for wheel in wheels:
        print(f"== {wheel.name}")
        try:
            lines = check_wheel(wheel, args.monge)
            seen.add(lines[1])
            for line in lines:
                print(f"  ok: {line}")
        except CheckError as e:
            failed += 1
            print(f"  FAILED: {e}")
    missing = {p.name for p in PLATFORMS} - seen
    if missing:
        failed += 1
        print(f"FAILED: no wheel for {', '.join(sorted(missing))}")
    print(f"{len(wheels)} wheels, {failed} failures")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env bash
# The abi3 wheels of the Python package (crates/monge-py) for the platforms
# Rhino and designers run on, cross-built on a Linux x86_64 machine into one
# folder, target/wheels-all, then checked by scripts/check-wheels.py (tags,
# RECORD, the exported PyInit__monge, the libraries linked, the size; the Linux
# one is also installed in a clean venv and run):
#
#   manylinux_2_17 x86_64   maturin --zig (zig's glibc 2.17 headers and stubs)
#   macOS 10.12+ x86_64     maturin --zig --target x86_64-apple-darwin
#   macOS 11+ arm64         maturin --zig --target aarch64-apple-darwin
#   Windows x86_64          maturin --target x86_64-pc-windows-gnu, linked by
#                           MinGW-w64 (Debian's gcc-mingw-w64-x86-64-win32:
#                           the win32 thread model, so no libwinpthread DLL);
#                           python3.dll's import library is made by pyo3
#                           (generate-import-lib) with MinGW's dlltool. zig's
#                           lld-link could not link it: it took the module's
#                           export as an undefined symbol PyInit_monge._monge.
#
#   scripts/wheels.sh                 build the wheels, then check them
#   scripts/wheels.sh --check-only    check the wheels already in target/wheels-all
#
# Needs rustup (the script adds the three cross targets), MinGW-w64 (the script
# installs it with apt-get if it is missing) and network access to
# PyPI (maturin, ziglang and the checkers go to a venv of their own,
# target/wheels-venv). Each build is a release build of the whole extension
# into target/wheels-build: a few minutes per target on two cores; not part of
# CI for that reason.
set -euo pipefail
cd "$(dirname "$0")/.."

target="$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json,sys; print(json.load(sys.stdin)["target_directory"])')"
venv="$target/wheels-venv"
out="$target/wheels-all"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet "maturin>=1.9.4,<2" ziglang pefile macholib pyelftools auditwheel

if [ "${1:-}" != --check-only ]; then
  rustup target add x86_64-apple-darwin aarch64-apple-darwin x86_64-pc-windows-gnu
  if ! command -v x86_64-w64-mingw32-gcc >/dev/null; then
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gcc-mingw-w64-x86-64-win32 binutils-mingw-w64-x86-64 >/dev/null
  fi
  rm -rf "$out"
  build() {
    echo "== maturin build --release $*"
    # maturin finds zig as `python -m ziglang` of the venv it runs from.
    (cd crates/monge-py &&
      PATH="$venv/bin:$PATH" CARGO_TARGET_DIR="$target/wheels-build" CARGO_INCREMENTAL=0 \
        maturin build --release --locked --out "$out" "$@")
  }
  build --zig --compatibility manylinux2014 # manylinux2014 = manylinux_2_17
  build --zig --target x86_64-apple-darwin
  build --zig --target aarch64-apple-darwin
  build --target x86_64-pc-windows-gnu
fi

echo "== wheels in $out"
for wheel in "$out"/*.whl; do
  printf '%s  %s bytes\n' "$(basename "$wheel")" "$(stat -c %s "$wheel")"
done
# The Linux wheel's vertices are compared with those of the `monge` the tests use.
cargo build --quiet --locked -p monge-cli
"$venv/bin/python" scripts/check-wheels.py "$out" --monge "$target/debug/monge"

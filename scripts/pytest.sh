#!/usr/bin/env bash
# The Python package's tests: builds the abi3 wheel of crates/monge-py with
# maturin in a virtual environment (target/venv, created if missing), installs
# it, and runs pytest over crates/monge-py/tests against the `monge` binary
# built by cargo (the tests compare the package's output with the command's).
#
#   scripts/pytest.sh [PYTEST_ARGS]   set up the venv, build and install the wheel, run pytest
#   scripts/pytest.sh --setup         only set up the venv (CI does it while Rust compiles)
#   scripts/pytest.sh --install       set up the venv, build and install the wheel, no pytest
#                                     (scripts/docs-numbers.py, with MONGE_WHEEL_PROFILE=--release)
set -euo pipefail
cd "$(dirname "$0")/.."

target="$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json,sys; print(json.load(sys.stdin)["target_directory"])')"
venv="$target/venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
# dask and pandas: monge.dask on a local cluster; pefile, macholib, pyelftools,
# auditwheel: the checks of the cross-built wheels (scripts/wheels.sh), when
# target/wheels-all holds them.
packages=("maturin>=1.9.4,<2" numpy pytest pytest-xdist rhino3dm compas ghhops-server flask mypy
  "dask[distributed]" pandas pefile macholib pyelftools auditwheel)
# What the venv holds is installed once: a stamp names it, and a change of the
# list installs again.
requirements="bpy then ${packages[*]}"
stamp="$venv/monge-requirements.txt"
if [ "$(cat "$stamp" 2>/dev/null)" != "$requirements" ]; then
  # Blender as a Python module (about 370 MB) for the Blender tests, first: it
  # pins numpy < 2, which then also satisfies the rest. The package index has it
  # for one CPython version at a time (3.11 for bpy 4.1–5.0).
  "$venv/bin/python" -m pip install --quiet bpy ||
    echo "warning: no bpy for $("$venv/bin/python" --version); the Blender tests will be skipped" >&2
  "$venv/bin/python" -m pip install --quiet "${packages[@]}"
  echo "$requirements" >"$stamp"
fi
[ "${1:-}" = --setup ] && exit 0

# The workspace's test build (nothing to do after `cargo test --workspace`): the
# tests run the `monge` it holds, and the debug wheel below reuses it.
[ "${1:-}" = --install ] || cargo test --workspace --locked --no-run --quiet

# A debug wheel by default: the tests are small (MONGE_WHEEL_PROFILE=--release
# builds the wheel that users get). It is named as the release wheel is, so it
# goes to a folder of its own, target/wheels-test: target/wheels, where the
# README's `maturin build --release` puts the wheel to install, is neither
# written nor emptied here.
profile="${MONGE_WHEEL_PROFILE:-}"
wheels="$target/wheels-test"
echo "== wheel (maturin build ${profile:-(debug)}, into $wheels)"
rm -rf "$wheels"
log="$(mktemp)"
(cd crates/monge-py && "$venv/bin/maturin" build $profile --locked --out "$wheels") 2>&1 | tee "$log"
# The debug wheel compiles only what the test build has not built: pyo3 as an
# extension module, and the crates only this crate uses (`cargo test` does not
# build it). Compiling again a crate the rest of the workspace uses means a
# dependency's features differ between the two builds (see
# crates/monge-py/Cargo.toml).
if [ -z "$profile" ] && [ "${1:-}" != --install ]; then
  shared="$(cargo tree --locked --workspace --exclude monge-py -e normal,build,dev --prefix none --format '{p}' |
    sed 's/ .*//' | sort -u)"
  extra="$(sed -n 's/^ *Compiling \([^ ]*\) .*/\1/p' "$log" | sort -u | comm -12 - <(echo "$shared"))"
  if [ -n "$extra" ]; then
    echo "error: the debug wheel's build compiled again what \`cargo test --workspace\` had built:" $extra >&2
    echo "  their features differ from the workspace's: align them in crates/monge-py/Cargo.toml" >&2
    exit 2
  fi
fi
rm -f "$log"
wheel="$(ls "$wheels"/monge-*.whl)"
case "$(basename "$wheel")" in
  *-cp39-abi3-*) echo "wheel: $(basename "$wheel") (abi3, CPython ≥ 3.9)" ;;
  *) echo "error: $(basename "$wheel") is not an abi3 wheel for CPython ≥ 3.9" >&2; exit 2 ;;
esac
"$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps "$wheel"
[ "${1:-}" = --install ] && exit 0

echo "== pytest"
export MONGE_BIN="$target/debug/monge"
export MONGE_TEST_WHEEL="$wheel"
# Run from outside the source tree so that the installed wheel is imported; one
# worker process per core (pytest-xdist).
cd "$target"
"$venv/bin/python" -m pytest -q -n auto "$OLDPWD/crates/monge-py/tests" "$@"

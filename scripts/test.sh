#!/usr/bin/env bash
# The whole test suite, Rust and Python: the README's test command, run by CI.
#
# The workspace is built once; then the Rust tests and the Python package's
# (its wheel and pytest) run side by side: much of the Rust tests' time is spent
# waiting (on the processes they start, on the server's timeouts), which the
# Python tests fill. The Python tests' output is printed when they end.
set -euo pipefail
cd "$(dirname "$0")/.."
# Twice as many test threads as cores: the command's tests spend much of their
# time waiting on the processes they start and on the server's timeouts.
export RUST_TEST_THREADS="${RUST_TEST_THREADS:-$((2 * $(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)))}"
cargo test --workspace --locked --no-run
python_log="$(mktemp)"
scripts/pytest.sh >"$python_log" 2>&1 &
python_pid=$!
trap 'kill "$python_pid" 2>/dev/null || true; rm -f "$python_log"' EXIT
rust=0
cargo test --workspace --locked || rust=$?
python=0
wait "$python_pid" || python=$?
echo "== the Python package's tests (scripts/pytest.sh)"
cat "$python_log"
if [ "$rust" -ne 0 ] || [ "$python" -ne 0 ]; then
  echo "error: the tests failed: Rust (cargo test) exit $rust, Python (scripts/pytest.sh) exit $python" >&2
  exit 1
fi

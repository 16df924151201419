#!/usr/bin/env bash
# The whole test suite, Rust then Python: the README's test command, run by CI.
set -euo pipefail
cd "$(dirname "$0")/.."
# Twice as many test threads as cores: the command's tests spend much of their
# time waiting on the processes they start and on the server's timeouts.
export RUST_TEST_THREADS="${RUST_TEST_THREADS:-$((2 * $(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)))}"
cargo test --workspace --locked
scripts/pytest.sh

#!/usr/bin/env bash
# The whole test suite, Rust then Python: the README's test command, run by CI.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --locked
scripts/pytest.sh

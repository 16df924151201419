#!/usr/bin/env bash
# Measures the README's first build: a clone of this repository's HEAD built as
# the Quick start's first command builds it (`cargo build --release -p
# monge-cli`) into an empty target/. Prints the processor time (user + system:
# it does not depend on what else the machine is doing, unlike the wall time),
# the disk target/ takes, and the size of the binary.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
git clone -q "$repo" "$dir/monge"
cd "$dir/monge"
export CARGO_TARGET_DIR="$dir/monge/target"
/usr/bin/time -f "%U %S" -o "$dir/time" cargo build -q --release --locked -p monge-cli
read -r user system <"$dir/time"
python3 - "$user" "$system" "$(du -sb target | cut -f1)" "$(stat -c %s target/release/monge)" <<'PY'
import sys
user, system, disk, binary = map(float, sys.argv[1:])
print("first build: %.1f min of processor time, target/ %.0f MB, binary %.1f MB"
      % ((user + system) / 60, disk / 1e6, binary / 1e6))
PY

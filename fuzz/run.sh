#!/usr/bin/env bash
# Builds the libFuzzer targets on stable Rust (coverage instrumentation through
# the stable -C passes / -C llvm-args flags, as `cargo fuzz build -s none`
# does; no nightly, no cargo-fuzz) and runs them.
#
#   fuzz/run.sh build                  build every target
#   fuzz/run.sh TARGET [LIBFUZZER_ARGS] run one target on its seed corpus
#   fuzz/run.sh all SECONDS            every target for SECONDS each (CI)
#
# New inputs go to fuzz/target/corpus/TARGET (not committed); crashes to
# fuzz/artifacts/TARGET/. Targets: design_json design_toml mesh_obj mesh_ply
# mesh_json iges.
set -euo pipefail
cd "$(dirname "$0")"
TARGETS="design_json design_toml mesh_obj mesh_ply mesh_json iges"
TRIPLE="$(rustc -vV | sed -n 's/^host: //p')"
# Per-input limits: 64 KB inputs, 1 s, 512 MB in one allocation, 2 GB RSS.
LIMITS=(-max_len=65536 -timeout=1 -malloc_limit_mb=512 -rss_limit_mb=2048)

build() {
  RUSTFLAGS="-Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 \
-Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table \
-Cllvm-args=-sanitizer-coverage-trace-compares -Cllvm-args=-sanitizer-coverage-stack-depth \
--cfg fuzzing -Cdebug-assertions -Coverflow-checks" \
    cargo build --release --locked --target "$TRIPLE" --bins
}

run() {
  local target=$1; shift
  mkdir -p "target/corpus/$target" "artifacts/$target"
  "target/$TRIPLE/release/$target" "${LIMITS[@]}" -artifact_prefix="artifacts/$target/" \
    "$@" "target/corpus/$target" "corpus/$target"
}

case "${1:-}" in
  build) build ;;
  all)
    build
    for t in $TARGETS; do run "$t" -max_total_time="${2:-10}" -print_final_stats=1; done ;;
  "") sed -n '2,12p' "$0"; exit 2 ;;
  *) build; run "$@" ;;
esac

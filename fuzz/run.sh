#!/usr/bin/env bash
# Builds the libFuzzer targets on stable Rust (coverage instrumentation through
# the stable -C passes / -C llvm-args flags, as `cargo fuzz build -s none`
# does; no nightly, no cargo-fuzz) and runs them.
#
#   fuzz/run.sh build                  build every target
#   fuzz/run.sh TARGET [LIBFUZZER_ARGS] run one target on its seed corpus
#   fuzz/run.sh all SECONDS            every target for SECONDS each (CI), as many
#                                      at a time as there are cores
#
# New inputs go to fuzz/target/corpus/TARGET (not committed); crashes to
# fuzz/artifacts/TARGET/. FUZZ_PROFILE=quick builds with less optimisation (for
# short runs; see Cargo.toml). Targets: design_json design_toml mesh_obj mesh_ply
# mesh_json iges points.
set -euo pipefail
cd "$(dirname "$0")"
TARGETS="design_json design_toml mesh_obj mesh_ply mesh_json iges points"
TRIPLE="$(rustc -vV | sed -n 's/^host: //p')"
PROFILE="${FUZZ_PROFILE:-release}"
# Per-input limits: 64 KB inputs, 1 s, 512 MB in one allocation, 2 GB RSS.
LIMITS=(-max_len=65536 -timeout=1 -malloc_limit_mb=512 -rss_limit_mb=2048)

build() {
  RUSTFLAGS="-Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 \
-Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table \
-Cllvm-args=-sanitizer-coverage-trace-compares -Cllvm-args=-sanitizer-coverage-stack-depth \
--cfg fuzzing -Cdebug-assertions -Coverflow-checks" \
    cargo build --profile "$PROFILE" --locked --target "$TRIPLE" --bins
}

run() {
  local target=$1; shift
  mkdir -p "target/corpus/$target" "artifacts/$target"
  "target/$TRIPLE/$PROFILE/$target" "${LIMITS[@]}" -artifact_prefix="artifacts/$target/" \
    "$@" "target/corpus/$target" "corpus/$target"
}

case "${1:-}" in
  build) build ;;
  all)
    build
    # One libFuzzer process per core; each target's output is printed whole
    # when it ends, and any failing target fails the run.
    mkdir -p target/logs
    cores="$(nproc)" pids=() names=() failed=0
    finish() {
      local i=$1
      wait "${pids[$i]}" || { echo "fuzz target ${names[$i]} failed" >&2; failed=1; }
      cat "target/logs/${names[$i]}.log"
    }
    for t in $TARGETS; do
      run "$t" -max_total_time="${2:-10}" -print_final_stats=1 >"target/logs/$t.log" 2>&1 &
      pids+=($!) names+=("$t")
      if [ "${#pids[@]}" -ge "$cores" ]; then
        for i in "${!pids[@]}"; do finish "$i"; done
        pids=() names=()
      fi
    done
    for i in "${!pids[@]}"; do finish "$i"; done
    exit "$failed" ;;
  "") sed -n '2,12p' "$0"; exit 2 ;;
  *) build; run "$@" ;;
esac

#!/usr/bin/env bash
# Makes every picture of docs/gallery/gallery.txt, in docs/gallery/.
#
#   docs/gallery/make.sh                                 # with `cargo run -q -p monge-cli --`
#   MONGE=target/release/monge docs/gallery/make.sh      # with a built binary
#
# crates/monge-cli/tests/gallery.rs checks that the committed pictures are what
# this script makes; run it after changing the renderer or an example.
set -euo pipefail
cd "$(dirname "$0")/../.."
MONGE=${MONGE:-cargo run -q -p monge-cli --}
grep -Ev '^[[:space:]]*(#|$)' docs/gallery/gallery.txt | while read -r out args; do
    # Word splitting of $MONGE and $args is intended.
    # shellcheck disable=SC2086
    $MONGE render $args -o "docs/gallery/$out" </dev/null
done

#!/bin/sh
# Regenerates the speed table of docs/speed.md from `monge bench --all` (release build):
# every command on 100², 400² and 1000² faces of the bundled design, three times each.
# Usage: docs/speed/make.sh  (from the repository root; about five minutes).
set -eu
cargo build --release --locked -q -p monge-cli
out=docs/speed/bench.jsonl
./target/release/monge bench --all --runs 3 "$@" > "$out"
python3 - "$out" <<'PY'
import json, re, subprocess, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
cpu = next(l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name"))
cores = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
sizes = list(dict.fromkeys(r["faces"] for r in rows))
table = ["Measured on %s, %s cores (`nproc`), by `docs/speed/make.sh` (`monge bench --all`, release"
         " build, each command three times as a child process, each time into a new output; raw"
         " lines in `docs/speed/bench.jsonl`). Each cell: median wall time, largest peak RSS, bytes"
         " written, and the ratio of the wall time to the median of one `write_all` + `sync_all` of"
         " as many bytes into a new file in the same directory after each run." % (cpu, cores), "",
         "| command | " + " | ".join(s.replace("x", " × ") + " faces" for s in sizes) + " |",
         "|---|" + "---|" * len(sizes)]
def cell(r):
    mb = r["bytes"] / 1e6
    ratio = "" if r["ratio_to_raw"] is None else ", ×%.1f raw" % r["ratio_to_raw"]
    size = "" if r["bytes"] == 0 else ", %s" % ("%.0f MB" % mb if mb >= 1 else "%.2f MB" % mb)
    return "%.2f s, %.0f MB RSS%s%s" % (r["wall_ms"] / 1e3, r["peak_rss_mb"], size, ratio)
for cmd in dict.fromkeys(r["command"] for r in rows):
    cells = [cell(r) for s in sizes for r in rows if r["command"] == cmd and r["faces"] == s]
    table.append("| `%s` | %s |" % (cmd, " | ".join(cells)))
readme = open("docs/speed.md").read()
begin, end = "<!-- speed table: docs/speed/make.sh -->", "<!-- end of speed table -->"
new = begin + "\n" + "\n".join(table) + "\n" + end
readme, k = re.subn(re.escape(begin) + ".*?" + re.escape(end), lambda m: new, readme, flags=re.S)
if k != 1:
    sys.exit("docs/speed.md has no speed table markers")
open("docs/speed.md", "w").write(readme)
PY

#!/usr/bin/env python3
"""Regenerates the numbers of README.md and docs/*.md from the commands that make them.

Every measured number of the documents sits between markers,
`<!-- num:NAME -->VALUE<!-- /num -->` (or, for a command's whole output,
`<!-- out:NAME -->` a ```text block `<!-- /out -->`), and scripts/docs-numbers.txt
says which command prints it and where. This script builds `monge` (release), runs
each command once in a fresh folder holding `examples/`, and rewrites the markers.

    scripts/docs-numbers.py            # every number (a few minutes)
    scripts/docs-numbers.py --cheap    # the cheap ones only (seconds)
    scripts/docs-numbers.py --speed    # also the speed table (docs/speed/make.sh, ~5 min)
    scripts/docs-numbers.py --only dask-,binary-mb   # the rows whose names start so

Commands that use $MONGE_PYTHON get the Python of scripts/pytest.sh's venv with
the release wheel installed (built first, a few minutes).

crates/monge-cli/tests/docs_commands.rs checks that the cheap numbers are what this
script writes, and that no marker names a number this list does not make.
"""
import glob, json, os, re, shutil, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def spec():
    rows = []
    for line in open(os.path.join(ROOT, "scripts/docs-numbers.txt"), encoding="utf-8"):
        if line.strip() and not line.startswith("#"):
            name, cls, fmt, after, command = (f.strip() for f in line.split("|", 4))
            rows.append(dict(name=name, cls=cls, fmt=fmt, after=after, command=command))
    return rows


def fmt_number(text, fmt):
    """The number as the documents write it; the same rules as docs_commands.rs."""
    x = float(text)
    if fmt == "int":
        return str(int(x))
    if fmt[0] == "f":
        return "%.*f" % (int(fmt[1:]), x)
    if fmt[0] == "e":
        mantissa, exp = ("%.*e" % (int(fmt[1:]), x)).split("e")
        return "%se%d" % (mantissa, int(exp))  # Rust's form: 3.4e-4, 1e5
    sys.exit("unknown format %r" % fmt)


def extract(output, after, fmt):
    if fmt == "block":
        return output
    at = 0
    for piece in after.split(" ... "):
        k = output.find(piece, at)
        if k < 0:
            sys.exit("`%s` not found in:\n%s" % (piece, output))
        at = k + len(piece)
    m = NUMBER.search(output, at)
    return fmt_number(m.group(0), fmt)


def run(command, binary, cache):
    if command not in cache:
        with tempfile.TemporaryDirectory() as d:
            os.symlink(os.path.join(ROOT, "examples"), os.path.join(d, "examples"))
            bindir = os.path.join(d, ".bin")
            os.mkdir(bindir)
            os.symlink(binary, os.path.join(bindir, "monge"))
            env = dict(os.environ, PATH=bindir + os.pathsep + os.environ["PATH"], MONGE_REPO=ROOT,
                       MONGE_PYTHON=os.path.join(os.path.dirname(os.path.dirname(binary)), "venv", "bin", "python"))
            print("$ " + command, file=sys.stderr)
            p = subprocess.run(["sh", "-c", command], cwd=d, env=env, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit("failed (%d): %s\n%s" % (p.returncode, command, p.stderr))
            cache[command] = (p.stdout, p.stdout + p.stderr)
    return cache[command]


def main():
    cheap_only = "--cheap" in sys.argv
    os.chdir(ROOT)
    if "--speed" in sys.argv:
        subprocess.run(["docs/speed/make.sh"], check=True)
    profile = [] if cheap_only else ["--release"]
    subprocess.run(["cargo", "build", "-q", "--locked", "-p", "monge-cli"] + profile, check=True)
    meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"],
                          check=True, capture_output=True, text=True).stdout
    target = json.loads(meta)["target_directory"]  # CARGO_TARGET_DIR if set
    binary = os.path.join(target, "debug" if cheap_only else "release", "monge")
    only = sys.argv[sys.argv.index("--only") + 1].split(",") if "--only" in sys.argv else None
    rows = [r for r in spec() if not (cheap_only and r["cls"] != "cheap")
            and (only is None or any(r["name"].startswith(o) for o in only))]
    if any("$MONGE_PYTHON" in r["command"] for r in rows):
        subprocess.run(["scripts/pytest.sh", "--install"], check=True,
                       env=dict(os.environ, MONGE_WHEEL_PROFILE="--release"))
    cache, values = {}, {}
    for row in rows:
        stdout, both = run(row["command"], binary, cache)
        values[row["name"]] = extract(stdout if row["fmt"] == "block" else both, row["after"], row["fmt"])
    pages = ["README.md"] + sorted(glob.glob("docs/*.md"))
    for page in pages:
        text = open(page, encoding="utf-8").read()
        new = re.sub(r"(<!-- num:([\w-]+) -->).*?(<!-- /num -->)",
                     lambda m: m.group(1) + values.get(m.group(2), "\0") + m.group(3)
                     if m.group(2) in values else m.group(0), text, flags=re.S)
        new = re.sub(r"(<!-- out:([\w-]+) -->\n).*?(<!-- /out -->)",
                     lambda m: m.group(1) + "```text\n" + values[m.group(2)].rstrip("\n") + "\n```\n" + m.group(3)
                     if m.group(2) in values else m.group(0), new, flags=re.S)
        if new != text:
            open(page, "w", encoding="utf-8").write(new)
            print("rewrote " + page, file=sys.stderr)
    used = set()
    for page in pages:
        used |= set(re.findall(r"<!-- (?:num|out):([\w-]+) -->", open(page, encoding="utf-8").read()))
    missing = {r["name"] for r in spec()} - used
    if missing:
        sys.exit("no marker in the documents for: " + ", ".join(sorted(missing)))


if __name__ == "__main__":
    main()

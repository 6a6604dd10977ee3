#!/usr/bin/env python3
"""Run every command block of README.md, CONTRIBUTING.md and docs/*.md as written, in a clean
clone of this repository, each file in its own copy, its blocks in order (files side by side).

A block is a fenced ```sh or ```python block. A word after the language marks one that is not
run here, and why: `long` (a build or a study of minutes), `network` (it downloads: PyPI, a
dataset) or `cluster` (it needs a SLURM cluster). The blocks of one file run
as a new user would type them into one shell on a clean clone after `make demo`: the clone's
target/release holds the built binaries (--bin-dir, default target/debug: the same programs),
the PATH is the user's own (a block that calls `cosco` bare must put the binaries on it, as the
README says), and what a shell block exports stays for the file's next blocks. Python blocks
run with --python (default target/py-venv/bin/python, where `make test-python` installs the
package) and are skipped, said so, when it cannot import cosco_hsom. Each block has a time
limit. Exit status 1 when any block fails.

Usage: scripts/doc_commands.py [--bin-dir DIR] [--python EXE] [--timeout S] [--jobs N] [FILE ...]
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

FENCE = re.compile(r"^```(sh|python)(?:\s+(long|network|cluster))?\s*$")


def blocks(path):
    """(line, language, why it is not run or None, text) of every ```sh / ```python block."""
    out, current = [], None
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if current is None:
                m = FENCE.match(line.rstrip("\n"))
                if m:
                    current = (n, m.group(1), m.group(2), [])
            elif line.startswith("```"):
                out.append((current[0], current[1], current[2], "".join(current[3])))
                current = None
            else:
                current[3].append(line)
    return out


def main():
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin-dir", default=os.path.join(root, "target", "debug"))
    ap.add_argument("--python", default=os.path.join(root, "target", "py-venv", "bin", "python"))
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per block")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="files run side by side")
    ap.add_argument("files", nargs="*")
    a = ap.parse_args()
    files = a.files or ["README.md", "CONTRIBUTING.md"] + sorted(glob.glob("docs/*.md", root_dir=root))
    bin_dir = os.path.abspath(a.bin_dir)
    for exe in ("cosco",):
        if not os.access(os.path.join(bin_dir, exe), os.X_OK):
            sys.exit(f"error: {bin_dir}/{exe} not found: build first (cargo build --bins)")
    python_ok = (
        os.access(a.python, os.X_OK)
        and subprocess.run([a.python, "-c", "import cosco_hsom"], capture_output=True).returncode == 0
    )
    # The PATH a new user has: the system's, without any build directory of this repository.
    path = [d for d in os.environ.get("PATH", "").split(os.pathsep) if d and not os.path.abspath(d).startswith(os.path.join(root, "target"))]
    env = dict(os.environ, PATH=os.pathsep.join(path))
    def run_file(rel, tmp, clone):
        """Run one file's blocks in order in its own copy of the clone: (lines, ran, failed, skipped)."""
        out, ran, failed, skipped = [], 0, 0, 0
        path = os.path.join(root, rel)
        work = os.path.join(tmp, rel.replace("/", "_"))
        shutil.copytree(clone, work, symlinks=True, ignore=shutil.ignore_patterns(".git"))
        # As after `make demo`: the binaries in the clone's target/release.
        os.makedirs(os.path.join(work, "target"), exist_ok=True)
        os.symlink(bin_dir, os.path.join(work, "target", "release"))
        state = os.path.join(tmp, rel.replace("/", "_") + ".env")
        open(state, "w").close()
        for line, lang, why, text in blocks(path):
            where = f"{rel}:{line}"
            if why:
                skipped += 1
                out.append(f"skip  {where} ({why})")
                continue
            if lang == "python" and not python_ok:
                skipped += 1
                out.append(f"skip  {where} (no cosco_hsom in {a.python}: make test-python)")
                continue
            # One shell per file: what a block exports stays for the next (`export -p`).
            shell = f". {state}\n{text}\nexport -p > {state}\n"
            cmd = ["bash", "-euo", "pipefail", "-c", shell] if lang == "sh" else [a.python, "-c", text]
            t0 = time.monotonic()
            try:
                r = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=a.timeout)
                ok, detail = r.returncode == 0, (r.stderr or r.stdout)[-2000:]
            except subprocess.TimeoutExpired:
                ok, detail = False, f"timed out after {a.timeout:.0f} s"
            ran += 1
            out.append(f"{'ok' if ok else 'FAIL':5} {where} ({time.monotonic() - t0:.1f} s)")
            if not ok:
                failed += 1
                out.append("      " + detail.replace("\n", "\n      "))
        return out, ran, failed, skipped

    failed = ran = skipped = 0
    with tempfile.TemporaryDirectory(prefix="doc-commands-") as tmp:
        clone = os.path.join(tmp, "clone")
        subprocess.run(["git", "clone", "-q", root, clone], check=True)
        files = [rel for rel in files if os.path.exists(os.path.join(root, rel))]
        # Files are independent (each its own copy and shell): they run side by side, and each
        # file's lines are printed together, in the order of the files.
        with ThreadPoolExecutor(max_workers=a.jobs) as pool:
            for out, r, f, k in pool.map(lambda rel: run_file(rel, tmp, clone), files):
                print("\n".join(out), flush=True)
                ran, failed, skipped = ran + r, failed + f, skipped + k
    print(f"{ran} blocks run, {failed} failed, {skipped} skipped")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()

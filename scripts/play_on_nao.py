#!/usr/bin/env python3
"""Play a motion exported by `cosco export --format naoqi` on a real Nao.

    cosco export --reproduction rep.csv --format naoqi --out rep.json
    python3 scripts/play_on_nao.py rep.json --ip 192.168.1.10
    python3 scripts/play_on_nao.py rep.json --dry-run     # the calls, printed; no robot

Calls, through NAOqi's ALMotion (the `qi` Python package, from Aldebaran/SoftBank's SDK):
wakeUp; stiffness on for the file's joints; angleInterpolationWithSpeed to the first posture
of the motion, at a slow speed; angleInterpolation(names, angleLists, timeLists, isAbsolute)
with the file's arguments; rest (unless --no-rest). The file is checked first: its lists of
one length per joint, its times positive and strictly increasing.
"""

import argparse
import json
import sys


def load(path):
    """The angleInterpolation arguments of the file, checked."""
    with open(path) as f:
        doc = json.load(f)
    for key in ("names", "angleLists", "timeLists", "isAbsolute"):
        if key not in doc:
            raise ValueError(f"{path}: no `{key}`; expected the output of `cosco export --format naoqi`")
    names, angles, times = doc["names"], doc["angleLists"], doc["timeLists"]
    if not (len(names) == len(angles) == len(times)) or not names:
        raise ValueError(f"{path}: {len(names)} names, {len(angles)} angle lists, {len(times)} time lists")
    for n, a, t in zip(names, angles, times):
        if len(a) != len(t) or not t:
            raise ValueError(f"{path}: joint {n}: {len(a)} angles for {len(t)} times")
        if t[0] <= 0 or any(b <= a for a, b in zip(t, t[1:])):
            raise ValueError(f"{path}: joint {n}: times must be positive and strictly increasing")
    return doc


def calls(doc, first_speed, rest):
    """The ALMotion calls, as (method, arguments)."""
    names = doc["names"]
    out = [
        ("wakeUp", ()),
        ("setStiffnesses", (names, 1.0)),
        ("angleInterpolationWithSpeed", (names, [a[0] for a in doc["angleLists"]], first_speed)),
        ("angleInterpolation", (names, doc["angleLists"], doc["timeLists"], doc["isAbsolute"])),
    ]
    if rest:
        out.append(("rest", ()))
    return out


def show(method, args):
    def short(v):
        if isinstance(v, list) and v and isinstance(v[0], list):
            return "[%s]" % ", ".join(f"<{len(x)} values>" for x in v)
        return json.dumps(v)

    return f"ALMotion.{method}({', '.join(short(a) for a in args)})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("file", help="JSON written by `cosco export --format naoqi`")
    ap.add_argument("--ip", default="nao.local", help="the robot's address (default nao.local)")
    ap.add_argument("--port", type=int, default=9559, help="NAOqi's port (default 9559)")
    ap.add_argument("--first-speed", type=float, default=0.2,
                    help="fraction of maximum speed to reach the first posture (default 0.2)")
    ap.add_argument("--no-rest", action="store_true", help="stay stiff at the end instead of rest")
    ap.add_argument("--dry-run", action="store_true", help="print the calls; no robot")
    a = ap.parse_args()
    if not 0 < a.first_speed <= 1:
        sys.exit(f"--first-speed {a.first_speed}: expected a fraction in (0, 1]")
    try:
        doc = load(a.file)
    except (OSError, ValueError) as e:
        sys.exit(str(e))
    todo = calls(doc, a.first_speed, not a.no_rest)
    last = doc["timeLists"][0][-1]
    if a.dry_run:
        print(f"dry run: {len(doc['names'])} joints, {len(doc['timeLists'][0])} points, {last:.3f} s; robot tcp://{a.ip}:{a.port}")
        for m, args in todo:
            print(show(m, args))
        return
    try:
        import qi
    except ImportError:
        sys.exit("the `qi` package is not installed (NAOqi's Python SDK); use --dry-run to see the calls")
    session = qi.Session()
    try:
        session.connect(f"tcp://{a.ip}:{a.port}")
    except RuntimeError as e:
        sys.exit(f"cannot connect to tcp://{a.ip}:{a.port}: {e}")
    motion = session.service("ALMotion")
    for m, args in todo:
        print(show(m, args), flush=True)
        getattr(motion, m)(*args)


if __name__ == "__main__":
    main()

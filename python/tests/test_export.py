"""From the testbed to a robot, read back with real readers: `cosco export --format ros2`
decoded by `mcap-ros2-support`; bags written by `mcap-ros2-support` imported by
`cosco demos import`; the NAOqi JSON and `play_on_nao.py --dry-run`; the limit check."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from conftest import ROOT, write_csv

mcap_ros2_reader = pytest.importorskip("mcap_ros2.reader")
mcap_ros2_writer = pytest.importorskip("mcap_ros2.writer")

ARM = ["LShoulderPitch", "LShoulderRoll", "LElbowYaw", "LElbowRoll", "LWristYaw", "LHand"]
# Nao H25 V5 ranges (docs/EXPORT.md)
RANGES = {
    "LShoulderPitch": (-2.08567, 2.08567),
    "LShoulderRoll": (-0.314159, 1.32645),
    "LElbowYaw": (-2.08567, 2.08567),
    "LElbowRoll": (-1.54462, -0.0349066),
    "LWristYaw": (-1.82387, 1.82387),
    "LHand": (0.0, 1.0),
}
STAND_INIT = [1.4, 0.3, -1.39, -1.01, 0.0, 0.25]
STAND = [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3]

JOINT_STATE_DEF = """std_msgs/Header header
string[] name
float64[] position
float64[] velocity
float64[] effort
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


def motion(n=81, rate=40.0):
    """StandInit -> Stand -> StandInit, `n` postures at `rate`, as rows."""
    u = np.sin(np.pi * np.arange(n) / (n - 1))
    a, b = np.array(STAND_INIT), np.array(STAND)
    return np.arange(n) / rate, a + np.outer(u, b - a)


@pytest.fixture
def reproduction(tmp_path):
    """A reproduction CSV as `cosco reproduce` writes it (`step`, then the arm's joints)."""
    _, rows = motion()
    path = tmp_path / "rep.csv"
    write_csv(path, ["step"] + ARM, [[i] + list(r) for i, r in enumerate(rows)])
    return path, rows


def test_ros2_export_decodes_with_mcap_ros2_support(cosco_bin, reproduction, tmp_path):
    path, rows = reproduction
    out = tmp_path / "rep.mcap"
    r = run(cosco_bin, "export", "--reproduction", path, "--format", "ros2", "--out", out)
    assert r.returncode == 0, r.stderr
    msgs = list(mcap_ros2_reader.read_ros2_messages(str(out)))
    assert len(msgs) == 1
    m = msgs[0]
    assert m.channel.topic == "/joint_trajectory"
    assert m.schema.name == "trajectory_msgs/msg/JointTrajectory"
    assert m.schema.encoding == "ros2msg" and m.channel.message_encoding == "cdr"
    traj = m.ros_msg
    assert list(traj.joint_names) == ARM
    assert len(traj.points) == len(rows)
    for i, (p, row) in enumerate(zip(traj.points, rows)):
        assert list(p.positions) == list(row)  # float64 through CDR: exact
        t = p.time_from_start.sec + p.time_from_start.nanosec * 1e-9
        assert abs(t - i / 40.0) < 1e-9
        assert len(p.velocities) == len(ARM)
    # velocities: central differences (the apex is at rest)
    mid = traj.points[40]
    assert max(abs(v) for v in mid.velocities) < 1e-9
    assert abs(traj.points[20].velocities[3] - (rows[21][3] - rows[19][3]) / 0.05) < 1e-9


def test_naoqi_json_and_the_dry_run(cosco_bin, reproduction, tmp_path):
    path, rows = reproduction
    out = tmp_path / "rep.json"
    r = run(cosco_bin, "export", "--reproduction", path, "--format", "naoqi", "--duration", "4", "--out", out)
    assert r.returncode == 0, r.stderr
    doc = json.loads(out.read_text())
    assert doc["names"] == ARM and doc["isAbsolute"] is True
    assert len(doc["angleLists"]) == len(doc["timeLists"]) == len(ARM)
    for name, angles, times in zip(doc["names"], doc["angleLists"], doc["timeLists"]):
        assert len(angles) == len(times) == len(rows)
        assert times[0] > 0 and all(b > a for a, b in zip(times, times[1:]))
        lo, hi = RANGES[name]
        assert all(lo <= a <= hi for a in angles)
    # --duration 4: the last point 4 s after the first
    assert abs(doc["timeLists"][0][-1] - doc["timeLists"][0][0] - 4.0) < 1e-9
    r = run(sys.executable, ROOT / "scripts" / "play_on_nao.py", out, "--dry-run")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert [line.split("(")[0] for line in lines[1:]] == [
        "ALMotion.wakeUp",
        "ALMotion.setStiffnesses",
        "ALMotion.angleInterpolationWithSpeed",
        "ALMotion.angleInterpolation",
        "ALMotion.rest",
    ]
    assert "81 points" in lines[0]


def test_a_sped_up_motion_is_refused_and_clamp_reports_the_longer_duration(cosco_bin, reproduction, tmp_path):
    path, _ = reproduction
    out = tmp_path / "fast.json"
    ok = run(cosco_bin, "export", "--reproduction", path, "--format", "naoqi", "--out", out)
    assert ok.returncode == 0, ok.stderr
    fast = run(cosco_bin, "export", "--reproduction", path, "--format", "naoqi", "--speed", "20", "--out", out)
    assert fast.returncode != 0
    assert "LElbowRoll" in fast.stderr and "--clamp" in fast.stderr
    clamped = run(cosco_bin, "export", "--reproduction", path, "--format", "naoqi", "--speed", "20", "--clamp", "--out", out)
    assert clamped.returncode == 0, clamped.stderr
    line = [x for x in clamped.stdout.splitlines() if x.startswith("--clamp")][0]
    before, after = [float(v.rstrip(" s")) for v in line.split(": ")[-1].split(" -> ")]
    assert before == pytest.approx(0.1) and after > before
    doc = json.loads(out.read_text())
    assert doc["timeLists"][0][-1] - doc["timeLists"][0][0] == pytest.approx(after, abs=1e-3)
    # the velocity fraction changes the limit: at 0.25 the clamped motion lasts twice as long
    quarter = run(cosco_bin, "export", "--reproduction", path, "--format", "naoqi", "--speed", "20", "--clamp",
                  "--velocity-fraction", "0.25", "--out", out)
    line = [x for x in quarter.stdout.splitlines() if x.startswith("--clamp")][0]
    assert float(line.split(" -> ")[-1].rstrip(" s")) == pytest.approx(2 * after, abs=2e-3)  # printed to 1 ms


def test_a_posture_out_of_range_is_refused(cosco_bin, tmp_path):
    _, rows = motion()
    rows[30][1] = 1.5  # LShoulderRoll's upper limit is 1.32645
    path = tmp_path / "bad.csv"
    write_csv(path, ["step"] + ARM, [[i] + list(r) for i, r in enumerate(rows)])
    r = run(cosco_bin, "export", "--reproduction", path, "--format", "ros2", "--clamp", "--out", tmp_path / "x.mcap")
    assert r.returncode != 0
    assert "LShoulderRoll" in r.stderr and "outside its range" in r.stderr and "t = 0.750" in r.stderr
    assert not (tmp_path / "x.mcap").exists()


def write_bag(path, times, names, rows, topic="/joint_states", t0_ns=1_700_000_000_123_456_789):
    """A ROS 2 bag of sensor_msgs/msg/JointState written by mcap-ros2-support."""
    with open(path, "wb") as f:
        w = mcap_ros2_writer.Writer(output=f)
        schema = w.register_msgdef("sensor_msgs/msg/JointState", JOINT_STATE_DEF)
        for i, (t, row) in enumerate(zip(times, rows)):
            ns = t0_ns + round(t * 1e9)
            w.write_message(
                topic=topic,
                schema=schema,
                message={
                    "header": {"stamp": {"sec": ns // 10**9, "nanosec": ns % 10**9}, "frame_id": ""},
                    "name": list(names),
                    "position": [float(v) for v in row],
                    "velocity": [],
                    "effort": [],
                },
                log_time=ns,
                publish_time=ns,
                sequence=i,
            )
        w.finish()


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
        data = np.array([[float(v) for v in line.split(",")] for line in f if line.strip()])
    return header, data


def test_a_bag_written_by_mcap_ros2_support_imports_as_the_csv_it_was_made_from(cosco_bin, tmp_path):
    times, rows = motion(rate=50.0)
    src = tmp_path / "source.csv"
    write_csv(src, ["time"] + ARM, [[t] + list(r) for t, r in zip(times, rows)])
    # the bag lists more joints than the arm's, in another order (as a whole-body robot does)
    names = ["HeadYaw"] + ARM[::-1]
    bag_rows = [[0.1] + list(r[::-1]) for r in rows]
    bag = tmp_path / "arm.mcap"
    write_bag(bag, times, names, bag_rows)
    out = tmp_path / "imported"
    r = run(cosco_bin, "demos", "import", "--bag", bag, "--topic", "/joint_states", "--out", out)
    assert r.returncode == 0, r.stderr
    header, got = read_csv(out / "arm.csv")
    want_header, want = read_csv(src)
    assert header == want_header
    assert got.shape == want.shape
    assert np.array_equal(got[:, 1:], want[:, 1:])  # positions exact
    assert np.max(np.abs(got[:, 0] - want[:, 0])) < 1e-9  # times from nanosecond stamps
    # chosen joints, in the order asked
    r = run(cosco_bin, "demos", "import", "--bag", bag, "--out", out / "two", "--joints", "LHand,HeadYaw")
    assert r.returncode == 0, r.stderr
    header, got = read_csv(out / "two" / "arm.csv")
    assert header == ["time", "LHand", "HeadYaw"]
    assert np.array_equal(got[:, 1], rows[:, 5]) and np.all(got[:, 2] == 0.1)


def test_split_idle_cuts_a_bag_at_its_pauses(cosco_bin, tmp_path):
    t1, m1 = motion(rate=50.0)
    still = np.repeat(m1[-1:], 100, axis=0)  # 2 s at rest
    rows = np.vstack([m1, still, m1])
    times = np.arange(len(rows)) / 50.0
    bag = tmp_path / "two.mcap"
    write_bag(bag, times, ARM, rows)
    out = tmp_path / "split"
    r = run(cosco_bin, "demos", "import", "--bag", bag, "--out", out, "--split-idle", "1.0")
    assert r.returncode == 0, r.stderr
    files = sorted(p.name for p in out.iterdir())
    assert files == ["two_01.csv", "two_02.csv"]
    for f in files:
        _, d = read_csv(out / f)
        assert 1.3 < d[-1, 0] < 2.0  # one motion (1.6 s) each, the pause left out


@pytest.mark.parametrize(
    "case, expected",
    [
        ("no topic", "no message on topic /joint_states; the bag has: /other"),
        ("other joints", "has no joint `LShoulderPitch`"),
        ("non-monotone", "must strictly increase"),
        ("empty", "the file is empty"),
        ("truncated", "truncated"),
        ("not mcap", "not a readable MCAP file"),
    ],
)
def test_bad_bags_are_refused_naming_the_file(cosco_bin, tmp_path, case, expected):
    times, rows = motion(n=20)
    bag = tmp_path / "bad.mcap"
    if case == "no topic":
        write_bag(bag, times, ARM, rows, topic="/other")
    elif case == "other joints":
        write_bag(bag, times, [f"j{i}" for i in range(6)], rows)
    elif case == "non-monotone":
        t = times.copy()
        t[7], t[8] = t[8], t[7]
        write_bag(bag, t, ARM, rows)
    elif case == "empty":
        bag.write_bytes(b"")
    elif case == "truncated":
        write_bag(bag, times, ARM, rows)
        data = bag.read_bytes()
        bag.write_bytes(data[: len(data) // 2])
    else:
        bag.write_text("time,a\n0,1\n")
    r = run(cosco_bin, "demos", "import", "--bag", bag, "--out", tmp_path / "out")
    assert r.returncode != 0
    assert "panicked" not in r.stderr
    assert str(bag) in r.stderr and expected in r.stderr, r.stderr


def test_read_demos_resamples_files_at_different_rates(tmp_path):
    import cosco_hsom

    # one motion drawn at 50 Hz and at 125 Hz: refused as a set, then both at 40 Hz
    for name, rate in [("a.csv", 50.0), ("b.csv", 125.0)]:
        t = np.arange(0, 2.0 + 1e-9, 1 / rate)
        rows = np.column_stack([np.sin(t), np.cos(t)])
        write_csv(tmp_path / name, ["time", "x", "y"], [[ti] + list(r) for ti, r in zip(t, rows)])
    with pytest.raises(ValueError, match="resample="):
        cosco_hsom.read_demos([tmp_path])
    demos, columns = cosco_hsom.read_demos([tmp_path], resample=40.0)
    assert columns == ["x", "y"]
    assert [d.shape for d in demos] == [(81, 2), (81, 2)]
    t = np.arange(81) / 40.0
    for d in demos:
        assert np.max(np.abs(d[:, 0] - np.sin(t))) < 1e-4
    with pytest.raises(ValueError, match="--resample -1"):
        cosco_hsom.read_demos([tmp_path], resample=-1.0)

"""The Nao's upper body (14 joints: the head, the left arm, the right arm) through Python:
demonstrations recorded by `cosco demos --robot upper-body`, a model trained on them with
configs/nao-upper-body.xml (as `cosco train` trains it) that reproduces the 14 joints in NAOqi
order within the demonstrations' range, and a model of two upper-body gestures that
recognises a held-out demonstration of each; beside negative controls (another gesture's
reproduction, the labels swapped)."""

import subprocess

import numpy as np
import pytest

import cosco_hsom
from conftest import ROOT

UPPER_BODY_XML = ROOT / "configs" / "nao-upper-body.xml"
JOINTS = [
    "HeadYaw", "HeadPitch",
    "LShoulderPitch", "LShoulderRoll", "LElbowYaw", "LElbowRoll", "LWristYaw", "LHand",
    "RShoulderPitch", "RShoulderRoll", "RElbowYaw", "RElbowRoll", "RWristYaw", "RHand",
]
GESTURES = ["clap", "nod"]
# how far (rad; the hands: open fraction) a reproduction may leave the demonstrations' range
MARGIN = 0.05


def record(cosco_bin, out, gesture, count, seed):
    """`cosco demos --robot upper-body`: the files and, read back, the arrays."""
    r = subprocess.run(
        [cosco_bin, "demos", "--robot", "upper-body", "--gesture", gesture,
         "--count", str(count), "--seed", str(seed), "--out", str(out)],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    files = sorted(out.glob("demo_*.csv"))
    assert len(files) == count
    demos, columns = cosco_hsom.read_demos(files)
    assert columns == JOINTS
    assert all(d.shape[1] == 14 for d in demos)
    return demos


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return tmp_path_factory.mktemp("upper_body")


@pytest.fixture(scope="module")
def taught(cosco_bin, root):
    return {g: record(cosco_bin, root / "taught" / g, g, 3, 7) for g in GESTURES}


@pytest.fixture(scope="module")
def held_out(cosco_bin, root):
    """A demonstration of each gesture from another seed, never taught."""
    return {g: record(cosco_bin, root / "held" / g, g, 1, 8)[0] for g in GESTURES}


@pytest.fixture(scope="module")
def cfg():
    c = cosco_hsom.Config.from_xml(UPPER_BODY_XML)
    assert c.state_length == 14
    return c


def outside(path, demos):
    """The joints where `path` leaves the demonstrations' range by more than MARGIN."""
    rows = np.vstack(demos)
    lo, hi = rows.min(axis=0) - MARGIN, rows.max(axis=0) + MARGIN
    return [JOINTS[j] for j in range(14) if path[:, j].min() < lo[j] or path[:, j].max() > hi[j]]


def mean_dtw(path, demos):
    return np.mean([cosco_hsom.dtw(path, d, per_step=True) for d in demos])


def test_an_upper_body_model_reproduces_its_14_joints_within_the_demonstrations(
    cosco_bin, cfg, taught, root, tmp_path
):
    clap = taught["clap"]
    model = cosco_hsom.Hsom.fit(cfg, clap, columns=JOINTS)
    assert model.columns == JOINTS
    assert model.columns[0] == "HeadYaw" and model.columns[-1] == "RHand"
    path = model.reproduce(clap[0][0])
    assert isinstance(path, np.ndarray) and path.shape[1] == 14 and len(path) > 40
    np.testing.assert_allclose(path[0], clap[0][0], rtol=0, atol=1e-12)
    assert outside(path, clap) == []
    # it claps: nearer the clap's demonstrations than the nod's (whose arms stay at rest, as a
    # reproduction that never moved would)
    assert mean_dtw(path, clap) < 0.5 * mean_dtw(path, taught["nod"])
    # Negative control: the nod's reproduction leaves the clap's range (the head nods, the arms
    # stay down).
    nod = cosco_hsom.Hsom.fit(cfg, taught["nod"], columns=JOINTS).reproduce(taught["nod"][0][0])
    assert outside(nod, clap) != []

    # `cosco train` on the files trains the same model: it loads with the 14 columns and
    # reproduces the same postures (its file also keeps the sample period of the files' `time`
    # column, which arrays have not, so the bytes differ there)
    cli = tmp_path / "cli.bin"
    r = subprocess.run(
        [cosco_bin, "train", "--demos", str(root / "taught" / "clap"),
         "--config", str(UPPER_BODY_XML), "--out", str(cli)],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    loaded = cosco_hsom.Hsom.load(cli)
    assert loaded.columns == JOINTS
    np.testing.assert_array_equal(loaded.reproduce(clap[0][0]), path)


def test_a_model_of_two_upper_body_gestures_recognises_held_out_ones(cfg, taught, held_out):
    model = cosco_hsom.GestureModel.fit(cfg, taught, columns=JOINTS)
    assert model.labels == GESTURES and model.columns == JOINTS
    for g, d in held_out.items():
        r = model.recognize(d)
        assert r.label == g, r.to_dict()
        path = model.reproduce(g, d[0])
        assert path.shape[1] == 14 and outside(path, taught[g]) == []
    # Negative control: the labels swapped, neither is recognised as itself.
    swapped = cosco_hsom.GestureModel.fit(
        cfg, {"clap": taught["nod"], "nod": taught["clap"]}, columns=JOINTS
    )
    for g, d in held_out.items():
        assert swapped.recognize(d).label != g


def rot(axis, a):
    """The rotation by `a` about the unit axis x, y or z (0, 1, 2)."""
    c, s = np.cos(a), np.sin(a)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def pointing_deg(rows, target):
    """The angle between the left arm's pointing ray (shoulder through l_gripper, the chain of
    models/nao_upper_body.xml) and the direction to `target`, per row, degrees."""
    shoulder = np.array([0.0, 0.098, 0.100])
    out = []
    for q in rows[:, 2:7]:
        r1 = rot(1, q[0]) @ rot(2, q[1])
        r2 = r1 @ rot(0, q[2]) @ rot(2, q[3])
        r3 = r2 @ rot(0, q[4])
        g = shoulder + r1 @ [0.105, 0.015, 0] + r2 @ [0.05595, 0, 0] + r3 @ [0.05775, 0, -0.01231]
        a, b = g - shoulder, np.asarray(target) - shoulder
        out.append(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1))))
    return np.array(out)


def gaze_deg(rows, target):
    """The angle between the top camera's optical axis and the direction to `target`, degrees."""
    out = []
    for q in rows[:, :2]:
        r = rot(2, q[0]) @ rot(1, q[1])
        o = np.array([0, 0, 0.1265]) + r @ [0.05871, 0, 0.06364]
        d = r @ rot(1, 0.0209435) @ [1.0, 0, 0]
        b = np.asarray(target) - o
        out.append(np.degrees(np.arccos(np.clip(d @ b / np.linalg.norm(b), -1, 1))))
    return np.array(out)


def longest_within(values, tolerance):
    best = run = 0
    for v in values:
        run = run + 1 if v <= tolerance else 0
        best = max(best, run)
    return best


def test_a_pointing_gesture_points_and_looks_at_a_target_and_follows_it_when_it_moves(cosco_bin, root, cfg):
    demos = record(cosco_bin, root / "point", "point-left", 4, 9)
    model = cosco_hsom.Hsom.fit(cfg, demos[:3], columns=JOINTS)
    initial = demos[3][0]
    target = (1.2, 1.0, 0.5)
    plain = model.reproduce(initial)
    aimed = model.reproduce(initial, point_at=target, look_at=target)
    # the held part points within 2 degrees for at least 0.5 s (20 rows at 40 Hz), the camera
    # looks within 1 degree; the unconditioned reproduction (the negative control) does neither
    assert longest_within(pointing_deg(aimed, target), 2.0) >= 20
    assert longest_within(gaze_deg(aimed, target), 1.0) >= 20
    assert longest_within(pointing_deg(plain, target), 2.0) < 20
    assert longest_within(gaze_deg(plain, target), 1.0) < 20
    # in the loop, the target moved before the held part: the rest follows the new one
    moved = (1.5, 0.6, 0.9)
    s = model.stepper(initial, point_at=target)
    assert s.point_at == target and s.look_at is None
    commands, observed = [], initial
    while not s.done:
        if len(commands) == 15:
            s.point_at = moved
        observed = s.step(observed)
        commands.append(observed)
    commands = np.array(commands)
    assert s.point_at == moved
    assert longest_within(pointing_deg(commands, moved), 2.0) >= 20
    assert longest_within(pointing_deg(commands, target), 2.0) < 20
    # no jump where the target moved
    assert np.abs(np.diff(commands, axis=0)).max() < 0.15
    # a target the arm cannot point at names the closest direction it can
    with pytest.raises(ValueError, match="closest direction"):
        model.reproduce(initial, point_at=(-0.5, -2.0, 0.1))
    with pytest.raises(ValueError, match="made without point_at"):
        model.stepper(initial).point_at = target

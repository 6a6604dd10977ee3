# Reversal counts of a model of the 8 upper-body gestures, held out (leave-one-out over 4
# demonstrations a gesture, the model learned from the other 3 of each): the reproduction's
# velocity reversals on the gesture's most moving joint against the held-out demonstration's.
# Usage: COSCO=target/release/cosco python3 scripts/reversals_study.py 41,42,43,44,45 WORKDIR
# (numpy; ALONE=1: each gesture learned alone instead)
import csv, os, subprocess, sys, shutil, numpy as np
C = os.environ.get("COSCO", "/work/main/target/release/cosco")
G = ["clap","nod","reading-watch","salute","shake-head","shrug","wave-right","welcome"]
def load(p):
    with open(p) as f:
        r = list(csv.reader(f)); h = r[0]; a = np.array([[float(x) for x in row] for row in r[1:]])
    return h, a
def rev(x, dt=0.025, db=0.25):
    v = np.diff(x)/dt; last=None; c=0
    for s in v:
        if abs(s) > db:
            p = s > 0
            if last is not None and p != last: c += 1
            last = p
    return c
seeds = [int(s) for s in sys.argv[1].split(",")]
work = sys.argv[2]
out = []
for seed in seeds:
    d = f"{work}/d{seed}"
    if not os.path.exists(d):
        subprocess.run([C,"demos","--robot","upper-body","--gesture","all","--count","4","--seed",str(seed),"--out",d],check=True,capture_output=True)
    for k in range(4):
        t = f"{work}/t{seed}_{k}"; shutil.rmtree(t, ignore_errors=True)
        for g in G:
            os.makedirs(f"{t}/{g}")
            for i in range(4):
                if i != k: shutil.copy(f"{d}/{g}/demo_{i+1:02}.csv", f"{t}/{g}/demo_{i+1:02}.csv")
        m = f"{t}.bin"
        ALONE = os.environ.get("ALONE")
        if not ALONE: subprocess.run([C,"train","--demos",t,"--out",m],check=True,capture_output=True)
        for g in G:
            h, held = load(f"{d}/{g}/demo_{k+1:02}.csv")
            trains = [load(f"{d}/{g}/demo_{i+1:02}.csv")[1] for i in range(4) if i != k]
            o = f"{t}_{g}.csv"
            if ALONE:
                m = f"{t}_{g}.bin"; subprocess.run([C,"train","--demos",f"{t}/{g}","--out",m],check=True,capture_output=True)
            subprocess.run([C,"reproduce","--model",m]+([] if ALONE else ["--gesture",g])+["--initial-from",f"{d}/{g}/demo_{k+1:02}.csv","--out",o],check=True,capture_output=True)
            _, rep = load(o)
            # the gesture's most active joint (over the training demos)
            act = np.mean([a[:,1:].std(0) for a in trains],0); j = int(np.argmax(act))
            rd = rev(held[:,1+j]); rr = rev(rep[:,1+j])
            amp_d = np.ptp(held[:,1+j]); amp_r = np.ptp(rep[:,1+j])
            out.append((seed,k,g,h[1+j],rd,rr,amp_d,amp_r))
            print(seed,k,g,h[1+j],rd,rr,f"{amp_d:.3f}",f"{amp_r:.3f}",flush=True)
ok = sum(abs(r[4]-r[5])<=1 for r in out)
import json; json.dump(out, open(os.environ.get("OUTJSON","/dev/null"),"w"))
print("within 1:", ok, "of", len(out))
for g in G:
    rs=[r for r in out if r[2]==g]; print(g, sum(abs(r[4]-r[5])<=1 for r in rs), "of", len(rs))

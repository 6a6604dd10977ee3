#!/usr/bin/env bash
# The upper body's studies (docs/RESULTS.md, "Upper body"; docs/CONFIG.md, "The upper body"):
# the configuration's tuning on seeds 31-34 (held-out relative DTW, and recognition of the 8
# gestures taught at once), held out on seeds 41-45 (the two arms' lag and the contacts on the
# simulated model beside the DTW), recognition of the 8 gestures taught at once, and each
# gesture left untaught in turn (the other 7 taught, `cosco train` then `cosco recognize`);
# then rewrites those parts of the docs from the outputs.
# Usage: scripts/upper_body_results.sh [OUT_DIR]  (default target/results; scripts/results.sh
# runs it). BIN=DIR takes the binaries in DIR instead of building target/release.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/results}
mkdir -p "$out"
log() { printf '%s\n' "$*" >&2; }
if [ -z "${BIN:-}" ]; then
  cargo build --release --bins
  bin=target/release
else
  bin=$BIN
fi
git rev-parse --short HEAD > "$out/ub_commit"

run() { # run NAME COMMAND...: stdout to $out/NAME.md, the command line to $out/NAME.cmd
  local name=$1; shift
  log "== $name: $*"
  printf '%s\n' "$*" > "$out/$name.cmd"
  "$@" > "$out/$name.md"
}
ub_sets() { # ub_sets DIR SEED...: each seed's 8 gestures (4 demonstrations each) as sets DIR/<gesture>-<seed>
  local dir=$1 seed g; shift
  for seed in "$@"; do
    [ -d "$out/ub-demos/$seed" ] || $bin/cosco demos --robot upper-body --gesture all --count 4 --seed "$seed" --out "$out/ub-demos/$seed" > /dev/null
    for g in "$out/ub-demos/$seed"/*/; do
      mkdir -p "$dir"; ln -sfn "$(cd "$g" && pwd)" "$dir/$(basename "$g")-$seed"
    done
  done
}
config=configs/nao-upper-body.xml
# Tuning on seeds 31-34 (never reported): the candidates, the hierarchy alone.
ub_sets "$out/ub-tune" 31 32 33 34
gestures="clap nod reading-watch salute shake-head shrug wave-right welcome"
taught() { # taught SEED: the 8 gestures' directories of that seed
  for g in $gestures; do printf '%s ' "$out/ub-demos/$1/$g"; done
}
for c in $config configs/ablations/upper-body-change-ratio-0.6.xml configs/ablations/upper-body-bottom-24.xml \
  configs/ablations/upper-body-change-ratio-0.4.xml; do
  run "ub_tune_$(basename "$c" .xml)" $bin/cosco heldout --demos "$out/ub-tune" --config "$c" \
    --no-height-1 --no-gmr --no-promp --no-dmp --no-in-sample --json "$out/ub_tune_$(basename "$c" .xml).json"
done
# ... and recognition on seeds 31-34, the recommended beside the event hysteresis of the
# left arm's configuration (changeRatio 0.6).
for c in $config configs/ablations/upper-body-change-ratio-0.6.xml; do
  for seed in 31 32 33 34; do
    run "ub_tune_recognition_$(basename "$c" .xml)_$seed" $bin/cosco heldout --recognition --no-control --config "$c" \
      --taught $(taught "$seed") --json "$out/ub_tune_recognition_$(basename "$c" .xml)_$seed.json"
  done
done
# Held out on seeds 41-45: every method, the two arms' lag, the contacts when executed.
ub_sets "$out/ub-report" 41 42 43 44 45
run ub_heldout $bin/cosco heldout --demos "$out/ub-report" --config $config --no-in-sample --json "$out/ub_heldout.json"
# Recognition on seeds 41-45: the 8 gestures taught at once, held out; then each left
# untaught in turn: a model taught the other 7 (labelled directories of links) recognises it.
for seed in ${UB_RECOGNITION_SEEDS:-41 42 43 44 45}; do
  run "ub_recognition_$seed" $bin/cosco heldout --recognition --no-control --config $config \
    --taught $(taught "$seed") --json "$out/ub_recognition_$seed.json"
  for left in $gestures; do
    seven="$out/ub-seven/$seed-without-$left"
    rm -rf "$seven" && mkdir -p "$seven"
    for g in $gestures; do
      [ "$g" = "$left" ] || ln -sfn "$(cd "$out/ub-demos/$seed/$g" && pwd)" "$seven/$g"
    done
    run "ub_seven_${seed}_$left" $bin/cosco train --config $config --demos "$seven" --out "$seven.bin"
    run "ub_untaught_${seed}_$left" $bin/cosco recognize --model "$seven.bin" --demos "$out/ub-demos/$seed/$left" \
      --json "$out/ub_untaught_${seed}_$left.json"
  done
done
python3 scripts/results.py --upper-body "$out"

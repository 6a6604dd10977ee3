#!/usr/bin/env bash
# The long fuzzing campaign of docs/RELIABILITY.md: every fuzz target of
# tests/algorithm/fuzz_loaders.rs and tests/sim/fuzz_mjcf.rs for MINUTES minutes each (default
# 10), one target at a time on one core, in batches of BATCH cases (default 1000000; MJCF: a
# tenth) with seeds 1000, 1001, ... Prints per target the batches, cases and any failure
# (proptest prints the minimal case). Usage: scripts/fuzz-campaign.sh [MINUTES] [BATCH]
# (TARGETS="a b" to run only some)
set -uo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-10}
batch=${2:-1000000}
cargo build --release --tests >/dev/null 2>&1 || { echo "build failed" >&2; exit 1; }
run_target() { # test-target module::target cases
  local file=$1 target=$2 cases=$3 end=$(( $(date +%s) + minutes * 60 )) seed=1000 n=0 fails=0 start
  start=$(date +%s)
  while [ "$(date +%s)" -lt "$end" ]; do
    if ! out=$(PROPTEST_RNG_SEED=$seed PROPTEST_CASES=$cases cargo test --release --test "$file" -- --exact "$target" --test-threads 1 -q 2>&1); then
      fails=$((fails + 1))
      echo "$target: FAILED with seed $seed:"
      echo "$out" | grep -E "panicked|minimal failing|Test failed" | head -5
    fi
    n=$((n + cases)); seed=$((seed + 1))
  done
  echo "$target: $n cases in $(( $(date +%s) - start )) s, $fails failing batch(es)"
}
targets=${TARGETS:-config_parser csv_reader model_binary_reader model_text_reader gmr_model_reader mjcf_loading}
for t in $targets; do
  if [ "$t" = mjcf_loading ]; then
    run_target sim fuzz_mjcf::mjcf_loading $(( batch / 10 ))
  else
    run_target algorithm "fuzz_loaders::$t" "$batch"
  fi
done

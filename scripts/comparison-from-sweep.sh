#!/usr/bin/env bash
# Regenerate the sweep section of docs/COMPARISON.md: run (or resume) the paper-comparison
# sweep, then put its merged tables (headings two levels down) between the markers
# `<!-- BEGIN sweep paper-comparison -->` and `<!-- END sweep paper-comparison -->`, and copy
# its joint-DTW box plot to docs/figures/. The hand-written text around the markers stays.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-sweeps/paper-comparison}
cargo build --release --bin cosco
target/release/cosco sweep --spec configs/sweeps/paper-comparison.toml --out "$out"
mkdir -p docs/figures
cp "$out/plots/joint_dtw_rad_per_step.png" docs/figures/paper-comparison-joint-dtw.png
tables=$(mktemp)
trap 'rm -f "$tables"' EXIT
sed -e 's/^# /### /' -e 's/^## /#### /' "$out/tables.md" > "$tables"
doc=docs/COMPARISON.md
grep -q '^<!-- BEGIN sweep paper-comparison -->$' "$doc" && grep -q '^<!-- END sweep paper-comparison -->$' "$doc" || {
  echo "error: $doc has no BEGIN/END sweep paper-comparison markers" >&2
  exit 1
}
awk -v tables="$tables" '
  /^<!-- BEGIN sweep paper-comparison -->$/ { print; while ((getline line < tables) > 0) print line; skip = 1; next }
  /^<!-- END sweep paper-comparison -->$/ { skip = 0 }
  !skip { print }
' "$doc" > "$doc.tmp"
mv "$doc.tmp" "$doc"
echo "updated $doc and docs/figures/paper-comparison-joint-dtw.png from $out"

#!/usr/bin/env bash
# Regenerate src/mujoco/ffi.rs with bindgen from Debian's MuJoCo 2.2.2 and OSMesa headers.
# Needs libclang-dev (`make bindings` installs it when missing). The output is committed.
set -euo pipefail
cd "$(dirname "$0")/.."
CARGO="${CARGO:-cargo}"
# build.rs re-runs only when build.rs or wrapper.h changed: touch the header to force it
touch src/mujoco/wrapper.h
"$CARGO" build --lib --features regen-bindings
rustfmt --edition 2021 src/mujoco/ffi.rs
echo "src/mujoco/ffi.rs regenerated; review with: git diff --stat src/mujoco/ffi.rs"

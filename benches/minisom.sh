#!/bin/sh
# The SOM kernel against MiniSom on the same map and data, in one run (issue 13).
# MiniSom is installed from PyPI into target/minisom-venv (git-ignored, made on first use).
#   benches/minisom.sh [--plot docs/figures/som-step-vs-size.png]
set -eu
cd "$(dirname "$0")/.."
VENV=target/minisom-venv
if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import minisom, numpy" 2>/dev/null; then
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install --quiet "minisom==2.3.6" "numpy>=1.26,<3"
fi
echo "MiniSom $("$VENV/bin/python" -c 'import importlib.metadata as m; print(m.version("minisom"))'), numpy $("$VENV/bin/python" -c 'import numpy; print(numpy.__version__)'), $("$VENV/bin/python" --version)"
MINISOM_PYTHON="$VENV/bin/python" exec ${CARGO:-cargo} bench --bench som_kernel -- "$@"

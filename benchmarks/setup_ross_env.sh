#!/usr/bin/env bash
# Create (or reuse) the separate virtualenv in which ROSS runs for the benchmarks.
#
#   bash benchmarks/setup_ross_env.sh            # -> .venv-ross in the repository
#   ROSS_VENV=/tmp/rossenv bash benchmarks/setup_ross_env.sh
#
# rotorsim never imports ROSS: benchmarks/bench_vs_ross.py runs benchmarks/ross_side.py with
# this virtualenv's python in a subprocess and exchanges JSON with it.
#
# On Python < 3.13 pip can only install ROSS 2.3.0, which registers a plotly template with the
# 'scattermapbox' trace that plotly 6+ rejects at `import ross`: plotly is then pinned below 6.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="${ROSS_VENV:-$repo/.venv-ross}"
# ROSS 3.x needs Python >= 3.13; with an older interpreter pip falls back to ROSS 2.3.0.
if [ -n "${PYTHON:-}" ]; then
    python="$PYTHON"
else
    python=python3
    pyenv_root="$(pyenv root 2>/dev/null || true)"
    for candidate in python3.14 python3.13 "$pyenv_root"/versions/3.1[3-9]*/bin/python3; do
        if "$candidate" -c "" >/dev/null 2>&1; then
            python="$candidate"
            break
        fi
    done
fi

if [ ! -x "$venv/bin/python" ]; then
    echo "creating virtualenv $venv"
    "$python" -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import ross" >/dev/null 2>&1; then
    "$venv/bin/python" -m pip install -q --upgrade pip
    if "$venv/bin/python" -c "import sys; sys.exit(sys.version_info < (3, 13))"; then
        "$venv/bin/python" -m pip install -q "ross-rotordynamics>=3"
    else
        "$venv/bin/python" -m pip install -q "ross-rotordynamics" "plotly<6"
    fi
fi
"$venv/bin/python" - <<'EOF' 2>/dev/null | tail -n 1
import contextlib, io
with contextlib.redirect_stdout(io.StringIO()):
    import ross
print(f"ROSS {ross.__version__} ready")
EOF
echo "use it with: ROSS_VENV=$venv .venv/bin/python benchmarks/run_all.py"

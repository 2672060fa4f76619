#!/usr/bin/env bash
# `pip install --no-build-isolation` of the source tree into a fresh venv (no network), then
# the installed package from another folder: the ctest python_pip.
#
#   bash python/tests/pip_install.sh REPOSITORY_ROOT [PYTHON]
#
# PYTHON (default /usr/bin/python3) makes the venv, with --system-site-packages so that its
# NumPy, setuptools and wheel (Debian's) serve the build and the package. Exits 77 (ctest:
# skipped) when that Python has no venv or pip. Leaves the source tree as it was: setup.py
# builds in a temporary folder of its own.
set -euo pipefail

root=$(cd "${1:?usage: pip_install.sh REPOSITORY_ROOT [PYTHON]}" && pwd)
python=${2:-/usr/bin/python3}
unset PYTHONPATH PYTHONHOME  # the installed package, not a build tree's

# A venv with its own pip (ensurepip), or without one, using the system's pip through
# --system-site-packages.
if ! "$python" -c 'import venv' 2>/dev/null; then
  echo "pip_install.sh: $python has no venv (Debian: python3-venv); skipped"
  exit 77
elif "$python" -c 'import ensurepip' 2>/dev/null; then
  venv_options=()
elif "$python" -m pip --version >/dev/null 2>&1; then
  venv_options=(--without-pip)
else
  echo "pip_install.sh: $python has no pip (Debian: python3-pip, python3-venv); skipped"
  exit 77
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/heavytop-pip-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

# What setuptools would leave in the source tree if it built there.
strays() {
  ls -d "$root"/*.egg-info "$root"/python/*.egg-info "$root"/python/heavytop/*.egg-info \
        "$root"/python/heavytop/_core*.so "$root"/build/lib "$root"/build/lib.* "$root"/build/temp.* \
        "$root"/build/bdist.* 2>/dev/null || true
}
before=$(strays)

"$python" -m venv --system-site-packages ${venv_options[@]+"${venv_options[@]}"} "$work/venv"
venv_python="$work/venv/bin/python"

start=$(date +%s)
PIP_NO_INPUT=1 PIP_DISABLE_PIP_VERSION_CHECK=1 \
  "$venv_python" -m pip install --no-build-isolation --no-deps --no-index --no-cache-dir "$root" \
  > "$work/pip.log" 2>&1 || { cat "$work/pip.log"; echo "pip_install.sh: pip install failed"; exit 1; }
echo "pip_install.sh: pip install took $(( $(date +%s) - start )) s"

after=$(strays)
if [ "$before" != "$after" ]; then
  echo "pip_install.sh: the build wrote into the source tree:"
  diff <(echo "$before") <(echo "$after") || true
  exit 1
fi

mkdir "$work/elsewhere"
cd "$work/elsewhere"
"$venv_python" -c 'import heavytop._core' || { echo "pip_install.sh: import heavytop._core failed"; exit 1; }
VENV="$work/venv" "$venv_python" - <<'EOF'
import math
import os

import heavytop

venv = os.path.realpath(os.environ["VENV"])
package = os.path.dirname(os.path.realpath(heavytop.__file__))
assert package.startswith(venv + os.sep), f"heavytop imported from {package}, not from the venv {venv}"
assert os.path.realpath(heavytop._core.__file__).startswith(package + os.sep), heavytop._core.__file__
for name in ("py.typed", "_core.pyi", "__init__.py", "results.py"):
    assert os.path.isfile(os.path.join(package, name)), f"{name} is not installed"

# The symmetric toy top: the linearized model's critical spin is sqrt(4 A m g R) / C.
top = heavytop.example_toy_top()
result = heavytop.stability(top, 200.0)
critical = result.models["linearized"].critical_spin
expected = math.sqrt(4 * top.A * top.mass * top.gravity * top.length) / top.C
assert abs(critical - expected) <= 1e-12 * expected, (critical, expected)
assert result["models"]["linearized"]["critical_spin"] == critical
assert heavytop.HAS_DERIVE, "built without the symbolic derivations"
assert heavytop.derive().stability_condition == "omega0^2 > (sqrt(A)+sqrt(B))^2*m*g*R/C^2"
trajectory = heavytop.simulate(top, **heavytop.example_motion(), t_end=0.1, samples=11)
assert trajectory.theta.shape == (11,) and trajectory.summary.ok
# The examples' data ships with the package (a copied notebook finds it from anywhere).
config = heavytop.load(heavytop.example_file("toy-top.toml"))
assert config.body == top, config.body
assert heavytop.load(heavytop.example_file("mesh-top.toml")).body.mass > 0  # its meshes/ beside it
assert os.path.realpath(heavytop.example_file("spin-decay.csv")).startswith(package + os.sep)

from importlib import metadata
assert metadata.version("heavytop") == heavytop.__version__, (metadata.version("heavytop"), heavytop.__version__)
print(f"pip_install.sh: heavytop {heavytop.__version__} from {package}: critical spin {critical!r} rad/s "
      f"(closed form {expected!r})")
EOF

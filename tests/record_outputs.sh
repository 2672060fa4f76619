#!/usr/bin/env bash
# Records what the command line writes for a set of runs covering every model, every
# integrator, every kind of body (symmetric, asymmetric, general with offsets and products,
# damped, driven, from parts and a mesh) and the analyses (stability with its Lyapunov verdict
# and wander, compare, sweep with every integrator, lifetime, precession), so a refactoring can
# be checked byte for byte:
#   tests/record_outputs.sh HEAVYTOP_BINARY OUT_DIR      # writes OUT_DIR/NNN.{cmd,out,err,rc}
#   diff -r OUT_BEFORE OUT_AFTER                         # nothing: the outputs are unchanged
# Each run's stdout, stderr and exit status are kept (a refusal's message is output too).
set -u
H=$(realpath "${1:?usage: record_outputs.sh HEAVYTOP OUT_DIR}")
out=$(realpath -m "${2:?usage: record_outputs.sh HEAVYTOP OUT_DIR}")
examples=$(realpath "$(dirname "$0")/../examples")
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
n=0
run() {
  n=$((n + 1))
  local id
  id=$(printf '%03d' $n)
  printf '%s\n' "$*" > "$out/$id.cmd"
  (exec -a heavytop "$H" "$@") > "$out/$id.out" 2> "$out/$id.err"  # argv[0] as in help, whichever binary
  echo $? > "$out/$id.rc"
}

printf '[body]\nA = 1\nB = 1\nC = 1.5\nmass = 1\nlength = 0.1\nIxy = 0.01\nIxz = 0.002\nIyz = -0.003\noffset_x = 0.001\noffset_y = -0.002\n[motion]\nspin = 20\ntheta0 = 0.1\n' > general.toml
printf '[body]\nA = 1.2e-4\nB = 1.5e-4\nC = 4e-5\nmass = 0.1\nlength = 0.03\n[motion]\nspin = 300\ntheta0 = 0.05\nphi_rate0 = 0.2\n[damping]\ntransverse = 1e-6\naxial = 2e-7\nfriction = 1e-6\n' > damped.toml
printf '[body]\nA = 1.2e-4\nB = 1.2e-4\nC = 4e-5\nmass = 0.1\nlength = 0.03\n[motion]\nspin = 300\ntheta0 = 0.05\ndriven = true\n[damping]\ntransverse = 1e-6\naxial = 2e-7\n' > driven.toml
printf '[[body.part]]\nshape = "cone"\nradius = 0.02\nheight = 0.02\napex = "down"\ndensity = 700.0\n[[body.part]]\nshape = "cylinder"\nradius = 0.025\nheight = 0.006\nz0 = 0.02\nmass = 0.03\n[motion]\nspin = 250\ntheta0 = 0.05\n' > parts.toml

# ---- help: the lists of models and integrators ----
run --help
run simulate --help
run sweep --help
run lifetime --help
run stability --help

# ---- every model, the toy top and the examples ----
for model in first-order body-fixed linearized nonlinear lagrange-exact; do
  run simulate --model "$model" --t-end 2 --samples 201
  run simulate --model "$model" --t-end 2 --samples 51 --format json
done
for model in first-order body-fixed linearized; do
  run simulate --model "$model" --method numeric --t-end 2 --samples 101
done
for ex in toy-top asymmetric-plate equal-moments hanging-gyroscope horizontal-gyroscope lab-gyroscope mesh-top; do
  run simulate --config "$examples/$ex.toml" --t-end 1 --samples 101
  run simulate --config "$examples/$ex.toml" --model linearized --t-end 1 --samples 51
done

# ---- every integrator on every kind of body ----
for body in "" "--config $examples/asymmetric-plate.toml" "--config $examples/horizontal-gyroscope.toml" \
            "--config general.toml" "--config damped.toml" "--config driven.toml" "--config parts.toml" \
            "--config $examples/mesh-top.toml"; do
  for integ in auto taylor dop853 dopri5 adaptive; do
    # shellcheck disable=SC2086
    run simulate $body --model nonlinear --integrator "$integ" --t-end 1.5 --samples 151
    # shellcheck disable=SC2086
    run simulate $body --model nonlinear --integrator "$integ" --t-end 0.7 --samples 23 --format json
    # shellcheck disable=SC2086
    run simulate $body --model nonlinear --integrator "$integ" --rtol 1e-8 --atol 1e-10 --t-end 1 --samples 11 --format json
  done
  for order in 2 4; do
    # shellcheck disable=SC2086
    run simulate $body --model nonlinear --integrator splitting --order "$order" --step 2e-4 --t-end 0.5 --samples 101
  done
done
# many samples (the chunked flushing), few samples (long steps between them)
for integ in taylor dop853 dopri5 splitting; do
  run simulate --model nonlinear --integrator "$integ" --t-end 5 --samples 40001
  run simulate --model nonlinear --integrator "$integ" --t-end 20 --samples 3
  run simulate --config damped.toml --model nonlinear --integrator "$integ" --t-end 3 --samples 30001
done
# failures: too few steps, a tolerance out of range, options the model does not use
for integ in taylor dop853 dopri5 splitting; do
  run simulate --model nonlinear --integrator "$integ" --t-end 5 --samples 11 --max-steps 20
  run simulate --model nonlinear --integrator "$integ" --t-end 5 --samples 11 --max-steps 20 --format json
done
run simulate --model nonlinear --rtol 1e-16
run simulate --model nonlinear --integrator nonsense
run simulate --model first-order --integrator taylor
run simulate --model nonlinear --integrator dopri5 --step 1e-3
run simulate --model nonlinear --config general.toml --integrator splitting

# ---- the analyses ----
for body in "" "--config $examples/asymmetric-plate.toml" "--config $examples/equal-moments.toml" \
            "--config $examples/hanging-gyroscope.toml" "--config damped.toml" "--config driven.toml" \
            "--config $examples/mesh-top.toml" "--spin 100"; do
  # shellcheck disable=SC2086
  run stability $body --format json --horizon 20
  # shellcheck disable=SC2086
  run stability $body --horizon 20
  # shellcheck disable=SC2086
  run compare $body --t-end 2 --samples 2001 --format json
  # shellcheck disable=SC2086
  run compare $body --t-end 2 --samples 2001 --format csv
  # shellcheck disable=SC2086
  run lifetime $body --format json --horizon 30
  # shellcheck disable=SC2086
  run precession $body --tilt 0.3 --format json
done
run lifetime --config damped.toml --format json --horizon 300 --max-tilt 0.8
run lifetime --config driven.toml --format json --horizon 50
run lifetime --config damped.toml --horizon 100
run stability --config general.toml
run body --config "$examples/mesh-top.toml" --format json
run body --config parts.toml --format json
run sweep --vary spin=0:400:41 --vary B/A=1:1.2:6
run sweep --config "$examples/asymmetric-plate.toml" --vary spin=0:3:31
for integ in auto taylor dopri5 dop853; do
  run sweep --vary spin=50:300:6 --vary C/A=0.25:0.3:2 --theta0 0.1 --model nonlinear --horizon 3 --integrator "$integ"
  run sweep --config "$examples/asymmetric-plate.toml" --vary spin=0.5:3:6 --model nonlinear --horizon 20 --max-tilt 0.3 --integrator "$integ"
  run sweep --config damped.toml --vary spin=100:400:4 --model nonlinear --horizon 5 --integrator "$integ"
done
run sweep --vary spin=100:200:3 --model nonlinear --horizon 3 --integrator splitting
echo "$n runs recorded in $out"

"""Writes examples/spin-decay.csv: a GENERATED spin decay for `heavytop fit-decay`.

The closed-form law of SPEC section 6 for a free symmetric top, C w' = -d_a w - tau0 sign(w),
for the built-in toy top (C = 1.2e-5 kg m^2) with d_a = 2e-7 N m s and tau0 = 1e-5 N m from
w0 = 200 rad/s: w(t) = (w0 + tau0/d_a) exp(-d_a t / C) - tau0/d_a until it reaches 0 at
t = C/d_a ln(1 + d_a w0 / tau0) = 96.57 s, then 0. Sampled every 2 s from 0 to 110 s, with
Gaussian noise of 1 rad/s (numpy.random.default_rng(18)) while the top spins; a stopped top
reads exactly 0, and a noisy reading below 0 is written as 0.

    /usr/bin/python3 examples/python/make_spin_decay.py > examples/spin-decay.csv
"""
import numpy as np

C, D_A, TAU0, W0, NOISE, SEED = 1.2e-5, 2e-7, 1e-5, 200.0, 1.0, 18

t = np.arange(0.0, 110.0 + 1e-9, 2.0)
offset = TAU0 / D_A
spin = np.maximum((W0 + offset) * np.exp(-D_A * t / C) - offset, 0.0)
rng = np.random.default_rng(SEED)
noisy = np.where(spin > 0.0, np.maximum(spin + rng.normal(0.0, NOISE, t.size), 0.0), 0.0)

print("# GENERATED, not measured: the spin-decay law C w' = -d_a w - tau0 sign(w) for the toy top "
      "(C = 1.2e-5 kg m^2)")
print(f"# with d_a = {D_A:g} N m s, tau0 = {TAU0:g} N m, w0 = {W0:g} rad/s (stops at 96.57 s), "
      f"Gaussian noise {NOISE:g} rad/s, numpy seed {SEED}.")
print("# Regenerate: /usr/bin/python3 examples/python/make_spin_decay.py > examples/spin-decay.csv")
print("# Fit: heavytop fit-decay --data examples/spin-decay.csv   (t in s, spin in rad/s)")
print("t,spin")
for ti, wi in zip(t, noisy):
    print(f"{ti:g},{wi:.2f}")

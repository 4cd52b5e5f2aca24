#!/usr/bin/env python3
"""Two elastic bars impacting, in 1D: what the implicit midpoint rule with the persistence
condition does at the contact node (docs/contact.md, "Sustained contact").

The bars of inputs/two_bars.xml (L = 1 m, section A = 0.1 m^2 per metre of depth, rho = 1000,
c = 53.4 m/s, gap 0.01 m, the left one at v0 = 1 m/s), linear 2-node elements with the
consistent mass, linear elasticity (the midpoint rule is then the trapezoidal rule), steps
of 0.5 ms. The contact node pair is active from the first step whose leapfrog gap
d_n + (d_n - d_{n-1})/2 is <= 0 until its multiplier turns tensile; active, it satisfies

  persistence:   u_s - u_m does not change over the step       (the scheme of src/contact), or
  entry:         on the step it enters, the relative displacement is dt/2 times the relative
                 velocity at t_n, so its relative velocity at t_{n+1} is 0 (then persistence).

Printed per scheme: the contact force per step (the multiplier: the step's impulse / dt),
its two-step mean, the 1D value rho c v0 A / 2, the energy, the contact nodes' velocities.
Usage: python3 perf/studies/contact_persistence_1d.py [steps to print]
"""
import sys

import numpy as np

RHO, C, A, L, GAP, V0, N, DT, STEPS = 1000.0, 53.4, 0.1, 1.0, 0.01, 1.0, 40, 5e-4, 160


def run(entry):
    E, h, nn = RHO * C * C, L / N, 2 * (N + 1)
    M, K = np.zeros((nn, nn)), np.zeros((nn, nn))
    for b in range(2):
        for e in range(N):
            i = b * (N + 1) + e
            M[i:i + 2, i:i + 2] += RHO * A * h / 6 * np.array([[2, 1], [1, 2]])
            K[i:i + 2, i:i + 2] += E * A / h * np.array([[1, -1], [-1, 1]])
    s, m = N, N + 1  # the left bar's end (slave) and the right bar's end (master)
    X = np.concatenate([np.linspace(0, L, N + 1), np.linspace(L + GAP, 2 * L + GAP, N + 1)])
    u, v = np.zeros(nn), np.zeros(nn)
    v[:N + 1] = V0
    G = np.zeros(nn)
    G[s], G[m] = 1.0, -1.0  # G du: the approach of the two ends
    gap = lambda w: X[m] + w[m] - X[s] - w[s]
    d_prev, active, rows = gap(u) + DT * V0, False, []
    E0 = 0.5 * v @ M @ v
    S = np.zeros((nn + 1, nn + 1))
    S[:nn, :nn] = 2 / DT**2 * M + 0.5 * K
    S[:nn, nn], S[nn, :nn] = -G, G
    for k in range(STEPS):
        d_n = gap(u)
        rhs = 2 / DT * M @ v - K @ u
        lam = 0.0
        if active or d_n + 0.5 * (d_n - d_prev) <= 0:
            target = 0.5 * DT * (G @ v) if (entry and not active) else 0.0
            sol = np.linalg.solve(S, np.concatenate([rhs, [target]]))
            du, lam = sol[:nn], sol[nn]
            active = lam < 0.0
        if not active:
            du, lam = np.linalg.solve(S[:nn, :nn], rhs), 0.0
        v = 2 * du / DT - v
        d_prev, u = d_n, u + du
        energy = 0.5 * v @ M @ v + 0.5 * u @ K @ u
        rows.append((k + 1, -lam, gap(u), energy / E0 - 1.0, v[s], v[m], active))
    return rows


def main():
    show = int(sys.argv[1]) if len(sys.argv) > 1 else 12
    F1d = RHO * C * V0 / 2 * A
    res = {}
    for name, entry in (("persistence", False), ("entry", True)):
        rows = res[name] = run(entry)
        act = [r for r in rows if r[6]]
        F = np.array([r[1] for r in act])
        mean2 = 0.5 * (F[1:] + F[:-1])
        core, core2 = F[2:-10], mean2[2:-10]
        print(f"{name}: {len(act)} contact steps (2L/c = {2 * L / C / DT:.1f} steps), energy change at the end "
              f"{rows[-1][3]:+.2e} E0, min gap {min(r[2] for r in act):+.2e} m")
        print(f"  force: plateau mean {core.mean():.1f} N/m ({100 * (core.mean() / F1d - 1):+.2f} % of rho c v0 A/2 = {F1d:.1f}), "
              f"max |F - mean| {100 * np.max(np.abs(core - core.mean())) / core.mean():.1f} %")
        print(f"  two-step mean: plateau mean {core2.mean():.1f} N/m ({100 * (core2.mean() / F1d - 1):+.2f} %), "
              f"max |F - mean| {100 * np.max(np.abs(core2 - core2.mean())) / core2.mean():.1f} %")
        print("   step      F [N/m]   two-step mean   v_slave   v_master")
        for i, r in enumerate(act[:show]):
            print(f"  {r[0]:5d} {r[1]:12.1f} {(0.5 * (F[i] + F[i - 1]) if i else 0.5 * F[0]):14.1f} {r[4]:9.3f} {r[5]:10.3f}")
    Fp = np.array([r[1] for r in res["persistence"]])
    Fe = np.array([r[1] for r in res["entry"]])
    both = [i for i, r in enumerate(res["persistence"]) if r[6] and res["entry"][i][6] and res["persistence"][i - 1][6]]
    diff = max(abs(0.5 * (Fp[i] + Fp[i - 1]) - Fe[i]) for i in both)
    print(f"two-step mean of the persistence force vs the force of the entry scheme, steps both in contact: max difference {diff:.1e} N/m")


if __name__ == "__main__":
    main()

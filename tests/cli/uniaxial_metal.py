#!/usr/bin/env python3
"""A stent-metal deck in uniaxial tension against the closed form of its 1D curve.

Runs inputs/uniaxial_316l.xml or inputs/uniaxial_l605.xml (a 1 mm cube in homogeneous
uniaxial tension to 20 % strain, mm-N-s) and checks every step's reaction_pull_x against
the finite-strain closed form of the deck's law (docs/plasticity.md, "Stent metals"): with
the flow direction fixed at diag(1, -1/2, -1/2) the exponential update is exact, so at
stretch lam the equivalent plastic strain alpha solves
    tau(lam e^-alpha) = sigma_y(alpha)
(tau the axial Kirchhoff stress of the elastic law in uniaxial stress) and the reaction on
the 1 mm^2 face is P11 = tau / lam. It also compares the Cauchy stress with the 1D
small-strain curve sigma_y(eps_p), eps_p = ln lam - sigma / E (the deck's stated curve),
which the law must follow up to the elastic strain's second order.
usage: uniaxial_metal.py STENTOR WORKDIR DECK
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def material(deck):
    root = ET.parse(deck).getroot()
    mats = [c for c in root if c.get("name") == "Materials"][0]
    m = list(mats)[0]
    p = {c.get("name"): c.get("value") for c in m if c.tag == "Parameter"}
    return p


def bisect(f, lo, hi, n=200):
    """Root of f, f(lo) > 0 > f(hi)."""
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        if f(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def elastic_state(p):
    """(axial Kirchhoff stress, lateral c_2 = c_3) of the elastic law in uniaxial stress at stretch l."""
    E, nu = float(p["E"]), float(p["nu"])
    mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
    if p["model"] == "neo-Hookean plasticity":
        # tau_A = mu c_A + lam ln J - mu; lateral tau_2 = 0 fixes m = c_2 = c_3.
        def tau(l):
            c = l * l
            m = bisect(lambda m: -(mu * m + lam * 0.5 * math.log(c * m * m) - mu), 1e-3, 10.0)
            return mu * (c - m), m
        return tau
    # Ciarlet-Geymonat with C2 = 0: C1 = mu/2, D = lam/4, K = C1 + D; lateral m in closed form.
    C1, D = mu / 2, lam / 4
    K = C1 + D

    def tau(l):
        c = l * l
        a, b = D * c, C1
        m = 2 * K / (b + math.sqrt(b * b + 4 * a * K))
        return 2 * (C1 * c + D * c * m * m - K), m
    return tau


def yield_curve(p):
    Y, H = float(p["yield stress"]), float(p.get("hardening", "0"))
    if p.get("hardening law", "linear") == "Voce":
        Q, d = float(p["saturation stress"]) - Y, float(p["saturation rate"])
        return lambda a: Y + H * a + Q * (1 - math.exp(-d * a))
    return lambda a: Y + H * a


def main():
    stentor, work, deck = sys.argv[1:4]
    deck = os.path.abspath(deck)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(work)
    r = subprocess.run([stentor, "--output", "out", deck], capture_output=True, text=True, timeout=240)
    print(r.stdout[-400:])
    if r.returncode != 0:
        print(r.stderr)
        raise SystemExit(f"FAIL: exit status {r.returncode}")
    base = os.path.splitext(os.path.basename(deck))[0]
    with open(f"out/{base}_history.csv") as f:
        rows = list(csv.DictReader(f))
    p = material(deck)
    state, sy, E = elastic_state(p), yield_curve(p), float(p["E"])

    def tau_e(l):
        return state(l)[0]
    worst, worst_1d, n = 0.0, 0.0, 0
    for row in rows:
        t = float(row["time"])
        if t == 0.0:
            continue
        lam = 1.0 + 0.2 * t
        F = float(row["reaction_pull_x"])
        if tau_e(lam) <= sy(0.0):
            alpha = 0.0
        else:
            alpha = bisect(lambda a: tau_e(lam * math.exp(-a)) - sy(a), 0.0, math.log(lam))
        P = tau_e(lam * math.exp(-alpha)) / lam
        worst = max(worst, abs(F - P) / P)
        # Cauchy stress sigma = F / current area (lateral stretch of the elastic state times
        # the isochoric plastic one) against the 1D curve at eps_p = ln lam - sigma / E.
        n += 1
        if alpha > 0.0:
            le = lam * math.exp(-alpha)
            J = le * state(le)[1]  # the plastic flow is isochoric: J = J_e = lam_e sqrt(c_2 c_3)
            sigma = F * lam / J  # Cauchy = Kirchhoff / J, Kirchhoff = P11 lam
            eps_p = math.log(lam) - sigma / E
            worst_1d = max(worst_1d, abs(sigma - sy(eps_p)) / sy(eps_p))
    last = rows[-1]
    print(f"{base}: {n} steps, max |F - P11 A0| / P11 A0 = {worst:.2e} (closed form, finite strain); "
          f"Cauchy stress vs the 1D curve sigma_y(ln lam - sigma/E): {worst_1d:.2e}; "
          f"F at 20 % = {float(last['reaction_pull_x']):.3f} N")
    if n < 40:
        raise SystemExit(f"FAIL: {n} steps in the history, expected 40")
    if worst > 1e-8:
        raise SystemExit(f"FAIL: reaction vs closed form {worst:.2e} > 1e-8")
    if worst_1d > 5e-3:
        raise SystemExit(f"FAIL: 1D curve {worst_1d:.2e} > 5e-3")
    print("PASS")


main()

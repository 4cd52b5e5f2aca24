#!/usr/bin/env python3
"""The balloon angioplasty scene (inputs/axi_angioplasty.xml), coarse: lumen gain and recoil.

Runs the shipped deck on a coarse mesh of its own .geo (Mesh->Parameters: cells of 0.2 mm
along the axis, 3 through plaque and intima, 1 through media, adventitia and balloon) three
times: as shipped (elastoplastic plaque), with an elastic plaque (yield stress 1e6 MPa) and
with the balloon alone (contact off: its free inflation). From the history CSV's probes
(throat: the lumen's node at the throat; balloon: the balloon's inner node at z = 0) at the
end of each stage (inflate, deflate, withdrawn) it requires:
  - at peak inflation the balloon presses on the plaque (contact active, no penetration
    beyond 1e-6 mm) and the throat has opened (radius above 1.2 times the stenosed 0.9487 mm),
    while the plaque holds the balloon back (its radius below the free balloon's at 0.6 MPa);
  - the elastoplastic plaque yields during inflation (plastic dissipation > 0);
  - after deflation the balloon has left the wall (no active contact node, the balloon back
    at its reference radius to 1e-9 mm: it is elastic) and the throat keeps part of its gain:
    0 < recoil = (r_peak - r_after) / (r_peak - r0) < 1, with bounds 0.1 and 0.9;
  - with the elastic plaque the whole artery is hyperelastic, so unloaded it returns to its
    reference shape: the throat's radius after deflation is r0 to 1e-8 mm (full recoil, no
    gain): the gain of the first run is the plaque's plastic strain;
  - the withdrawn stage (balloon's contact and pressure off) changes nothing (1e-12 mm).
usage: axi_angioplasty.py STENTOR WORKDIR DECK

With --dynamic (after DECK): the same coarse deck with every stage dynamic (Gonzalez, a
density of 1.1e-9 t/mm^3 for every material, the stages' durations of 1 s: quasi-static),
run beside the static one. The energy CSV's identity E_{n+1} - E_n = W_ext + W_sup - D +
W_contact - D_friction holds per step and over the run to 1e-10 of the largest total energy
(the audit's external work of the follower pressure is f_ext(x_{n+1/2}) . du, which the
step balances; the pressure's exact work on the revolved surface differs from it by the
time discretisation error, docs/axisymmetric.md), the dissipation is the plaque's plastic
dissipation (no viscosity), frictionless contact between the two bodies does no net work,
the kinetic energy stays below 1e-5 of the total, the throat opens and keeps part of its
gain as in the static run, and its radii at peak inflation and after deflation are the
static run's to 5 % of the gain (the dynamic steps and cut-backs differ).
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

R_THROAT = 1.5 * math.sqrt(1.0 - 0.6)  # the deck's 60 % area stenosis of a 1.5 mm lumen
R_BALLOON_INNER = 0.85


def child(node, tag, name):
    for c in node:
        if c.tag == tag and c.get("name") == name:
            return c
    raise SystemExit(f"FAIL: no {tag} '{name}' in the deck")


def variant(src, dst, plaque_yield=None, free=False, dynamic=False):
    tree = ET.parse(src)
    root = tree.getroot()
    mesh = child(root, "ParameterList", "Mesh")
    f = child(mesh, "Parameter", "file")
    f.set("value", os.path.join(os.path.dirname(os.path.abspath(src)), f.get("value")))
    params = ET.SubElement(mesh, "ParameterList", name="Parameters")
    for k, v in (("dz", "0.2"), ("nin", "3"), ("nm", "1"), ("na", "1"), ("nb", "1")):
        ET.SubElement(params, "Parameter", name=k, type="double", value=v)
    if plaque_yield:
        plaque = child(child(root, "ParameterList", "Materials"), "ParameterList", "plaque")
        child(plaque, "Parameter", "yield stress").set("value", plaque_yield)
    if free:
        for stage in child(root, "ParameterList", "Stages"):
            if stage.get("name") != "withdrawn":
                ET.SubElement(stage, "Parameter", name="contact", type="string", value="none")
    if dynamic:
        child(child(root, "ParameterList", "Problem"), "Parameter", "analysis").set("value", "dynamic")
        for m in child(root, "ParameterList", "Materials"):
            ET.SubElement(m, "Parameter", name="density", type="double", value="1.1e-9")
        ti = ET.SubElement(root, "ParameterList", name="Time Integration")
        ET.SubElement(ti, "Parameter", name="scheme", type="string", value="gonzalez")
    out = child(root, "ParameterList", "Output")
    ET.SubElement(out, "Parameter", name="fields", type="bool", value="false")
    tree.write(dst)


def run(stentor, work, name, **kw):
    deck = os.path.join(work, name + ".xml")
    variant(sys.argv[3], deck, **kw)
    out = os.path.join(work, name)
    r = subprocess.run([stentor, "--output", out, deck], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-4000:], r.stderr[-4000:])
        raise SystemExit(f"FAIL: {name}: stentor exit status {r.returncode}")
    with open(os.path.join(out, "axi_angioplasty_history.csv")) as fh:
        rows = list(csv.DictReader(fh))
    ends = {}
    for row in rows:  # the last row of each stage
        ends[int(float(row["stage"]))] = {k: float(v) for k, v in row.items()}
    if sorted(ends) != [1, 2, 3]:
        raise SystemExit(f"FAIL: {name}: stages {sorted(ends)} in the history, expected 1, 2, 3")
    return ends, rows


def main_dynamic(stentor, work, check):
    static, _ = run(stentor, work, "static")
    dyn, rows = run(stentor, work, "dynamic", dynamic=True)
    with open(os.path.join(work, "dynamic", "axi_angioplasty_energy.csv")) as fh:
        e = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(fh)]
    emax = max(abs(r["total"]) for r in e)
    bal = max(abs(r["balance_residual"]) for r in e)
    kmax = max(r["kinetic"] for r in e)
    n, z = e[-1], e[0]
    run_defect = n["total"] - z["total"] - (n["external_work"] + n["support_work"] - n["dissipation"] + n["contact_work"] -
                                            n["friction_dissipation"])
    r0 = R_THROAT
    peak, after = r0 + dyn[1]["u_throat_x"], r0 + dyn[2]["u_throat_x"]
    s_peak, s_after = r0 + static[1]["u_throat_x"], r0 + static[2]["u_throat_x"]
    recoil = (peak - after) / (peak - r0)
    print(f"[axi_angioplasty dynamic] {len(e)} rows, largest E {emax:.6e} mJ, max |balance| per step {bal / emax:.2e} E, "
          f"over the run {run_defect / emax:.2e} E; W_ext {n['external_work']:.6e}, D_plastic {n['plastic_dissipation']:.6e}, "
          f"W_contact {n['contact_work']:.1e}, max kinetic {kmax / emax:.1e} E; throat {r0:.6f} -> {peak:.6f} -> {after:.6f} "
          f"(static {s_peak:.6f} -> {s_after:.6f}), recoil {100 * recoil:.2f} %")
    check(len(e) > 31, f"every step in the energy CSV ({len(e)} rows)")
    check(bal < 1e-10 * emax, f"energy identity per step: {bal / emax:.2e} E < 1e-10 E")
    check(abs(run_defect) < 1e-10 * emax, f"energy identity over the run: {abs(run_defect) / emax:.2e} E < 1e-10 E")
    check(n["plastic_dissipation"] > 0, "the plaque yields")
    check(abs(n["dissipation"] - n["plastic_dissipation"]) < 1e-12 * emax, "the dissipation is plastic (no viscosity)")
    check(abs(n["contact_work"]) < 1e-10 * emax and abs(n["friction_dissipation"]) < 1e-10 * emax,
          "frictionless contact between the two bodies does no net work")
    check(0 < kmax < 1e-5 * emax, f"quasi-static: max kinetic {kmax / emax:.1e} E in (0, 1e-5 E)")
    check(dyn[1]["contact_balloon_lumen_active"] >= 1 and dyn[2]["contact_balloon_lumen_active"] == 0,
          "contact at peak inflation, none after deflation")
    check(peak > 1.2 * r0 and 0.1 < recoil < 0.9 and after > r0, "the throat opens and keeps part of its gain")
    for what, d, s in (("peak inflation", peak, s_peak), ("after deflation", after, s_after)):
        check(abs(d - s) < 0.05 * (s - r0), f"{what}: dynamic {d:.6f} vs static {s:.6f} within 5 % of the gain")


def main():
    stentor, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    fails = []

    def check(ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            fails.append(what)

    if len(sys.argv) > 4 and sys.argv[4] == "--dynamic":
        main_dynamic(stentor, work, check)
        if fails:
            raise SystemExit(f"FAIL: {len(fails)} check(s)")
        print("PASS")
        return

    plastic, rows = run(stentor, work, "plastic")
    elastic, _ = run(stentor, work, "elastic", plaque_yield="1e6")
    free, _ = run(stentor, work, "free", free=True)

    r0 = R_THROAT
    r_peak = r0 + plastic[1]["u_throat_x"]
    r_after = r0 + plastic[2]["u_throat_x"]
    recoil = (r_peak - r_after) / (r_peak - r0)
    rb_peak = R_BALLOON_INNER + plastic[1]["u_balloon_x"]
    rb_free = R_BALLOON_INNER + free[1]["u_balloon_x"]
    dissipation = sum(float(r["plastic_dissipation"]) for r in rows if int(float(r["stage"])) == 1)
    print(f"[axi_angioplasty] throat radius {r0:.6f} -> {r_peak:.6f} at 0.6 MPa -> {r_after:.6f} after deflation "
          f"(gain {r_after - r0:.6f} mm, recoil {100 * recoil:.2f} % of the peak gain); balloon inner radius at peak "
          f"{rb_peak:.6f} (free {rb_free:.6f}); plastic dissipation in inflation {dissipation:.6e} mJ; elastic plaque: "
          f"peak {r0 + elastic[1]['u_throat_x']:.6f}, after deflation {r0 + elastic[2]['u_throat_x']:.6f} "
          f"(off r0 by {elastic[2]['u_throat_x']:.1e})")

    check(plastic[1]["contact_balloon_lumen_active"] >= 1, "contact active at peak inflation")
    check(plastic[1]["contact_balloon_lumen_min_gap"] > -1e-6, "no penetration at peak inflation (min gap > -1e-6 mm)")
    check(r_peak > 1.2 * r0, f"the throat opened: r_peak {r_peak:.4f} > 1.2 r0 = {1.2 * r0:.4f}")
    check(rb_peak < rb_free, f"the plaque holds the balloon back: {rb_peak:.4f} < free {rb_free:.4f}")
    check(dissipation > 0, "the plaque yields during inflation")
    check(plastic[2]["contact_balloon_lumen_active"] == 0, "the deflated balloon has left the wall")
    check(abs(plastic[2]["u_balloon_x"]) < 1e-9, "the deflated balloon is back at its radius (1e-9 mm)")
    check(0.1 < recoil < 0.9, f"partial recoil: 0.1 < {recoil:.4f} < 0.9")
    check(r_after > r0, f"lumen gain after deflation: {r_after:.4f} > {r0:.4f}")
    check(abs(elastic[2]["u_throat_x"]) < 1e-8, "elastic plaque: full recoil (1e-8 mm)")
    check(elastic[1]["u_throat_x"] > 0.2 * r0, "elastic plaque: the throat opened at peak")
    for name, ends in (("plastic", plastic), ("elastic", elastic)):
        check(abs(ends[3]["u_throat_x"] - ends[2]["u_throat_x"]) < 1e-12, f"{name}: the withdrawn stage changes nothing")
    if fails:
        raise SystemExit(f"FAIL: {len(fails)} check(s)")
    print("PASS")


if __name__ == "__main__":
    main()

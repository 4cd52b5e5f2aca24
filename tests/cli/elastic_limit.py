#!/usr/bin/env python3
"""S5 with an unreachable yield stress is S4 (issue 11: "Y >> 1 reproduces S4 exactly").

Runs the S4 cross-section (inputs/s4_ring_section.xml) and the S5 deck
(inputs/s5_ring_plastic.xml) with the stent's yield stress set to 1e12 Pa, both cut to
their first stage shortened to 20 steps (0.4 s) (the balloon unfolds the ring and presses it into
the wall: contact, friction, viscosity), and requires the history, energy and stent
metrics CSVs to be equal digit for digit in every common column, with zero plastic
dissipation: the plastic kernel below yield is the elastic one.
usage: elastic_limit.py STENTOR WORKDIR S4_DECK S5_DECK
"""
import csv
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def child(node, tag, name):
    for c in node:
        if c.tag == tag and c.get("name") == name:
            return c
    raise SystemExit(f"FAIL: no {tag} '{name}' in the deck")


def shortened(src, dst, yield_stress):
    tree = ET.parse(src)
    root = tree.getroot()
    f = child(child(root, "ParameterList", "Mesh"), "Parameter", "file")
    f.set("value", os.path.join(os.path.dirname(os.path.abspath(src)), f.get("value")))
    stages = child(root, "ParameterList", "Stages")
    for name in ("deflation", "recoil"):
        stages.remove(child(stages, "ParameterList", name))
    first = child(stages, "ParameterList", "inflation")
    child(first, "Parameter", "duration").set("value", "0.4")  # the step of the deck: 0.02 s
    child(first, "Parameter", "steps").set("value", "20")
    if yield_stress:
        stent = child(child(root, "ParameterList", "Materials"), "ParameterList", "stent")
        child(stent, "Parameter", "yield stress").set("value", yield_stress)
    child(child(root, "ParameterList", "Output"), "Parameter", "basename").set("value", "ring")
    tree.write(dst)


def read(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def main():
    stentor, work, s4, s5 = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(work)
    for tag, deck, y in (("elastic", s4, None), ("plastic", s5, "1e12")):
        shortened(deck, tag + ".xml", y)
        r = subprocess.run([stentor, "--output", tag, tag + ".xml"], capture_output=True, text=True, timeout=240)
        print(r.stdout[-600:])
        if r.returncode != 0:
            print(r.stderr)
            raise SystemExit(f"FAIL: the {tag} run ended with exit status {r.returncode}")
    for what in ("history", "energy", "metrics"):
        h1, r1 = read(f"elastic/ring_{what}.csv")
        h2, r2 = read(f"plastic/ring_{what}.csv")
        if len(r1) != len(r2) or len(r1) < 20:
            raise SystemExit(f"FAIL: {what}: {len(r1)} and {len(r2)} rows")
        common = [c for c in h1 if c in h2]
        if len(common) != len(h1):
            raise SystemExit(f"FAIL: {what}: columns of the elastic run missing in the plastic one")
        for i, (a, b) in enumerate(zip(r1, r2)):
            for c in common:
                if a[h1.index(c)] != b[h2.index(c)]:
                    raise SystemExit(f"FAIL: {what} row {i + 1}, column {c}: {a[h1.index(c)]} (elastic) != {b[h2.index(c)]}")
        if "plastic_dissipation" in h2:
            k = h2.index("plastic_dissipation")
            if any(float(row[k]) != 0.0 for row in r2):
                raise SystemExit(f"FAIL: {what}: plastic dissipation below an unreachable yield stress")
        print(f"{what}: {len(r1)} rows, {len(common)} columns equal digit for digit")
    print("PASS")


main()

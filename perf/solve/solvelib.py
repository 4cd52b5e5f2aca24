"""Shared pieces of the linear-solver scripts in perf/solve/ (time_to_solution.sh,
muelu_variants.sh): a deck copy with parameters set by path, and the numbers of one run
read from its log.

  python3 perf/solve/solvelib.py deck SRC DST [--set PATH=TYPE:VALUE]... [--remove PATH]...
      Copy deck SRC to DST (Mesh->file made absolute, perf/studies/studylib.Deck), first
      removing each PATH (a parameter or sublist, "Linear Solver/MueLu"), then setting each
      PATH ("Linear Solver/MueLu/smoother: params/chebyshev: degree") to VALUE with TYPE
      (int, double, bool, string, Array(double)); missing sublists and parameters are created.

  python3 perf/solve/solvelib.py parse LOG [--label K=V]... [--history CSV --column NAME]
                                           [--row FORMAT] [--csv FILE]
      Read a stentor log (stdout + stderr, with the line "TIME wall user sys maxrss_kb" of
      `/usr/bin/time -f "TIME %e %U %S %M"` if it was timed) and print FORMAT filled with the
      fields below and the labels (str.format); --csv appends the labels and fields to FILE
      (header written when FILE is new). --column: that history column's last value (field
      `column`).

Fields: dofs, steps, cutbacks, newton, linear (totals of the "Summary:" line; "failed" / "-"
without one), per_newton (GMRES iterations per Newton iteration), setup, setups, builds,
solve (the "(newton: linear set-up ...)" line, seconds), newton_s (the newton timer),
wall, cpu, rss (MB) from the TIME line, fallbacks (linear-solver fallbacks), fallback_step
(the step during which the first one happened), status ("yes", "FAILED: ...", "input error",
"timeout", "crash (exit N)"), completed (status, and each
fallback with its step), exit (the exit status from "EXIT n", if the caller logged it).
"""
import argparse
import csv
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studies"))
import studylib  # noqa: E402  (Deck: the deck templating the studies share)

FIELDS = ["dofs", "steps", "cutbacks", "newton", "linear", "per_newton", "builds", "setups", "setup", "solve",
          "newton_s", "wall", "cpu", "rss", "fallbacks", "fallback_step", "status", "completed", "exit"]


def convert(typ, value):
    if typ == "bool":
        return value.lower() in ("1", "true", "yes")
    return value


def make_deck(src, dst, sets, removes):
    d = studylib.Deck(src)
    for path in removes:
        d.remove(path)
    for item in sets:
        path, _, tv = item.partition("=")
        typ, _, value = tv.partition(":")
        if not path or not typ:
            raise SystemExit("solvelib: expected PATH=TYPE:VALUE, got '%s'" % item)
        d.set(path, convert(typ, value), type=typ)
    d.write(dst)


def parse_log(text):
    f = {k: "?" for k in FIELDS}
    g = lambda p: re.search(p, text, re.M)
    m = g(r"^\s*dofs\s+(\d+)")
    if m:
        f["dofs"] = m.group(1)
    m = g(r"^Summary: (\d+) steps, (\d+) cut-backs, (\d+) Newton iterations, (\d+) linear iterations")
    if m:
        f["steps"], f["cutbacks"], f["newton"], f["linear"] = m.groups()
        n, lin = int(m.group(3)), int(m.group(4))
        f["per_newton"] = "%.1f" % (lin / n) if n else "-"
    else:
        f["newton"], f["linear"], f["per_newton"] = "failed", "-", "-"
    m = g(r"linear set-up ([\d.]+) s in (\d+) calls, (\d+) preconditioner builds; linear solve ([\d.]+) s")
    if m:
        f["setup"], f["setups"], f["builds"], f["solve"] = m.groups()
    m = g(r"^  newton\s+([\d.]+) s")
    if m:
        f["newton_s"] = m.group(1)
    m = g(r"^TIME ([\d.]+) ([\d.]+) ([\d.]+) (\d+)")
    if m:
        f["wall"] = m.group(1)
        f["cpu"] = "%.1f" % (float(m.group(2)) + float(m.group(3)))
        f["rss"] = "%.0f" % (int(m.group(4)) / 1024)
    # Fallbacks (LinearSolver::fall_back): the warning comes after the last finished step.
    warn = list(re.finditer(r"^warning: linear solver .*using (.*) from here on$", text, re.M))
    f["fallbacks"] = str(len(warn))
    f["fallback_step"] = "-"
    falls = []  # (to, step) of each fallback
    for w in warn:
        steps = re.findall(r"^\s*step\s+(\d+)\s", text[:w.start()], re.M)
        to = re.search(r"Schwarz|direct", w.group(1))
        falls.append((to.group(0).lower() if to else w.group(1), int(steps[-1]) + 1 if steps else 1))
    if falls:
        f["fallback_step"] = str(falls[0][1])
    m = g(r"^EXIT (\d+)")
    f["exit"] = m.group(1) if m else "?"
    failed = g(r"^FAILED: (.*)$")
    if failed:
        f["status"] = "FAILED: " + failed.group(1)[:80]
    elif f["exit"] == "2":
        err = g(r"error: ([^\n]*)")
        f["status"] = "input error" + (": " + err.group(1)[:100] if err else "")
    elif f["exit"] in ("124", "137"):
        f["status"] = "timeout"
    elif f["exit"] not in ("0", "?") or f["steps"] == "?":
        f["status"] = "crash (exit %s)" % f["exit"]
    else:
        f["status"] = "yes"
    f["completed"] = f["status"]
    if falls:
        f["completed"] += ", fell back to " + ", then ".join("%s in step %d" % fs for fs in falls)
    return f


def last_value(hist, column):
    try:
        with open(hist) as fh:
            rows = list(csv.DictReader(fh))
        return "%.10g" % float(rows[-1][column])
    except (OSError, KeyError, IndexError, ValueError):
        return "?"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("deck")
    d.add_argument("src")
    d.add_argument("dst")
    d.add_argument("--set", action="append", default=[])
    d.add_argument("--remove", action="append", default=[])
    p = sub.add_parser("parse")
    p.add_argument("log")
    p.add_argument("--label", action="append", default=[])
    p.add_argument("--history")
    p.add_argument("--column")
    p.add_argument("--row")
    p.add_argument("--csv")
    a = ap.parse_args()
    if a.cmd == "deck":
        make_deck(a.src, a.dst, a.set, a.remove)
        return
    with open(a.log, errors="replace") as fh:
        f = parse_log(fh.read())
    labels = dict(kv.split("=", 1) for kv in a.label)
    if a.column:
        f["column"] = last_value(a.history, a.column)
    allf = {**labels, **f}
    if a.row:
        print(a.row.format(**allf))
    if a.csv:
        new = not os.path.exists(a.csv)
        with open(a.csv, "a") as fh:
            w = csv.writer(fh, lineterminator="\n")
            keys = list(labels) + FIELDS + (["column"] if a.column else [])
            if new:
                w.writerow(keys)
            w.writerow([allf[k] for k in keys])


if __name__ == "__main__":
    main()

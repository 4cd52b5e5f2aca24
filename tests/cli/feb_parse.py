"""cli.perf.feb_parse: `perf/solve/feb.py parse` on FEBio 4.11 output of the P1 cube (h = 0.5,
135 DOF) laid out as perf/solve/time_to_solution.sh leaves it, in tests/cli/febio/. FEBio
is not installed here: the .feb files are feb.py's own, and the FEBio output was written
line by line from FEBio 4.11's format strings (github.com/febiosoftware/FEBio, the files
named below), with plausible numbers (3 and 4 Newton iterations per step, PARDISO):

  cube_p1_h0.5_febio{,_tight}.feb           written by `feb.py write` (default tolerances;
                                            --tolerances stentor: rtol 1e-20, etol = dtol = 0)
  cube_p1_h0.5_febio{,_tight}.log           FEBio's log file (-o)
  cube_p1_h0.5_febio{,_tight}.Rx.txt        the node_data file of Rx on the pulled face
  cube_p1_h0.5_febio{,_tight}_t1.screen.txt FEBio's screen output and /usr/bin/time's line

The text follows FEBio's format strings (FEBioLib/FEBioModel.cpp: on_cb_stepSolved,
on_cb_solved; FECore/FEAnalysis.cpp; FEBioMech/FESolidSolver2.cpp; FECore/DataRecord.cpp:
12 significant digits) and, as FEBio on Linux does (FEBio/console.cpp), sets the terminal
title ESC ] 0 ; ... BEL after every converged step and at the end, with no newline, so
/usr/bin/time's "TIME" line starts after the BEL. Checked:
- wall, CPU and RSS read from that TIME line (they were '?' while the pattern was anchored
  at a line start);
- the linear column "direct" for FEBio's default solver (PARDISO reports one iteration per
  solve, which made the column the number of solves), the product calls x average for an
  iterative solver named in the .feb (fgmres);
- the reaction to 10 significant digits; the tolerance label of each .feb;
- a run killed before its end (no summary, no TIME line): status crash, Newton failed.
usage: feb_parse.py WORKDIR SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys

work, src = sys.argv[1], sys.argv[2]
FEB = os.path.join(src, "perf", "solve", "feb.py")
FIX = os.path.join(src, "tests", "cli", "febio")
ROW = "{dofs}|{newton}|{linear}|{solve}|{wall}|{cpu}|{rss}|{column}|{status}|{tol}"
failures = []


def check(ok, what):
    print("%s: %s" % ("ok" if ok else "FAIL", what))
    if not ok:
        failures.append(what)


def parse(base, screen):
    r = subprocess.run([sys.executable, FEB, "parse", os.path.join(work, base + ".feb"), screen, "--row", ROW],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    return r.returncode, r.stdout.strip()


shutil.rmtree(work, ignore_errors=True)
shutil.copytree(FIX, work)

# The two runs: FEBio's defaults (3 iterations a step) and Stentor's tolerance (4).
for base, want in (("cube_p1_h0.5_febio", "135|12|direct|0.01|0.09|0.1|20|459213.9894|yes|default"),
                   ("cube_p1_h0.5_febio_tight", "135|16|direct|0.02|0.11|0.1|20|459213.9895|yes|rtol=1e-20")):
    screen = os.path.join(work, base + "_t1.screen.txt")
    with open(screen, "rb") as f:
        raw = f.read()
    check(b"\x07TIME " in raw and not raw.startswith(b"TIME") and b"\nTIME" not in raw,
          "%s: the fixture's TIME line follows FEBio's title escape on the same line" % base)
    rc, out = parse(base, screen)
    check(rc == 0 and out == want, "%s: %r, expected %r" % (base, out, want))

# An iterative linear solver named in the .feb: GMRES iterations = calls x average.
base = "cube_p1_h0.5_febio_gmres"
for ext in (".feb", ".log", ".Rx.txt"):
    with open(os.path.join(work, "cube_p1_h0.5_febio" + ext)) as f:
        text = f.read()
    text = text.replace("cube_p1_h0.5_febio.Rx.txt", base + ".Rx.txt")
    if ext == ".feb":
        text = text.replace('\t\t\t<qn_method type="full Newton"/>',
                            '\t\t\t<qn_method type="full Newton"/>\n\t\t\t<linear_solver type="fgmres"/>')
    if ext == ".log":
        text = text.replace("Avg iterations per solve ............ : 1\n", "Avg iterations per solve ............ : 23.5\n")
    with open(os.path.join(work, base + ext), "w") as f:
        f.write(text)
rc, out = parse(base, os.path.join(work, "cube_p1_h0.5_febio_t1.screen.txt"))
check(out.split("|")[2] == "282", "fgmres: linear column 12 x 23.5 = 282: %r" % out)

# A run killed in its third step: the screen and log cut there, no TIME line.
base = "cube_p1_h0.5_febio_killed"
for ext in (".feb", ".log", "_t1.screen.txt"):
    with open(os.path.join(work, "cube_p1_h0.5_febio" + ext), "rb") as f:
        text = f.read()
    if ext != ".feb":
        text = text[:text.index(b"===== beginning time step 3")]
    with open(os.path.join(work, base + ext), "wb") as f:
        f.write(text)
rc, out = parse(base, os.path.join(work, base + "_t1.screen.txt"))
f = out.split("|")
check(rc == 0 and f[1] == "failed" and f[4] == "?" and f[8] == "crash", "killed run: %r" % out)

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("OK: feb.py parse on FEBio 4.11 output")

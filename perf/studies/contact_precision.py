#!/usr/bin/python3
"""Error against run time for the contact scenes (docs/studies/README.md, section 3).

For each scene (S1(a): the ring thrown at the rigid plane, frictionless; S1(b): the same
with viscosity eta = 1000 Pa s; S1(c): with mu = 0.3; S1(d): eta = 1000 and mu = 0.3;
S2: the 3D torus dropped on the rigid plane, frictionless; S3: the ring on the deformable
foundation, frictionless), each time scheme
(gonzalez, midpoint, newmark, hht) and each contact condition (persistence, gap) the scene
runs to T at dt = T/N for N in NS, by default with no cut-back (Stepping->max cutbacks = 0:
every run uses the dt it names; a step that fails ends the run with exit 3, recorded as
failed); CUTBACKS="" allows the deck's cut-backs (S3 needs them, see the README).
Errors are measured in quantities that converge through the impacts, at T, against a
reference run of the same scene (gonzalez + persistence at N = NREF; a run at NREF/2 shows
the reference's own error):
  probe  |u_top(T) - u_top,ref(T)|, the displacement of the body's top node [m] (S1, S3:
          the ring's top (0, 2.1); S2: the torus's highest surface point (0, 0.866, 1.55))
  impulse |p(T) - p_ref(T)| / |p_ref(T) - p(0)|: the total contact impulse received by the
          body up to T (its momentum change; no other force acts on it), relative
  drift  max over the run of |E + D - E0| / E0 (D: viscous + friction dissipation), the
          energy error
  balance max over the run of |balance residual| / E0 (the discrete work identity)
Cost: wall time and CPU time (user + system) of the run.

  perf/studies/contact_precision.py [stentor]        (default build-dev/stentor)
Environment: SCENES="s1a s1b s1b100 s1b5000 s1c s1d s1d2 s2 s3" (s1b: eta = 1000; s1d2:
  eta = 5000 with mu = 0.1), SCHEMES="gonzalez midpoint newmark hht",
  FORMS="persistence gap", NS="50 100 200 400", NREF=3200, T (default per scene: 0.2 s;
  S2 0.1 s, the first impact and the free flight after it), SIZE (mesh size, default per
  scene: 0.05 for the ring, 0.12 for the torus as in its deck), CUTBACKS=0 (Stepping->max cutbacks; empty: the deck's default, then dt is the
  largest step), WORK=<folder for the runs> (default /tmp/stentor_contact_precision),
  PLOT_ONLY=1 (redraw from docs/studies/contact_precision.csv), REUSE=1 (load the outcome of
  runs already made in WORK instead of running them again).
The CSV keeps the rows of scenes not run this time. Run scene by scene, with the settings of
docs/studies/README.md section 3 (S2: NS="25 50 100 200" NREF=800; the defaults would
give S2 a reference of 3200 steps, about 6 CPU min for that run alone; S3: CUTBACKS="").
Writes docs/studies/contact_precision.csv and contact_precision_<scene>.png.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studylib as sl  # noqa: E402

env = os.environ.get
STENTOR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(sl.ROOT, "build-dev", "stentor"))
SCENES = env("SCENES", "s1a s1b s1b100 s1b5000 s1c s1d s1d2 s2 s3").split()
SCHEMES = env("SCHEMES", "gonzalez midpoint newmark hht").split()
FORMS = env("FORMS", "persistence gap").split()
NS = [int(n) for n in env("NS", "50 100 200 400").split()]
NREF = int(env("NREF", "3200"))
T_ENV = env("T")
SIZE_ENV = env("SIZE")
WORK = os.path.abspath(env("WORK", "/tmp/stentor_contact_precision"))
REUSE = bool(env("REUSE"))
CUTBACKS = env("CUTBACKS", "0")  # Stepping->max cutbacks; "" keeps the deck's default
OUT = os.path.join(sl.ROOT, "docs", "studies")
CSV = os.path.join(OUT, "contact_precision.csv")
RING_TOP = (0.0, 2.1)  # the ring's top point (inputs/ring.geo: centre (0, 1.1), Ro = 1)
# The torus's highest point (inputs/torus.geo: centre (0, 0, 0.8), R = 1, r = 0.25, axis
# tilted 30 degrees about x): tube centre (0, cos 30, 0.8 + sin 30) plus r upwards; the
# probe takes the nearest mesh node.
TORUS_TOP = (0.0, 0.8660254, 1.55)

SCENE = {  # deck, contact pair, friction, viscosity [Pa s], probe point, T [s], mesh size, label
    "s1a": ("s1_ring.xml", "floor", 0.0, 0.0, RING_TOP, 0.2, 0.05, "S1(a): ring on a rigid plane, frictionless"),
    "s1b": ("s1_ring.xml", "floor", 0.0, 1000.0, RING_TOP, 0.2, 0.05,
            "S1(b): ring on a rigid plane, eta = 1000 Pa s, frictionless"),
    "s1b100": ("s1_ring.xml", "floor", 0.0, 100.0, RING_TOP, 0.2, 0.05,
               "S1(b): ring on a rigid plane, eta = 100 Pa s, frictionless"),
    "s1b5000": ("s1_ring.xml", "floor", 0.0, 5000.0, RING_TOP, 0.2, 0.05,
                "S1(b): ring on a rigid plane, eta = 5000 Pa s, frictionless"),
    "s1c": ("s1_ring.xml", "floor", 0.3, 0.0, RING_TOP, 0.2, 0.05, "S1(c): ring on a rigid plane, mu = 0.3"),
    "s1d": ("s1_ring.xml", "floor", 0.3, 1000.0, RING_TOP, 0.2, 0.05,
            "S1(d): ring on a rigid plane, eta = 1000 Pa s, mu = 0.3"),
    "s1d2": ("s1_ring.xml", "floor", 0.1, 5000.0, RING_TOP, 0.2, 0.05,
             "S1(d): ring on a rigid plane, eta = 5000 Pa s, mu = 0.1"),
    "s2": ("s2_torus.xml", "floor", 0.0, 0.0, TORUS_TOP, 0.1, 0.12, "S2: 3D torus on a rigid plane, frictionless"),
    "s3": ("s3_ring_foundation.xml", "impact", 0.0, 0.0, RING_TOP, 0.2, 0.05,
           "S3: ring on a deformable foundation, frictionless"),
}


def end_time(scene):
    return float(T_ENV) if T_ENV else SCENE[scene][5]


def mesh_size(scene):
    return float(SIZE_ENV) if SIZE_ENV else SCENE[scene][6]


def deck(scene, scheme, form, n):
    name = "%s_%s_%s_N%d" % (scene, scheme, form, n)
    src, pair, mu, eta, top, _, _, _ = SCENE[scene]
    T = end_time(scene)
    d = sl.Deck(os.path.join(sl.INPUTS, src))
    d.set("Mesh/size", mesh_size(scene), "double")
    if eta:
        d.set("Materials/rubber/viscosity", eta, "double")
    d.set("Time Integration/scheme", scheme)
    d.set("Contact/%s/formulation" % pair, form)
    d.set("Contact/%s/friction" % pair, mu)
    d.set("Stepping/end time", T)
    d.set("Stepping/steps", n)
    if CUTBACKS != "":
        d.set("Stepping/max cutbacks", int(CUTBACKS), "int")
    d.set("Output/basename", "run")
    d.set("Output/fields", False, "bool")
    d.set("Output/Probes/top/point", top, "Array(double)")
    return name, d.write(os.path.join(WORK, scene, name + ".xml"))


def measure(scene, scheme, form, n):
    name, path = deck(scene, scheme, form, n)
    T = end_time(scene)
    r = sl.run(STENTOR, path, os.path.join(WORK, scene, name), name, limit_s=900, reuse=REUSE)
    h, e = r.csv("history", "run"), r.csv("energy", "run")
    row = {"scene": scene, "scheme": scheme, "formulation": form, "N": n, "dt": T / n, "rc": r.rc, "steps": r.steps,
           "cutbacks": r.cutbacks,
           "newton": r.newton, "wall_s": r.wall, "cpu_s": r.cpu}
    done = r.rc == 0 and h and e and abs(h["time"][-1] - T) < 1e-9 * T
    if done:
        e0 = e["total"][0]
        zero = [0.0] * len(e["total"])
        d = [e["total"][k] + e.get("friction_dissipation", zero)[k] + e.get("dissipation", zero)[k]
             for k in range(len(e["total"]))]
        row.update(u_x=h["u_top_x"][-1], u_y=h["u_top_y"][-1], u_z=h.get("u_top_z", [0.0])[-1],
                   p_x=e["momentum_x"][-1], p_y=e["momentum_y"][-1], p_z=e.get("momentum_z", [0.0])[-1],
                   p0_x=e["momentum_x"][0], p0_y=e["momentum_y"][0], p0_z=e.get("momentum_z", [0.0])[0],
                   drift=max(abs(x - e0) for x in d) / e0, balance=max(abs(x) for x in e["balance_residual"]) / e0)
    print("  %-4s %-9s %-11s N=%-5d rc=%d cut-backs=%-4d newton=%-6d wall=%7.1f s cpu=%7.1f s%s" %
          (scene, scheme, form, n, r.rc, r.cutbacks, r.newton, r.wall, r.cpu,
           "  drift %.1e" % row["drift"] if done else "  (failed: %s)" % r.failure()[:120]), flush=True)
    row["failure"] = "" if done else r.failure()
    return row


HEADER = ["scene", "scheme", "formulation", "N", "dt", "rc", "steps", "cutbacks", "newton", "wall_s", "cpu_s", "u_x", "u_y", "p_x",
          "p_y", "probe_error", "impulse_error", "drift", "balance", "reference", "failure", "u_z",
          "p_z"]


def errors(rows):
    out = []
    for scene in SCENES:
        rs = [r for r in rows if r["scene"] == scene]
        ref = next(r for r in rs if r["scheme"] == "gonzalez" and r["formulation"] == "persistence" and r["N"] == NREF)
        for r in rs:
            r["reference"] = int(r["scheme"] == "gonzalez" and r["formulation"] == "persistence" and r["N"] >= NREF // 2)
            if "u_x" in r and "u_x" in ref:
                r["probe_error"] = math.sqrt(sum((r[k] - ref[k]) ** 2 for k in ("u_x", "u_y", "u_z")))
                j = math.sqrt(sum((ref["p" + c] - ref["p0" + c]) ** 2 for c in ("_x", "_y", "_z")))
                r["impulse_error"] = math.sqrt(sum((r[k] - ref[k]) ** 2 for k in ("p_x", "p_y", "p_z"))) / j
            out.append([r.get(k, "") for k in HEADER])
    return out


def plot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = sl.read_rows(CSV)
    for scene in sorted({r["scene"] for r in rows}):
        fig, ax = plt.subplots(1, 3, figsize=(16, 5))
        for scheme in SCHEMES:
            for form, style in (("persistence", "-o"), ("gap", "--s")):
                pts = [r for r in rows if r["scene"] == scene and r["scheme"] == scheme and r["formulation"] == form
                       and r["reference"] == "0" and r["probe_error"] != ""]
                pts.sort(key=lambda r: float(r["dt"]))
                if not pts:
                    continue
                lbl = "%s + %s" % (scheme, form)
                ax[0].loglog([float(r["cpu_s"]) for r in pts], [float(r["probe_error"]) for r in pts], style, label=lbl)
                ax[1].loglog([float(r["dt"]) * 1e3 for r in pts], [float(r["impulse_error"]) for r in pts], style,
                             label=lbl)
                ax[2].loglog([float(r["dt"]) * 1e3 for r in pts], [max(float(r["drift"]), 1e-16) for r in pts], style,
                             label=lbl)
        ax[0].set(xlabel="CPU time of the run [s]", ylabel="probe displacement error at T [m]",
                  title="error against cost")
        ax[1].set(xlabel="time step [ms]", ylabel="contact impulse error at T (relative)", title="impulse")
        ax[2].set(xlabel="time step [ms]", ylabel="max |E + D - E0| / E0", title="energy error (1e-16 floor)")
        for a in ax:
            a.grid(True, which="both", alpha=0.3)
        ax[0].legend(fontsize=8)
        refs = [r for r in rows if r["scene"] == scene and r["reference"] == "1"]
        nref = max(int(r["N"]) for r in refs)
        t_end = nref * float(next(r["dt"] for r in refs if int(r["N"]) == nref))
        fig.suptitle("%s, T = %g s, reference gonzalez + persistence, N = %d" % (SCENE[scene][7], t_end, nref))
        fig.tight_layout()
        fig.savefig(os.path.join(OUT, "contact_precision_%s.png" % scene), dpi=90)
        plt.close(fig)


def main():
    if env("PLOT_ONLY"):
        plot()
        return
    print(sl.banner(STENTOR), flush=True)
    rows = []
    for scene in SCENES:
        print("== %s: reference gonzalez + persistence N = %d and %d" % (scene, NREF, NREF // 2), flush=True)
        rows += [measure(scene, "gonzalez", "persistence", NREF), measure(scene, "gonzalez", "persistence", NREF // 2)]
        for scheme in SCHEMES:
            for form in FORMS:
                for n in NS:
                    rows.append(measure(scene, scheme, form, n))
    os.makedirs(OUT, exist_ok=True)
    # rows of scenes not run this time are kept (studies run scene by scene)
    kept = [[r.get(k, "") for k in HEADER] for r in (sl.read_rows(CSV) if os.path.exists(CSV) else [])
            if r["scene"] not in SCENES]
    sl.write_csv(CSV, HEADER, kept + errors(rows))
    # one banner per scene (scenes are run at different times, on different executables)
    for scene in SCENES:
        with open(os.path.join(OUT, "contact_precision_machine_%s.txt" % scene), "w") as f:
            f.write(sl.banner(STENTOR) + "\n")
    plot()
    print("== wrote %s and contact_precision_<scene>.png" % CSV)


if __name__ == "__main__":
    main()

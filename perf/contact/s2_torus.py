"""Scene S2 in dynamics, Stentor against FEBio 4 on the same gmsh mesh (perf/contact/s2_torus.sh).

The hyperelastic torus of inputs/s2_torus.xml (inputs/torus.geo: R = 1, r = 0.25, axis tilted
30 degrees, lowest point 0.05 above the plane z = 0), thrown at v0 = (1, 0, -4) m/s at the rigid
plane z = 0, frictionless, no gravity, tet4. Material: Stentor's Ciarlet-Geymonat law of the
scene (C1 = 0.5e6, C2 = 0.005e6, D = 0.35e6 Pa, rho = 1000 kg/m^3), written for FEBio as its
generic "hyperelastic" law with the same W (perf/solve/feb.py, strain_energy): the same law in
both codes, not a small-strain match. N equal steps to the end time T.

  python3 perf/contact/s2_torus.py deck OUT.xml --geo NAME [--size H --steps N --end T]
      Stentor's deck: the S2 deck (Gonzalez energy-consistent midpoint, persistence condition
      against the analytic plane, exact active-set constraint, direct solver KLU2) with the
      fields displacement and velocity written after every step (the measurements read them).
  python3 perf/contact/s2_torus.py feb OUT.feb --geo GEO [--size H --steps N --end T
                                   --contact C --penalty P --atol A --maxaug M --rule R ...]
      Mesh GEO with the gmsh executable as Stentor meshes it (perf/solve/feb.py, run_gmsh, on
      a copy of GEO that ends with Stentor's size options, which Stentor sets after reading
      the file and so override the .geo's own) and write FEBio 4's input: the same nodes and tets (element type R, default
      TET4G4: 4 Gauss points, so FEBio's mass matrix is the consistent one, Stentor's; the
      stiffness of a tet4 is the same with 1 or 4 points, F being constant); the floor: a
      rigid body (material "rigid body", every dof fixed by rigid_fixed), a 10 x 10 hex8
      slab x, y in [-2, 2.5], z in [-0.1, 0]; contact C (default sliding-node-on-facet:
      primary = the torus surface's nodes, secondary = the slab's top facets, normal +z,
      node-to-facet as Stentor's nodal constraint; or sliding-elastic, facet-to-facet),
      augmented Lagrangian, auto_penalty with factor P, augmentation tolerance A, at most M
      augmentations per step; analysis DYNAMIC with FEBio's default integrator, written out:
      rhoi -2 (= "use alpha, beta, gamma"), alpha 1, beta 0.25, gamma 0.5, i.e. Newmark's
      trapezoidal rule (average acceleration), unconditionally stable, second order, no
      numerical damping; exactly energy conserving only for a linear system; full Newton,
      |R| <= 1e-10 |R0| (rtol 1e-20 on squared norms), dtol = etol = 0; the initial velocity
      as an "ic" of type velocity on every torus node. Also writes OUT's basename.json (the
      nodes, tets, surface facets and the problem data, for the measurements).
  python3 perf/contact/s2_torus.py same-mesh STENTOR.h5 OUT.json
      Stentor's HDF5 mesh against the .feb's nodes (count, largest coordinate difference).
  python3 perf/contact/s2_torus.py stentor RESULTS_DIR LOG OUT.json --geo GEO.json
  python3 perf/contact/s2_torus.py febio RUN_DIR LOG OUT.json --geo GEO.json
      Measure one run into OUT.json: per output time the fields' histories below, the
      code's own contact force, Newton iterations (FEBio: equilibrium iterations,
      augmentations included, and augmentations), cut-backs, wall time.
  python3 perf/contact/s2_torus.py table REF.json RUN.json ... --label L ... --row FMT
      One Markdown row per run (FMT, str.format), the differences against REF.
  python3 perf/contact/s2_torus.py curves RUN.json ... --label L ... --every K
      The force and energy histories of the runs side by side (Markdown): every K-th step
      from one step before the first run's contact to one after, and the last step.

The histories are computed from each code's nodal displacements u and velocities v at the
step ends with one formula for both (numpy; tet4 fields are linear per cell):
  M, p     mass and momentum: the consistent mass's row sums m_i = rho sum_e V_e / 4 over the
           cells at node i, p = sum m_i v_i (exact for the consistent mass of either code);
  x_c, v_c centre of mass: sum m_i (X_i + u_i) / M, p / M;
  K        kinetic energy with the consistent mass, K = sum_e rho V_e / 40 (sum_a |v_a|^2 +
           |sum_a v_a|^2) (M_e = rho V_e / 20 (I + 1 1^T) per component);
  W        strain energy sum_e V_e W(F_e), W of Ciarlet-Geymonat (feb.py's W_TEMPLATE);
  E        K + W; the drift max |E - E0| / E0 and E_end / E0 - 1 (no work is done on the
           torus by a fixed frictionless floor, so an exact scheme keeps E = E0);
  Fz_p     the step's mean contact force from the momentum balance, (p_z,n+1 - p_z,n) / dt
           (no other external force acts): what each integrator's own equations carry;
           Stentor's Gonzalez step has M (v_n+1 - v_n) / dt = the contact force of the step,
           FEBio's trapezoidal step = the mean of its end-of-step forces;
  gap      the smallest z of the surface nodes (< 0: penetration).
  F2       the two-step mean of Fz_p (consecutive steps), at their common step end: both
           codes' step forces alternate from step to step in contact, this mean does not.
Each code's own force: Stentor's history contact_floor_force_z (the active nodes' normal
forces of the step, = Fz_p for the Gonzalez step); FEBio's rigid_body_data Fz of the floor
(its reaction, + up: the contact force on the torus at the step's end).
Table columns: F own, the peak of the code's own force; F step, the peak of Fz_p; F 2-step
and t peak, the peak of F2 and its time; contact, from the start of the first to the end of
the last step with Fz_p > 0.1 % of its peak (the end: the lift-off of the rebound); v_c,z
after and z_c at the end time; dF, the largest difference of F2 against REF's (REF's
times, linear interpolation) over REF's peak F2; dz_c, the largest difference of z_c;
penetration, the smallest surface z over the run; E drift, max |E - E0| / E0; E(T)/E0 - 1.
"""
import argparse
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "solve"))
import feb as febio_tools  # noqa: E402  (perf/solve/feb.py: gmsh as Stentor, MSH 2.2 reader, W)

C1, C2, D, RHO = 0.5e6, 0.005e6, 0.35e6, 1000.0
V0 = (1.0, 0.0, -4.0)
SLAB = (-2.0, 2.5, -0.1, 10)  # x and y from, to; z bottom; cells per side


def p(name, typ, value):
    return '    <Parameter name="%s" type="%s" value="%s"/>' % (name, typ, value)


def write_deck(a):
    text = "\n".join([
        '<ParameterList name="stentor">',
        "  <!-- Scene S2 (inputs/s2_torus.xml) for the comparison with FEBio (perf/contact/s2_torus.py):",
        "       the torus thrown at the rigid plane z = 0, %d steps to t = %g s, Mesh->size %g. -->" % (
            a.steps, a.end, a.size),
        '  <ParameterList name="Problem">',
        p("title", "string", "S2: hyperelastic torus falling on a rigid plane"),
        p("analysis", "string", "dynamic"),
        "  </ParameterList>",
        '  <ParameterList name="Mesh">',
        p("file", "string", a.geo), p("size", "double", repr(a.size)),
        "  </ParameterList>",
        '  <ParameterList name="Materials">',
        '   <ParameterList name="rubber">',
        p("C1", "double", repr(C1)), p("C2", "double", repr(C2)), p("D", "double", repr(D)),
        p("density", "double", repr(RHO)), p("viscosity", "double", "0"),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Bodies">',
        '   <ParameterList name="torus">', p("material", "string", "rubber"), "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Initial Conditions">',
        p("velocity", "Array(double)", "{%r, %r, %r}" % V0),
        "  </ParameterList>",
        '  <ParameterList name="Time Integration">', p("scheme", "string", "gonzalez"), "  </ParameterList>",
        '  <ParameterList name="Contact">',
        '   <ParameterList name="floor">',
        p("slave", "string", "surface"), p("obstacle", "string", "plane"),
        p("point", "Array(double)", "{0.0, 0.0, 0.0}"), p("normal", "Array(double)", "{0.0, 0.0, 1.0}"),
        p("friction", "double", "0"), p("formulation", "string", a.formulation),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Stepping">',
        p("end time", "double", repr(a.end)), p("steps", "int", str(a.steps)),
        "  </ParameterList>",
        '  <ParameterList name="Newton">', p("max iterations", "int", "40"), "  </ParameterList>",
        '  <ParameterList name="Linear Solver">', p("method", "string", a.solver), "  </ParameterList>",
        '  <ParameterList name="Output">',
        p("basename", "string", "s2"), p("field list", "string", "displacement, velocity"),
        "  </ParameterList>",
        "</ParameterList>", ""])
    with open(a.out, "w") as f:
        f.write(text)


# ---------------------------------------------------------------- the .feb
def boundary_tris(tets, x):
    """The faces that belong to one tet only, oriented outward (away from the tet's fourth node)."""
    seen = {}
    for c in tets:
        for opp in range(4):
            f = [c[k] for k in range(4) if k != opp]
            key = tuple(sorted(f))
            if key in seen:
                seen[key] = None
            else:
                seen[key] = (f, c[opp])
    tris = []
    for v in seen.values():
        if v is None:
            continue
        f, o = v
        a, b, c = (x[i] for i in f)
        n = cross(sub(b, a), sub(c, a))
        if dot(n, sub(x[o], a)) > 0:
            f = [f[0], f[2], f[1]]
        tris.append(f)
    return tris


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def write_feb(a):
    import shutil
    import tempfile
    tmp = tempfile.mkdtemp(prefix="s2feb-")
    try:
        # Stentor sets its size options after gmsh has read the .geo (GmshReader.cpp, set_size_max),
        # so they override the .geo's own Mesh.MeshSize* lines (torus.geo has three); the gmsh
        # executable applies -clmax before the file, so a copy of the .geo ends with them.
        geo = os.path.join(tmp, os.path.basename(a.geo))
        with open(a.geo) as src, open(geo, "w") as dst:
            dst.write(src.read() + "\n// perf/contact/s2_torus.py: Stentor's size options\n"
                      "Mesh.MeshSizeMax = %r;\nMesh.MeshSizeMin = 0;\nMesh.MeshSizeFromPoints = 0;\n"
                      "Mesh.MeshSizeFromCurvature = 0;\n" % a.size)
        msh = os.path.join(tmp, "mesh.msh")
        febio_tools.run_gmsh(geo, a.size, 1, msh, a.gmsh)
        m = febio_tools.febio_mesh(msh, "torus")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    x, tets = m["x"], m["tets"]
    nb = len(x) - 1
    tris = boundary_tris(tets, x)
    surf_nodes = sorted({i for t in tris for i in t})
    if set(surf_nodes) != set(m["sets"]["surface"]):
        raise SystemExit("s2_torus.py: the tets' boundary is not the physical surface 'surface'")
    x0, x1, zb, n = SLAB
    bcoord, hexes, quads = febio_tools.rigid_slab(n, x0, x1, zb, nb + 1)
    fmt = febio_tools.fmt
    base = os.path.splitext(os.path.basename(a.out))[0]
    dt = a.end / a.steps
    dtol, etol, rtol = (0.0, 0.0, a.rtol) if a.tolerances == "strict" else (0.001, 0.01, 0.0)
    W = febio_tools.strain_energy(C1, C2, D)
    L = ['<?xml version="1.0" encoding="ISO-8859-1"?>',
         "<!-- Written by perf/contact/s2_torus.py from %s (Mesh->size %s): scene S2, the torus thrown at a"
         " rigid floor, %d steps to t = %s, %s -->" % (os.path.basename(a.geo), fmt(a.size), a.steps, fmt(a.end),
                                                      a.contact),
         '<febio_spec version="4.0">', '\t<Module type="solid"/>', "\t<Control>",
         "\t\t<analysis>DYNAMIC</analysis>", "\t\t<time_steps>%d</time_steps>" % a.steps,
         "\t\t<step_size>%s</step_size>" % fmt(dt), "\t\t<plot_level>PLOT_NEVER</plot_level>",
         "\t\t<output_level>OUTPUT_MAJOR_ITRS</output_level>",
         '\t\t<time_stepper type="default">', "\t\t\t<max_retries>5</max_retries>", "\t\t\t<opt_iter>1000</opt_iter>",
         "\t\t\t<dtmin>0</dtmin>", "\t\t\t<dtmax>%s</dtmax>" % fmt(dt), "\t\t\t<aggressiveness>0</aggressiveness>",
         "\t\t\t<cutback>0.5</cutback>", "\t\t\t<dtforce>0</dtforce>", "\t\t</time_stepper>",
         '\t\t<solver type="solid">', "\t\t\t<symmetric_stiffness>%s</symmetric_stiffness>" % a.symmetric,
         "\t\t\t<max_refs>%d</max_refs>" % a.max_refs,
         "\t\t\t<dtol>%g</dtol>" % dtol, "\t\t\t<etol>%g</etol>" % etol, "\t\t\t<rtol>%g</rtol>" % rtol,
         '\t\t\t<qn_method type="full Newton"/>',
         "\t\t\t<rhoi>-2</rhoi>", "\t\t\t<alpha>1</alpha>", "\t\t\t<beta>0.25</beta>", "\t\t\t<gamma>0.5</gamma>",
         "\t\t</solver>", "\t</Control>",
         "\t<Material>", '\t\t<material id="1" name="rubber" type="hyperelastic">',
         "\t\t\t<density>%s</density>" % fmt(RHO), "\t\t\t<W>%s</W>" % W, "\t\t</material>",
         '\t\t<material id="2" name="floor" type="rigid body">', "\t\t\t<density>%s</density>" % fmt(RHO),
         "\t\t\t<E>1</E>", "\t\t\t<v>0</v>", "\t\t</material>", "\t</Material>",
         "\t<Mesh>", '\t\t<Nodes name="all_nodes">']
    L += ['\t\t\t<node id="%d">%s,%s,%s</node>' % ((k,) + tuple(fmt(c) for c in x[k])) for k in range(1, nb + 1)]
    L += ['\t\t\t<node id="%d">%s,%s,%s</node>' % ((v,) + tuple(fmt(c) for c in bcoord[v])) for v in sorted(bcoord)]
    L += ["\t\t</Nodes>", '\t\t<Elements type="%s" name="torus">' % a.rule]
    L += ['\t\t\t<elem id="%d">%s</elem>' % (k + 1, ",".join(map(str, c))) for k, c in enumerate(tets)]
    L += ["\t\t</Elements>", '\t\t<Elements type="hex8" name="floor">']
    L += ['\t\t\t<elem id="%d">%s</elem>' % (len(tets) + k + 1, ",".join(map(str, c))) for k, c in enumerate(hexes)]
    L += ["\t\t</Elements>", '\t\t<NodeSet name="torus_all">',
          "\t\t\t" + febio_tools.ids_text(list(range(1, nb + 1)), "\t\t\t"), "\t\t</NodeSet>"]
    L += ['\t\t<Surface name="torus_surface">']
    L += ['\t\t\t<tri3 id="%d">%s</tri3>' % (k + 1, ",".join(map(str, c))) for k, c in enumerate(tris)]
    L += ["\t\t</Surface>", '\t\t<Surface name="floor_top">']
    L += ['\t\t\t<quad4 id="%d">%s</quad4>' % (k + 1, ",".join(map(str, c))) for k, c in enumerate(quads)]
    L += ["\t\t</Surface>", '\t\t<SurfacePair name="floor_contact">', "\t\t\t<primary>torus_surface</primary>",
          "\t\t\t<secondary>floor_top</secondary>", "\t\t</SurfacePair>", "\t</Mesh>",
          "\t<MeshDomains>", '\t\t<SolidDomain name="torus" mat="rubber"/>', '\t\t<SolidDomain name="floor" mat="floor"/>',
          "\t</MeshDomains>",
          "\t<Initial>", '\t\t<ic name="v0" node_set="torus_all" type="velocity">',
          "\t\t\t<value>%s,%s,%s</value>" % tuple(fmt(v) for v in V0), "\t\t</ic>", "\t</Initial>",
          "\t<Rigid>", '\t\t<rigid_bc name="floor_fixed" type="rigid_fixed">', "\t\t\t<rb>floor</rb>"]
    L += ["\t\t\t<%s_dof>1</%s_dof>" % (d, d) for d in ("Rx", "Ry", "Rz", "Ru", "Rv", "Rw")]
    L += ["\t\t</rigid_bc>", "\t</Rigid>",
          "\t<Contact>", '\t\t<contact type="%s" surface_pair="floor_contact">' % a.contact,
          "\t\t\t<laugon>AUGLAG</laugon>", "\t\t\t<tolerance>%g</tolerance>" % a.atol,
          "\t\t\t<gaptol>0</gaptol>", "\t\t\t<penalty>%g</penalty>" % a.penalty,
          "\t\t\t<auto_penalty>1</auto_penalty>", "\t\t\t<two_pass>0</two_pass>",
          "\t\t\t<minaug>0</minaug>", "\t\t\t<maxaug>%d</maxaug>" % a.maxaug,
          "\t\t\t<search_tol>0.01</search_tol>", "\t\t\t<fric_coeff>0</fric_coeff>"]
    if a.contact == "sliding-elastic":
        L += ["\t\t\t<symmetric_stiffness>%d</symmetric_stiffness>" % (a.symmetric == "symmetric")]
    L += ["\t\t</contact>", "\t</Contact>",
          "\t<Output>", "\t\t<logfile>",
          '\t\t\t<node_data data="ux;uy;uz;vx;vy;vz" node_set="torus_all" file="%s.uv.txt" delim=","/>' % base,
          '\t\t\t<rigid_body_data data="Fx;Fy;Fz" file="%s.rb.txt" delim=",">2</rigid_body_data>' % base,
          "\t\t</logfile>", "\t</Output>", "</febio_spec>", ""]
    with open(a.out, "w") as f:
        f.write("\n".join(L))
    with open(os.path.splitext(a.out)[0] + ".json", "w") as f:
        json.dump({"x": [list(v) for v in x[1:]], "tets": tets, "tris": tris, "nodes": nb, "cells": len(tets),
                   "C1": C1, "C2": C2, "D": D, "rho": RHO, "v0": V0, "dt": dt, "steps": a.steps, "end": a.end,
                   "size": a.size, "contact": a.contact}, f)
    print("s2_torus.py: %s: %d nodes, %d tet4 (%s), %d surface facets; floor %d hex8 (rigid); %s" % (
        a.out, nb, len(tets), a.rule, len(tris), len(hexes), a.contact))


# ---------------------------------------------------------------- measurements
class Mesh:
    def __init__(self, geo):
        import numpy as np
        self.np = np
        self.X = np.array(geo["x"])
        self.T = np.array(geo["tets"]) - 1
        self.S = np.array(sorted({i for t in geo["tris"] for i in t})) - 1
        self.c1, self.c2, self.d, self.rho = geo["C1"], geo["C2"], geo["D"], geo["rho"]
        e = self.X[self.T]
        self.Dm = np.stack([e[:, 1] - e[:, 0], e[:, 2] - e[:, 0], e[:, 3] - e[:, 0]], axis=2)  # columns
        self.V = np.linalg.det(self.Dm) / 6.0
        self.Dinv = np.linalg.inv(self.Dm)
        self.m = np.zeros(len(self.X))
        for k in range(4):
            np.add.at(self.m, self.T[:, k], self.rho * self.V / 4)
        self.M = self.m.sum()

    def state(self, u, v):
        np = self.np
        u, v = np.asarray(u), np.asarray(v)
        xc = (self.m[:, None] * (self.X + u)).sum(0) / self.M
        pm = (self.m[:, None] * v).sum(0)
        ve = v[self.T]
        K = (self.rho * self.V / 40 * ((ve ** 2).sum((1, 2)) + (ve.sum(1) ** 2).sum(1))).sum()
        x = self.X + u
        e = x[self.T]
        Ds = np.stack([e[:, 1] - e[:, 0], e[:, 2] - e[:, 0], e[:, 3] - e[:, 0]], axis=2)
        F = Ds @ self.Dinv
        C = np.transpose(F, (0, 2, 1)) @ F
        I1 = np.trace(C, axis1=1, axis2=2)
        I2 = 0.5 * (I1 ** 2 - np.einsum("eij,eji->e", C, C))
        J = np.linalg.det(F)
        Kb = self.c1 + 2 * self.c2 + self.d
        Wd = self.c1 * (I1 - 3) + self.c2 * (I2 - 3) + self.d * (J ** 2 - 1) - 2 * Kb * np.log(J)
        W = (self.V * Wd).sum()
        zmin = float(x[self.S, 2].min())
        return {"xc": xc.tolist(), "p": pm.tolist(), "K": float(K), "W": float(W), "zmin": zmin}


def histories(mesh, times, U, V):
    out = {"t": [], "xc": [], "vc": [], "p": [], "K": [], "W": [], "E": [], "zmin": []}
    for t, u, v in zip(times, U, V):
        s = mesh.state(u, v)
        out["t"].append(t)
        out["xc"].append(s["xc"])
        out["p"].append(s["p"])
        out["vc"].append([q / mesh.M for q in s["p"]])
        out["K"].append(s["K"])
        out["W"].append(s["W"])
        out["E"].append(s["K"] + s["W"])
        out["zmin"].append(s["zmin"])
    out["M"] = float(mesh.M)
    # the step's mean contact force from the momentum balance, at the step's mid-time
    out["Fp"] = [[0.5 * (out["t"][k] + out["t"][k - 1]),
                  (out["p"][k][2] - out["p"][k - 1][2]) / (out["t"][k] - out["t"][k - 1])]
                 for k in range(1, len(out["t"]))]
    return out


def measure_stentor(res, log, out, geo_json):
    import h5py
    f = {"code": "Stentor", "status": "failed"}
    text = febio_tools.ESCAPES.sub("", febio_tools.read_text(log))
    m = re.search(r"Summary: (\d+) steps, (\d+) cut-backs, (\d+) Newton iterations", text)
    t = febio_tools.time_line(text)
    f["wall"] = float(t[0]) if t else None
    mt = re.search(r"^\s+mesh\s+([\d.]+) s", text, re.M)
    f["mesh_s"] = float(mt.group(1)) if mt else None
    if m:
        f["steps"], f["cutbacks"], f["newton"] = int(m.group(1)), int(m.group(2)), int(m.group(3))
    geo = json.load(open(geo_json))
    h5 = os.path.join(res, "s2.h5")
    if not (m and os.path.exists(h5)):
        json.dump(f, open(out, "w"))
        return
    with h5py.File(h5, "r") as h:
        steps = sorted((k for k in h.keys() if k.startswith("step_")), key=lambda s: int(s.split("_")[1]))
        times = [float(h[s].attrs["time"]) for s in steps]
        U = [h[s]["displacement"][()] for s in steps]
        V = [h[s]["velocity"][()] for s in steps]
    f.update(histories(Mesh(geo), times, U, V))
    hist = febio_tools.read_text(os.path.join(res, "s2_history.csv")).splitlines()
    head = hist[0].split(",")
    rows = [dict(zip(head, l.split(","))) for l in hist[1:]]
    f["Fown"] = [[float(r["time"]), float(r["contact_floor_force_z"])] for r in rows]
    f["active_max"] = max(int(r["contact_floor_active"]) for r in rows)
    en = febio_tools.read_text(os.path.join(res, "s2_energy.csv")).splitlines()
    head = en[0].split(",")
    rows = [dict(zip(head, l.split(","))) for l in en[1:]]
    f["Eown"] = [[float(r["time"]), float(r["total"])] for r in rows]
    f["status"] = "yes" if abs(times[-1] - geo["end"]) < 1e-9 * geo["end"] else "no"
    json.dump(f, open(out, "w"))


def measure_febio(run, log, out, geo_json):
    f = {"code": "FEBio", "status": "failed"}
    feb = next(os.path.join(run, n) for n in os.listdir(run) if n.endswith(".feb"))
    base = os.path.splitext(feb)[0]
    geo = json.load(open(geo_json))
    flog = febio_tools.read_text(base + ".log")
    screen = febio_tools.ESCAPES.sub("", febio_tools.read_text(log))
    both = screen + "\n" + flog
    normal = "N O R M A L   T E R M I N A T I O N" in both
    its = re.findall(r"Total number of equilibrium iterations \.+ : (\d+)", flog or screen)
    t = febio_tools.time_line(screen)
    f["wall"] = float(t[0]) if t else None
    f["aug"] = len(re.findall(r"sliding interface # \d+", flog or screen))
    f["cutbacks"] = len(re.findall(r"Retrying time step", flog or screen))
    if its and normal:
        f["newton"] = int(its[-1])
    recs = febio_tools.records(base + ".uv.txt")
    if not recs:
        json.dump(f, open(out, "w"))
        return
    n = geo["nodes"]
    times, U, V = [0.0], [[[0.0] * 3] * n], [[list(geo["v0"])] * n]
    for tm, rows in recs:
        if tm is None or tm <= 0:
            continue
        times.append(tm)
        U.append([rows[i][0:3] for i in range(1, n + 1)])
        V.append([rows[i][3:6] for i in range(1, n + 1)])
    f.update(histories(Mesh(geo), times, U, V))
    # the floor's reaction (rigid_body_data Fz: + up), i.e. the contact force on the torus, at the step ends
    f["Fown"] = [[tm, rows[2][2]] for tm, rows in febio_tools.records(base + ".rb.txt") if tm and 2 in rows]
    f["status"] = "yes" if normal and abs(times[-1] - geo["end"]) < 1e-9 * geo["end"] else "no"
    json.dump(f, open(out, "w"))


def two_step(Fp):
    """The mean of consecutive step forces, at the common step end: smooths the step-to-step
    alternation that both codes show in contact (see the docs)."""
    return [[0.5 * (Fp[k][0] + Fp[k + 1][0]), 0.5 * (Fp[k][1] + Fp[k + 1][1])] for k in range(len(Fp) - 1)]


def summary(f):
    """The scalar results of one run's histories."""
    s = {}
    Fp = f["Fp"]
    k = max(range(len(Fp)), key=lambda i: Fp[i][1])
    s["Fpeak"], s["tpeak"] = Fp[k][1], Fp[k][0]
    F2 = two_step(Fp)
    k = max(range(len(F2)), key=lambda i: F2[i][1])
    s["F2peak"], s["t2peak"] = F2[k][1], F2[k][0]
    on = [tm for tm, F in Fp if F > 1e-3 * s["Fpeak"]]
    dt = f["t"][1] - f["t"][0]
    s["t_on"], s["t_off"] = on[0] - dt / 2, on[-1] + dt / 2  # the steps' starts and ends
    s["impulse"] = f["p"][-1][2] - f["p"][0][2]
    E0 = f["E"][0]
    s["Edrift"] = max(abs(e - E0) for e in f["E"]) / E0
    s["Eend"] = f["E"][-1] / E0 - 1
    s["vz_end"], s["vx_end"], s["zc_end"] = f["vc"][-1][2], f["vc"][-1][0], f["xc"][-1][2]
    s["gap"] = min(f["zmin"])
    if f.get("Fown"):
        s["Fown_peak"] = max(F for tm, F in f["Fown"])
    return s


def interp(ts, ys, t):
    if t <= ts[0]:
        return ys[0]
    for i in range(1, len(ts)):
        if t <= ts[i] + 1e-12:
            w = (t - ts[i - 1]) / (ts[i] - ts[i - 1])
            return ys[i - 1] * (1 - w) + ys[i] * w
    return ys[-1]


def table(a):
    ref = json.load(open(a.ref))
    rs = summary(ref) if ref.get("status") == "yes" else None
    for path, label in zip(a.runs, a.label):
        f = json.load(open(path))
        naug = str(f.get("newton", "failed"))
        if f.get("aug") is not None and "newton" in f:
            naug += " (%d)" % f["aug"]
        if f.get("cutbacks"):
            naug += ", %d cut-backs" % f["cutbacks"]
        row = {k: "?" for k in ("Fown", "Fpeak", "F2peak", "tpeak", "on", "vz", "zc", "dF", "dz", "gap", "Ed", "Ee")}
        row.update({"label": label, "naug": naug, "wall": "%.2f" % f["wall"] if f.get("wall") else "?"})
        if f.get("status") == "yes":
            s = summary(f)
            row["Fown"] = "%.1f" % (s["Fown_peak"] / 1e3) if "Fown_peak" in s else "-"
            row["Fpeak"] = "%.1f" % (s["Fpeak"] / 1e3)
            row["F2peak"] = "%.1f" % (s["F2peak"] / 1e3)
            row["tpeak"] = "%.0f" % (1e3 * s["t2peak"])
            row["on"] = "%.0f–%.0f" % (1e3 * s["t_on"], 1e3 * s["t_off"])
            row["vz"] = "%.4f" % s["vz_end"]
            row["zc"] = "%.5f" % s["zc_end"]
            row["gap"] = "%.1e" % s["gap"]
            row["Ed"] = "%.1e" % s["Edrift"]
            row["Ee"] = "%+.1e" % s["Eend"]
            if rs:
                # the two-step mean forces on the reference's times (interpolated), against its peak
                F2, R2 = two_step(f["Fp"]), two_step(ref["Fp"])
                ts, Fs = [q[0] for q in F2], [q[1] for q in F2]
                row["dF"] = "%.1e" % (max(abs(interp(ts, Fs, tm) - F) for tm, F in R2) / rs["F2peak"])
                zs = [x[2] for x in f["xc"]]
                row["dz"] = "%.1e" % max(abs(interp(f["t"], zs, tm) - x[2]) for tm, x in zip(ref["t"], ref["xc"]))
        print(a.row.format(**row))


def curves(a):
    """F step and E/E0 - 1 of each run at every K-th step from one step before the reference's
    first contact step to one after its last, and at the end."""
    runs = [json.load(open(p)) for p in a.runs]
    print("| t [ms] | " + " | ".join("%s: F step [kN]" % l for l in a.label) + " | "
          + " | ".join("%s: E/E0 - 1" % l for l in a.label) + " |")
    print("|---" * (1 + 2 * len(runs)) + "|")
    ref = runs[0]
    s = summary(ref)
    dt = ref["t"][1] - ref["t"][0]
    ks = [k for k, (tm, F) in enumerate(ref["Fp"]) if s["t_on"] - 1.5 * dt <= tm <= s["t_off"] + 1.5 * dt][::a.every]
    ks += [len(ref["Fp"]) - 1] if ks[-1] != len(ref["Fp"]) - 1 else []
    for k in ks:
        tm = ref["Fp"][k][0]
        te = ref["t"][k + 1]
        Fs = ["%.1f" % (interp([q[0] for q in r["Fp"]], [q[1] for q in r["Fp"]], tm) / 1e3) for r in runs]
        Es = ["%+.1e" % (interp(r["t"], r["E"], te) / r["E"][0] - 1) for r in runs]
        print("| %.0f | %s | %s |" % (1e3 * tm, " | ".join(Fs), " | ".join(Es)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sp = ap.add_subparsers(dest="cmd")
    sp.required = True
    problem = argparse.ArgumentParser(add_help=False)
    problem.add_argument("out")
    problem.add_argument("--geo", required=True)
    problem.add_argument("--size", type=float, default=0.12)
    problem.add_argument("--steps", type=int, default=40)
    problem.add_argument("--end", type=float, default=0.08)
    d = sp.add_parser("deck", parents=[problem])
    d.add_argument("--solver", default="direct", choices=["direct", "gmres"])
    d.add_argument("--formulation", default="persistence", choices=["persistence", "gap"])
    fb = sp.add_parser("feb", parents=[problem])
    fb.add_argument("--contact", default="sliding-node-on-facet",
                    choices=["sliding-node-on-facet", "sliding-facet-on-facet", "sliding-elastic"])
    fb.add_argument("--penalty", type=float, default=100.0)
    fb.add_argument("--atol", type=float, default=1e-2)
    fb.add_argument("--maxaug", type=int, default=50)
    fb.add_argument("--rtol", type=float, default=1e-20)
    fb.add_argument("--tolerances", default="strict", choices=["strict", "default"])
    fb.add_argument("--max-refs", type=int, default=25)
    fb.add_argument("--rule", default="TET4G4", choices=["TET4G4", "tet4"])
    fb.add_argument("--symmetric", default="non-symmetric", choices=["symmetric", "non-symmetric"])
    fb.add_argument("--gmsh", default=os.environ.get("GMSH", "gmsh"))
    for name in ("stentor", "febio"):
        m = sp.add_parser(name)
        m.add_argument("dir")
        m.add_argument("log")
        m.add_argument("out")
        m.add_argument("--geo", required=True)
    t = sp.add_parser("table")
    t.add_argument("ref")
    t.add_argument("runs", nargs="+")
    t.add_argument("--label", action="append", default=[])
    t.add_argument("--row", required=True)
    c = sp.add_parser("curves")
    c.add_argument("runs", nargs="+")
    c.add_argument("--label", action="append", default=[])
    c.add_argument("--every", type=int, default=1)
    sm = sp.add_parser("same-mesh")
    sm.add_argument("h5")
    sm.add_argument("geo")
    a = ap.parse_args()
    if a.cmd == "deck":
        write_deck(a)
    elif a.cmd == "feb":
        write_feb(a)
    elif a.cmd == "stentor":
        measure_stentor(a.dir, a.log, a.out, a.geo)
    elif a.cmd == "febio":
        measure_febio(a.dir, a.log, a.out, a.geo)
    elif a.cmd == "table":
        table(a)
    elif a.cmd == "curves":
        curves(a)
    else:
        print(febio_tools.same_mesh(a.h5, a.geo, "tet4", " m"))


if __name__ == "__main__":
    main()

"""The S6 stent sector expanded by a cylinder, Stentor against FEBio 4 on the same hex8 mesh
(perf/contact/stent_sector.sh).

The one-strut sector of the S6 ring (inputs/s6_ring_sector.xml: 8 crowns, OD 3 mm as cut,
struts 0.1 x 0.1 mm, 3 x 3 hex8 through the strut, 0 <= theta <= 22.5 deg), ELASTIC
(neo-Hookean W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, E = 196000 MPa, nu = 0.3: the
same W in both codes), standard hex8 (Stentor `element technology` = full, FEBio's hex8 with
its default 2 x 2 x 2 Gauss rule), expanded as cut (no crimp) by a cylinder against `inner`
whose radius grows linearly from R0 to R0 + dR in N equal static steps. Frictionless.
Symmetry: y = 0 held in y, the plane theta = 22.5 deg held along its normal, the `anchor`
node held in z.

  python3 perf/contact/stent_sector.py deck OUT.xml [--r0 R0 --dr DR --steps N --solver S]
      Stentor's deck (Mesh->write mesh = true: Stentor writes the generated mesh as
      <basename>_mesh.msh, the input of `feb`). Contact: the analytic cylinder obstacle
      against `inner` (exact active-set constraint).
  python3 perf/contact/stent_sector.py feb OUT.feb --msh MESH.msh [--r0 --dr --steps
                                       --contact C --penalty P --atol A --maxaug M ...]
      FEBio 4's input on the nodes and hex8 of MESH.msh (Stentor's numbering):
      * y = 0: zero displacement y on `symmetry_y`'s nodes; `anchor`: zero z;
      * theta = 22.5 deg: one exact linear constraint per node of `symmetry_sector`
        (Boundary, type "linear constraint": parent u_y = tan(22.5 deg) x child u_x, i.e.
        n.u = 0; FEBio eliminates the parent dof, no penalty);
      * the balloon: a thin tube of hex8 (radii R0 - 0.02 .. R0, theta -2 .. 24.5 deg in NT
        cells, one cell axially, longer than the stent) of a neo-Hookean with E = 1e-6
        (its own forces: about 1e-8 N), every node prescribed: u = (X, Y, 0) dR/R0 ramped
        linearly (the tube scaled radially: its outer facets' vertices on the cylinder of
        radius R0 + t dR; chord sag R (dtheta)^2 / 8 = 7e-7 mm at NT = 256);
      * contact: C = sliding-node-on-facet (the default: primary = `inner`'s nodes, secondary
        = the tube's outer facets, node-to-facet as Stentor's nodal constraint),
        sliding-facet-on-facet or sliding-elastic (primary = `inner`'s facets); AUGLAG,
        auto_penalty with factor P, augmentation tolerance A, at most M augmentations;
      * full Newton, |R| <= 1e-10 |R0| (rtol 1e-20 on squared norms), dtol = etol = 0
        (--tolerances strict, the default), or FEBio's defaults (dtol 0.001, etol 0.01, no
        residual test: --tolerances default).
      Also writes OUT's basename.json: the nodes, the outer / balloon node sets, R0, dR.
  python3 perf/contact/stent_sector.py stentor RESULTS_DIR LOG OUT.json
  python3 perf/contact/stent_sector.py febio RUN_DIR LOG OUT.json
      Measure one run into OUT.json: per step the balloon radius and the radial contact
      force of the sector (Stentor: the history's contact_balloon_normal_force, the sum of
      the active nodes' normal forces; FEBio: the radial part of the reactions of the
      tube's outer nodes, sum (Rx X + Ry Y) / sqrt(X^2 + Y^2)), the final displacements,
      Newton iterations (FEBio: equilibrium iterations, augmentations included; and the
      augmentations), wall time.
  python3 perf/contact/stent_sector.py table REF.json RUN.json ... --label ...
      One Markdown row per run against REF (Stentor, 1 core): F at the end, its relative
      difference, the largest relative difference of F over the steps with F > 1 % of the
      final F, the outer diameter (mean and largest of 2 r over `outer`'s nodes, r the
      current distance from the axis; the plain mean over the sector's outer nodes, the
      same formula for both codes), and the largest nodal displacement difference against
      REF (same numbering).
  python3 perf/contact/stent_sector.py same-mesh STENTOR.h5 OUT.json
      Stentor's HDF5 mesh against the .feb's nodes (count, largest coordinate difference).
"""
import argparse
import json
import math
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "solve"))
import feb as febio_tools  # noqa: E402  (perf/solve/feb.py: MSH 2.2 reader, number format)

E, NU = 196000.0, 0.3
THETA = math.pi / 8  # 22.5 deg: 8 crowns, one strut
febio_tools.GMSH_NODES.update({3: 4, 5: 8})  # the reader of feb.py, extended to quad4 and hex8


def p(name, typ, value):
    return '    <Parameter name="%s" type="%s" value="%s"/>' % (name, typ, value)


def write_deck(a):
    text = "\n".join([
        '<ParameterList name="stentor">',
        "  <!-- The S6 one-strut sector (inputs/s6_ring_sector.xml), elastic (neo-Hookean), full hex8,",
        "       expanded as cut by a rigid cylinder against `inner`, radius %g -> %g in %d static steps" % (
            a.r0, a.r0 + a.dr, a.steps),
        "       (perf/contact/stent_sector.py). -->",
        '  <ParameterList name="Problem">',
        p("title", "string", "S6 sector, elastic, expanded by a cylinder"),
        p("analysis", "string", "static"), p("units", "string", "mm-N-s"),
        "  </ParameterList>",
        '  <ParameterList name="Mesh">',
        p("generator", "string", "stent"), p("write mesh", "bool", "true"),
        '   <ParameterList name="Stent">',
        p("rings", "int", "1"), p("crowns", "int", "8"), p("outer diameter", "double", "3.0"),
        p("thickness", "double", "0.1"), p("strut width", "double", "0.1"), p("ring length", "double", "1.0"),
        p("elements through width", "int", str(a.nw)), p("elements through thickness", "int", str(a.nt)),
        p("sector", "string", "period"),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Materials">',
        '   <ParameterList name="steel">',
        p("model", "string", "neo-Hookean"), p("E", "double", repr(E)), p("nu", "double", repr(NU)),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Bodies">',
        '   <ParameterList name="stent">',
        p("material", "string", "steel"), p("element technology", "string", "full"),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Boundary Conditions">',
        '   <ParameterList name="sym_sector">',
        p("type", "string", "Dirichlet"), p("boundary", "string", "symmetry_sector"),
        p("components", "string", "normal"),
        "   </ParameterList>",
        '   <ParameterList name="sym_y">',
        p("type", "string", "Dirichlet"), p("boundary", "string", "symmetry_y"), p("components", "string", "y"),
        "   </ParameterList>",
        '   <ParameterList name="axial">',
        p("type", "string", "Dirichlet"), p("boundary", "string", "anchor"), p("components", "string", "z"),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Contact">',
        '   <ParameterList name="balloon">',
        p("slave", "string", "inner"), p("obstacle", "string", "cylinder"),
        p("point", "Array(double)", "{0, 0, 0}"), p("axis", "Array(double)", "{0, 0, 1}"),
        p("radius", "double", repr(a.r0)), p("radius change", "double", repr(a.dr)),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Stepping">',
        p("end time", "double", "1.0"), p("steps", "int", str(a.steps)),
        "  </ParameterList>",
        '  <ParameterList name="Linear Solver">', p("method", "string", a.solver), "  </ParameterList>",
        '  <ParameterList name="Output">',
        p("basename", "string", "sector"),
        p("field list", "string", "displacement, contact_status, contact_lambda_normal"),
        "  </ParameterList>",
        "</ParameterList>", ""])
    with open(a.out, "w") as f:
        f.write(text)


def hex_volume_sign(x, c):
    """Sign of the hex8's Jacobian at its centre (gmsh = FEBio node order)."""
    P = [x[i] for i in c]
    d = [[0.0] * 3 for _ in range(3)]
    # derivatives of the trilinear map at the centre
    sg = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
    for k in range(8):
        for j in range(3):
            for i in range(3):
                d[i][j] += sg[k][j] / 8.0 * P[k][i]
    return (d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0])
            + d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]))


def read_mesh(msh):
    nodes, names, elems = febio_tools.read_msh22(msh)
    n = len(nodes)
    if sorted(nodes) != list(range(1, n + 1)):
        raise SystemExit("stent_sector.py: %s: nodes not numbered 1..%d" % (msh, n))
    x = [None] + [nodes[t] for t in range(1, n + 1)]
    groups = {}
    for typ, phys, conn in elems:
        groups.setdefault(names.get(phys, "tag%d" % phys), []).append((typ, conn))
    hexes = []
    for typ, conn in groups["stent"]:
        if typ != 5:
            raise SystemExit("stent_sector.py: the stent must be hex8 (gmsh type 5), got %d" % typ)
        if hex_volume_sign(x, conn) <= 0:
            raise SystemExit("stent_sector.py: a hex8 with a negative Jacobian: %s" % conn)
        hexes.append(list(conn))
    # `inner`'s quads oriented away from the stent (towards the axis): FEBio's contact normals
    quads = []
    for typ, conn in groups["inner"]:
        c = list(conn)
        e1 = [x[c[1]][i] - x[c[0]][i] for i in range(3)]
        e2 = [x[c[3]][i] - x[c[0]][i] for i in range(3)]
        nrm = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        mid = [sum(x[k][i] for k in c) / 4 for i in range(3)]
        if nrm[0] * mid[0] + nrm[1] * mid[1] > 0:  # outward radial: flip to point to the axis
            c = [c[0], c[3], c[2], c[1]]
        quads.append(c)
    sets = {name: sorted({v for typ, conn in groups[name] for v in conn})
            for name in ("inner", "outer", "symmetry_y", "symmetry_sector", "anchor")}
    return {"x": x, "hexes": hexes, "inner_quads": quads, "sets": sets}


def write_feb(a):
    m = read_mesh(a.msh)
    x, hexes, sets = m["x"], m["hexes"], m["sets"]
    ns = len(x) - 1
    fmt = febio_tools.fmt
    # the balloon tube
    zs = [x[k][2] for k in range(1, ns + 1)]
    z0, z1 = min(zs) - 0.1, max(zs) + 0.1
    t0, t1 = math.radians(-2.0), THETA + math.radians(2.0)
    r_in, r_out = a.r0 - 0.02, a.r0
    bid = {}
    bx = {}
    for k, z in enumerate((z0, z1)):
        for j, r in enumerate((r_in, r_out)):
            for i in range(a.nballoon + 1):
                t = t0 + (t1 - t0) * i / a.nballoon
                v = ns + 1 + len(bid)
                bid[i, j, k] = v
                bx[v] = (r * math.cos(t), r * math.sin(t), z)
    bhex = []
    for i in range(a.nballoon):
        c = [bid[i, 0, 0], bid[i + 1, 0, 0], bid[i + 1, 1, 0], bid[i, 1, 0],
             bid[i, 0, 1], bid[i + 1, 0, 1], bid[i + 1, 1, 1], bid[i, 1, 1]]
        bhex.append(c)
    allx = list(x) + [bx[v] for v in sorted(bx)]
    if hex_volume_sign(allx, bhex[0]) <= 0:
        bhex = [[c[0], c[3], c[2], c[1], c[4], c[7], c[6], c[5]] for c in bhex]
    # outer facets of the tube (r = r_out), normal outward (towards the stent)
    bquads = []
    for i in range(a.nballoon):
        c = [bid[i, 1, 0], bid[i + 1, 1, 0], bid[i + 1, 1, 1], bid[i, 1, 1]]
        e1 = [allx[c[1]][q] - allx[c[0]][q] for q in range(3)]
        e2 = [allx[c[3]][q] - allx[c[0]][q] for q in range(3)]
        nrm = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        mid = [sum(allx[k][q] for k in c) / 4 for q in range(3)]
        if nrm[0] * mid[0] + nrm[1] * mid[1] < 0:
            c = [c[0], c[3], c[2], c[1]]
        bquads.append(c)
    b_outer = sorted({v for (i, j, k), v in bid.items() if j == 1})
    b_all = sorted(bx)
    dt = 1.0 / a.steps
    k = a.dr / a.r0
    # strict: the residual test alone, |R| <= 1e-10 |R0| (Stentor's static test); default:
    # FEBio's own (dtol 0.001, etol 0.01, no residual test)
    dtol, etol, rtol = (0.0, 0.0, a.rtol) if a.tolerances == "strict" else (0.001, 0.01, 0.0)
    base = os.path.splitext(os.path.basename(a.out))[0]
    tan = math.tan(THETA)
    L = ['<?xml version="1.0" encoding="ISO-8859-1"?>',
         "<!-- Written by perf/contact/stent_sector.py from %s: the S6 sector (neo-Hookean E=%s nu=%s, hex8)"
         " expanded by a tube whose radius grows %s -> %s, %s -->" % (os.path.basename(a.msh), fmt(E), fmt(NU),
                                                                   fmt(a.r0), fmt(a.r0 + a.dr), a.contact),
         '<febio_spec version="4.0">', '\t<Module type="solid"/>', "\t<Control>",
         "\t\t<analysis>STATIC</analysis>", "\t\t<time_steps>%d</time_steps>" % a.steps,
         "\t\t<step_size>%s</step_size>" % fmt(dt), "\t\t<plot_level>PLOT_NEVER</plot_level>",
         "\t\t<output_level>OUTPUT_MAJOR_ITRS</output_level>",
         '\t\t<time_stepper type="default">', "\t\t\t<max_retries>5</max_retries>", "\t\t\t<opt_iter>1000</opt_iter>",
         "\t\t\t<dtmin>0</dtmin>", "\t\t\t<dtmax>%s</dtmax>" % fmt(dt), "\t\t\t<aggressiveness>0</aggressiveness>",
         "\t\t\t<cutback>0.5</cutback>", "\t\t\t<dtforce>0</dtforce>", "\t\t</time_stepper>",
         '\t\t<solver type="solid">', "\t\t\t<symmetric_stiffness>%s</symmetric_stiffness>" % a.symmetric,
         "\t\t\t<max_refs>%d</max_refs>" % a.max_refs,
         "\t\t\t<dtol>%g</dtol>" % dtol, "\t\t\t<etol>%g</etol>" % etol, "\t\t\t<rtol>%g</rtol>" % rtol,
         '\t\t\t<qn_method type="full Newton"/>', "\t\t</solver>", "\t</Control>",
         "\t<Material>",
         '\t\t<material id="1" name="steel" type="neo-Hookean">', "\t\t\t<density>1</density>",
         "\t\t\t<E>%s</E>" % fmt(E), "\t\t\t<v>%s</v>" % fmt(NU), "\t\t</material>",
         '\t\t<material id="2" name="tube" type="neo-Hookean">', "\t\t\t<density>1</density>",
         "\t\t\t<E>1e-06</E>", "\t\t\t<v>0.3</v>", "\t\t</material>",
         "\t</Material>", "\t<Mesh>", '\t\t<Nodes name="all_nodes">']
    L += ['\t\t\t<node id="%d">%s,%s,%s</node>' % ((v,) + tuple(fmt(c) for c in allx[v])) for v in range(1, len(allx))]
    L += ["\t\t</Nodes>", '\t\t<Elements type="hex8" name="stent">']
    L += ['\t\t\t<elem id="%d">%s</elem>' % (e + 1, ",".join(map(str, c))) for e, c in enumerate(hexes)]
    L += ["\t\t</Elements>", '\t\t<Elements type="hex8" name="tube">']
    L += ['\t\t\t<elem id="%d">%s</elem>' % (len(hexes) + e + 1, ",".join(map(str, c))) for e, c in enumerate(bhex)]
    L += ["\t\t</Elements>"]
    nsets = {"symmetry_y": sets["symmetry_y"], "anchor": sets["anchor"], "inner": sets["inner"],
             "outer": sets["outer"], "stent_all": list(range(1, ns + 1)), "tube_all": b_all, "tube_outer": b_outer}
    for name, ids in nsets.items():
        L += ['\t\t<NodeSet name="%s">' % name, "\t\t\t" + febio_tools.ids_text(ids, "\t\t\t"), "\t\t</NodeSet>"]
    L += ['\t\t<Surface name="stent_inner">']
    L += ['\t\t\t<quad4 id="%d">%s</quad4>' % (e + 1, ",".join(map(str, c))) for e, c in enumerate(m["inner_quads"])]
    L += ["\t\t</Surface>", '\t\t<Surface name="tube_outer">']
    L += ['\t\t\t<quad4 id="%d">%s</quad4>' % (e + 1, ",".join(map(str, c))) for e, c in enumerate(bquads)]
    L += ["\t\t</Surface>", '\t\t<SurfacePair name="balloon">', "\t\t\t<primary>stent_inner</primary>",
          "\t\t\t<secondary>tube_outer</secondary>", "\t\t</SurfacePair>", "\t</Mesh>",
          "\t<MeshDomains>", '\t\t<SolidDomain name="stent" mat="steel"/>', '\t\t<SolidDomain name="tube" mat="tube"/>',
          "\t</MeshDomains>", "\t<Boundary>",
          '\t\t<bc name="sym_y" node_set="symmetry_y" type="zero displacement">',
          "\t\t\t<x_dof>0</x_dof>", "\t\t\t<y_dof>1</y_dof>", "\t\t\t<z_dof>0</z_dof>", "\t\t</bc>",
          '\t\t<bc name="axial" node_set="anchor" type="zero displacement">',
          "\t\t\t<x_dof>0</x_dof>", "\t\t\t<y_dof>0</y_dof>", "\t\t\t<z_dof>1</z_dof>", "\t\t</bc>",
          '\t\t<bc name="tube_z" node_set="tube_all" type="zero displacement">',
          "\t\t\t<x_dof>0</x_dof>", "\t\t\t<y_dof>0</y_dof>", "\t\t\t<z_dof>1</z_dof>", "\t\t</bc>"]
    for d, X in (("x", "X"), ("y", "Y")):
        L += ['\t\t<bc name="tube_%s" node_set="tube_all" type="prescribed displacement">' % d, "\t\t\t<dof>%s</dof>" % d,
              '\t\t\t<value lc="1" type="math">%s*%s</value>' % (X, repr(k)), "\t\t\t<relative>0</relative>", "\t\t</bc>"]
    for v in sets["symmetry_sector"]:
        L += ['\t\t<bc type="linear constraint">', "\t\t\t<node>%d</node>" % v, "\t\t\t<dof>y</dof>",
              "\t\t\t<child_dof>", "\t\t\t\t<node>%d</node>" % v, "\t\t\t\t<dof>x</dof>",
              "\t\t\t\t<value>%s</value>" % repr(tan), "\t\t\t</child_dof>", "\t\t</bc>"]
    L += ["\t</Boundary>", "\t<Contact>", '\t\t<contact type="%s" surface_pair="balloon">' % a.contact,
          "\t\t\t<laugon>AUGLAG</laugon>", "\t\t\t<tolerance>%g</tolerance>" % a.atol,
          "\t\t\t<gaptol>0</gaptol>", "\t\t\t<penalty>%g</penalty>" % a.penalty,
          "\t\t\t<auto_penalty>1</auto_penalty>", "\t\t\t<two_pass>0</two_pass>",
          "\t\t\t<minaug>0</minaug>", "\t\t\t<maxaug>%d</maxaug>" % a.maxaug,
          "\t\t\t<search_tol>0.01</search_tol>", "\t\t\t<fric_coeff>0</fric_coeff>"]
    if a.contact == "sliding-elastic":
        L += ["\t\t\t<symmetric_stiffness>%d</symmetric_stiffness>" % (a.symmetric == "symmetric")]
    L += ["\t\t</contact>", "\t</Contact>",
          "\t<LoadData>", '\t\t<load_controller id="1" name="ramp" type="loadcurve">',
          "\t\t\t<interpolate>LINEAR</interpolate>", "\t\t\t<extend>CONSTANT</extend>", "\t\t\t<points>",
          "\t\t\t\t<pt>0,0</pt>", "\t\t\t\t<pt>1,1</pt>", "\t\t\t</points>", "\t\t</load_controller>", "\t</LoadData>",
          "\t<Output>", "\t\t<logfile>",
          '\t\t\t<node_data data="Rx;Ry;Rz" node_set="tube_outer" file="%s.R.txt" delim=","/>' % base,
          '\t\t\t<node_data data="ux;uy;uz" node_set="stent_all" file="%s.u.txt" delim=","/>' % base,
          "\t\t</logfile>", "\t</Output>", "</febio_spec>", ""]
    with open(a.out, "w") as f:
        f.write("\n".join(L))
    with open(os.path.splitext(a.out)[0] + ".json", "w") as f:
        json.dump({"x": [list(v) for v in x[1:]], "outer": sets["outer"], "tube_outer": b_outer,
                   "tube_x": {str(v): list(bx[v]) for v in b_outer}, "r0": a.r0, "dr": a.dr, "steps": a.steps,
                   "cells": len(hexes), "contact": a.contact}, f)
    print("stent_sector.py: %s: %d nodes, %d hex8, %d on the oblique plane; tube %d hex8; %s" % (
        a.out, ns, len(hexes), len(sets["symmetry_sector"]), len(bhex), a.contact))


# ---------------------------------------------------------------- measurements
def outer_diameters(geo, u):
    d = []
    for v in geo["outer"]:
        X = geo["x"][v - 1]
        d.append(2 * math.hypot(X[0] + u[v - 1][0], X[1] + u[v - 1][1]))
    return sum(d) / len(d), max(d)


def measure_stentor(res, log, out, geo_json):
    import h5py
    f = {"code": "Stentor", "status": "failed"}
    text = febio_tools.ESCAPES.sub("", febio_tools.read_text(log))
    m = re.search(r"Summary: (\d+) steps, (\d+) cut-backs, (\d+) Newton iterations", text)
    t = febio_tools.time_line(text)
    f["wall"] = float(t[0]) if t else None
    if m:
        f["newton"], f["cutbacks"] = int(m.group(3)), int(m.group(2))
    hist = febio_tools.read_text(os.path.join(res, "sector_history.csv")).splitlines()
    geo = json.load(open(geo_json))
    if m and len(hist) >= 2:
        head = hist[0].split(",")
        rows = [dict(zip(head, l.split(","))) for l in hist[1:]]
        f["curve"] = [(float(r["time"]), float(r["contact_balloon_obstacle_diameter"]) / 2,
                       float(r["contact_balloon_normal_force"])) for r in rows]
        with h5py.File(os.path.join(res, "sector.h5"), "r") as h:
            steps = sorted((k for k in h.keys() if k.startswith("step_")), key=lambda s: int(s.split("_")[1]))
            s = h[steps[-1]]
            f["t_end"] = float(s.attrs["time"])
            f["u"] = s["displacement"][()].tolist()
            f["active"] = int(sum(1 for v in s["contact_status"][()].reshape(-1) if v >= 2))
        f["status"] = "yes" if abs(f["t_end"] - 1) < 1e-9 else "no"
        f["D_mean"], f["D_max"] = outer_diameters(geo, f["u"])
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
    gaps = re.findall(r"(?:gap function|maximum gap)\s*:\s*(\S+)", flog or screen)
    f["gap"] = float(gaps[-1]) if gaps else None
    if its and normal:
        f["newton"] = int(its[-1])
    R = febio_tools.records(base + ".R.txt")
    U = febio_tools.records(base + ".u.txt")
    if normal and R and U:
        curve = []
        for tm, rows in R:
            F = 0.0
            for v, (rx, ry, rz) in rows.items():
                X = geo["tube_x"][str(v)]
                F += (rx * X[0] + ry * X[1]) / math.hypot(X[0], X[1])
            curve.append((tm, geo["r0"] + geo["dr"] * tm, F))
        f["curve"] = curve
        tm, rows = U[-1]
        ns = len(geo["x"])
        f["u"] = [rows[v] for v in range(1, ns + 1)]
        f["t_end"] = tm
        f["status"] = "yes" if abs(tm - 1) < 1e-9 else "no"
        f["D_mean"], f["D_max"] = outer_diameters(geo, f["u"])
    json.dump(f, open(out, "w"))


def table(a):
    ref = json.load(open(a.ref))
    rc = {round(t, 9): F for t, r, F in ref.get("curve", [])}
    Fend = ref["curve"][-1][2] if ref.get("curve") else None
    for path, label in zip(a.runs, a.label):
        f = json.load(open(path))
        naug = str(f.get("newton", "failed"))
        if f.get("aug") is not None and "newton" in f:
            naug += " (%d)" % f["aug"]
        row = {"label": label, "naug": naug,
               "wall": "%.2f" % f["wall"] if f.get("wall") else "?", "F": "?", "dF": "?", "dFmax": "?",
               "D": "?", "Dmax": "?", "du": "?", "gap": "%.1e" % f["gap"] if f.get("gap") is not None else "-"}
        if f.get("status") == "yes" and Fend:
            F = f["curve"][-1][2]
            row["F"] = "%.6g" % F
            row["dF"] = "%+.1e" % (F / Fend - 1)
            worst = 0.0
            for t, r, Fi in f["curve"]:
                Fr = rc.get(round(t, 9))
                if Fr is not None and abs(Fr) > 0.01 * abs(Fend):
                    worst = max(worst, abs(Fi / Fr - 1))
            row["dFmax"] = "%.1e" % worst
            row["D"] = "%.5f" % f["D_mean"]
            row["Dmax"] = "%.5f" % f["D_max"]
            du = max(abs(f["u"][i][c] - ref["u"][i][c]) for i in range(len(ref["u"])) for c in range(3))
            row["du"] = "%.1e" % du
        print(a.row.format(**row))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sp = ap.add_subparsers(dest="cmd")
    sp.required = True
    d = sp.add_parser("deck")
    d.add_argument("out")
    d.add_argument("--r0", type=float, default=1.38)
    d.add_argument("--dr", type=float, default=0.42)
    d.add_argument("--steps", type=int, default=21)
    d.add_argument("--nw", type=int, default=3)
    d.add_argument("--nt", type=int, default=3)
    d.add_argument("--solver", default="direct", choices=["direct", "gmres"])
    fb = sp.add_parser("feb")
    fb.add_argument("out")
    fb.add_argument("--msh", required=True)
    fb.add_argument("--r0", type=float, default=1.38)
    fb.add_argument("--dr", type=float, default=0.42)
    fb.add_argument("--steps", type=int, default=21)
    fb.add_argument("--nballoon", type=int, default=256)
    fb.add_argument("--contact", default="sliding-node-on-facet",
                    choices=["sliding-node-on-facet", "sliding-facet-on-facet", "sliding-elastic"])
    fb.add_argument("--penalty", type=float, default=100.0)
    fb.add_argument("--atol", type=float, default=1e-3)
    fb.add_argument("--maxaug", type=int, default=50)
    fb.add_argument("--rtol", type=float, default=1e-20)
    fb.add_argument("--tolerances", default="strict", choices=["strict", "default"])
    fb.add_argument("--max-refs", type=int, default=25)
    fb.add_argument("--symmetric", default="non-symmetric", choices=["symmetric", "non-symmetric"])
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
    else:
        print(febio_tools.same_mesh(a.h5, a.geo, "hex8", " mm"))


if __name__ == "__main__":
    main()

"""3D Hertz contact, Stentor against FEBio 4 on the same gmsh mesh (perf/contact/hertz3d.sh).

A quarter of the lower half of an elastic sphere (radius R, centre (0, 0, R)) pressed onto a
rigid plane z = 0: symmetry planes x = 0 and y = 0 (rollers), the equator z = R moved down by
delta (u_z prescribed, u_x and u_y free: by symmetry, a whole sphere squeezed between two
plates by 2 delta). Frictionless, static, tet4 (gmsh), Ciarlet-Geymonat from E, nu.

  python3 perf/contact/hertz3d.py geo OUT.geo --hc HC [--R R --delta D --grade G]
      The .geo: gmsh's OpenCASCADE sphere octant, physical groups ball (volume), surface (the
      spherical face: the contact surface), sym_x, sym_y, top (the equator). Size field:
      hc within 1.5 sqrt(R delta) of the pole, growing by G per unit distance beyond,
      capped by Mesh->size (gmsh's Mesh.MeshSizeMax).
  python3 perf/contact/hertz3d.py deck OUT.xml --geo NAME [--size H --delta D --steps N]
      The Stentor deck: plane obstacle z = 0 (exact active-set constraint), gap condition.
  python3 perf/contact/hertz3d.py feb OUT.feb --geo GEO [--size H --delta D --steps N
                                  --penalty P --atol A --gaptol G --maxaug M]
      Mesh GEO with the gmsh executable exactly as Stentor meshes it (perf/solve/feb.py,
      run_gmsh) and write the FEBio 4 input: the same tets and sets, plus a block of 4 x 4
      hex8 under the plane (x, y in [-0.05, 0.35] R, z in [-0.05 R, 0]) whose nodes are all
      fixed, i.e. a rigid immobile plane; sliding-elastic contact, primary = the spherical
      face (tri3, oriented outward), secondary = the block's top (quad4, normal +z),
      augmented Lagrangian (laugon AUGLAG), auto_penalty with factor P, tolerance A (relative
      change of the multipliers' norm between augmentations), gaptol G, at most M
      augmentations per step; full Newton, residual test |R| <= 1e-10 |R0| (rtol 1e-20 on
      squared norms, as Stentor's static default), no energy or displacement test.
  python3 perf/contact/hertz3d.py same-mesh STENTOR.h5 OUT.facets.json
      Node and cell counts of Stentor's mesh (its HDF5 output) and of the .feb's, and the
      largest coordinate difference in the same node numbering.
  python3 perf/contact/hertz3d.py stentor RESULTS_DIR LOG [--label K=V ...] --row FMT
  python3 perf/contact/hertz3d.py febio RUN_DIR LOG [--label K=V ...] --row FMT
      Measure one run and print FMT (str.format) with the fields below.

Fields (full sphere: the quarter's forces times 4; delta and R from the deck / .feb):
  F        total contact force (Stentor: the history's contact_floor_force_z; FEBio: minus
           the sum of Rz over the equator nodes, the reaction of the prescribed dofs), x 4
  eF       F / F_H(delta) - 1, F_H = 4/3 E* sqrt(R) delta^1.5, E* = E / (1 - nu^2)
  a        contact radius from the force moment: Hertz's p = p0 sqrt(1 - r^2/a^2) has
           <r^2>_p = 2/5 a^2, so a = sqrt(5/2 sum(f r^2) / sum(f)), r the reference radius
           sqrt(x^2 + y^2); f = Stentor's nodal normal forces (contact_lambda_normal of the
           active nodes), FEBio's facet pressure x facet area with the exact integral of r^2
           over the facet (constant pressure per facet)
  ea       a / a_H(F) - 1, a_H(F) = (3 F R / (4 E*))^(1/3), with the run's own F
  p0       peak pressure: Stentor's largest contact_pressure (nodal, recovered), FEBio's
           largest facet "contact pressure" (face_data: the mean over the facet's points)
  ep       p0 / p0_H(F) - 1, p0_H = 3 F / (2 pi a_H^2)
  a_rd     a_H of sqrt(R delta) (Hertz's a at the prescribed delta), for reference
  newton   Newton iterations of all steps (FEBio: its equilibrium iterations, augmentations
           included); aug: FEBio's augmentations
  wall     seconds (/usr/bin/time of the whole process; Stentor's includes its meshing,
           field `mesh`)
  nodes, cells, active (contact nodes or facets with pressure > 0, of the quarter)
  Fchk     FEBio: sum of facet pressure x area x 4 against F (relative), a check of the
           pressure output
"""
import argparse
import json
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "solve"))
import feb as febio_tools  # noqa: E402  (perf/solve/feb.py: gmsh as Stentor, MSH 2.2 reader)

E_DEFAULT, NU_DEFAULT = 1.0, 0.3


def lame(E, nu):
    mu = E / (2 * (1 + nu))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    return mu, lam


def cg_constants(E, nu):
    """Ciarlet-Geymonat C1, C2, D with the small-strain limit E, nu (C2 = 0): C1 = mu/2,
    D = lambda/4 (inputs/hertz.xml)."""
    mu, lam = lame(E, nu)
    return mu / 2, 0.0, lam / 4


def hertz(E, nu, R, delta=None, F=None):
    Es = E / (1 - nu * nu)
    out = {"Es": Es}
    if delta is not None:
        out["F_d"] = 4.0 / 3.0 * Es * math.sqrt(R) * delta ** 1.5
        out["a_d"] = math.sqrt(R * delta)
    if F is not None:
        a = (3 * F * R / (4 * Es)) ** (1.0 / 3.0)
        out["a_F"] = a
        out["p0_F"] = 3 * F / (2 * math.pi * a * a)
    return out


# ---------------------------------------------------------------- writers
def write_geo(a):
    a0 = math.sqrt(a.R * a.delta)
    r0 = 1.5 * a0
    text = """// 3D Hertz (perf/contact/hertz3d.py): the quarter of the lower half of a sphere of radius R
// centred (0, 0, R), touching the plane z = 0 at the origin. hc: element size within r0 of the
// pole (r0 = 1.5 sqrt(R delta), 1.5 Hertz contact radii), growing by g per unit distance beyond;
// Mesh->size caps it (gmsh's Mesh.MeshSizeMax).
SetFactory("OpenCASCADE");
R = {R!r};
hc = {hc!r};
r0 = {r0!r};
g = {g!r};
Sphere(1) = {{0, 0, R, R, -Pi/2, 0, Pi/2}};
e = 1e-6 * R;
sx() = Surface In BoundingBox{{-e, -e, -e, e, R + e, R + e}};
sy() = Surface In BoundingBox{{-e, -e, -e, R + e, e, R + e}};
tp() = Surface In BoundingBox{{-e, -e, R - e, R + e, R + e, R + e}};
sp() = Surface In BoundingBox{{-e, -e, -e, R + e, R + e, R + e}};
sp() -= {{sx(), sy(), tp()}};
Field[1] = MathEval;
Field[1].F = Sprintf("%.17g + %.17g*0.5*(Sqrt(x*x+y*y+z*z) - %.17g + Fabs(Sqrt(x*x+y*y+z*z) - %.17g))", hc, g, r0, r0);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Physical Volume("ball") = {{1}};
Physical Surface("surface") = {{sp()}};
Physical Surface("sym_x") = {{sx()}};
Physical Surface("sym_y") = {{sy()}};
Physical Surface("top") = {{tp()}};
""".format(R=a.R, hc=a.hc, r0=r0, g=a.grade)
    with open(a.out, "w") as f:
        f.write(text)


def p(name, typ, value):
    return '    <Parameter name="%s" type="%s" value="%s"/>' % (name, typ, value)


def write_deck(a):
    C1, C2, D = cg_constants(a.E, a.nu)
    solver = [p("method", "string", a.solver)]
    text = "\n".join([
        '<ParameterList name="stentor">',
        "  <!-- 3D Hertz (perf/contact/hertz3d.py): quarter of the lower half of a sphere R = %r on the" % a.R,
        "       rigid plane z = 0 (symmetry planes x = 0, y = 0; the equator moved down by delta = %r)," % a.delta,
        "       E = %r, nu = %r (Ciarlet-Geymonat, small-strain limit), frictionless, gap, statics. -->" % (a.E, a.nu),
        '  <ParameterList name="Problem">',
        p("title", "string", "Hertz 3D: quarter hemisphere on a rigid plane"),
        p("analysis", "string", "static"),
        p("units", "string", "none"),
        "  </ParameterList>",
        '  <ParameterList name="Mesh">',
        p("file", "string", a.geo),
        p("size", "double", repr(a.size)),
        "  </ParameterList>",
        '  <ParameterList name="Materials">',
        '   <ParameterList name="solid">',
        p("C1", "double", "%.17g" % C1), p("C2", "double", "%.17g" % C2), p("D", "double", "%.17g" % D),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Bodies">',
        '   <ParameterList name="ball">', p("material", "string", "solid"), "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Boundary Conditions">',
        '   <ParameterList name="top">',
        p("type", "string", "Dirichlet"), p("boundary", "string", "top"), p("components", "string", "z"),
        p("values", "Array(double)", "{%r}" % (-a.delta)),
        "   </ParameterList>",
        '   <ParameterList name="sym_x">',
        p("type", "string", "Dirichlet"), p("boundary", "string", "sym_x"), p("components", "string", "x"),
        "   </ParameterList>",
        '   <ParameterList name="sym_y">',
        p("type", "string", "Dirichlet"), p("boundary", "string", "sym_y"), p("components", "string", "y"),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Contact">',
        '   <ParameterList name="floor">',
        p("slave", "string", "surface"), p("obstacle", "string", "plane"),
        p("point", "Array(double)", "{0.0, 0.0, 0.0}"), p("normal", "Array(double)", "{0.0, 0.0, 1.0}"),
        p("formulation", "string", "gap"),
        "   </ParameterList>",
        "  </ParameterList>",
        '  <ParameterList name="Stepping">',
        p("end time", "double", "1.0"), p("steps", "int", str(a.steps)),
        "  </ParameterList>",
        '  <ParameterList name="Linear Solver">'] + solver + [
        "  </ParameterList>",
        '  <ParameterList name="Output">',
        p("basename", "string", "hertz3d"),
        p("field list", "string", "displacement, contact_status, contact_lambda_normal, contact_pressure"),
        "  </ParameterList>",
        "</ParameterList>", ""])
    with open(a.out, "w") as f:
        f.write(text)


def tet_volume(x, c):
    return febio_tools.signed_volume(x, c)


def sub(u, v):
    return [u[i] - v[i] for i in range(3)]


def cross(u, v):
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def dot(u, v):
    return sum(u[i] * v[i] for i in range(3))


def read_mesh(msh):
    """The ball's mesh from gmsh: nodes numbered as Stentor numbers them (the nodes used by the
    physical groups, compactly, by increasing gmsh tag), tets (positive volume), the
    spherical face's triangles oriented outward, node sets of the planes."""
    nodes, names, elems = febio_tools.read_msh22(msh)
    groups = {}
    for typ, phys, conn in elems:
        if phys:
            groups.setdefault(names.get(phys, "tag%d" % phys), []).append((typ, conn))
    used = sorted({n for g in groups.values() for typ, conn in g for n in conn})
    ids = {t: k + 1 for k, t in enumerate(used)}
    x = [None] + [nodes[t] for t in used]
    tets = []
    for typ, conn in groups["ball"]:
        if typ != 4:
            raise SystemExit("hertz3d.py: the ball must be tet4 (gmsh type 4), got %d" % typ)
        c = [ids[n] for n in conn]
        if tet_volume(x, c) < 0:
            c[1], c[2] = c[2], c[1]
        tets.append(c)
    # outward orientation of the contact facets: the tet holding the face, its fourth node inside
    face_tet = {}
    for c in tets:
        for k in range(4):
            f = tuple(sorted(c[:k] + c[k + 1:]))
            face_tet[f] = c[k]
    tris = []
    for typ, conn in groups["surface"]:
        c = [ids[n] for n in conn]
        inner = face_tet[tuple(sorted(c))]
        nrm = cross(sub(x[c[1]], x[c[0]]), sub(x[c[2]], x[c[0]]))
        if dot(nrm, sub(x[inner], x[c[0]])) > 0:
            c[1], c[2] = c[2], c[1]
        tris.append(c)
    sets = {name: sorted({ids[n] for typ, conn in groups[name] for n in conn}) for name in ("top", "sym_x", "sym_y")}
    return {"x": x, "tets": tets, "tris": tris, "sets": sets}


def write_feb(a):
    import shutil
    import tempfile
    tmp = tempfile.mkdtemp(prefix="hertz3d-")
    try:
        msh = a.msh or os.path.join(tmp, "mesh.msh")
        febio_tools.run_gmsh(a.geo, a.size, 1, msh, a.gmsh)
        m = read_mesh(msh)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    C1, C2, D = cg_constants(a.E, a.nu)
    x, nb = m["x"], len(m["x"]) - 1
    # the fixed block under the plane: 4 x 4 x 1 hex8
    n, lo, hi, t = 4, -0.05 * a.R, 0.35 * a.R, 0.05 * a.R
    bcoord, hexes, quads = febio_tools.rigid_slab(n, lo, hi, -t, nb + 1)
    fmt = febio_tools.fmt
    base = os.path.splitext(os.path.basename(a.out))[0]
    dt = 1.0 / a.steps
    W = febio_tools.strain_energy(C1, C2, D)
    L = ['<?xml version="1.0" encoding="ISO-8859-1"?>',
         "<!-- Written by perf/contact/hertz3d.py from %s (Mesh->size %s): 3D Hertz, quarter hemisphere"
         " R=%s on a fixed block, delta=%s, E=%s, nu=%s -->" % (os.path.basename(a.geo), fmt(a.size), fmt(a.R),
                                                                  fmt(a.delta), fmt(a.E), fmt(a.nu)),
         '<febio_spec version="4.0">', '\t<Module type="solid"/>', "\t<Control>",
         "\t\t<analysis>STATIC</analysis>", "\t\t<time_steps>%d</time_steps>" % a.steps,
         "\t\t<step_size>%s</step_size>" % fmt(dt), "\t\t<plot_level>PLOT_NEVER</plot_level>",
         "\t\t<output_level>OUTPUT_MAJOR_ITRS</output_level>",
         '\t\t<time_stepper type="default">', "\t\t\t<max_retries>5</max_retries>", "\t\t\t<opt_iter>%d</opt_iter>" % a.opt_iter,
         "\t\t\t<dtmin>0</dtmin>", "\t\t\t<dtmax>%s</dtmax>" % fmt(dt), "\t\t\t<aggressiveness>0</aggressiveness>",
         "\t\t\t<cutback>0.5</cutback>", "\t\t\t<dtforce>0</dtforce>", "\t\t</time_stepper>",
         '\t\t<solver type="solid">', "\t\t\t<symmetric_stiffness>%s</symmetric_stiffness>" % a.symmetric,
         "\t\t\t<max_refs>%d</max_refs>" % a.max_refs,
         "\t\t\t<dtol>0</dtol>", "\t\t\t<etol>0</etol>", "\t\t\t<rtol>%g</rtol>" % a.rtol,
         '\t\t\t<qn_method type="full Newton"/>', "\t\t</solver>", "\t</Control>",
         "\t<Material>", '\t\t<material id="1" name="rubber" type="hyperelastic">', "\t\t\t<density>1</density>",
         "\t\t\t<W>%s</W>" % W, "\t\t</material>", "\t</Material>", "\t<Mesh>", '\t\t<Nodes name="all_nodes">']
    L += ['\t\t\t<node id="%d">%s,%s,%s</node>' % ((k,) + tuple(fmt(c) for c in x[k])) for k in range(1, nb + 1)]
    L += ['\t\t\t<node id="%d">%s,%s,%s</node>' % ((v,) + tuple(fmt(c) for c in bcoord[v])) for v in sorted(bcoord)]
    L += ["\t\t</Nodes>", '\t\t<Elements type="tet4" name="ball">']
    L += ['\t\t\t<elem id="%d">%s</elem>' % (k + 1, ",".join(map(str, c))) for k, c in enumerate(m["tets"])]
    L += ["\t\t</Elements>", '\t\t<Elements type="hex8" name="block">']
    L += ['\t\t\t<elem id="%d">%s</elem>' % (len(m["tets"]) + k + 1, ",".join(map(str, c))) for k, c in enumerate(hexes)]
    L += ["\t\t</Elements>"]
    sets = dict(m["sets"])
    sets["block_all"] = sorted(bcoord)
    for name in ("top", "sym_x", "sym_y", "block_all"):
        L += ['\t\t<NodeSet name="%s">' % name, "\t\t\t" + febio_tools.ids_text(sets[name], "\t\t\t"), "\t\t</NodeSet>"]
    L += ['\t\t<Surface name="ball_surface">']
    L += ['\t\t\t<tri3 id="%d">%s</tri3>' % (k + 1, ",".join(map(str, c))) for k, c in enumerate(m["tris"])]
    L += ["\t\t</Surface>", '\t\t<Surface name="block_top">']
    L += ['\t\t\t<quad4 id="%d">%s</quad4>' % (k + 1, ",".join(map(str, c))) for k, c in enumerate(quads)]
    L += ["\t\t</Surface>", '\t\t<SurfacePair name="floor">', "\t\t\t<primary>ball_surface</primary>",
          "\t\t\t<secondary>block_top</secondary>", "\t\t</SurfacePair>", "\t</Mesh>",
          "\t<MeshDomains>", '\t\t<SolidDomain name="ball" mat="rubber"/>', '\t\t<SolidDomain name="block" mat="rubber"/>',
          "\t</MeshDomains>", "\t<Boundary>",
          '\t\t<bc name="sym_x" node_set="sym_x" type="zero displacement">',
          "\t\t\t<x_dof>1</x_dof>", "\t\t\t<y_dof>0</y_dof>", "\t\t\t<z_dof>0</z_dof>", "\t\t</bc>",
          '\t\t<bc name="sym_y" node_set="sym_y" type="zero displacement">',
          "\t\t\t<x_dof>0</x_dof>", "\t\t\t<y_dof>1</y_dof>", "\t\t\t<z_dof>0</z_dof>", "\t\t</bc>",
          '\t\t<bc name="block" node_set="block_all" type="zero displacement">',
          "\t\t\t<x_dof>1</x_dof>", "\t\t\t<y_dof>1</y_dof>", "\t\t\t<z_dof>1</z_dof>", "\t\t</bc>",
          '\t\t<bc name="top" node_set="top" type="prescribed displacement">', "\t\t\t<dof>z</dof>",
          '\t\t\t<value lc="1">%s</value>' % fmt(-a.delta), "\t\t\t<relative>0</relative>", "\t\t</bc>",
          "\t</Boundary>", "\t<Contact>",
          '\t\t<contact type="sliding-elastic" surface_pair="floor">',
          "\t\t\t<laugon>AUGLAG</laugon>", "\t\t\t<tolerance>%g</tolerance>" % a.atol,
          "\t\t\t<gaptol>%g</gaptol>" % a.gaptol, "\t\t\t<penalty>%g</penalty>" % a.penalty,
          "\t\t\t<auto_penalty>1</auto_penalty>", "\t\t\t<two_pass>0</two_pass>",
          "\t\t\t<symmetric_stiffness>%d</symmetric_stiffness>" % (a.symmetric == "symmetric"),
          "\t\t\t<minaug>0</minaug>", "\t\t\t<maxaug>%d</maxaug>" % a.maxaug,
          "\t\t\t<search_tol>0.01</search_tol>", "\t\t\t<fric_coeff>0</fric_coeff>",
          "\t\t</contact>", "\t</Contact>",
          "\t<LoadData>", '\t\t<load_controller id="1" name="ramp" type="loadcurve">',
          "\t\t\t<interpolate>LINEAR</interpolate>", "\t\t\t<extend>CONSTANT</extend>", "\t\t\t<points>",
          "\t\t\t\t<pt>0,0</pt>", "\t\t\t\t<pt>1,1</pt>", "\t\t\t</points>", "\t\t</load_controller>", "\t</LoadData>",
          "\t<Output>", "\t\t<logfile>",
          '\t\t\t<node_data data="Rz" node_set="top" file="%s.Rz.txt" delim=","/>' % base,
          '\t\t\t<face_data data="contact pressure" surface="ball_surface" file="%s.pc.txt" delim=","/>' % base,
          "\t\t</logfile>", "\t</Output>", "</febio_spec>", ""]
    with open(a.out, "w") as f:
        f.write("\n".join(L))
    # the facets and their reference geometry, for the measurements
    with open(os.path.splitext(a.out)[0] + ".facets.json", "w") as f:
        json.dump({"x": x[1:], "tris": m["tris"], "R": a.R, "delta": a.delta, "E": a.E, "nu": a.nu,
                   "nodes": nb, "cells": len(m["tets"])}, f)
    print("hertz3d.py: %s: %d nodes, %d tet4, %d contact facets (+ %d fixed hex8)" % (a.out, nb, len(m["tets"]),
          len(m["tris"]), len(hexes)))


# ---------------------------------------------------------------- measurements
def finish(f, E, nu, R, delta):
    h = hertz(E, nu, R, delta=delta, F=f["F"] if f.get("F") else None)
    f["a_rd"] = "%.5f" % h["a_d"]
    if f.get("F"):
        F = f["F"]
        f["eF"] = "%+.2f %%" % (100 * (F / h["F_d"] - 1))
        f["ea"] = "%+.2f %%" % (100 * (f["a"] / h["a_F"] - 1)) if f.get("a") else "?"
        f["ep"] = "%+.2f %%" % (100 * (f["p0"] / h["p0_F"] - 1)) if f.get("p0") else "?"
        f["F"] = "%.5e" % F
        f["a"] = "%.5f" % f["a"] if f.get("a") else "?"
        f["p0"] = "%.5f" % f["p0"] if f.get("p0") else "?"
        f["F_H"] = "%.5e" % h["F_d"]
    return f


def blank():
    return {k: "?" for k in ("F", "eF", "a", "ea", "p0", "ep", "newton", "aug", "wall", "mesh", "nodes", "cells",
                             "active", "Fchk", "status", "a_rd", "F_H")}


def measure_stentor(res, log):
    import h5py
    f = blank()
    deck = os.path.join(res, "hertz3d_deck.xml")
    root = ET.parse(deck).getroot()

    def param(*path):
        node = root
        for name in path[:-1]:
            node = next(c for c in node if c.tag == "ParameterList" and c.get("name") == name)
        return next(c for c in node if c.tag == "Parameter" and c.get("name") == path[-1]).get("value")
    delta = -float(param("Boundary Conditions", "top", "values").strip("{}"))
    C1 = float(param("Materials", "solid", "C1"))
    D = float(param("Materials", "solid", "D"))
    mu, lam = 2 * C1, 4 * D
    nu = lam / (2 * (lam + mu))
    E = mu * 2 * (1 + nu)
    text = febio_tools.ESCAPES.sub("", febio_tools.read_text(log))
    m = re.search(r"mesh\s+\S+: 3D, (\d+) nodes, (\d+) cells", text)
    if m:
        f["nodes"], f["cells"] = m.group(1), m.group(2)
    m = re.search(r"Summary: \d+ steps, (\d+) cut-backs, (\d+) Newton iterations", text)
    f["newton"] = m.group(2) if m else "failed"
    f["status"] = "yes" if m else "no"
    m = re.search(r"^\s+mesh\s+([\d.]+) s", text, re.M)
    f["mesh"] = m.group(1) if m else "?"
    t = febio_tools.time_line(text)
    if t:
        f["wall"] = t[0]
    hist = febio_tools.read_text(os.path.join(res, "hertz3d_history.csv")).splitlines()
    if len(hist) < 2 or f["status"] != "yes":
        return finish(f, E, nu, 1.0, delta)
    head = hist[0].split(",")
    last = dict(zip(head, hist[-1].split(",")))
    if abs(float(last["time"]) - 1.0) > 1e-9:
        return finish(f, E, nu, 1.0, delta)
    f["F"] = 4 * float(last["contact_floor_force_z"])
    with h5py.File(os.path.join(res, "hertz3d.h5"), "r") as h:
        X = h["/mesh/coordinates"][()]
        steps = sorted((k for k in h.keys() if k.startswith("step_")), key=lambda s: int(s.split("_")[1]))
        s = h[steps[-1]]
        lam_n = s["contact_lambda_normal"][()].reshape(-1)
        status = s["contact_status"][()].reshape(-1)
        pc = s["contact_pressure"][()].reshape(-1)
    R = float(max(X[:, 2]))  # the equator z = R
    act = [i for i in range(len(status)) if status[i] >= 2]
    # contact_lambda_normal: the nodal normal force (its sign as written; the moment uses |f|)
    w = [abs(lam_n[i]) for i in act]
    r2 = [X[i, 0] ** 2 + X[i, 1] ** 2 for i in act]
    if sum(w) > 0:
        f["a"] = math.sqrt(2.5 * sum(wi * ri for wi, ri in zip(w, r2)) / sum(w))
    f["p0"] = float(max(abs(v) for v in pc if v == v))
    f["active"] = str(len(act))
    f["Fchk"] = "%.1e" % (4 * sum(w) / f["F"] - 1)
    return finish(f, E, nu, R, delta)


def tri_r2_integral(p):
    """Exact integral of x^2 + y^2 over a (flat) triangle with vertices p, and its area."""
    n = cross(sub(p[1], p[0]), sub(p[2], p[0]))
    A = 0.5 * math.sqrt(dot(n, n))
    s = 0.0
    for c in (0, 1):
        v = [q[c] for q in p]
        s += v[0] ** 2 + v[1] ** 2 + v[2] ** 2 + v[0] * v[1] + v[1] * v[2] + v[2] * v[0]
    return A / 6.0 * s, A


def last_record(path):
    """(time, {id: value}) of the last record of an FEBio log-file data file; (None, None)
    without one."""
    recs = febio_tools.records(path)
    if not recs:
        return None, None
    tm, rows = recs[-1]
    return tm, {k: v[0] for k, v in rows.items()}


def measure_febio(run, log):
    f = blank()
    feb = next(os.path.join(run, n) for n in os.listdir(run) if n.endswith(".feb"))
    base = os.path.splitext(feb)[0]
    geo = json.load(open(base + ".facets.json"))
    E, nu, R, delta = geo["E"], geo["nu"], geo["R"], geo["delta"]
    f["nodes"], f["cells"] = str(geo["nodes"]), str(geo["cells"])
    f["mesh"] = "-"
    flog = febio_tools.read_text(base + ".log")
    screen = febio_tools.ESCAPES.sub("", febio_tools.read_text(log))
    both = screen + "\n" + flog
    normal = "N O R M A L   T E R M I N A T I O N" in both
    f["status"] = "yes" if normal else "no"
    its = re.findall(r"Total number of equilibrium iterations \.+ : (\d+)", flog or screen)
    f["newton"] = its[-1] if its and normal else "failed"
    # augmentations: FEBio prints the contact's table once per augmentation
    f["aug"] = str(len(re.findall(r"sliding interface # \d+", flog or screen)))
    t = febio_tools.time_line(screen)
    if t:
        f["wall"] = t[0]
    if not normal:
        return finish(f, E, nu, R, delta)
    tm, rz = last_record(base + ".Rz.txt")
    if rz is None or tm is None or abs(tm - 1.0) > 1e-9:
        return finish(f, E, nu, R, delta)
    f["F"] = -4 * sum(rz.values())
    tm, pc = last_record(base + ".pc.txt")
    X = geo["x"]
    num = den = 0.0
    act = 0
    for k, c in enumerate(geo["tris"]):
        pk = pc.get(k + 1, 0.0) if pc else 0.0
        if pk > 0:
            act += 1
            I, A = tri_r2_integral([X[i - 1] for i in c])
            num += pk * I
            den += pk * A
    if den > 0:
        f["a"] = math.sqrt(2.5 * num / den)
        f["p0"] = max(pc.values())
        f["Fchk"] = "%.1e" % (4 * den / f["F"] - 1)
    f["active"] = str(act)
    return finish(f, E, nu, R, delta)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sp = ap.add_subparsers(dest="cmd")
    sp.required = True
    g = sp.add_parser("geo")
    g.add_argument("out")
    g.add_argument("--hc", type=float, required=True)
    g.add_argument("--R", type=float, default=1.0)
    g.add_argument("--delta", type=float, default=5e-3)
    g.add_argument("--grade", type=float, default=0.3)
    # The problem, the same for both codes' inputs.
    problem = argparse.ArgumentParser(add_help=False)
    problem.add_argument("out")
    problem.add_argument("--geo", required=True)
    problem.add_argument("--size", type=float, default=0.15)
    problem.add_argument("--delta", type=float, default=5e-3)
    problem.add_argument("--R", type=float, default=1.0)
    problem.add_argument("--E", type=float, default=E_DEFAULT)
    problem.add_argument("--nu", type=float, default=NU_DEFAULT)
    problem.add_argument("--steps", type=int, default=2)
    d = sp.add_parser("deck", parents=[problem])
    d.add_argument("--solver", default="direct", choices=["direct", "gmres"])
    fb = sp.add_parser("feb", parents=[problem])
    fb.add_argument("--penalty", type=float, default=100.0)
    fb.add_argument("--atol", type=float, default=1e-2)
    fb.add_argument("--gaptol", type=float, default=0.0)
    fb.add_argument("--maxaug", type=int, default=50)
    fb.add_argument("--rtol", type=float, default=1e-20)
    fb.add_argument("--max-refs", type=int, default=25)
    fb.add_argument("--opt-iter", type=int, default=1000)
    fb.add_argument("--symmetric", default="non-symmetric", choices=["symmetric", "non-symmetric"])
    fb.add_argument("--gmsh", default=os.environ.get("GMSH", "gmsh"))
    fb.add_argument("--msh")
    sm = sp.add_parser("same-mesh")
    sm.add_argument("h5")
    sm.add_argument("facets")
    for name in ("stentor", "febio"):
        m = sp.add_parser(name)
        m.add_argument("dir")
        m.add_argument("log")
        m.add_argument("--label", action="append", default=[])
        m.add_argument("--row", required=True)
    a = ap.parse_args()
    if a.cmd == "geo":
        write_geo(a)
    elif a.cmd == "deck":
        write_deck(a)
    elif a.cmd == "feb":
        write_feb(a)
    elif a.cmd == "same-mesh":
        print(febio_tools.same_mesh(a.h5, a.facets, "tets"))
    else:
        f = measure_stentor(a.dir, a.log) if a.cmd == "stentor" else measure_febio(a.dir, a.log)
        labels = dict(kv.split("=", 1) for kv in a.label)
        print(a.row.format(**{**labels, **f}))


if __name__ == "__main__":
    main()

"""FEBio 4 input (.feb) for the cube stretch of perf/decks/cube_p1.xml / cube_p2.xml, from
the same gmsh mesh Stentor uses, and the numbers of an FEBio run (FEBio is the yardstick of
perf/solve/time_to_solution.sh). Python 3 standard library and the gmsh command line only.

  python3 perf/solve/feb.py write DECK OUT.feb [--size H] [--gmsh GMSH] [--msh KEEP.msh]
                                               [--tet10-rule TET10G8] [--qn "full Newton"]
                                               [--tolerances default|stentor]
      Mesh DECK's Mesh->file (a .geo) with gmsh as Stentor does and write the .feb of
      DECK's problem: one body of Ciarlet-Geymonat rubber, Dirichlet sets (zero or
      prescribed with the default linear ramp), Stepping->steps equal static steps to
      Stepping->end time. Prints one line: nodes, cells, DOF. --size replaces Mesh->size.
      --tolerances: FEBio's default convergence tests (dtol 0.001, etol 0.01, no residual
      test; looser than Stentor's) or "stentor": the residual test alone at the deck's
      Newton->relative residual tolerance (febio_tolerances below).
      Anything else in the deck (other loads, ramps, laws, stages) is refused (exit 2).

  python3 perf/solve/feb.py parse FEB LOG [--label K=V]... --row FORMAT
      Read FEBio's screen output LOG (with the "TIME wall user sys maxrss_kb" line of
      `/usr/bin/time -f "TIME %e %U %S %M"`), its log file (FEB with .log) and the reaction
      file the .feb asks for, and print FORMAT (str.format) with the labels and the fields
      dofs, newton, linear ("direct" for a direct linear solver, else the total iterations),
      setup, solve, wall, cpu, rss, column (the last step's reaction of the pulled set: sum
      of its nodes' Rx, 10 significant digits), status, tol (the .feb's convergence tests:
      "default" or e.g. "rtol=1e-20").
      FEBio on Linux sets the terminal title while it runs (FEBio/console.cpp: ESC ] 0 ;
      title BEL) and ends its screen output with such a title and no newline, so the
      "TIME" line of /usr/bin/time follows the BEL on the same line: the parser drops these
      sequences before it reads the lines.

How Stentor meshes a .geo (src/mesh/GmshReader.cpp, read_mesh_here/mesh_geo): the gmsh API,
no configuration files, Mesh.MeshSizeMax = Mesh->size, Mesh.MeshSizeMin = 0,
Mesh.MeshSizeFromPoints = 0, Mesh.MeshSizeFromCurvature = 0, Mesh.ElementOrder = order,
Mesh.SecondOrderIncomplete = 1, generate(3); the nodes used by the physical groups are
numbered compactly by increasing gmsh tag. The gmsh executable below gets the same options
(-clmax/-clmin/-setnumber; HOME and GMSH_HOME point to an empty folder, so no user option
file is read) and writes MSH 2.2, read here. Same gmsh library (Debian's gmsh 4.8.4 ships
the executable and libgmsh the stentor binary links): same mesh. Checked: node and cell
counts equal `stentor --check`'s at h = 0.5, 0.3, 0.2, 0.1 (and 0.05 for P1) for P1 and P2
(tests/cli/feb_cube.py repeats this at h = 0.5); at h = 0.3, P2, the nodes (coordinates, in
the same numbering) and the tets equal those of Stentor's HDF5 output, whose tet10 node
order (VTK's, src/io/XdmfWriter.cpp) is FEBio's below.

The .feb (FEBio 4.0 format), as read from FEBio's source (github.com/febiosoftware/FEBio)
and its test inputs (github.com/febiosoftware/TestSuite, Verify/ma36.feb: the generic
hyperelastic material; Verify/mi42.feb: tet10):
- sections in FEBioXML/FEBioImport.cpp (version 0x0400): Module, Control
  (FEBioControlSection4: FEAnalysis parameters), Material (FEBioMaterialSection3), Mesh
  (FEBioMeshSection4: Nodes, Elements type/name, NodeSet "1,2,..."), MeshDomains
  (SolidDomain name= the Elements' name, mat= the material's name), Boundary
  (FEBioBoundarySection3: bc name/node_set/type), LoadData (FEBioLoadDataSection3), Output.
- the law: FEBioMech/FEGenericHyperelastic.cpp, registered as "hyperelastic"
  (FEBioMech/FEBioMechModule.cpp), parameter "W": a *coupled* strain energy W(I1, I2, J)
  (the uncoupled one is "uncoupled hyperelastic"), variables I1, I2 (of B, = those of C),
  J, X, Y, Z; Cauchy stress s = 2/J [(W1 + I1 W2) B - W2 B^2] + WJ I with symbolic
  derivatives. The math parser (FECore/MObjBuilder.cpp): "ln" is the natural log, "log" is
  log10; '^' power; an expression of at most 511 characters. Ciarlet-Geymonat (Stentor's
  src/material/CiarletGeymonat.hpp) with I3 = J^2:
      W = C1 (I1-3) + C2 (I2-3) + D (J^2-1) - 2 K ln J,   K = C1 + 2 C2 + D.
- boundary conditions (FEBioMech/FEFixedDisplacement.cpp, FEPrescribedDisplacement.cpp):
  "zero displacement" (x_dof, y_dof, z_dof) and "prescribed displacement" (dof, value
  with lc=, relative); the ramp: load_controller type "loadcurve" (FECore/FELoadCurve.cpp:
  interpolate LINEAR, extend CONSTANT, points).
- solver: "solid" (FEBioMech/FESolidSolver2.cpp), qn_method "full Newton" (FECore/
  FECore.cpp; each iteration a new stiffness, i.e. Newton's method as Stentor's; FEBio's
  default is BFGS), FEBio's default convergence tests (dtol 0.001, etol 0.01, rtol 0) or,
  with --tolerances stentor, rtol only (febio_tolerances),
  max_refs 25 (= Stentor's default Newton->max iterations), the default linear solver
  (PARDISO, direct). The time stepper (FECore/FETimeStepController.cpp) only cuts back a
  failed step (dtmax = the step size), as Stentor does; FEBio uses no time stepper unless
  the file has one.
- output: logfile node_data data="Rx" node_set= the pulled set, file= (FEBioXML/
  FEBioOutputSection.cpp; "Rx" is FENodeForceX, FEBioMech/FEBioMechData.cpp: the reaction
  at a prescribed dof; FECore/DataRecord.cpp writes "*Step", "*Time", "*Data" and one
  "id,value" line per node). No plot file (plot_level PLOT_NEVER).
- integration: FEBio's defaults (FEBioXML/FEModelBuilder.cpp): tet4 1 point (exact here: F
  is constant per tet4, as Stentor's 1-point stiffness rule), tet10 8 points (TET10G8;
  Stentor uses 14; --tet10-rule TET10GL11 for FEBio's 11-point rule).

Node order. tet4: gmsh and FEBio number the corners alike (0 at the origin of the reference
tet, 1, 2, 3 along r, s, t). tet10 mid-edge nodes:
  gmsh (its documentation, "Node ordering", and Stentor's src/fem/Shape.hpp):
      4: 0-1, 5: 1-2, 6: 2-0, 7: 3-0, 8: 3-2, 9: 3-1
  FEBio (FECore/FESolidElementShape.cpp, FETet10::shape_fnc: H[4] = 4 r1 r2, H[5] = 4 r2 r3,
  H[6] = 4 r3 r1, H[7] = 4 r1 r4, H[8] = 4 r2 r4, H[9] = 4 r3 r4, r1..r4 = nodes 0..3):
      4: 0-1, 5: 1-2, 6: 2-0, 7: 0-3, 8: 1-3, 9: 2-3
  so FEBio's node 8 is gmsh's 9 and FEBio's 9 is gmsh's 8: GMSH_TO_FEBIO_TET10 below.
A tet whose corners (in FEBio's order) have a negative volume would be turned by swapping
corners 1 and 2 (and the mid-edge nodes with them); gmsh's tets have not needed it.
"""
import argparse
import os
import json
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

# FEBio's tet10 node k is gmsh's node GMSH_TO_FEBIO_TET10[k] (see above).
GMSH_TO_FEBIO_TET10 = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]
# The corner pair of each FEBio tet10 mid-edge node 4..9 (FETet10::shape_fnc).
FEBIO_TET10_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
# gmsh element types (MSH 2.2): number of nodes.
GMSH_NODES = {1: 2, 2: 3, 4: 4, 8: 3, 9: 6, 11: 10, 15: 1}
GMSH_TET = {4: "tet4", 11: "tet10"}

# The strain energy FEBio evaluates: C1, C2, D, K are filled in (as numbers: no ';' string
# substitutions of FEBio's parser), I1, I2, J are FEBio's variables.
W_TEMPLATE = "{C1}*(I1-3) + {C2}*(I2-3) + {D}*(J^2-1) - 2*{K}*ln(J)"


class Refused(Exception):
    pass


# ---------------------------------------------------------------- the Stentor deck
class Deck:
    def __init__(self, path):
        self.path = os.path.abspath(path)
        self.root = ET.parse(self.path).getroot()

    def sub(self, node, name):
        return next((c for c in node if c.tag == "ParameterList" and c.get("name") == name), None)

    def lists(self, node):
        return [c for c in node if c.tag == "ParameterList"]

    def param(self, node, name, default=None):
        p = next((c for c in node if c.tag == "Parameter" and c.get("name") == name), None) if node is not None else None
        return default if p is None else p.get("value")

    def get(self, path, default=None):
        node = self.root
        parts = path.split("/")
        for name in parts[:-1]:
            node = self.sub(node, name)
            if node is None:
                return default
        return self.param(node, parts[-1], default)


def array(text):
    text = text.strip().strip("{}")
    return [float(v) for v in text.split(",") if v.strip()]


def problem_from_deck(deck, size=None):
    """The cube stretch's data from a Stentor deck; Refused for anything it cannot say."""
    d = Deck(deck)
    known = {"Problem", "Mesh", "Materials", "Bodies", "Boundary Conditions", "Stepping", "Linear Solver",
             "Output", "Newton"}
    for top in d.lists(d.root):
        if top.get("name") not in known:
            raise Refused("%s: the sublist '%s' has no FEBio counterpart here" % (deck, top.get("name")))
    mesh = d.sub(d.root, "Mesh")
    geo = d.param(mesh, "file")
    if geo is None or not geo.endswith(".geo"):
        raise Refused("%s: Mesh->file must be a .geo (got %r)" % (deck, geo))
    if not os.path.isabs(geo):
        geo = os.path.join(os.path.dirname(d.path), geo)
    h = float(size if size is not None else d.param(mesh, "size", "0"))
    if not h > 0:
        raise Refused("%s: a Mesh->size > 0 is needed (the .geo's own sizes are not reproduced)" % deck)
    order = int(d.param(mesh, "order", "1"))
    if order not in (1, 2):
        raise Refused("%s: Mesh->order must be 1 or 2" % deck)
    for k in ("recombine", "dimension"):
        if d.param(mesh, k) not in (None, "false", "0", "3"):
            raise Refused("%s: Mesh->%s is not supported here" % (deck, k))
    mats = d.lists(d.sub(d.root, "Materials"))
    if len(mats) != 1:
        raise Refused("%s: exactly one material expected" % deck)
    m = mats[0]
    extra = {c.get("name") for c in m if c.tag == "Parameter"} - {"C1", "C2", "D", "model", "density"}
    if extra or d.param(m, "model", "Ciarlet-Geymonat").lower() != "ciarlet-geymonat" or d.param(m, "C1") is None:
        raise Refused("%s: only the Ciarlet-Geymonat law given by C1, D (and C2) is supported" % deck)
    C1, C2, D = (float(d.param(m, k, "0")) for k in ("C1", "C2", "D"))
    bodies = d.lists(d.sub(d.root, "Bodies"))
    if len(bodies) != 1:
        raise Refused("%s: exactly one body expected" % deck)
    body = bodies[0].get("name")
    bcs = []
    for bc in d.lists(d.sub(d.root, "Boundary Conditions")):
        name = bc.get("name")
        if d.param(bc, "type") != "Dirichlet":
            raise Refused("%s: Boundary Conditions->%s: only Dirichlet sets are supported" % (deck, name))
        if d.param(bc, "ramp", "linear") != "linear":
            raise Refused("%s: Boundary Conditions->%s: only the linear ramp is supported" % (deck, name))
        comps = d.param(bc, "components", "all").lower()
        comps = ["x", "y", "z"] if comps == "all" else re.findall(r"[xyz]", comps)
        vals = array(d.param(bc, "values", "{}"))
        if not vals:
            vals = [0.0] * len(comps)
        if len(vals) != len(comps):
            raise Refused("%s: Boundary Conditions->%s: one value per component expected" % (deck, name))
        bcs.append({"name": name, "set": d.param(bc, "boundary"), "values": dict(zip(comps, vals))})
    end = float(d.get("Stepping/end time", "1"))
    steps = int(d.get("Stepping/steps", "1"))
    return {"deck": d.path, "geo": geo, "h": h, "order": order, "C1": C1, "C2": C2, "D": D,
            "body": body, "bcs": bcs, "end": end, "steps": steps,
            "title": d.get("Problem/title", os.path.basename(deck)),
            "rtol": float(d.get("Newton/relative residual tolerance", "1e-10"))}


# ---------------------------------------------------------------- the mesh
def run_gmsh(geo, h, order, msh, gmsh="gmsh"):
    """Mesh geo as Stentor does (see the header) into msh (MSH 2.2, ASCII)."""
    home = tempfile.mkdtemp(prefix="feb-gmsh-home-")
    try:
        env = dict(os.environ, HOME=home, GMSH_HOME=home)
        cmd = [gmsh, geo, "-3", "-order", str(order), "-clmax", repr(float(h)), "-clmin", "0",
               "-setnumber", "Mesh.MeshSizeFromPoints", "0", "-setnumber", "Mesh.MeshSizeFromCurvature", "0",
               "-setnumber", "Mesh.SecondOrderIncomplete", "1", "-format", "msh22", "-o", msh, "-v", "1", "-nopopup"]
        r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        if r.returncode != 0 or not os.path.exists(msh):
            raise Refused("gmsh failed (%s): %s" % (" ".join(cmd), r.stdout.strip()[-500:]))
    finally:
        shutil.rmtree(home, ignore_errors=True)


def read_msh22(path):
    """MSH 2.2 ASCII: {tag: (x, y, z)}, {physical tag: name}, [(type, physical, [node tags])]."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    nodes, names, elems = {}, {}, []
    while i < len(lines):
        s = lines[i].strip()
        if s == "$MeshFormat":
            if not lines[i + 1].split()[0].startswith("2.") or lines[i + 1].split()[1] != "0":
                raise Refused("%s: MSH 2.x ASCII expected" % path)
        elif s == "$PhysicalNames":
            n = int(lines[i + 1])
            for k in range(n):
                dim, tag, name = lines[i + 2 + k].split(None, 2)
                names[int(tag)] = name.strip().strip('"')
            i += n + 1
        elif s == "$Nodes":
            n = int(lines[i + 1])
            for k in range(n):
                t, x, y, z = lines[i + 2 + k].split()
                nodes[int(t)] = (float(x), float(y), float(z))
            i += n + 1
        elif s == "$Elements":
            n = int(lines[i + 1])
            for k in range(n):
                v = [int(a) for a in lines[i + 2 + k].split()]
                typ, ntags = v[1], v[2]
                if typ not in GMSH_NODES:
                    raise Refused("%s: gmsh element type %d is not supported" % (path, typ))
                conn = v[3 + ntags:]
                if len(conn) != GMSH_NODES[typ]:
                    raise Refused("%s: element %d has %d nodes" % (path, v[0], len(conn)))
                elems.append((typ, v[3] if ntags else 0, conn))
            i += n + 1
        i += 1
    return nodes, names, elems


def signed_volume(x, c):
    a, b, d, e = (x[k] for k in c[:4])
    u = [b[i] - a[i] for i in range(3)]
    v = [d[i] - a[i] for i in range(3)]
    w = [e[i] - a[i] for i in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0


def febio_mesh(msh, body):
    """The .feb's mesh from a gmsh file: nodes (1-based, compact, by increasing gmsh tag as in
    Stentor), the body's tets in FEBio's node order, and each physical surface's node set."""
    nodes, names, elems = read_msh22(msh)
    groups = {}
    for typ, phys, conn in elems:
        if phys:
            groups.setdefault(names.get(phys, "tag%d" % phys), []).append((typ, conn))
    if body not in groups:
        raise Refused("%s: no physical group '%s'" % (msh, body))
    used = sorted({n for g in groups.values() for typ, conn in g for n in conn})
    ids = {t: k + 1 for k, t in enumerate(used)}
    x = [None] + [nodes[t] for t in used]
    types = {typ for typ, conn in groups[body]}
    if len(types) != 1 or next(iter(types)) not in GMSH_TET:
        raise Refused("%s: the body '%s' must be all tet4 or all tet10" % (msh, body))
    gtype = next(iter(types))
    tets, flipped = [], 0
    for typ, conn in groups[body]:
        c = [ids[n] for n in conn]
        if gtype == 11:
            c = [c[g] for g in GMSH_TO_FEBIO_TET10]
        if signed_volume(x, c) < 0:
            flipped += 1
            c[1], c[2] = c[2], c[1]
            if gtype == 11:  # 4 (0-1) <-> 6 (2-0), 8 (1-3) <-> 9 (2-3); 5 (1-2) and 7 (0-3) stay
                c[4], c[6], c[8], c[9] = c[6], c[4], c[9], c[8]
        tets.append(c)
    sets = {}
    for name, g in groups.items():
        if name != body and all(GMSH_NODES[typ] in (3, 6) for typ, conn in g):
            sets[name] = sorted({ids[n] for typ, conn in g for n in conn})
    return {"x": x, "type": GMSH_TET[gtype], "tets": tets, "sets": sets, "flipped": flipped}


# ---------------------------------------------------------------- the .feb
ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def shown_path(path):
    """path relative to the repository when inside it (the comment of the .feb)."""
    rel = os.path.relpath(path, ROOT)
    return path if rel.startswith("..") else rel


def rigid_slab(n, lo, hi, z_bottom, first):
    """An n x n x 1 block of hex8 over [lo, hi]^2 x [z_bottom, 0] (a rigid floor for FEBio):
    ({node id: (x, y, z)}, hex8 connectivities, the top face's quad4s, counter-clockwise
    seen from +z so their normal is +z); node ids from `first` on."""
    bx = [lo + (hi - lo) * i / n for i in range(n + 1)]
    node = {}
    for k in range(2):
        for j in range(n + 1):
            for i in range(n + 1):
                node[i, j, k] = first + len(node)
    coord = {v: (bx[i], bx[j], (z_bottom, 0.0)[k]) for (i, j, k), v in node.items()}
    hexes = [[node[i, j, 0], node[i + 1, j, 0], node[i + 1, j + 1, 0], node[i, j + 1, 0],
              node[i, j, 1], node[i + 1, j, 1], node[i + 1, j + 1, 1], node[i, j + 1, 1]]
             for j in range(n) for i in range(n)]
    quads = [[node[i, j, 1], node[i + 1, j, 1], node[i + 1, j + 1, 1], node[i, j + 1, 1]]
             for j in range(n) for i in range(n)]
    return coord, hexes, quads


def fmt(v):
    return "%.17g" % v


def strain_energy(C1, C2, D):
    return W_TEMPLATE.format(C1=fmt(C1), C2=fmt(C2), D=fmt(D), K=fmt(C1 + 2 * C2 + D))


def ids_text(ids, indent, per_line=16):
    rows = [",".join(str(i) for i in ids[k:k + per_line]) for k in range(0, len(ids), per_line)]
    return (",\n" + indent).join(rows)


def febio_tolerances(p, tolerances):
    """FEBio's convergence tests (FESolidSolver2::Quasin) as (dtol, etol, rtol).

    FEBio converges when every test with a tolerance > 0 passes, each on squared norms of
    the step: |du|^2 <= dtol^2 |U|^2, |du.R| <= etol |du0.R0|, |R|^2 <= rtol |R0|^2.
    "default": FEBio's defaults (dtol 0.001, etol 0.01, rtol 0: no residual test).
    "stentor": the residual test alone with rtol = (Stentor's relative residual tolerance)^2,
    i.e. |R| <= tol |R0| as Stentor's residual test (1e-10 for a static deck), at least as
    strict as Stentor, whose increment test can stop Newton earlier."""
    if tolerances == "default":
        return 0.001, 0.01, 0.0
    return 0.0, 0.0, p["rtol"] ** 2


def write_feb(p, mesh, out, tet10_rule=None, qn="full Newton", tolerances="default"):
    x, tets = mesh["x"], mesh["tets"]
    dtol, etol, rtol = febio_tolerances(p, tolerances)
    dt = p["end"] / p["steps"]
    base = os.path.splitext(os.path.basename(out))[0]
    pulled = [bc for bc in p["bcs"] if any(v != 0 for v in bc["values"].values())]
    L = ['<?xml version="1.0" encoding="ISO-8859-1"?>',
         "<!-- Written by perf/solve/feb.py from %s (Mesh->size %s, order %d): %s -->"
         % (shown_path(p["deck"]), fmt(p["h"]), p["order"], p["title"].replace("--", "-")),
         '<febio_spec version="4.0">',
         '\t<Module type="solid"/>',
         "\t<Control>",
         "\t\t<analysis>STATIC</analysis>",
         "\t\t<time_steps>%d</time_steps>" % p["steps"],
         "\t\t<step_size>%s</step_size>" % fmt(dt),
         "\t\t<plot_level>PLOT_NEVER</plot_level>",
         "\t\t<output_level>OUTPUT_MAJOR_ITRS</output_level>",
         '\t\t<time_stepper type="default">',
         "\t\t\t<max_retries>5</max_retries>",
         "\t\t\t<opt_iter>25</opt_iter>",
         "\t\t\t<dtmin>0</dtmin>",
         "\t\t\t<dtmax>%s</dtmax>" % fmt(dt),
         "\t\t\t<aggressiveness>0</aggressiveness>",
         "\t\t\t<cutback>0.5</cutback>",
         "\t\t\t<dtforce>0</dtforce>",
         "\t\t</time_stepper>",
         '\t\t<solver type="solid">',
         "\t\t\t<symmetric_stiffness>symmetric</symmetric_stiffness>",
         "\t\t\t<max_refs>25</max_refs>",
         "\t\t\t<dtol>%g</dtol>" % dtol,
         "\t\t\t<etol>%g</etol>" % etol,
         "\t\t\t<rtol>%g</rtol>" % rtol,
         '\t\t\t<qn_method type="%s"/>' % qn,
         "\t\t</solver>",
         "\t</Control>",
         "\t<Material>",
         '\t\t<material id="1" name="%s" type="hyperelastic">' % "rubber",
         "\t\t\t<density>1</density>",
         "\t\t\t<W>%s</W>" % strain_energy(p["C1"], p["C2"], p["D"]),
         "\t\t</material>",
         "\t</Material>",
         "\t<Mesh>",
         '\t\t<Nodes name="%s_nodes">' % p["body"]]
    L += ['\t\t\t<node id="%d">%s,%s,%s</node>' % ((k,) + tuple(fmt(c) for c in x[k])) for k in range(1, len(x))]
    if tet10_rule and mesh["type"] != "tet10":
        raise Refused("--tet10-rule needs a P2 mesh")
    L += ["\t\t</Nodes>", '\t\t<Elements type="%s" name="%s">' % (tet10_rule or mesh["type"], p["body"])]
    L += ['\t\t\t<elem id="%d">%s</elem>' % (k + 1, ",".join(str(n) for n in c)) for k, c in enumerate(tets)]
    L += ["\t\t</Elements>"]
    for bc in p["bcs"]:
        if bc["set"] not in mesh["sets"]:
            raise Refused("boundary '%s' of %s is no physical surface of the mesh" % (bc["set"], bc["name"]))
    for name in sorted({bc["set"] for bc in p["bcs"]}):
        L += ['\t\t<NodeSet name="%s">' % name, "\t\t\t" + ids_text(mesh["sets"][name], "\t\t\t"), "\t\t</NodeSet>"]
    L += ["\t</Mesh>", "\t<MeshDomains>", '\t\t<SolidDomain name="%s" mat="rubber"/>' % p["body"], "\t</MeshDomains>",
          "\t<Boundary>"]
    for bc in p["bcs"]:
        zero = [c for c in "xyz" if bc["values"].get(c) == 0]
        if zero:
            L += ['\t\t<bc name="%s_zero" node_set="%s" type="zero displacement">' % (bc["name"], bc["set"])]
            L += ["\t\t\t<%s_dof>%d</%s_dof>" % (c, c in zero, c) for c in "xyz"]
            L += ["\t\t</bc>"]
        for c in "xyz":
            v = bc["values"].get(c)
            if v:
                L += ['\t\t<bc name="%s_%s" node_set="%s" type="prescribed displacement">' % (bc["name"], c, bc["set"]),
                      "\t\t\t<dof>%s</dof>" % c, '\t\t\t<value lc="1">%s</value>' % fmt(v),
                      "\t\t\t<relative>0</relative>", "\t\t</bc>"]
    L += ["\t</Boundary>", "\t<LoadData>", '\t\t<load_controller id="1" name="linear_ramp" type="loadcurve">',
          "\t\t\t<interpolate>LINEAR</interpolate>", "\t\t\t<extend>CONSTANT</extend>", "\t\t\t<points>",
          "\t\t\t\t<pt>0,0</pt>", "\t\t\t\t<pt>%s,1</pt>" % fmt(p["end"]), "\t\t\t</points>",
          "\t\t</load_controller>", "\t</LoadData>", "\t<Output>", "\t\t<logfile>"]
    if pulled:
        L += ['\t\t\t<node_data data="Rx" node_set="%s" file="%s.Rx.txt" delim=","/>' % (pulled[0]["set"], base)]
    L += ["\t\t</logfile>", "\t</Output>", "</febio_spec>", ""]
    with open(out, "w") as f:
        f.write("\n".join(L))


def cmd_write(a):
    p = problem_from_deck(a.deck, a.size)
    tmp = tempfile.mkdtemp(prefix="feb-")
    try:
        msh = a.msh or os.path.join(tmp, "mesh.msh")
        run_gmsh(p["geo"], p["h"], p["order"], msh, a.gmsh)
        mesh = febio_mesh(msh, p["body"])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    write_feb(p, mesh, a.out, a.tet10_rule, a.qn, a.tolerances)
    n = len(mesh["x"]) - 1
    print("feb.py: %s: %d nodes, %d cells (%s), %d DOF, h=%s%s" % (a.out, n, len(mesh["tets"]), mesh["type"], 3 * n,
          fmt(p["h"]), ", %d tets turned" % mesh["flipped"] if mesh["flipped"] else ""))


# ---------------------------------------------------------------- FEBio's output
# Terminal control sequences FEBio writes to its screen output: the window title (OSC,
# ESC ] ... BEL or ESC ] ... ESC \\) and any CSI sequence (ESC [ ... letter).
ESCAPES = re.compile(r"\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)|\x1b\[[0-9;?]*[A-Za-z]")
# FEBio's linear solvers that factorise (NumCore: UpdateStats(1) per solve, so "Avg
# iterations per solve" is 1 for them and the product calls x avg counts solves).
DIRECT_SOLVERS = {"pardiso", "pardiso_project", "mkl_dss", "skyline", "superlu", "superlu_mt", "accelerate"}


def read_text(path):
    try:
        with open(path, errors="replace") as fh:
            return fh.read()
    except OSError:
        return ""


def time_line(screen):
    """The last `TIME wall user sys maxrss_kb` line of /usr/bin/time in a screen output with
    its escapes removed, as strings; None without one."""
    m = re.findall(r"^TIME ([\d.]+) ([\d.]+) ([\d.]+) (\d+)", screen, re.M)
    return m[-1] if m else None


def records(path):
    """[(time, {id: [values]})], one per record of an FEBio log-file data file
    (FECore/DataRecord.cpp: "*Step", "*Time", "*Data" lines, then one "id<delim>values" line
    per item)."""
    out = []
    for b in read_text(path).split("*Step")[1:]:
        tm = re.search(r"\*Time\s*=\s*(\S+)", b)
        rows = {}
        for l in b.splitlines()[1:]:
            if l.strip() and not l.startswith("*"):
                parts = [q for q in re.split(r"[,\s]+", l.strip()) if q]
                rows[int(parts[0])] = [float(q) for q in parts[1:]]
        out.append((float(tm.group(1)) if tm else None, rows))
    return out


def same_mesh(h5file, geo_json, cells, unit=""):
    """Stentor's mesh (its HDF5 output) against the one a .feb was written from (the JSON
    beside it: "x", the node coordinates, and "cells", their count): node and cell counts,
    the largest coordinate difference in the same numbering. `cells`: the cells' name."""
    import h5py
    with open(geo_json) as fh:
        g = json.load(fh)
    with h5py.File(h5file, "r") as h:
        X = h["/mesh/coordinates"][()]
        ncell = len(h["/mesh/cell_block"][()])
    if len(X) != len(g["x"]) or ncell != g["cells"]:
        return "different meshes: Stentor %d nodes, %d cells; .feb %d nodes, %d %s" % (len(X), ncell, len(g["x"]), g["cells"], cells)
    d = max(abs(X[i][c] - g["x"][i][c]) for i in range(len(X)) for c in range(3))
    return "same mesh: %d nodes, %d %s, largest coordinate difference %.1e%s" % (len(X), ncell, cells, d, unit)


def feb_settings(feb):
    """From the .feb: DOF, the reaction file, the linear solver type, the convergence tests."""
    text = read_text(feb)
    s = {"dofs": str(3 * len(re.findall(r"<node id=", text))) if text else "?", "rxfile": None}
    rx = re.search(r'<node_data data="Rx"[^>]*file="([^"]+)"', text)
    if rx:
        s["rxfile"] = os.path.join(os.path.dirname(feb), rx.group(1))
    ls = re.search(r'<linear_solver\s+type="([^"]+)"', text)
    s["solver"] = ls.group(1).lower() if ls else "pardiso"  # FEBio's default (FECoreKernel)
    tol = {}
    for k, default in (("dtol", 0.001), ("etol", 0.01), ("rtol", 0.0)):
        m = re.search(r"<%s>\s*([^<\s]+)\s*</%s>" % (k, k), text)
        tol[k] = float(m.group(1)) if m else default
    if (tol["dtol"], tol["etol"], tol["rtol"]) == (0.001, 0.01, 0.0):
        s["tol"] = "default"
    else:
        s["tol"] = ",".join("%s=%g" % (k, tol[k]) for k in ("rtol", "etol", "dtol") if tol[k] > 0) or "none"
    return s


def reaction_sum(rxfile):
    """Sum of the last record's values in a node_data file (FECore/DataRecord.cpp: "*Step",
    "*Time", "*Data" lines, then one "id<delim>value" line per node)."""
    try:
        recs = records(rxfile)
        return "%.10g" % sum(v[0] for v in recs[-1][1].values()) if recs and recs[-1][1] else "?"
    except (IndexError, ValueError):
        return "?"


def parse_febio(feb, log):
    f = {k: "?" for k in ("dofs", "newton", "linear", "setup", "solve", "wall", "cpu", "rss", "column", "status", "tol")}
    s = feb_settings(feb)
    f["dofs"], f["tol"] = s["dofs"], s["tol"]
    screen = ESCAPES.sub("", read_text(log))
    flog = read_text(os.path.splitext(feb)[0] + ".log")
    both = screen + "\n" + flog
    m = time_line(screen)
    if m:
        wall, user, sys_, rss = m
        f["wall"] = wall
        f["cpu"] = "%.1f" % (float(user) + float(sys_))
        f["rss"] = "%.0f" % (int(rss) / 1024)
    # FEBioLib/FEBioModel.cpp, on_cb_stepSolved: one block per analysis step (one here).
    its = re.findall(r"Total number of equilibrium iterations \.+ : (\d+)", flog or screen)
    normal = "N O R M A L   T E R M I N A T I O N" in both
    f["newton"] = its[-1] if its and normal else "failed"
    calls = re.findall(r"Total calls to linear solver \.+ : (\d+)", flog or screen)
    avg = re.findall(r"Avg iterations per solve \.+ : ([\d.eE+-]+)", flog or screen)
    if s["solver"] in DIRECT_SOLVERS:
        f["linear"] = "direct"
    elif calls and avg:
        f["linear"] = "%.0f" % (int(calls[-1]) * float(avg[-1]))
    else:
        f["linear"] = "-"
    f["setup"] = "-"
    m = re.search(r"time in linear solver \.+ : \S+ \(([\d.eE+-]+) sec\)", flog)
    f["solve"] = "%.2f" % float(m.group(1)) if m else "?"
    f["status"] = "yes" if normal else ("E R R O R   T E R M I N A T I O N" if "E R R O R" in both else "crash")
    if s["rxfile"]:
        f["column"] = reaction_sum(s["rxfile"])
    return f


def cmd_parse(a):
    f = parse_febio(a.feb, a.log)
    labels = dict(kv.split("=", 1) for kv in a.label)
    print(a.row.format(**{**labels, **f}))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd")
    sub.required = True
    w = sub.add_parser("write")
    w.add_argument("deck")
    w.add_argument("out")
    w.add_argument("--size", type=float)
    w.add_argument("--gmsh", default=os.environ.get("GMSH", "gmsh"))
    w.add_argument("--msh", help="keep gmsh's mesh in this file")
    w.add_argument("--tet10-rule", choices=["TET10G4", "TET10G8", "TET10GL11"],
                   help="FEBio's integration rule for tet10 (default: FEBio's, TET10G8)")
    w.add_argument("--qn", default="full Newton", choices=["full Newton", "BFGS", "Broyden"],
                   help="FEBio's qn_method (default: full Newton)")
    w.add_argument("--tolerances", default="default", choices=["default", "stentor"],
                   help="FEBio's convergence tests: its defaults (dtol 0.001, etol 0.01) or the residual "
                        "test of the deck's Newton->relative residual tolerance (rtol = tol^2)")
    p = sub.add_parser("parse")
    p.add_argument("feb")
    p.add_argument("log")
    p.add_argument("--label", action="append", default=[])
    p.add_argument("--row", required=True)
    a = ap.parse_args()
    try:
        cmd_write(a) if a.cmd == "write" else cmd_parse(a)
    except Refused as e:
        print("feb.py: %s" % e, file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()

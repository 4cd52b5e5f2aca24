"""cli.perf.feb_cube: the FEBio input perf/solve/feb.py writes for the cube stretch (issue 14)
is the problem Stentor solves, in FEBio 4's format. FEBio itself is not run (not installed);
what FEBio's source says (see feb.py's header) is checked on the file:

- XML: root febio_spec version 4.0; the sections FEBio 4 reads (FEBioXML/FEBioImport.cpp),
  in an order where each reference is defined first; Control: STATIC, the deck's steps and
  step size, solver "solid"; node ids 1..N, element ids 1..E, every node in an element.
- the mesh: node and tet counts equal gmsh's .msh (counted here) and `stentor --check`'s
  for the same deck and size; every tet has a positive volume in FEBio's node order and the
  volumes add up to the cube's; for tet10 each node 4..9 is the midpoint of its corner pair
  in FEBio's order (FETet10::shape_fnc: 0-1, 1-2, 2-0, 0-3, 1-3, 2-3).
- node sets left, front, bottom, right = the nodes with x = 0, y = 0, z = 0, x = 1; the
  boundary conditions and the linear load curve name them.
- the law: W uses only FEBio's variables (I1, I2, J, X, Y, Z) and parser functions ("ln" is
  the natural log, "log" log10, as FECore/MObjBuilder.cpp); W = 0 and FEBio's stress
  s = 2/J [(W1 + I1 W2) B - W2 B^2] + WJ I is 0 at I1 = I2 = 3, J = 1, and equals the
  Cauchy stress of Stentor's Ciarlet-Geymonat law (src/material/CiarletGeymonat.hpp) at a
  finite stretch.
- `feb.py parse` on FEBio output written with FEBio's own format strings.

Usage: feb_cube.py STENTOR WORKDIR SOURCE_ROOT. Exit 77 (skip) without gmsh.
"""
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

stentor, work, root = sys.argv[1], sys.argv[2], os.path.abspath(sys.argv[3])
FEB = os.path.join(root, "perf", "solve", "feb.py")
H = 0.5
failures = []
nodes_of = {}


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


if shutil.which(os.environ.get("GMSH", "gmsh")) is None:
    print("SKIP: no gmsh on PATH")
    sys.exit(77)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

# FEBio's tet10 edges (FECore/FESolidElementShape.cpp): H[4] = 4 r1 r2, H[5] = 4 r2 r3,
# H[6] = 4 r3 r1, H[7] = 4 r1 r4, H[8] = 4 r2 r4, H[9] = 4 r3 r4 (r1..r4: nodes 0..3).
EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
# The sections of a version-4.0 file (FEBioImport.cpp), in the order this file needs them.
SECTIONS = ["Module", "Control", "Globals", "Material", "Mesh", "MeshDomains", "Boundary", "Loads",
            "LoadData", "Output"]
FUNCS = {"ln": math.log, "log": math.log10, "exp": math.exp, "sqrt": math.sqrt, "abs": abs,
         "pow": math.pow}
VARS = ["I1", "I2", "J", "X", "Y", "Z"]


def msh_counts(path):
    """(nodes used by the tets, tets) counted from gmsh's MSH 2.2 file."""
    lines = open(path).read().split("\n")
    i = lines.index("$Elements")
    used, tets = set(), 0
    for l in lines[i + 2:i + 2 + int(lines[i + 1])]:
        v = [int(a) for a in l.split()]
        if v[1] in (4, 11):
            tets += 1
            used.update(v[3 + v[2]:])
    return len(used), tets


def stentor_counts(deck, order):
    """(nodes, cells) of `stentor --check` on deck with Mesh->size H."""
    t = ET.parse(deck)
    mesh = next(c for c in t.getroot() if c.get("name") == "Mesh")
    for p in mesh:
        if p.get("name") == "file":
            p.set("value", os.path.join(os.path.dirname(deck), p.get("value")))
        if p.get("name") == "size":
            p.set("value", repr(H))
    copy = os.path.join(work, "cube_p%d_check.xml" % order)
    t.write(copy)
    r = subprocess.run([stentor, copy, "--check"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, cwd=work)
    m = re.search(r"(\d+) nodes, (\d+) cells \(block: \d+ tet(\d+)\)", r.stdout)
    check(r.returncode == 0 and m is not None, "stentor --check %s: %s" % (copy, r.stdout[-400:]))
    return (int(m.group(1)), int(m.group(2)), int(m.group(3))) if m else (None, None, None)


def energy(expr):
    """W(I1, I2, J) as FEBio evaluates expr (whitespace removed, '^' power)."""
    e = re.sub(r"\s", "", expr)
    check(";" not in e and len(e) < 512, "W: no ';' substitutions and < 512 characters: %r" % expr)
    names = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", re.sub(r"\d+\.?\d*[eE][-+]?\d+", "0", e)))
    check(names <= set(VARS) | set(FUNCS), "W uses only FEBio's variables and functions: %s" % sorted(names))
    check("J" in names and "I3" not in names, "W is written with J (FEBio has no I3)")
    code = compile(e.replace("^", "**"), "W", "eval")
    return lambda I1, I2, J: eval(code, {"__builtins__": {}}, dict(FUNCS, I1=I1, I2=I2, J=J, X=0.0, Y=0.0, Z=0.0))


def febio_stress(W, lam):
    """FEBio's Cauchy stress (FEGenericHyperelastic::Stress) for F = diag(lam): principal values."""
    B = [l * l for l in lam]
    I1 = sum(B)
    I2 = B[0] * B[1] + B[1] * B[2] + B[2] * B[0]
    J = lam[0] * lam[1] * lam[2]
    d = 1e-4
    W1 = (W(I1 + d, I2, J) - W(I1 - d, I2, J)) / (2 * d)
    W2 = (W(I1, I2 + d, J) - W(I1, I2 - d, J)) / (2 * d)
    dj = 1e-6
    WJ = (W(I1, I2, J + dj) - W(I1, I2, J - dj)) / (2 * dj)
    return [2 / J * ((W1 + I1 * W2) * b - W2 * b * b) + WJ for b in B]


def stentor_stress(C1, C2, D, lam):
    """Cauchy stress of Stentor's Ciarlet-Geymonat law: S = 2[(C1 + C2 I1) I - C2 C + (D I3 - K) C^-1],
    sigma = F S F^T / J, for F = diag(lam)."""
    K = C1 + 2 * C2 + D
    C = [l * l for l in lam]
    I1, I3 = sum(C), C[0] * C[1] * C[2]
    J = math.sqrt(I3)
    S = [2 * ((C1 + C2 * I1) - C2 * c + (D * I3 - K) / c) for c in C]
    return [l * l * s / J for l, s in zip(lam, S)]


for order in (1, 2):
    deck = os.path.join(root, "perf", "decks", "cube_p%d.xml" % order)
    feb = os.path.join(work, "cube_p%d.feb" % order)
    msh = os.path.join(work, "cube_p%d.msh" % order)
    r = subprocess.run([sys.executable, FEB, "write", deck, feb, "--size", repr(H), "--msh", msh],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        check(False, "feb.py write P%d: exit %d" % (order, r.returncode))
        continue
    tree = ET.parse(feb)  # well-formed XML or an exception
    top = tree.getroot()
    check(top.tag == "febio_spec" and top.get("version") == "4.0", "root <febio_spec version=\"4.0\">")
    names = [c.tag for c in top]
    check(all(n in SECTIONS for n in names) and names == sorted(names, key=SECTIONS.index) and len(set(names)) == len(names),
          "P%d sections %s in FEBio 4's order" % (order, names))
    for need in ("Module", "Control", "Material", "Mesh", "MeshDomains", "Boundary", "LoadData", "Output"):
        check(top.find(need) is not None, "P%d has <%s>" % (order, need))
    check(top.find("Module").get("type") == "solid", "Module type solid")
    ctl = top.find("Control")
    check(ctl.findtext("analysis") == "STATIC", "Control/analysis STATIC")
    steps, dt = int(ctl.findtext("time_steps")), float(ctl.findtext("step_size"))
    check(steps == 4 and abs(steps * dt - 1.0) < 1e-15, "4 steps of 0.25 (the deck's Stepping)")
    check(ctl.find("solver").get("type") == "solid", "Control/solver type solid")
    check(ctl.find("solver/qn_method").get("type") in ("full Newton", "BFGS", "Broyden"), "qn_method registered")
    ts = ctl.find("time_stepper")
    check(ts is None or abs(float(ts.findtext("dtmax")) - dt) < 1e-15, "time stepper never grows the step")

    # mesh
    mesh = top.find("Mesh")
    nodes = mesh.find("Nodes")
    ids = [int(n.get("id")) for n in nodes]
    check(ids == list(range(1, len(ids) + 1)), "node ids 1..N")
    x = [None] + [tuple(float(v) for v in n.text.split(",")) for n in nodes]
    els = mesh.findall("Elements")
    check(len(els) == 1, "one Elements block")
    el = els[0]
    etype = el.get("type")
    npe = {"tet4": 4, "tet10": 10}.get(etype)
    check(npe == (4 if order == 1 else 10), "Elements type %s for order %d" % (etype, order))
    conn = [[int(v) for v in e.text.split(",")] for e in el]
    check([int(e.get("id")) for e in el] == list(range(1, len(conn) + 1)), "element ids 1..E")
    check(all(len(c) == npe and all(1 <= n < len(x) for n in c) for c in conn), "every element has %s valid node ids" % npe)
    check({n for c in conn for n in c} == set(range(1, len(x))), "every node is in an element")
    nn, ne = len(x) - 1, len(conn)
    nodes_of[order] = nn
    mn, me = msh_counts(msh)
    check((nn, ne) == (mn, me), "P%d: %d nodes, %d tets = gmsh's %d, %d" % (order, nn, ne, mn, me))
    sn, se, st = stentor_counts(deck, order)
    check((nn, ne, st) == (sn, se, 4 if order == 1 else 10),
          "P%d: %d nodes, %d tets = stentor --check's %s, %s (tet%s)" % (order, nn, ne, sn, se, st))
    vol, bad = 0.0, 0
    for c in conn:
        a, b, d, e = (x[k] for k in c[:4])
        u, v, w = ([p[i] - a[i] for i in range(3)] for p in (b, d, e))
        V = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6
        bad += V <= 0
        vol += V
        if npe == 10:
            for k, (i, j) in enumerate(EDGES):
                mid = [(x[c[i]][q] + x[c[j]][q]) / 2 for q in range(3)]
                if max(abs(mid[q] - x[c[4 + k]][q]) for q in range(3)) > 1e-12:
                    bad += 1
    check(bad == 0, "P%d: every tet has a positive volume%s in FEBio's order (%d bad)"
          % (order, " and mid-edge nodes at FEBio's edge midpoints" if npe == 10 else "", bad))
    check(abs(vol - 1.0) < 1e-12, "P%d: tet volumes add up to 1 (%r)" % (order, vol))
    sets = {s.get("name"): sorted(int(v) for v in s.text.replace("\n", ",").split(",") if v.strip())
            for s in mesh.findall("NodeSet")}
    for name, axis, val in (("left", 0, 0.0), ("front", 1, 0.0), ("bottom", 2, 0.0), ("right", 0, 1.0)):
        want = [k for k in range(1, len(x)) if abs(x[k][axis] - val) < 1e-12]
        check(sets.get(name) == want, "P%d: NodeSet %s = the %d nodes with %s = %g" % (order, name, len(want), "xyz"[axis], val))

    # domain, material, boundary conditions, load curve, output
    mat = top.find("Material/material")
    dom = top.find("MeshDomains/SolidDomain")
    check(dom.get("name") == el.get("name") and dom.get("mat") == mat.get("name"), "SolidDomain names the Elements and the material")
    check(mat.get("type") == "hyperelastic", "material type hyperelastic (FEGenericHyperelastic, coupled)")
    bcs = {b.get("node_set"): b for b in top.findall("Boundary/bc")}
    check(len(bcs) == 4 and set(bcs) <= set(sets), "the 4 boundary conditions name the node sets")
    for name, dof in (("left", "x"), ("front", "y"), ("bottom", "z")):
        b = bcs.get(name)
        check(b is not None and b.get("type") == "zero displacement"
              and [b.findtext(c + "_dof") for c in "xyz"] == ["1" if c == dof else "0" for c in "xyz"],
              "%s: zero displacement in %s only" % (name, dof))
    b = bcs.get("right")
    lc = top.find("LoadData/load_controller")
    check(b is not None and b.get("type") == "prescribed displacement" and b.findtext("dof") == "x"
          and float(b.findtext("value")) == 0.2 and b.find("value").get("lc") == lc.get("id") and b.findtext("relative") == "0",
          "right: prescribed x displacement 0.2 on load curve %s" % lc.get("id"))
    pts = [tuple(float(v) for v in p.text.split(",")) for p in lc.findall("points/pt")]
    check(lc.get("type") == "loadcurve" and lc.findtext("interpolate") == "LINEAR" and pts == [(0.0, 0.0), (1.0, 1.0)],
          "load curve: linear from (0, 0) to (1, 1): %s" % pts)
    nd = top.find("Output/logfile/node_data")
    check(nd is not None and nd.get("data") == "Rx" and nd.get("node_set") == "right", "logfile: Rx of the right set")

    W = energy(mat.findtext("W"))
    C1, C2, D = 0.5e6, 0.005e6, 0.35e6  # perf/decks/cube_p*.xml
    check(abs(W(3.0, 3.0, 1.0)) < 1e-9 * C1, "W(3, 3, 1) = 0: %r" % W(3.0, 3.0, 1.0))
    s0 = febio_stress(W, [1.0, 1.0, 1.0])
    check(max(abs(s) for s in s0) < 1e-6 * C1, "zero stress in the reference state: %s" % s0)
    for lam in ([1.2, 0.93, 0.95], [0.8, 1.1, 1.05]):
        a, b = febio_stress(W, lam), stentor_stress(C1, C2, D, lam)
        check(max(abs(p - q) for p, q in zip(a, b)) < 1e-6 * C1, "stress at F = diag%s: FEBio's %s = Stentor's %s" % (lam, a, b))

# feb.py parse on output in FEBio's formats (FEBioLib/FEBioModel.cpp, FECore/DataRecord.cpp).
feb = os.path.join(work, "cube_p1.feb")
base = os.path.splitext(feb)[0]
with open(os.path.join(work, "screen.txt"), "w") as f:
    f.write("\tTotal number of equilibrium iterations ............ : 17\n\n"
            "\n N O R M A L   T E R M I N A T I O N\n\nTIME 3.50 5.25 0.75 204800\n")
with open(base + ".log", "w") as f:
    f.write(" N O N L I N E A R   I T E R A T I O N   I N F O R M A T I O N\n\n"
            "\tNumber of time steps completed .................... : 4\n\n"
            "\tTotal number of equilibrium iterations ............ : 17\n\n"
            "\n L I N E A R   S O L V E R   S T A T S\n\n"
            "\tTotal calls to linear solver ........ : 17\n\n\tAvg iterations per solve ............ : 0\n\n"
            "\t   time in linear solver ........ : 0:00:01 (1.25 sec)\n\n"
            "\n N O R M A L   T E R M I N A T I O N\n\n")
with open(base + ".Rx.txt", "w") as f:
    f.write("*Step  = 1\n*Time  = 0.25\n*Data  = Rx\n2,100\n3,200\n"
            "*Step  = 4\n*Time  = 1\n*Data  = Rx\n2,1000.5\n3,2000.25\n7,-0.75\n")
r = subprocess.run([sys.executable, FEB, "parse", feb, os.path.join(work, "screen.txt"), "--label", "r=2",
                    "--row", "{r}|{dofs}|{newton}|{linear}|{solve}|{wall}|{cpu}|{rss}|{column}|{status}"],
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
want = "2|%s|17|direct|1.25|3.50|6.0|200|3000|yes" % (3 * nodes_of[1] if 1 in nodes_of else "?")
check(r.stdout.strip() == want, "feb.py parse: %r, expected %r" % (r.stdout.strip(), want))

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("OK: FEBio input for P1 and P2 at h = %g" % H)

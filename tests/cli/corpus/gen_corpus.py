#!/usr/bin/env python3
"""Generates a corpus of malformed and hostile inputs for stentor (issue 12).

usage: gen_corpus.py INPUTS_DIR OUT_DIR

From the shipped decks in INPUTS_DIR it writes OUT_DIR/decks/*.xml (mutated decks:
deleted, duplicated, renamed parameters and sublists, wrong types, NaN/Inf/huge/
negative/zero values, absurd mesh sizes, hostile file names, unwritable output
folders, truncated and binary files, entity bombs, deep nesting) and OUT_DIR/meshes/
*.msh (a valid gmsh 4.1 ASCII square and its malformed variants, each with a deck
that reads it). OUT_DIR/cases.tsv lists one case a line:
    name <TAB> kind <TAB> extra stentor arguments <TAB> deck [<TAB> flags]
(arguments space-separated, or a JSON list when they hold spaces; flags: see
issue16_cases). OUT_DIR/geo holds hostile .geo files and OUT_DIR/sentinel is the folder
injected commands try to write into (it must stay empty).
The output is deterministic (a fixed seed). Only the Python standard library is used.
"""
import json
import os
import random
import re
import sys
import xml.etree.ElementTree as ET

RNG = random.Random(12)

# Replacement values for a parameter, by mutation kind, per declared type.
NUMERIC_VALUES = {
    "nan": "nan", "inf": "inf", "neginf": "-inf", "huge": "1e308", "overflow": "1e400",
    "negative": "-1", "zero": "0", "tiny": "1e-300", "empty": "", "text": "abc",
    "hex": "0x1p3", "intmax": "9223372036854775808", "space": " 1 2 ",
}
ARRAY_VALUES = {
    "nan": "{nan}", "inf": "{inf, 0, 0}", "empty": "{}", "long": "{1,2,3,4,5,6,7}",
    "unterminated": "{1.0, 2.0", "text": "{a, b}", "huge": "{1e308, 1e308, 1e308}",
    "nobraces": "1 2 3",
}
STRING_VALUES = {
    "empty": "", "space": " ", "long": "x" * 100000, "traversal": "../../../../../etc/passwd",
    "backquote": "a`touch PWNED`", "newline": "a\nb", "unicode": "\u00e9\u4e2d\U0001F600",
    "nonexistent": "no_such_thing",
}
BOOL_VALUES = {"text": "maybe", "empty": "", "number": "2"}


def write(path, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(path, mode) as f:
        f.write(data)


def load_decks(inputs):
    """The shipped decks, parsed, with Mesh->file made absolute."""
    decks = {}
    for name in sorted(os.listdir(inputs)):
        if not name.endswith(".xml"):
            continue
        tree = ET.parse(os.path.join(inputs, name))
        for p in tree.iter("Parameter"):
            if p.get("name") == "file":
                p.set("value", os.path.abspath(os.path.join(inputs, p.get("value"))))
        decks[name[:-4]] = tree
    return decks


def param_path(root, target):
    """Element path as 'A->B->name' for a Parameter/ParameterList below the root."""
    parents = {c: p for p in root.iter() for c in p}
    names = []
    node = target
    while node is not root:
        names.append(node.get("name", "?"))
        node = parents[node]
    return "->".join(reversed(names)), parents


def values_for(ptype):
    if ptype in ("double", "int"):
        return NUMERIC_VALUES
    if ptype.startswith("Array"):
        return ARRAY_VALUES
    if ptype == "bool":
        return BOOL_VALUES
    return STRING_VALUES


def mutations(elem, is_list):
    """(kind, function(elem, parent)) pairs applicable to one element."""
    def delete(e, p):
        p.remove(e)

    def duplicate(e, p):
        p.insert(list(p).index(e) + 1, ET.fromstring(ET.tostring(e)))

    def rename(e, p):
        e.set("name", e.get("name") + "x")

    muts = [("delete", delete), ("duplicate", duplicate), ("rename", rename)]
    if is_list:
        muts.append(("emptylist", lambda e, p: [e.remove(c) for c in list(e)]))
        return muts
    ptype = elem.get("type", "string")
    muts.append(("type-" + ("string" if ptype != "string" else "double"),
                 lambda e, p: e.set("type", "string" if ptype != "string" else "double")))
    muts.append(("type-bogus", lambda e, p: e.set("type", "complex")))
    muts.append(("no-value", lambda e, p: e.attrib.pop("value", None)))
    for kind, val in values_for(ptype).items():
        muts.append(("value-" + kind, lambda e, p, v=val: e.set("value", v)))
    return muts


def mutate_deck(tree, index, mut):
    """A copy of `tree` with mutation `mut` applied to the index-th element."""
    root = ET.fromstring(ET.tostring(tree.getroot()))
    elems = [e for e in root.iter() if e is not root]
    target = elems[index]
    _, parents = param_path(root, target)
    mut(target, parents[target])
    return ET.tostring(root, encoding="unicode")


def deck_mutants(decks, per_deck):
    """Per shipped deck, `per_deck` mutants chosen at random among all (element, kind)."""
    out = []
    for dname, tree in decks.items():
        root = tree.getroot()
        elems = [e for e in root.iter() if e is not root]
        choices = []
        for i, e in enumerate(elems):
            for kind, fn in mutations(e, e.tag == "ParameterList"):
                choices.append((i, kind, fn))
        for i, kind, fn in RNG.sample(choices, min(per_deck, len(choices))):
            path, _ = param_path(root, elems[i])
            slug = "".join(c if c.isalnum() else "_" for c in path)[:60]
            out.append((f"{dname}.{slug}.{kind}", "param-" + kind.split("-")[0],
                        mutate_deck(tree, i, fn)))
    return out


def set_param(xml_text, listname, pname, ptype, value):
    """`xml_text` with <listname>-><pname> set (added if absent)."""
    root = ET.fromstring(xml_text)
    lst = next((e for e in root if e.get("name") == listname), None)
    if lst is None:
        lst = ET.SubElement(root, "ParameterList", name=listname)
    p = next((e for e in lst if e.get("name") == pname), None)
    if p is None:
        p = ET.SubElement(lst, "Parameter", name=pname)
    p.set("type", ptype)
    p.set("value", value)
    return ET.tostring(root, encoding="unicode")


def targeted_decks(base, meshdir):
    """Mesh, output-folder and file-name cases on one small deck."""
    cases = []
    for v in ["1e-6", "1e-9", "1e-300", "4.9e-324", "-1e-3", "nan", "inf", "1e308"]:
        cases.append((f"mesh_size_{v}", "mesh-size", set_param(base, "Mesh", "size", "double", v)))
    for v in ["1e-300", "-1", "nan", "inf"]:
        xml = set_param(set_param(base, "Mesh", "size", "double", "1e-5"),
                        "Mesh", "max cells", "double", v)
        cases.append((f"max_cells_{v}", "mesh-size", xml))
    for v in ["/dev/zero", "/dev/null", "/dev/urandom", "/", "/proc/self/mem", "/etc/passwd",
              meshdir, os.path.join(meshdir, "garbage.geo"), os.path.join(meshdir, "garbage.msh"),
              "x" * 5000 + ".geo", "/nonexistent/dir/m.msh", "mesh.stl", ""]:
        cases.append((f"mesh_file_{len(cases)}", "mesh-file", set_param(base, "Mesh", "file", "string", v)))
    for v in ["/proc/stentor_out", "/dev/null/out", "/etc/passwd/out", "/sys/out", "",
              "/", "x" * 5000, "../" * 50 + "proc/out"]:
        cases.append((f"outdir_{len(cases)}", "output-dir", set_param(base, "Output", "directory", "string", v)))
    return cases


def file_level_decks(base_text):
    """Truncated, binary and hostile XML files."""
    n = len(base_text)
    cases = [(f"truncated_{k}", "file-truncated", base_text[: n * k // 20]) for k in range(0, 20)]
    raw = base_text.encode()
    for k in range(8):
        pos = RNG.randrange(len(raw))
        cases.append((f"garbage_inserted_{k}", "file-binary", raw[:pos] + os.urandom(16) + raw[pos:]))
    cases.append(("random_bytes", "file-binary", bytes(RNG.randrange(256) for _ in range(4096))))
    cases.append(("nul_bytes", "file-binary", b"\0" * 1024))
    cases.append(("utf16", "file-binary", base_text.encode("utf-16")))
    cases.append(("bom", "file-binary", b"\xef\xbb\xbf" + raw))
    cases.append(("invalid_utf8", "file-binary", raw.replace(b"rubber", b"rub\xff\xfeer")))
    lol = "".join(f'<!ENTITY l{i} "{("&l%d;" % (i - 1)) * 10}">' for i in range(1, 10))
    cases.append(("billion_laughs", "xml-entity",
                  f'<?xml version="1.0"?><!DOCTYPE p [<!ENTITY l0 "lol">{lol}]>'
                  + base_text.replace('value="rubber"', 'value="&l9;"')))
    cases.append(("quadratic_blowup", "xml-entity",
                  f'<?xml version="1.0"?><!DOCTYPE p [<!ENTITY a "{"a" * 50000}">]>'
                  + base_text.replace('value="rubber"', 'value="' + "&a;" * 50000 + '"')))
    cases.append(("external_entity", "xml-entity",
                  '<?xml version="1.0"?><!DOCTYPE p [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
                  + base_text.replace('value="rubber"', 'value="&x;"')))
    cases.append(("external_dtd", "xml-entity",
                  '<?xml version="1.0"?><!DOCTYPE p SYSTEM "http://127.0.0.1:1/x.dtd">' + base_text))
    cases.append(("undefined_entity", "xml-entity", base_text.replace('value="rubber"', 'value="&nope;"')))
    cases.append(("char_ref_nul", "xml-entity", base_text.replace('value="rubber"', 'value="a&#0;b"')))
    for depth in (100, 1000, 10000, 100000):
        cases.append((f"nesting_{depth}", "xml-nesting",
                      '<ParameterList name="stentor">' + '<ParameterList name="a">' * depth
                      + "</ParameterList>" * depth + "</ParameterList>"))
    cases.append(("unclosed_nesting", "xml-nesting", '<ParameterList name="stentor">' + "<a>" * 10000))
    cases.append(("many_attributes", "xml-hostile",
                  base_text.replace("<Parameter ", "<Parameter " + " ".join(f'a{i}="1"' for i in range(5000)) + " ", 1)))
    cases.append(("wrong_root", "xml-hostile", base_text.replace('name="stentor"', 'name="other"', 1)))
    cases.append(("root_not_list", "xml-hostile", "<stentor/>"))
    cases.append(("two_roots", "xml-hostile", base_text + base_text))
    cases.append(("empty", "file-truncated", ""))
    cases.append(("whitespace_only", "file-truncated", "   \n\n  "))
    cases.append(("comment_only", "file-truncated", "<!-- nothing -->"))
    cases.append(("processing_instruction", "xml-hostile", '<?xml-stylesheet href="x"?>' + base_text))
    cases.append(("cdata", "xml-hostile", base_text.replace('value="rubber"', 'value="rubber"><![CDATA[x]]></Parameter><Parameter name="z" type="int" value="1"', 1)))
    return cases


# ---------------------------------------------------------------- meshes (gmsh 4.1 ASCII)

def square_mesh(n=4):
    """A unit square of 2 n^2 triangles: nodes, triangles, boundary lines per side."""
    nodes = [(1 + i + j * (n + 1), i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
    tag = lambda i, j: 1 + i + j * (n + 1)
    tris = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)
            tris += [[a, b, c], [a, c, d]]
    sides = {1: [[tag(i, 0), tag(i + 1, 0)] for i in range(n)],          # bottom
             2: [[tag(n, j), tag(n, j + 1)] for j in range(n)],          # right
             3: [[tag(i + 1, n), tag(i, n)] for i in range(n)],          # top
             4: [[tag(0, j + 1), tag(0, j)] for j in range(n)]}          # left
    return nodes, tris, sides


def msh_sections(nodes, tris, sides):
    """The sections of a gmsh 4.1 file, in order, as (name, body text)."""
    names = {1: "bottom", 2: "right", 3: "top", 4: "left"}
    phys = "\n".join([str(len(names) + 1)] + [f'1 {t} "{s}"' for t, s in names.items()]
                     + ['2 5 "block"'])
    ents = ["0 4 1 0"]
    box = {1: "0 0 0 1 0 0", 2: "1 0 0 1 1 0", 3: "0 1 0 1 1 0", 4: "0 0 0 0 1 0"}
    ents += [f"{t} {box[t]} 1 {t} 0" for t in range(1, 5)]
    ents.append("1 0 0 0 1 1 0 1 5 4 1 2 3 -4")
    ntags = [t for t, _, _ in nodes]
    nod = [f"1 {len(nodes)} {min(ntags)} {max(ntags)}", f"2 1 0 {len(nodes)}"]
    nod += [str(t) for t, _, _ in nodes] + [f"{x!r} {y!r} 0" for _, x, y in nodes]
    nel = len(tris) + sum(len(s) for s in sides.values())
    ele = [f"5 {nel} 1 {nel}"]
    k = 1
    for t, lines in sides.items():
        ele.append(f"1 {t} 1 {len(lines)}")
        for ln in lines:
            ele.append(f"{k} {ln[0]} {ln[1]}")
            k += 1
    ele.append(f"2 1 2 {len(tris)}")
    for tr in tris:
        ele.append(f"{k} {' '.join(map(str, tr))}")
        k += 1
    return [("MeshFormat", "4.1 0 8"), ("PhysicalNames", phys), ("Entities", "\n".join(ents)),
            ("Nodes", "\n".join(nod)), ("Elements", "\n".join(ele))]


def msh_text(sections):
    return "".join(f"${n}\n{b}\n$End{n}\n" for n, b in sections)


def replace_in(sections, name, fn):
    return [(n, fn(b) if n == name else b) for n, b in sections]


def line_edit(idx, fn):
    """A body transform that applies fn to line idx (negative: from the end)."""
    def edit(body):
        lines = body.split("\n")
        lines[idx] = fn(lines[idx])
        return "\n".join(lines)
    return edit


def mesh_mutants():
    nodes, tris, sides = square_mesh()
    base = msh_sections(nodes, tris, sides)
    text = msh_text(base)
    nn = len(nodes)
    out = [("valid", "mesh-valid", text)]
    out += [(f"truncated_{k}", "mesh-truncated", text[: len(text) * k // 12]) for k in range(12)]
    for ver in ["2.2", "4.0", "5.0", "abc", "4.1 1 8", "4.1 0 4", "4.1 0 8 extra"]:
        out.append((f"format_{ver.replace(' ', '_')}", "mesh-header", msh_text(replace_in(base, "MeshFormat", lambda b, v=ver: v))))
    for sec in ["MeshFormat", "PhysicalNames", "Entities", "Nodes", "Elements"]:
        out.append((f"missing_{sec}", "mesh-section", msh_text([s for s in base if s[0] != sec])))
        out.append((f"unterminated_{sec}", "mesh-section", text.replace(f"$End{sec}\n", "")))
    out.append(("sections_reversed", "mesh-section", msh_text(list(reversed(base)))))
    out.append(("nodes_twice", "mesh-section", msh_text(base + [base[3]])))
    for label, hdr in [("more", f"1 {nn + 5} 1 {nn}"), ("fewer", f"1 {nn - 5} 1 {nn}"),
                       ("huge", "1 99999999999999 1 99999999999999"), ("negative", f"1 -5 1 {nn}"),
                       ("blocks", f"7 {nn} 1 {nn}"), ("zero", f"1 0 1 {nn}"), ("text", "a b c d")]:
        out.append((f"node_count_{label}", "mesh-count", msh_text(replace_in(base, "Nodes", line_edit(0, lambda l, h=hdr: h)))))
    out.append(("node_block_count_huge", "mesh-count", msh_text(replace_in(base, "Nodes", line_edit(1, lambda l: "2 1 0 4000000000")))))
    out.append(("element_count_huge", "mesh-count", msh_text(replace_in(base, "Elements", line_edit(0, lambda l: "5 4000000000 1 4000000000")))))
    out.append(("element_block_more", "mesh-count", msh_text(replace_in(base, "Elements", line_edit(-33, lambda l: "2 1 2 40")))))
    for label, tag in [("zero", "0"), ("negative", "-3"), ("beyond", str(nn + 100)), ("huge", "18446744073709551615"), ("text", "x")]:
        out.append((f"element_node_{label}", "mesh-tag", msh_text(replace_in(base, "Elements", line_edit(-1, lambda l, t=tag: " ".join(l.split()[:2] + [t]))))))
    out.append(("element_short", "mesh-tag", msh_text(replace_in(base, "Elements", line_edit(-1, lambda l: " ".join(l.split()[:3]))))))
    out.append(("node_tag_duplicate", "mesh-tag", msh_text(replace_in(base, "Nodes", line_edit(3, lambda l: "1")))))
    out.append(("element_type_unknown", "mesh-tag", msh_text(replace_in(base, "Elements", line_edit(-33, lambda l: "2 1 99 32")))))
    out.append(("entity_undefined", "mesh-tag", msh_text(replace_in(base, "Elements", line_edit(-33, lambda l: "2 7 2 32")))))
    coord_line = 2 + nn + 6  # an interior node's coordinates
    for label, val in [("nan", "nan nan 0"), ("inf", "inf 0 0"), ("huge", "1e308 1e308 0"), ("text", "a b c"),
                       ("short", "0.5"), ("overflow", "1e999 0 0")]:
        out.append((f"coord_{label}", "mesh-coord", msh_text(replace_in(base, "Nodes", line_edit(coord_line, lambda l, v=val: v)))))
    out.append(("all_coords_same", "mesh-geometry", msh_text(msh_sections([(t, 0.0, 0.0) for t, _, _ in nodes], tris, sides))))
    flat = [(t, x, 0.0) for t, x, _ in nodes]
    out.append(("zero_area", "mesh-geometry", msh_text(msh_sections(flat, tris, sides))))
    out.append(("one_inverted", "mesh-geometry", msh_text(msh_sections(nodes, [[t[0], t[2], t[1]]] + tris[1:] if (t := tris[0]) else tris, sides))))
    out.append(("all_inverted", "mesh-geometry", msh_text(msh_sections(nodes, [[a, c, b] for a, b, c in tris], sides))))
    out.append(("collapsed_element", "mesh-geometry", msh_text(msh_sections(nodes, [[tris[0][0]] * 3] + tris[1:], sides))))
    out.append(("random_bytes", "mesh-binary", bytes(RNG.randrange(256) for _ in range(8192))))
    raw = text.encode()
    for k in range(4):
        pos = RNG.randrange(len(raw))
        out.append((f"garbage_{k}", "mesh-binary", raw[:pos] + os.urandom(32) + raw[pos:]))
    out.append(("binary_flag_ascii_body", "mesh-binary", text.replace("4.1 0 8", "4.1 1 8\n\x01\x00\x00\x00", 1)))
    out.append(("nul_file", "mesh-binary", b"\0" * 4096))
    out.append(("empty", "mesh-truncated", ""))
    out.append(("no_physical_surface", "mesh-physical", msh_text(replace_in(base, "PhysicalNames", lambda b: b.replace('2 5 "block"', '2 6 "block"')))))
    out.append(("physical_renamed", "mesh-physical", msh_text(replace_in(base, "PhysicalNames", lambda b: b.replace('"top"', '"lid"')))))
    out.append(("physical_unquoted", "mesh-physical", msh_text(replace_in(base, "PhysicalNames", lambda b: b.replace('"top"', "top")))))
    return out


MESH_DECK = """<ParameterList name="stentor">
  <ParameterList name="Mesh"><Parameter name="file" type="string" value="{mesh}"/></ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="D" type="double" value="0.35e6"/>
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block">
    <Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="clamp"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="bottom"/></ParameterList>
    <ParameterList name="pull"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="top"/>
      <Parameter name="components" type="string" value="y"/>
      <Parameter name="values" type="Array(double)" value="{{0.1}}"/></ParameterList>
  </ParameterList>
  <ParameterList name="Stepping"><Parameter name="steps" type="int" value="2"/></ParameterList>
</ParameterList>
"""


# ------------------------------------------------------------ issue 16: targeted classes
#
# Every case below may carry flags (the 5th column of cases.tsv, space-separated):
#   run            a real run follows a passing --check (the case is cheap)
#   np2            also one of the 2-rank cases (run_corpus.py --np2)
#   concurrent=N   N runs of the deck into one output folder at once (no --check)
#   failwrite=SPEC STENTOR_TEST_FAIL_WRITE=SPEC for the run (src/io/WriteError.hpp)
#   fsize=BYTES    a file size limit (RLIMIT_FSIZE) on the run
#   tmpfs=BYTES    the run writes into a tmpfs of that size (skipped where mount fails)
#   timeout=S      a longer wall-clock limit for this case
#   slow           run only with run_corpus.py --slow (it takes minutes by design)
#   prepare=KIND   run_corpus.py makes the case's folder hostile first (prepare_folder:
#                  links, planted manifests) or fuzzes a checkpoint to restart from
#                  (prepare=ckpt_*: fuzz_checkpoint)
# Injected commands try to create PWNED_<case> files: relative to the working folder
# of whatever runs them, and in the corpus' sentinel folder (absolute, and through
# $PWN_DIR, which run_corpus.py points at it). run_corpus.py asserts none appears.

STATIC_DECK = """<ParameterList name="stentor">
  <ParameterList name="Problem">
    <Parameter name="title" type="string" value="corpus: static pull"/>
  </ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value="{mesh}"/>
    <Parameter name="size" type="double" value="0.5"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="rubber">
      <Parameter name="C1" type="double" value="0.5e6"/>
      <Parameter name="D" type="double" value="0.35e6"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block">
      <Parameter name="material" type="string" value="rubber"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="clamp">
      <Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="left"/>
    </ParameterList>
    <ParameterList name="pull">
      <Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="right"/>
      <Parameter name="components" type="string" value="x"/>
      <Parameter name="values" type="Array(double)" value="{{0.1}}"/>
    </ParameterList>
    <ParameterList name="push">
      <Parameter name="type" type="string" value="traction"/>
      <Parameter name="boundary" type="string" value="top"/>
      <Parameter name="traction" type="Array(double)" value="{{0, -1e4}}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="1.0"/>
    <Parameter name="steps" type="int" value="2"/>
  </ParameterList>
  <ParameterList name="Linear Solver">
    <Parameter name="method" type="string" value="direct"/>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="basename" type="string" value="st"/>
    <ParameterList name="Probes">
      <ParameterList name="corner">
        <Parameter name="point" type="Array(double)" value="{{1, 1}}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
"""

DYNAMIC_DECK = """<ParameterList name="stentor">
  <ParameterList name="Problem">
    <Parameter name="title" type="string" value="corpus: block sliding on a plane"/>
    <Parameter name="analysis" type="string" value="dynamic"/>
  </ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value="{mesh}"/>
    <Parameter name="size" type="double" value="0.5"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="rubber">
      <Parameter name="C1" type="double" value="0.5e6"/>
      <Parameter name="D" type="double" value="0.35e6"/>
      <Parameter name="density" type="double" value="1000"/>
      <Parameter name="viscosity" type="double" value="1000"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block">
      <Parameter name="material" type="string" value="rubber"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="gravity">
      <Parameter name="type" type="string" value="body force"/>
      <Parameter name="force" type="Array(double)" value="{{0, -2e5}}"/>
      <Parameter name="ramp" type="string" value="constant"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Initial Conditions">
    <Parameter name="velocity" type="Array(double)" value="{{1.0, 0.0}}"/>
  </ParameterList>
  <ParameterList name="Contact">
    <ParameterList name="floor">
      <Parameter name="slave" type="string" value="bottom"/>
      <Parameter name="obstacle" type="string" value="plane"/>
      <Parameter name="point" type="Array(double)" value="{{0.0, 0.0}}"/>
      <Parameter name="normal" type="Array(double)" value="{{0.0, 1.0}}"/>
      <Parameter name="friction" type="double" value="0.3"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="0.01"/>
    <Parameter name="steps" type="int" value="5"/>
  </ParameterList>
  <ParameterList name="Linear Solver">
    <Parameter name="method" type="string" value="direct"/>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="basename" type="string" value="dyn"/>
    <ParameterList name="Probes">
      <ParameterList name="corner">
        <Parameter name="point" type="Array(double)" value="{{1, 1}}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
"""


def find_path(root, path):
    """The element at 'A->B->name' below `root` (lists and parameters by name), or None."""
    node = root
    for part in path.split("->"):
        node = next((e for e in node if e.get("name") == part), None)
        if node is None:
            return None
    return node


def set_path(xml_text, path, ptype, value):
    """`xml_text` with the parameter at 'A->B->name' set (sublists and parameter added
    where absent)."""
    root = ET.fromstring(xml_text)
    *lists, pname = path.split("->")
    node = root
    for part in lists:
        nxt = next((e for e in node if e.get("name") == part and e.tag == "ParameterList"), None)
        if nxt is None:
            nxt = ET.SubElement(node, "ParameterList", name=part)
        node = nxt
    p = next((e for e in node if e.get("name") == pname and e.tag == "Parameter"), None)
    if p is None:
        p = ET.SubElement(node, "Parameter", name=pname)
    p.set("type", ptype)
    p.set("value", value)
    return ET.tostring(root, encoding="unicode")


def rename_path(xml_text, path, new_name, refs=()):
    """`xml_text` with the sublist at `path` renamed, and every parameter value in
    `refs` (paths) that named it renamed too."""
    root = ET.fromstring(xml_text)
    old = find_path(root, path).get("name")
    find_path(root, path).set("name", new_name)
    for r in refs:
        e = find_path(root, r)
        if e is not None and e.get("value") == old:
            e.set("value", new_name)
    return ET.tostring(root, encoding="unicode")


def payloads(cid, sentinel):
    """(label, text) pairs: a command for the shell (backquotes, $(...)), for gnuplot
    (system(), quote breaking, a newline then !), and file-name oddities."""
    rel = f"touch PWNED_{cid}"
    env = f'touch "$PWN_DIR/PWNED_{cid}_env"'
    ab = f"touch {sentinel}/PWNED_{cid}_abs"
    return [
        ("bq", f"a`{rel}`b"), ("bqenv", f"a`{env}`b"), ("dollar", f"a$({env})b"),
        ("sq_bq", f"a'`{ab}`'b"), ("sq_break", f"x'; system('{ab}'); print 'x"),
        ("dq_break", f'x"; system("{ab}"); print "x'), ("concat", f"x' . system('{ab}') . 'x"),
        ("newline", f"x\n!{ab}\n"), ("crlf", f"x\r\nsystem('{ab}')\r\n"), ("pipe", f"|{ab}"),
        ("semicolon", f"x;{rel};"), ("backslash", f"x\\'; system('{ab}') #"),
        ("dash", "-x"), ("dots", ".."), ("space", " "), ("long", "n" * 300),
        ("rtl", "a\u202eb"), ("enhanced", "a@{/=40 x}^{2}_y"),
    ]


def injection_cases(mesh, sentinel):
    """Deck text that reaches gnuplot scripts, CSV headers or file names."""
    st = STATIC_DECK.format(mesh=mesh)
    dy = DYNAMIC_DECK.format(mesh=mesh)
    out = []
    places = [
        ("load", st, lambda x, v: rename_path(x, "Boundary Conditions->pull", v)),
        ("traction", st, lambda x, v: rename_path(x, "Boundary Conditions->push", v)),
        ("probe", st, lambda x, v: rename_path(x, "Output->Probes->corner", v)),
        ("basename", st, lambda x, v: set_path(x, "Output->basename", "string", v)),
        ("title", st, lambda x, v: set_path(x, "Problem->title", "string", v)),
        ("body", st, lambda x, v: rename_path(x, "Bodies->block", v)),
        ("material", st, lambda x, v: rename_path(x, "Materials->rubber", v, ["Bodies->block->material"])),
        ("directory", st, lambda x, v: set_path(x, "Output->directory", "string", "out_" + v)),
        ("contact", dy, lambda x, v: rename_path(x, "Contact->floor", v)),
        ("dynprobe", dy, lambda x, v: rename_path(x, "Output->Probes->corner", v)),
        ("stage", st, lambda x, v: set_path(set_path(x, f"Stages->{v}->steps", "int", "1"),
                                            "Stepping->steps", "int", "2")),
    ]
    for where, base, edit in places:
        for label, _ in payloads("x", sentinel):
            cid = f"inj_{where}_{label}"
            text = dict(payloads(cid, sentinel))[label]
            try:
                xml = edit(base, text)
            except (ValueError, TypeError):
                continue
            out.append((cid, "inject-" + where, xml, "", "run"))
    # The same through --output (a folder name) and a raw newline in an attribute (XML
    # normalises it to a space) rather than &#10;.
    for label, text in payloads("o", sentinel):
        if "\n" in text or "\r" in text or label in ("long", "space"):
            continue
        cid = f"inj_cli_output_{label}"
        text = dict(payloads(cid, sentinel))[label]
        out.append((cid, "inject-output", st, ["--output", "o_" + text], "run"))
    raw = st.replace('name="pull"', 'name="pu\nll`touch PWNED_inj_rawnl`"', 1)
    out.append(("inj_load_rawnewline", "inject-load", raw, "", "run"))
    return out


GEO_BASE = """// corpus: the unit square of block2d.geo
Point(1) = {0, 0, 0, 0.5};
Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5};
Point(4) = {0, 1, 0, 0.5};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("block") = {1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
"""


SLOW_GEO = ("loop", "loop_nested", "recursion", "mesh_smoothing")


def geo_cases(geodir, sentinel, bad_msh):
    """.geo files that try to run programs, write files, end the process, loop, or
    mesh without bounds, each read by the static deck (and its run where --check passes)."""
    s = sentinel
    other = os.path.join(geodir, "other")
    os.makedirs(other, exist_ok=True)
    # Helper files an Include/Merge can reach: commands in files without a .geo name.
    def helper(name, text):
        p = os.path.join(other, name)
        write(p, text)
        return p
    cases = {
        "systemcall": 'SystemCall "touch {s}/PWNED_{id}";',
        "system": 'System "touch {s}/PWNED_{id}";',
        "nonblocking": 'NonBlockingSystemCall "touch {s}/PWNED_{id}";',
        "onelabrun": 'OnelabRun("x", "touch {s}/PWNED_{id}");',
        "onelabaction": 'OnelabAction "x";',
        "printf_to_file": 'Printf("x") > "{s}/PWNED_{id}";',
        "printf_append": 'Printf("x") >> "{s}/PWNED_{id}";',
        "printf_relative": 'Printf("x") > "PWNED_{id}";',
        "save": 'Save "{s}/PWNED_{id}.msh";',
        "print": 'Print "{s}/PWNED_{id}.png";',
        "createdir": 'CreateDir "{s}/PWNED_{id}";',
        "exit": "Exit;",
        "abort": "Abort;",
        "sleep": "Sleep 1000;",
        "mesh2": "Mesh 2;",
        "refinemesh": "RefineMesh;",
        "abort_on_error": 'General.AbortOnError = 4;\nError("x");',
        "solver_executable": 'Solver.Executable0 = "/bin/sh";\nOnelabRun("x");',
        "general_filename": 'General.DefaultFileName = "{s}/PWNED_{id}.geo";',
        "save_options": 'General.OptionsFileName = "{s}/PWNED_{id}.opt";\nGeneral.SaveOptions = 1;',
        "single_quotes": "Printf('\"');\nSystemCall 'touch {s}/PWNED_{id}';\nPrintf('\"');",
        "backslash": 'Printf("\\");\nSystemCall "touch {s}/PWNED_{id}";\nPrintf("\\");',
        "comment_trick": '/* "*/ SystemCall "touch {s}/PWNED_{id}"; // "',
        "include_txt": 'Include "{h:inc.txt}";',
        "include_noext": 'Include "{h:incfile}";',
        "merge_txt": 'Merge "{h:inc.txt}";',
        "merge_bbox": 'MergeWithBoundingBox "{h:inc.txt}";',
        "merge_bbox_geo": 'MergeWithBoundingBox "{h:inc2.geo}";',
        "include_upper": 'Include "{h:inc.GEO}";',
        "include_geo": 'Include "{h:inc3.geo}";',
        "include_exit": 'Include "{h:exit.geo}";',
        "include_passwd": 'Include "/etc/passwd";',
        "include_devzero": 'Include "/dev/zero";',
        "include_stdin": 'Include "/dev/stdin";',
        "include_proc": 'Include "/proc/self/environ";',
        "include_dir": 'Include "/";',
        "include_missing": 'Include "/nonexistent/x.geo";',
        "include_traversal": 'Include "../../../../../../../../etc/hostname";',
        "include_computed": 'Include StrCat("in", "c.geo");',
        "include_self": 'Include "{self}";',
        "merge_bad_msh": 'Merge "{bad_msh}";',
        "merge_garbage_step": 'SetFactory("OpenCASCADE");\nMerge "{h:garbage.step}";',
        "shapefromfile": 'SetFactory("OpenCASCADE");\nv() = ShapeFromFile("/etc/passwd");',
        "listfromfile": 'x() = ListFromFile("/etc/hostname");',
        "format_s": 'Printf("%s %s %s %s", 1, 2, 3, 4);',
        "format_n": 'Printf("%n %n %n %n");',
        "format_width": 'Printf("%999999999g", 1);',
        "sprintf_n": 'x = StrLen(Sprintf("%n", 1));',
        "loop": "For i In {1:1e9}\n  x = i;\nEndFor",
        "loop_nested": "For i In {1:1e5}\nFor j In {1:1e5}\nEndFor\nEndFor",
        "recursion": "Macro m\n  Call m;\nReturn\nCall m;",
        "huge_list": "x[] = {1:1e9};",
        "mesh_size_factor": "Mesh.MeshSizeFactor = 1e-9;",
        "mesh_size_field": 'Field[1] = MathEval;\nField[1].F = "1e-9";\nBackground Field = 1;',
        "mesh_size_min_max": "Mesh.MeshSizeMin = 1e-9;\nMesh.MeshSizeMax = 1e-9;",
        "mesh_transfinite": "Transfinite Curve{1} = 1e9;",
        "mesh_layers": "Extrude {0, 0.1, 0} { Curve{3}; Layers{100000000}; }",
        "mesh_smoothing": "Mesh.Smoothing = 1000000000;",
        "mesh_algorithm8": "Mesh.Algorithm = 8;\nMesh.RecombineAll = 1;",
        "mesh_threads": "General.NumThreads = 100000;",
        "mesh_min_curve_points": "Mesh.MinimumCurvePoints = 1000000000;",
        "delete_physicals": "Delete Physicals;",
        "delete_model": "Delete Model;",
        "physical_injection": 'Physical Curve("r`touch {s}/PWNED_{id}`") = {2};',
        "getenv": 'Printf(GetEnv("HOME"));',
        "nan_point": "Point(99) = {0/0, 1e999, 0};",
        "tiny_point_size": "Characteristic Length{1, 2, 3, 4} = 1e-300;",
    }
    helper("inc.txt", f'SystemCall "touch {s}/PWNED_geo_include_txt";\n'
                      f'SystemCall "touch {s}/PWNED_geo_merge_txt";\n'
                      f'SystemCall "touch {s}/PWNED_geo_merge_bbox";\n')
    helper("incfile", f'SystemCall "touch {s}/PWNED_geo_include_noext";\n')
    helper("inc2.geo", f'SystemCall "touch {s}/PWNED_geo_merge_bbox_geo";\n')
    helper("inc.GEO", f'SystemCall "touch {s}/PWNED_geo_include_upper";\n')
    helper("inc3.geo", f'Include "incfile";\nPrintf("x") > "{s}/PWNED_geo_include_geo";\n')
    helper("exit.geo", "Exit;\n")
    helper("garbage.step", "ISO-10303-21;\nHEADER;\n#1=garbage(\x01\x02;\nEND-ISO-10303-21;\n" + "x" * 1000)
    out = []
    for name, tail in cases.items():
        cid = f"geo_{name}"
        path = os.path.join(geodir, cid + ".geo")
        text = tail.replace("{s}", s).replace("{id}", cid).replace("{self}", path)
        text = text.replace("{bad_msh}", bad_msh)
        text = re.sub(r"\{h:([^}]*)\}", lambda m: os.path.join(other, m.group(1)), text)
        write(path, GEO_BASE + text + "\n")
        deck = STATIC_DECK.format(mesh=path)
        if name.startswith("physical_injection"):
            deck = deck.replace('value="right"', f'value="r`touch {s}/PWNED_{cid}`"')
        # These run until the default 'Mesh->time limit' (600 s) stops gmsh: only with
        # run_corpus.py --slow; their *_limited twins below show the same with 3 s.
        flags = "run slow timeout=700" if name in SLOW_GEO else "run"
        out.append((cid, "geo-command", deck, "", flags))
    # The same commands with a time limit in the deck, for the ones that take forever.
    for name in SLOW_GEO:
        cid = f"geo_{name}_limited"
        path = os.path.join(geodir, f"geo_{name}.geo")
        deck = set_path(STATIC_DECK.format(mesh=path), "Mesh->time limit", "double", "3")
        out.append((cid, "geo-command", deck, "", "run"))
    # A mesh file whose name hides .msh content (gmsh reads it by content).
    dat = os.path.join(geodir, "bad_msh_content.dat")
    with open(bad_msh, "rb") as f:
        write(dat, f.read())
    out.append(("geo_msh_as_dat", "geo-command", STATIC_DECK.format(mesh=dat), "", "run"))
    # A file named with shell metacharacters (no shell is involved: it is just a name).
    odd = os.path.join(geodir, "b`touch PWNED_geo_name`$(touch PWNED_geo_name2).geo")
    write(odd, GEO_BASE)
    out.append(("geo_odd_name", "geo-command", STATIC_DECK.format(mesh=odd), "", "run"))
    return out


# Values no deck number may take silently: NaN, infinities, overflow, hex floats,
# denormals (accepted where in range: they are finite numbers), and near-misses of the
# number syntax.
SCALAR_SPECIALS = {
    "nan": "nan", "NaN": "NaN", "negnan": "-nan", "inf": "inf", "Infinity": "Infinity",
    "neginf": "-inf", "1e999": "1e999", "neg1e999": "-1e999", "hex": "0x1p-2", "hexint": "0x10",
    "denormal": "4.9e-324", "denormal2": "1e-310", "underflow": "1e-400", "minnormal": "2.2250738585072014e-308",
    "trailing": "1.0abc", "twodots": "1.0.0", "comma": "1,5", "exp_only": "1e", "arabic": "\u0661",
    "fullwidth": "\uff11", "space_inside": "1 0",
}
ARRAY_SPECIALS = {
    "nan": "{nan}", "inf": "{inf}", "hex": "{0x1p-2}", "1e999": "{1e999}", "neg1e999": "{-1e999}",
    "denormal": "{4.9e-324}", "denormal2": "{1e-310}", "mixed_nan": "{1, nan}", "spaced_inf": "{ inf , 0 }",
    "huge2": "{1e308, 1e308}", "text": "{1, a}", "nested": "{{1}}", "semicolon": "{1; 2}",
    "empty_item": "{1,,2}", "trailing_comma": "{1, 2,}", "hexint": "{0x10, 0}",
}


def nonfinite_cases(mesh):
    st = STATIC_DECK.format(mesh=mesh)
    dy = DYNAMIC_DECK.format(mesh=mesh)
    out = []
    scalars = [(st, "Materials->rubber->C1", "double"), (st, "Stepping->end time", "double"),
               (st, "Mesh->size", "double"), (st, "Stepping->steps", "int"),
               (dy, "Materials->rubber->density", "double"), (dy, "Contact->floor->friction", "double"),
               (st, "Newton->relative residual tolerance", "double"), (st, "Linear Solver->tolerance", "double")]
    arrays = [(st, "Boundary Conditions->pull->values"), (st, "Boundary Conditions->push->traction"),
              (st, "Output->Probes->corner->point"), (dy, "Contact->floor->point"),
              (dy, "Contact->floor->normal"), (dy, "Initial Conditions->velocity"),
              (dy, "Boundary Conditions->gravity->force")]
    for base, path, ptype in scalars:
        slug = path.split("->")[-1].replace(" ", "_")
        for label, v in SCALAR_SPECIALS.items():
            out.append((f"num_{slug}_{label}", "nonfinite-scalar", set_path(base, path, ptype, v), "", "run"))
    for base, path in arrays:
        slug = "_".join(path.split("->")[-2:]).replace(" ", "_")
        for label, v in ARRAY_SPECIALS.items():
            out.append((f"arr_{slug}_{label}", "nonfinite-array", set_path(base, path, "Array(double)", v), "", "run"))
    # Values that are finite but overflow what is computed from them.
    for path, v in [("Boundary Conditions->push->traction", "{0, 1e300}"), ("Materials->rubber->C1", "1e308"),
                    ("Materials->rubber->D", "1e-308"), ("Boundary Conditions->pull->values", "{1e200}")]:
        typ = "Array(double)" if v.startswith("{") else "double"
        out.append((f"overflow_{path.split('->')[-1]}", "nonfinite-overflow", set_path(st, path, typ, v), "", "run"))
    for path, v in [("Initial Conditions->velocity", "{1e300, 0}"), ("Materials->rubber->density", "1e-300"),
                    ("Boundary Conditions->gravity->force", "{0, -1e300}")]:
        typ = "Array(double)" if v.startswith("{") else "double"
        out.append((f"overflow_dyn_{path.split('->')[-1]}", "nonfinite-overflow", set_path(dy, path, typ, v), "", "run"))
    return out


def deep_xml_cases(mesh):
    st = STATIC_DECK.format(mesh=mesh)
    out = []
    for depth in (62, 63, 64, 65, 200, 300000):
        inner = '<ParameterList name="a">' * depth + "</ParameterList>" * depth
        out.append((f"deep_materials_{depth}", "xml-deep",
                    st.replace('<ParameterList name="Materials">', '<ParameterList name="Materials">' + inner, 1), "", "run"))
    out.append(("deep_parameters", "xml-deep", st.replace("<ParameterList name=\"Problem\">",
                "<ParameterList name=\"Problem\">" + '<Parameter name="p">' * 20000 + "</Parameter>" * 20000, 1), "", ""))
    out.append(("deep_other_elements", "xml-deep", st.replace("</ParameterList>\n</ParameterList>",
                "</ParameterList>" + "<x>" * 50000 + "</x>" * 50000 + "\n</ParameterList>", 1), "", ""))
    out.append(("deep_newlines", "xml-deep", '<ParameterList name="stentor">\n' + '<ParameterList name="a">\n' * 5000
                + "</ParameterList>\n" * 5000 + "</ParameterList>\n", "", ""))
    out.append(("deep_comments", "xml-deep", st.replace("<ParameterList name=\"Mesh\">",
                "<!--" + "<ParameterList name='a'>" * 100000 + "--><ParameterList name=\"Mesh\">", 1), "", "run"))
    out.append(("deep_unclosed_valid_prefix", "xml-deep", st[: st.index("<ParameterList name=\"Bodies\">")]
                + '<ParameterList name="a">' * 100000, "", ""))
    out.append(("wide_many_lists", "xml-deep", st.replace("<ParameterList name=\"Bodies\">",
                "".join(f'<ParameterList name="m{i}"><Parameter name="C1" type="double" value="1"/></ParameterList>'
                        for i in range(20000)) + "<ParameterList name=\"Bodies\">", 1), "", ""))
    out.append(("many_probes", "xml-deep", st.replace("<ParameterList name=\"Probes\">", "<ParameterList name=\"Probes\">"
                + "".join(f'<ParameterList name="p{i}"><Parameter name="point" type="Array(double)" value="{{0.5, 0.5}}"/>'
                          "</ParameterList>" for i in range(2000)), 1), "", "run"))
    return out


def tiny_size_cases(mesh, mesh3d):
    out = []
    for label, v in [("1e-7", "1e-7"), ("1e-12", "1e-12"), ("1e-200", "1e-200"), ("denormal", "1e-310"),
                     ("smallest", "4.9e-324"), ("minnormal", "2.2250738585072014e-308"), ("neg_denormal", "-1e-310"),
                     ("0", "0"), ("neg0", "-0")]:
        out.append((f"size2d_{label}", "mesh-tiny", set_path(STATIC_DECK.format(mesh=mesh), "Mesh->size", "double", v), "", "run"))
        deck3d = set_path(set_path(STATIC_DECK.format(mesh=mesh3d), "Mesh->size", "double", v),
                          "Boundary Conditions->push->traction", "Array(double)", "{0, -1e4, 0}")
        deck3d = set_path(deck3d, "Output->Probes->corner->point", "Array(double)", "{1, 1, 1}")
        out.append((f"size3d_{label}", "mesh-tiny", deck3d, "", ""))
    for label, v in [("max_cells_denormal", "1e-310"), ("max_cells_0", "0")]:
        out.append((f"size2d_{label}", "mesh-tiny", set_path(set_path(STATIC_DECK.format(mesh=mesh), "Mesh->size", "double", "1e-4"),
                                                               "Mesh->max cells", "double", v), "", ""))
    # 'Mesh->max cells' raised on purpose meshes as asked: bounded by 'Mesh->time limit'.
    big = set_path(set_path(STATIC_DECK.format(mesh=mesh), "Mesh->size", "double", "1e-4"), "Mesh->max cells", "double", "1e300")
    out.append(("size2d_max_cells_1e300_limited", "mesh-tiny", set_path(big, "Mesh->time limit", "double", "3"), "", ""))
    for label, v in [("0", "0"), ("neg", "-1"), ("nan", "nan"), ("inf", "inf"), ("denormal", "1e-310"), ("huge", "1e308")]:
        out.append((f"time_limit_{label}", "mesh-tiny", set_path(STATIC_DECK.format(mesh=mesh), "Mesh->time limit", "double", v), "", "run"))
    # The .geo's own tiny sizes (no Mesh->size): the curve mesh is made first.
    return out


def solver_cases(mesh):
    base = set_path(STATIC_DECK.format(mesh=mesh), "Linear Solver->method", "string", "gmres")
    cases = [
        ("Belos", "Num Blocks", "int", "0"), ("Belos", "Num Blocks", "int", "-1"), ("Belos", "Num Blocks", "int", "1000000000"),
        ("Belos", "Num Blocks", "string", "abc"), ("Belos", "Num Blocks", "double", "2.5"),
        ("Belos", "Maximum Iterations", "int", "-1"), ("Belos", "Maximum Iterations", "int", "0"),
        ("Belos", "Convergence Tolerance", "double", "nan"), ("Belos", "Convergence Tolerance", "double", "-1"),
        ("Belos", "Convergence Tolerance", "double", "inf"), ("Belos", "Convergence Tolerance", "string", "tight"),
        ("Belos", "Orthogonalization", "string", "NOPE"), ("Belos", "Verbosity", "int", "2147483647"),
        ("Belos", "Output Frequency", "int", "-5"), ("Belos", "Implicit Residual Scaling", "string", "NOPE"),
        ("Belos", "Maximum Restarts", "int", "-1"), ("Belos", "Block Size", "int", "0"),
        ("MueLu", "max levels", "int", "0"), ("MueLu", "max levels", "int", "-1"), ("MueLu", "max levels", "int", "1000000"),
        ("MueLu", "max levels", "string", "many"), ("MueLu", "smoother: type", "string", "NOPE"),
        ("MueLu", "coarse: type", "string", "NOPE"), ("MueLu", "coarse: max size", "int", "-1"),
        ("MueLu", "coarse: max size", "int", "0"), ("MueLu", "aggregation: type", "string", "NOPE"),
        ("MueLu", "multigrid algorithm", "string", "NOPE"), ("MueLu", "verbosity", "string", "NOPE"),
        ("MueLu", "number of equations", "int", "0"), ("MueLu", "number of equations", "int", "7"),
        ("MueLu", "problem: symmetric", "string", "maybe"), ("MueLu", "reuse: type", "string", "NOPE"),
        ("MueLu", "repartition: enable", "bool", "true"), ("MueLu", "aggregation: drop tol", "double", "nan"),
        ("MueLu", "sa: damping factor", "double", "inf"), ("MueLu", "smoother: params", "string", "x"),
        ("MueLu", "no such key", "int", "1"),
        ("Ifpack2", "schwarz: overlap level", "int", "-1"), ("Ifpack2", "schwarz: overlap level", "int", "1000000"),
        ("Ifpack2", "fact: iluk level-of-fill", "int", "-1"), ("Ifpack2", "fact: drop tolerance", "double", "nan"),
        ("Ifpack2", "schwarz: subdomain solver name", "string", "NOPE"), ("Ifpack2", "relaxation: type", "string", "NOPE"),
        ("Ifpack2", "schwarz: combine mode", "string", "NOPE"), ("Ifpack2", "fact: absolute threshold", "string", "x"),
        ("Amesos2", "Transpose", "string", "maybe"), ("Amesos2", "Foo", "int", "1"), ("Amesos2", "Transpose", "bool", "true"),
    ]
    out = []
    for pkg, key, typ, v in cases:
        pre = {"MueLu": "muelu", "Ifpack2": "schwarz", "Belos": "auto", "Amesos2": "auto"}[pkg]
        deck = set_path(base, "Linear Solver->preconditioner", "string", pre)
        if pkg == "Amesos2":
            deck = set_path(deck, "Linear Solver->method", "string", "direct")
        slug = re.sub(r"[^A-Za-z0-9]+", "_", f"{pkg}_{key}_{typ}_{v}")[:60]
        out.append((f"solver_{slug}", "solver-list", set_path(deck, f"Linear Solver->{pkg}->{key}", typ, v), "", "run"))
    # Sublists where parameters are expected, parameters where sublists are, and the
    # documented option combinations.
    out.append(("solver_belos_as_param", "solver-list", set_path(base, "Linear Solver->Belos", "string", "x"), "", "run"))
    nested = set_path(base, "Linear Solver->MueLu->level 0->smoother: type", "string", "NOPE")
    out.append(("solver_muelu_level_list", "solver-list", set_path(nested, "Linear Solver->preconditioner", "string", "muelu"), "", "run"))
    for pre, sub in [("schwarz", "KLU2"), ("schwarz", "RILUK"), ("schwarz", "NOPE"), ("muelu", "KLU2"), ("NOPE", "RILUK")]:
        d = set_path(set_path(base, "Linear Solver->preconditioner", "string", pre), "Linear Solver->subdomain solver", "string", sub)
        out.append((f"solver_combo_{pre}_{sub}", "solver-list", d, "", "run"))
    for key, v in [("fill level", "1000000"), ("overlap", "1000000"), ("restart", "1000000000"),
                   ("max iterations", "2147483647"), ("preconditioner reuse", "-1")]:
        d = set_path(set_path(base, "Linear Solver->preconditioner", "string", "schwarz"), f"Linear Solver->{key}", "int", v)
        out.append((f"solver_{key.replace(' ', '_')}_{v}", "solver-list", d, "", "run"))
    return out


def concurrent_cases(mesh, out_dir):
    """Runs into one output folder at once (run_corpus.py starts them together, or 0.3 s
    apart with `stagger`); `alt=FILE`: every other run reads that deck instead."""
    st = set_path(STATIC_DECK.format(mesh=mesh), "Stepping->steps", "int", "6")
    alt = os.path.join(os.path.abspath(out_dir), "decks", "concurrent_alt_deck.xml")
    write(alt, set_path(st, "Output->basename", "string", "other"))
    return [
        ("concurrent_2_same", "concurrent", st, "", "concurrent=2"),
        ("concurrent_3_same", "concurrent", st, "", "concurrent=3"),
        ("concurrent_4_same", "concurrent", st, "", "concurrent=4"),
        ("concurrent_2_other_basename", "concurrent", st, "", f"concurrent=2 alt={alt}"),
        ("concurrent_2_overwrite", "concurrent", st, ["--overwrite"], "concurrent=2"),
        ("concurrent_3_staggered", "concurrent", st, "", "concurrent=3 stagger"),
    ]


def write_failure_cases(mesh):
    st = set_path(STATIC_DECK.format(mesh=mesh), "Stepping->steps", "int", "4")
    dy = DYNAMIC_DECK.format(mesh=mesh)
    out = []
    for name, spec in [("history", "st_history.csv:2"), ("h5", "st.h5:2"), ("xdmf", "st.xdmf.tmp:3"), ("log", "st.log:5"),
                       ("gp", "st_reactions.gp"), ("probes_gp", "st_probes.gp"), ("manifest", "stentor-manifest.txt.tmp"),
                       ("h5_first", "st.h5")]:
        out.append((f"failwrite_{name}", "write-fail", st, "", f"failwrite={spec}"))
    for name, spec in [("energy", "dyn_energy.csv:2"), ("energy_gp", "dyn_energy.gp")]:
        out.append((f"failwrite_dyn_{name}", "write-fail", dy, "", f"failwrite={spec}"))
    # The limit is set once the run's folder exists (run_corpus.py): 200 steps keep the
    # run writing for a second or more after that, so it meets the .h5 and the CSV, not
    # only the plots at the end.
    long_run = set_path(st, "Stepping->steps", "int", "200")
    for size in (1, 512, 4096, 20000, 60000, 200000):
        out.append((f"fsize_{size}", "write-fail", long_run, "", f"fsize={size}"))
    for size in (4096, 32768, 131072, 262144):
        out.append((f"tmpfs_{size}", "write-fail", st, "", f"tmpfs={size}"))
        out.append((f"tmpfs_dyn_{size}", "write-fail", dy, "", f"tmpfs={size}"))
    return out


def output_trust_cases(mesh):
    """Links in and around the output folder, planted and malformed manifests, fuzzed
    checkpoints (prepared by run_corpus.py: prepare_folder, fuzz_checkpoint)."""
    st = set_path(STATIC_DECK.format(mesh=mesh), "Stepping->steps", "int", "3")
    ck = set_path(st, "Output->checkpoint every", "int", "1")
    out = []
    for kind in ("lock_link", "lock_dangling", "partial_link", "manifest_link", "manifest_planted", "manifest_v2_wrong_hash",
                 "manifest_forged_names", "manifest_garbage"):
        out.append((f"trust_{kind}", "output-trust", st, ["--output", "out"], f"run prepare={kind}"))
    out.append(("trust_result_link", "output-trust", st, ["--overwrite", "--output", "out"], "run np2 prepare=result_link"))
    for kind in ("truncated", "bitflip", "nan", "one_column", "int_values", "huge_rows", "time_array", "time_nan", "step_huge",
                 "ids_negative", "no_tables"):
        np2 = " np2" if kind in ("bitflip", "one_column", "time_array") else ""
        out.append((f"ckpt_{kind}", "checkpoint-fuzz", ck, ["--output", "out"], f"run{np2} prepare=ckpt_{kind} timeout=40"))
    return out


def issue16_cases(inputs, out_dir, meshdir):
    """All the issue-16 classes: (name, kind, deck text, args, flags)."""
    sentinel = os.path.join(os.path.abspath(out_dir), "sentinel")
    os.makedirs(sentinel, exist_ok=True)
    geodir = os.path.join(os.path.abspath(out_dir), "geo")
    os.makedirs(geodir, exist_ok=True)
    mesh = os.path.abspath(os.path.join(inputs, "block2d.geo"))
    mesh3d = os.path.abspath(os.path.join(inputs, "block3d.geo"))
    bad_msh = os.path.abspath(os.path.join(meshdir, "node_count_fewer.msh"))
    cases = []
    cases += injection_cases(mesh, sentinel)
    cases += geo_cases(geodir, sentinel, bad_msh)
    cases += nonfinite_cases(mesh)
    cases += deep_xml_cases(mesh)
    cases += tiny_size_cases(mesh, mesh3d)
    cases += solver_cases(mesh)
    cases += concurrent_cases(mesh, out_dir)
    cases += write_failure_cases(mesh)
    cases += output_trust_cases(mesh)
    return cases


def main():
    inputs, out = sys.argv[1], sys.argv[2]
    for sub in ("decks", "meshes"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    rows = []

    def add(name, kind, data, ext="xml", args="", flags=""):
        path = os.path.join(out, "decks", f"{name}.{ext}")
        write(path, data)
        if isinstance(args, list):
            args = json.dumps(args)
        rows.append((name, kind, args, path, flags))

    decks = load_decks(inputs)
    for name, kind, xml in deck_mutants(decks, 17):
        add(name, kind, xml)
    meshdir = os.path.join(out, "meshes")
    write(os.path.join(meshdir, "garbage.geo"), "Point(1) = {0,0,0;\nSurface(;\n")
    write(os.path.join(meshdir, "garbage.msh"), os.urandom(2048))
    small = ET.tostring(decks["block2d"].getroot(), encoding="unicode")
    for name, kind, xml in targeted_decks(small, meshdir):
        add(name, kind, xml)
    for name, kind, data in file_level_decks(small):
        add(name, kind, data)
    for target in ["/proc/stentor_out", "/dev/null/out", "/etc/hostname/out"]:
        add(f"cli_output_{len(rows)}", "output-dir", small, args=f"--output {target}")
    for name, kind, data in mesh_mutants():
        mpath = os.path.join(meshdir, f"{name}.msh")
        write(mpath, data)
        add(f"msh_{name}", kind, MESH_DECK.format(mesh=mpath))
    for name, kind, data, args, flags in issue16_cases(inputs, out, meshdir):
        add(name, kind, data, args=args, flags=flags)
    with open(os.path.join(out, "cases.tsv"), "w") as f:
        for r in rows:
            f.write("\t".join(r).rstrip("\t") + "\n")
    print(f"{len(rows)} cases ({sum(1 for r in rows if r[0].startswith('msh_'))} .msh files) in {out}")


if __name__ == "__main__":
    main()

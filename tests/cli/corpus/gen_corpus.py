#!/usr/bin/env python3
"""Generates a corpus of malformed and hostile inputs for stentor (issue 12).

usage: gen_corpus.py INPUTS_DIR OUT_DIR

From the shipped decks in INPUTS_DIR it writes OUT_DIR/decks/*.xml (mutated decks:
deleted, duplicated, renamed parameters and sublists, wrong types, NaN/Inf/huge/
negative/zero values, absurd mesh sizes, hostile file names, unwritable output
folders, truncated and binary files, entity bombs, deep nesting) and OUT_DIR/meshes/
*.msh (a valid gmsh 4.1 ASCII square and its malformed variants, each with a deck
that reads it). OUT_DIR/cases.tsv lists one case a line:
    name <TAB> kind <TAB> extra stentor arguments (space-separated, may be empty) <TAB> deck
The output is deterministic (a fixed seed). Only the Python standard library is used.
"""
import os
import random
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


def main():
    inputs, out = sys.argv[1], sys.argv[2]
    for sub in ("decks", "meshes"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    rows = []

    def add(name, kind, data, ext="xml", args=""):
        path = os.path.join(out, "decks", f"{name}.{ext}")
        write(path, data)
        rows.append((name, kind, args, path))

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
    with open(os.path.join(out, "cases.tsv"), "w") as f:
        for r in rows:
            f.write("\t".join(r) + "\n")
    print(f"{len(rows)} cases ({sum(1 for r in rows if r[0].startswith('msh_'))} .msh files) in {out}")


if __name__ == "__main__":
    main()

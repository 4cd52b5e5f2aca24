#!/usr/bin/env python3
"""Runs stentor on the corpus written by gen_corpus.py and classifies each outcome.

usage: run_corpus.py STENTOR CORPUS_DIR WORK_DIR [--jobs N] [--timeout S] [--mem-mb M]
                     [--subset N] [--match REGEX] [--report FILE]

Per case: `stentor --check [args] DECK` in its own folder WORK_DIR/<case>, under a
wall-clock limit (--timeout, default 20 s) and an address-space limit (--mem-mb,
default 4096; 0: none). Where --check passes and the case is cheap to run (derived from
block2d, a .msh case, or an output-folder / mesh-size case), a real run follows
under the same limits. Outcomes:
  good       exit 2 or 3 and stderr names the deck, mesh or output path
  accepted   exit 0 (fine only where the input is valid)
  BAD-...    unnamed (exit 2/3 naming nothing), internal (exit 1), crash (a signal or
             exit >= 128), timeout, or any other status
--subset N keeps N cases spread evenly over the corpus (the ctest subset).
Prints counts per outcome and per kind, and every BAD case; exits 1 if any is BAD.
"""
import argparse
import collections
import concurrent.futures
import os
import re
import resource
import shutil
import subprocess
import sys

RUN_PREFIXES = ("block2d.", "msh_", "mesh_size_", "max_cells_", "outdir_", "cli_output_")


def limits(mem_mb):
    def apply():
        if mem_mb > 0:  # 0: no limit (AddressSanitizer reserves terabytes of address space)
            m = mem_mb * 1024 * 1024
            resource.setrlimit(resource.RLIMIT_AS, (m, m))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def invoke(cmd, cwd, timeout, mem_mb):
    """(exit status or 'timeout' or -signal, stderr text)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_PROC_BIND="false")
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           timeout=timeout, preexec_fn=limits(mem_mb), env=env)
        return p.returncode, p.stderr.decode(errors="replace")
    except subprocess.TimeoutExpired as e:
        return "timeout", (e.stderr or b"").decode(errors="replace")


def names_something(err, deck, args):
    """Whether stderr names the deck, a parameter ('A->b'), or a file or folder that
    the deck's values or the arguments give (the mesh, the output folder)."""
    with open(deck, "rb") as f:
        text = f.read()
    values = [v for v in re.findall(rb'value="([^"]*)"', text) if b"/" in v]
    values += re.findall(rb'name="(?:file|directory)"[^>]*value="([^"]*)"', text)
    paths = [v.decode(errors="replace") for v in values]
    keys = [os.path.basename(deck), "->"] + args
    keys += [os.path.basename(p.rstrip("/")) or p for p in paths]
    return any(k.strip() and k in err for k in keys)


def classify(rc, err, deck, args):
    if rc == "timeout":
        return "BAD-timeout"
    if rc == 0:
        return "accepted"
    if rc in (2, 3):
        return "good" if names_something(err, deck, args) else "BAD-unnamed"
    if rc == 1:
        return "BAD-internal"
    if rc < 0 or rc >= 128:
        return "BAD-crash"
    return f"BAD-exit{rc}"


def run_case(case, opts):
    name, kind, args, deck = case
    args = args.split()
    work = os.path.join(opts.work, name)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    rc, err = invoke([opts.stentor, "--check"] + args + [deck], work, opts.timeout, opts.mem_mb)
    stage = "check"
    if rc == 0 and name.startswith(RUN_PREFIXES):
        stage = "run"
        rc, err = invoke([opts.stentor] + args + [deck], work, opts.timeout, opts.mem_mb)
    outcome = classify(rc, err, deck, args)
    if outcome.startswith("BAD"):
        with open(os.path.join(work, "stderr.txt"), "w") as f:
            f.write(err)
    else:
        shutil.rmtree(work, ignore_errors=True)
    last = err.strip().splitlines()[-1][:200] if err.strip() else ""
    return name, kind, stage, rc, outcome, last


def report(results, out):
    by_outcome = collections.Counter(r[4] for r in results)
    by_kind = collections.defaultdict(collections.Counter)
    for r in results:
        by_kind[r[1]][r[4]] += 1
    lines = [f"cases: {len(results)}"]
    lines += [f"  {k}: {v}" for k, v in sorted(by_outcome.items())]
    lines.append("per kind:")
    for kind in sorted(by_kind):
        lines.append(f"  {kind}: " + ", ".join(f"{k} {v}" for k, v in sorted(by_kind[kind].items())))
    bad = [r for r in results if r[4].startswith("BAD")]
    lines.append(f"BAD cases: {len(bad)}")
    lines += [f"  {r[4]} {r[0]} ({r[2]}, exit {r[3]}): {r[5]}" for r in bad]
    acc = [r for r in results if r[4] == "accepted"]
    lines.append(f"accepted cases: {len(acc)}")
    lines += [f"  {r[0]} ({r[2]})" for r in acc]
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if out:
        with open(out, "w") as f:
            f.write(text)
    return not bad


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stentor")
    ap.add_argument("corpus")
    ap.add_argument("work")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=20)
    ap.add_argument("--mem-mb", type=int, default=4096)
    ap.add_argument("--subset", type=int, default=0)
    ap.add_argument("--match", help="only the cases whose name matches this regex")
    ap.add_argument("--report")
    opts = ap.parse_args()
    opts.stentor = os.path.abspath(opts.stentor)
    with open(os.path.join(opts.corpus, "cases.tsv")) as f:
        cases = [l.rstrip("\n").split("\t") for l in f if l.strip()]
    if opts.match:
        cases = [c for c in cases if re.search(opts.match, c[0])]
    if opts.subset:
        step = max(1, len(cases) // opts.subset)
        cases = cases[::step][: opts.subset]
    os.makedirs(opts.work, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(opts.jobs) as pool:
        results = list(pool.map(lambda c: run_case(c, opts), cases))
    sys.exit(0 if report(results, opts.report) else 1)


if __name__ == "__main__":
    main()

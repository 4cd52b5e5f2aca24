#!/usr/bin/env python3
"""Runs stentor on the corpus written by gen_corpus.py and classifies each outcome.

usage: run_corpus.py STENTOR CORPUS_DIR WORK_DIR [--jobs N] [--timeout S] [--mem-mb M]
                     [--subset N [--also REGEX]] [--match REGEX] [--np2 N] [--slow]
                     [--mpiexec PATH] [--report FILE]

Per case: `stentor --check [args] DECK` in its own folder WORK_DIR/<case>, under a
wall-clock limit (--timeout, default 20 s) and an address-space limit (--mem-mb,
default 4096; 0: none), with HOME and TMPDIR inside that folder, stdin from /dev/null,
and in a process group of its own (killed as a whole at the end: nothing it started
outlives it). Where --check passes and the case is cheap to run (flag `run`, or a name
derived from block2d, a .msh case, an output-folder / mesh-size case) a real run
follows under the same limits. Cases flagged `concurrent=N` start N runs into one
folder at once; `failwrite=`, `fsize=`, `tmpfs=` make the run's writes fail (the test
hook STENTOR_TEST_FAIL_WRITE, a file size limit, a small tmpfs where mount works);
`prepare=KIND` makes the case's folder hostile first (links in and around the output
folder, planted or malformed manifests) or restarts from a fuzzed checkpoint
(`prepare=ckpt_*`); the user's files it plants in the output folder must survive.

Outcomes:
  good       exit 2 or 3 and stderr (for 3 also the log's FAILED line) names the deck,
             a parameter, the mesh or another input file, or the output path
  accepted   exit 0 (fine only where the input is valid)
  skipped    the case needs something this machine lacks (mount for tmpfs)
  BAD-...    exec (an injected command ran: a PWNED_* sentinel file appeared),
             outside (a file was written outside the run's output folder),
             nonfinite (exit 0 with NaN/Inf in a CSV or HDF5 dataset), corrupt (exit 0
             with an XDMF naming a missing .h5, a truncated PNG, a manifest listing a
             missing file), leftover (a process it started still ran after it ended),
             concurrent (concurrent runs: a status other than 0 or 2, no run succeeding,
             or an inconsistent folder), unnamed (exit 2/3 naming nothing), internal
             (exit 1), crash (a signal or exit >= 128), timeout, exitN
The issue-16 counts (command executions, files outside the output folder, hangs,
crashes, exit-0 runs with non-finite output) are printed at the end.
--subset N keeps N cases spread evenly over the corpus, and with --also REGEX the cases
whose name matches it (the ctest subset); --match keeps the cases whose name matches. --np2 N also runs N of the selected cases (spread
over those with a real run) on 2 MPI ranks (mpirun -np 2). --slow adds the cases
flagged slow (a .geo that loops until the default 'Mesh->time limit' of 600 s stops it).
Exits 1 if any case is BAD.
HDF5 files are scanned with h5py when it imports (else counted as not scanned).
"""
import argparse
import collections
import concurrent.futures
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import xml.etree.ElementTree as ET

try:
    import h5py
    import numpy
except ImportError:  # the HDF5 scan is then skipped (and says so)
    h5py = None

RUN_PREFIXES = ("block2d.", "msh_", "mesh_size_", "max_cells_", "outdir_", "cli_output_")


def parse_cases(path):
    cases = []
    with open(path) as f:
        for line in f:
            if not line.strip():
                continue
            cols = line.rstrip("\n").split("\t")
            name, kind, args, deck = cols[:4]
            flags = cols[4].split() if len(cols) > 4 else []
            args = json.loads(args) if args.startswith("[") else args.split()
            cases.append({"name": name, "kind": kind, "args": args, "deck": deck, "flags": flags})
    return cases


def flag(case, key):
    """The value of flag `key=value` ('' for a bare `key`), or None."""
    for f in case["flags"]:
        if f == key:
            return ""
        if f.startswith(key + "="):
            return f[len(key) + 1:]
    return None


# ----------------------------------------------------------------------- running

def case_env(opts, work, extra=None):
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_PROC_BIND="false", PWN_DIR=opts.sentinel,
               HOME=os.path.join(work, "home"), TMPDIR=os.path.join(work, "tmp"))
    if os.geteuid() == 0:  # Open MPI refuses root without these
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    env.update(extra or {})
    return env


class Drain:
    """Reads a pipe in a thread (a pipe, not a file: a file size limit set on the run must
    not cut what it says), keeping the first `keep` bytes."""
    def __init__(self, pipe, keep):
        self.data = bytearray()
        self.thread = threading.Thread(target=self.run, args=(pipe, keep), daemon=True)
        self.thread.start()

    def run(self, pipe, keep):
        for chunk in iter(lambda: pipe.read(65536), b""):
            if len(self.data) < keep:
                self.data += chunk[: keep - len(self.data)]
        pipe.close()

    def text(self):
        self.thread.join(timeout=5)
        return self.data.decode(errors="replace")


PRLIMIT = shutil.which("prlimit")


def start(cmd, cwd, opts, env):
    # The limits through prlimit(1), not a preexec_fn: a fork from this threaded process
    # can deadlock before exec in a preexec_fn (2 of 1309 cases "hung" 20 s that way).
    if PRLIMIT:
        lim = [PRLIMIT, "--core=0"] + ([f"--as={opts.mem_mb * 1024 * 1024}"] if opts.mem_mb > 0 else [])
        cmd = lim + ["--"] + cmd
    p = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         env=env, start_new_session=True)
    if not PRLIMIT:  # set just after the start instead
        try:
            resource.prlimit(p.pid, resource.RLIMIT_CORE, (0, 0))
            if opts.mem_mb > 0:
                m = opts.mem_mb * 1024 * 1024
                resource.prlimit(p.pid, resource.RLIMIT_AS, (m, m))
        except OSError:
            pass
    return p, (Drain(p.stderr, 1 << 22), Drain(p.stdout, 1 << 24))


def finish(p, pipes, deadline):
    """(exit status or 'timeout' or -signal, stderr text and stdout's FAILED lines,
    leftover): waits until `deadline`, then kills the process group; `leftover` is
    whether a process of the group still ran after the command ended (it is killed)."""
    try:
        rc = p.wait(timeout=max(0.0, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        rc = "timeout"
    leftover = False
    try:
        os.killpg(p.pid, 0)
        leftover = rc != "timeout"
        os.killpg(p.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    if rc == "timeout":
        p.wait()
    err, out = pipes
    # A failed solve (exit 3) says why in the log, on stdout: its FAILED line counts.
    text = err.text() + "".join(l + "\n" for l in out.text().splitlines() if l.startswith("FAILED"))
    return rc, text, leftover


def stray_processes(work, kill=True):
    """Live processes (not zombies) started by a case: any whose environment holds the
    case's TMPDIR or one below it (every process it starts inherits it, whatever its
    process group).
    They are killed; their command lines are returned."""
    key = ("TMPDIR=" + os.path.join(work, "tmp")).encode()
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            with open(f"/proc/{pid}/stat", "rb") as f:
                if f.read().rsplit(b")", 1)[1].split()[0] == b"Z":
                    continue
            with open(f"/proc/{pid}/environ", "rb") as f:
                if not any(e == key or e.startswith(key + b"/") for e in f.read().split(b"\0")):
                    continue
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                found.append(f.read().replace(b"\0", b" ").decode(errors="replace")[:120])
            if kill:
                os.kill(int(pid), signal.SIGKILL)
        except (OSError, IndexError):
            pass
    return found


def invoke(cmd, cwd, opts, env, timeout):
    p, err = start(cmd, cwd, opts, env)
    return finish(p, err, time.monotonic() + timeout)


# --------------------------------------------------------------- what a run left

def output_folder(case, work):
    """The folder the run writes into (absolute): --output, else Output->directory,
    else results/<deck name>, relative to the case's folder."""
    args = case["args"]
    for i, a in enumerate(args):
        if a in ("--output", "-o") and i + 1 < len(args):
            return os.path.normpath(os.path.join(work, args[i + 1]))
    stem = os.path.splitext(os.path.basename(case["deck"]))[0]
    d = "results/{deck}"
    try:
        root = ET.parse(case["deck"]).getroot()
        out = next((e for e in root if e.get("name") == "Output"), None)
        p = next((e for e in (out if out is not None else []) if e.get("name") == "directory"), None)
        if p is not None and p.get("value"):
            d = p.get("value")
    except (ET.ParseError, OSError, ValueError, RecursionError):
        pass
    return os.path.normpath(os.path.join(work, d.replace("{deck}", stem)))


def snapshot(top, skip):
    """{relative path: (is dir, size, mtime)} of everything below `top` except the
    paths in `skip` (and what lies below them)."""
    snap = {}
    for dirpath, dirnames, filenames in os.walk(top):
        keep = []
        for d in dirnames:
            full = os.path.join(dirpath, d)
            if full in skip:
                continue
            keep.append(d)
        dirnames[:] = keep
        for n in dirnames + filenames:
            full = os.path.join(dirpath, n)
            if full in skip:
                continue
            try:
                st = os.lstat(full)
            except OSError:
                continue
            snap[os.path.relpath(full, top)] = (n in dirnames, st.st_size, st.st_mtime_ns)
    return snap


def changed(before, after, top=None, allowed=()):
    """Paths created, removed or modified between two snapshots; a folder whose
    entries changed is not itself a change, nor a new folder on the way to an allowed
    path (a run creates the missing parents of its output folder)."""
    def parent_of_allowed(k):
        full = os.path.join(top or "", k) + os.sep
        return any(a.startswith(full) for a in allowed)
    out = []
    for k in set(before) | set(after):
        b, a = before.get(k), after.get(k)
        if b == a or (b and a and b[0] and a[0]):
            continue
        if a and a[0] and not b and parent_of_allowed(k):
            continue
        out.append(k)
    return sorted(out)


def sentinels(opts, case, work):
    """PWNED_* files made by this case: in the sentinel folder (by name) and anywhere in
    its own folder."""
    hits = [os.path.join(opts.sentinel, n) for n in os.listdir(opts.sentinel) if case["name"] in n]
    for dirpath, _, filenames in os.walk(work):
        hits += [os.path.join(dirpath, n) for n in filenames if n.startswith("PWNED")]
    return hits


def csv_nonfinite(path):
    with open(path, errors="replace") as f:
        next(f, None)
        for lineno, line in enumerate(f, 2):
            for field in line.strip().split(","):
                v = field.strip().strip('"').lower()
                if "nan" in v or "inf" in v:
                    return f"{os.path.basename(path)}:{lineno}: {field.strip()}"
    return None


def nonfinite_allowed(obj, data):
    """contact_gap is NaN by design at the nodes that are no slave node (docs/deck.md,
    "Outputs"): exactly where the step's contact_status is -1 when it was written; never inf."""
    if not obj.name.endswith("/contact_gap") or numpy.any(numpy.isinf(data)):
        return False
    status = obj.parent.get("contact_status")
    return status is None or numpy.array_equal(numpy.isnan(data), status[()] == -1)


def h5_nonfinite(path):
    bad = []

    def visit(name, obj):
        if bad or not isinstance(obj, h5py.Dataset) or obj.dtype.kind not in "fc":
            return
        data = obj[()]
        if not numpy.all(numpy.isfinite(data)) and not nonfinite_allowed(obj, data):
            bad.append(f"{os.path.basename(path)}:/{name}")
    try:
        with h5py.File(path, "r") as f:
            f.visititems(visit)
    except OSError as e:
        return f"{os.path.basename(path)}: unreadable ({e})"
    return bad[0] if bad else None


def check_results(folder):
    """(non-finite finding, corruption finding, h5 files not scanned) of an exit-0 run's
    output folder."""
    nonfinite = corrupt = None
    unscanned = 0
    if not os.path.isdir(folder):
        return None, f"no output folder {folder}", 0
    names = set()
    for dirpath, _, filenames in os.walk(folder):
        for n in filenames:
            path = os.path.join(dirpath, n)
            names.add(os.path.relpath(path, folder))
            if n.endswith(".csv"):
                nonfinite = nonfinite or csv_nonfinite(path)
            elif n.endswith(".h5"):
                if h5py is None:
                    unscanned += 1
                else:
                    nonfinite = nonfinite or h5_nonfinite(path)
            elif n.endswith((".xmf", ".xdmf")):
                with open(path, errors="replace") as f:
                    for ref in set(re.findall(r"([^\s<>\"]+\.h5):", f.read())):
                        if not os.path.exists(os.path.join(dirpath, ref)):
                            corrupt = corrupt or f"{n} names {ref}, which is missing"
            elif n.endswith(".png"):
                with open(path, "rb") as f:
                    data = f.read()
                if not (data.startswith(b"\x89PNG\r\n\x1a\n") and data.endswith(b"IEND\xaeB`\x82")):
                    corrupt = corrupt or f"{n} is not a whole PNG ({len(data)} bytes)"
    manifest = os.path.join(folder, "stentor-manifest.txt")
    if os.path.exists(manifest):  # "<size>[+] <FNV-1a> <%XX-encoded name>" lines (src/io/OutputDir.cpp)
        with open(manifest, errors="replace") as f:
            for line in f:
                m = re.match(r"^(\d+)(\+?) ([0-9a-f]{16}) (\S+)$", line.rstrip("\n"))
                if not m:
                    continue
                name = re.sub(r"%([0-9A-Fa-f]{2})", lambda x: chr(int(x.group(1), 16)), m.group(4))
                path = os.path.join(folder, name)
                if name not in names:
                    corrupt = corrupt or f"the manifest lists {name}, which is missing"
                elif not m.group(2):
                    with open(path, "rb") as g:
                        data = g.read()
                    if len(data) != int(m.group(1)) or f"{fnv1a(data):016x}" != m.group(3):
                        corrupt = corrupt or f"the manifest's size or hash of {name} does not match the file"
    return nonfinite, corrupt, unscanned


def names_something(err, deck, args):
    """Whether stderr names the deck, a parameter ('A->b'), or a file or folder that
    the deck's values or the arguments give (the mesh, the output folder)."""
    try:
        with open(deck, "rb") as f:
            text = f.read()
    except OSError:
        text = b""
    values = [v for v in re.findall(rb'value="([^"]*)"', text) if b"/" in v]
    values += re.findall(rb'name="(?:file|directory)"[^>]*value="([^"]*)"', text)
    paths = [v.decode(errors="replace") for v in values]
    keys = [os.path.basename(deck), "->"] + args
    keys += [os.path.basename(p.rstrip("/")) or p for p in paths]
    if any(k.strip() and k in err for k in keys):
        return True
    # A file the deck's files name in turn (a .geo's Include): an existing path in stderr.
    return any(os.path.isfile(p) for p in re.findall(r"(/[^\s:'\"]+)", err))


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


# ------------------------------------------------------------------------ a case

# ------------------------------------------------------------ prepared folders (prepare=KIND)
# The case's folder is made hostile before the run: links in and around the output folder,
# planted or malformed manifests, a fuzzed checkpoint to restart from. Returns the extra
# arguments and the files (path -> bytes) that must hold the same bytes after the run:
# the user's files inside the output folder (outside it, the folder snapshot checks).

def fnv1a(data, h=0xcbf29ce484222325):
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return h


def manifest_v2(entries):
    """A well-formed manifest (src/io/OutputDir.cpp) listing (size, hash, encoded name)."""
    text = "# planted\nstentor-manifest 2\n" + "".join(f"{n} {h} {e}\n" for n, h, e in entries)
    return text + f"end {fnv1a(text.encode()):016x}\n"


def user_file(path, text, protected):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    protected[path] = text.encode()


def prepare_folder(kind, work, out, protected):
    victim = os.path.join(work, "victim.txt")
    with open(victim, "w") as f:
        f.write("a file outside the output folder\n")
    if kind == "lock_link":
        os.makedirs(out + ".partial")
        os.symlink(victim, os.path.join(out + ".partial", ".stentor.lock"))
    elif kind == "lock_dangling":
        os.makedirs(out + ".partial")
        os.symlink(os.path.join(work, "new_file_outside"), os.path.join(out + ".partial", ".stentor.lock"))
    elif kind == "partial_link":
        os.makedirs(os.path.join(work, "victimdir"))
        user_file(os.path.join(work, "victimdir", "keep.txt"), "mine\n", protected)
        os.symlink(os.path.join(work, "victimdir"), out + ".partial")
    elif kind == "result_link":  # with --overwrite: the link is replaced, never written through
        user_file(os.path.join(out, "notes.txt"), "mine\n", protected)
        os.symlink(victim, os.path.join(out, "st_history.csv"))
    elif kind == "manifest_link":
        user_file(os.path.join(out, "a.txt"), "mine\n", protected)
        with open(os.path.join(work, "list.txt"), "w") as f:
            f.write("a.txt\n")
        os.symlink(os.path.join(work, "list.txt"), os.path.join(out, "stentor-manifest.txt"))
    elif kind == "manifest_planted":
        user_file(os.path.join(out, "a.txt"), "mine\n", protected)
        user_file(os.path.join(out, "st_history.csv"), "my own table\n", protected)
        user_file(os.path.join(out, "stentor-manifest.txt"), "# Stentor results folder\na.txt\nst_history.csv\n", protected)
        del protected[os.path.join(out, "stentor-manifest.txt")]  # the run may replace the manifest itself
    elif kind == "manifest_v2_wrong_hash":
        user_file(os.path.join(out, "st_history.csv"), "my own table\n", protected)
        user_file(os.path.join(out, "a.txt"), "mine\n", protected)
        with open(os.path.join(out, "stentor-manifest.txt"), "w") as f:
            f.write(manifest_v2([(13, "0123456789abcdef", "st_history.csv"), (5, "0123456789abcdef", "a.txt")]))
    elif kind == "manifest_forged_names":
        user_file(os.path.join(out, "a.txt"), "mine\n", protected)
        h = f"{fnv1a(open(victim, 'rb').read()):016x}"
        size = os.path.getsize(victim)
        with open(os.path.join(out, "stentor-manifest.txt"), "w") as f:
            f.write(manifest_v2([(size, h, "..%2Fvictim.txt"), (size, h, "%2Fetc%2Fhostname"), (0, h, "."), (5, h, "a.txt%00")]))
    elif kind == "manifest_garbage":
        user_file(os.path.join(out, "a.txt"), "mine\n", protected)
        with open(os.path.join(out, "stentor-manifest.txt"), "wb") as f:
            f.write(b"stentor-manifest 2\n" + os.urandom(4096) + b"\n" + b"9" * 100000 + b" x a.txt\nend 0\n")
    else:
        raise ValueError(f"unknown prepare kind {kind}")


def fuzz_checkpoint(kind, src, dst):
    """A copy of checkpoint `src` at `dst`, damaged as `kind` says."""
    data = bytearray(open(src, "rb").read())
    if kind == "truncated":
        data = data[: len(data) // 2]
    elif kind == "bitflip":  # a byte of the u values (the file's last quarter without h5py)
        at = len(data) * 3 // 4
        if h5py is not None:
            with h5py.File(src, "r") as f:
                at = f["tables/u/values"].id.get_offset() + 5
        data[at] ^= 0x10
    with open(dst, "wb") as f:
        f.write(data)
    if kind in ("truncated", "bitflip") or h5py is None:
        return
    with h5py.File(dst, "r+") as f:
        if kind == "nan":
            v = f["tables/u/values"]
            v[0, 0] = float("nan")
        elif kind == "one_column":
            v = f["tables/u/values"][...]
            del f["tables/u/values"]
            f["tables/u/values"] = v[:, :1]
        elif kind == "int_values":
            v = f["tables/u/values"][...]
            del f["tables/u/values"]
            f["tables/u/values"] = v.astype("i8")
        elif kind == "huge_rows":
            del f["tables/u/values"]
            f.create_dataset("tables/u/values", shape=(10 ** 12, 2), dtype="f8")
        elif kind == "time_array":
            del f["reals"].attrs["time"]
            f["reals"].attrs["time"] = numpy.zeros(1000)
        elif kind == "time_nan":
            f["reals"].attrs["time"] = float("nan")
        elif kind == "step_huge":
            f["ints"].attrs["step"] = numpy.int64(2 ** 40)
        elif kind == "ids_negative":
            f["tables/u/ids"][0] = -1
        elif kind == "no_tables":
            del f["tables"]
        else:
            raise ValueError(f"unknown checkpoint fuzz {kind}")


def prepare_case(case, work, out, opts, env, timeout):
    """(extra args, protected files) for a case flagged prepare=KIND."""
    kind = flag(case, "prepare")
    protected = {}
    if not kind.startswith("ckpt_"):
        prepare_folder(kind, work, out, protected)
        return [], protected
    # A checkpoint of the deck (checkpoint every step), fuzzed, to restart from.
    ck = os.path.join(work, "ck")
    invoke([opts.stentor, "--output", ck, case["deck"]], work, opts, env, timeout)
    src = os.path.join(ck, "st_checkpoint.h5")
    dst = os.path.join(work, "in_checkpoint.h5")
    if os.path.isfile(src):
        fuzz_checkpoint(kind[len("ckpt_"):], src, dst)
    return ["--restart", dst], protected


def run_case(case, opts, ranks=1):
    name = case["name"]
    work = os.path.join(opts.work, name + ("@np2" if ranks == 2 else ""))
    shutil.rmtree(work, ignore_errors=True)
    for sub in ("home", "tmp"):
        os.makedirs(os.path.join(work, sub))
    args = list(case["args"])
    deck = case["deck"]
    res = {"name": name, "kind": case["kind"], "ranks": ranks, "stage": "check", "rc": None, "err": "",
           "outcome": None, "findings": [], "leftover": False, "unscanned": 0}
    prefix = [opts.mpiexec, "-np", "2"] if ranks == 2 else []
    timeout = float(flag(case, "timeout") or opts.timeout) * (2 if ranks == 2 else 1)
    env = case_env(opts, work)
    out = output_folder(case, work)
    mount = None
    fsize = flag(case, "fsize")
    fsize = int(fsize) if fsize else None
    if flag(case, "failwrite") is not None:
        env["STENTOR_TEST_FAIL_WRITE"] = flag(case, "failwrite")
    if flag(case, "tmpfs") is not None:
        mount = os.path.join(work, "tmpfs")
        os.makedirs(mount)
        if subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={flag(case, 'tmpfs')}", "tmpfs", mount],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
            res.update(outcome="skipped", err="mount -t tmpfs failed (not permitted here)")
            shutil.rmtree(work, ignore_errors=True)
            return res
        out = os.path.join(mount, "out")
    if flag(case, "failwrite") is not None or fsize is not None or mount or flag(case, "concurrent"):
        if "--output" not in args:
            out = out if mount else os.path.join(work, "out")
            args = ["--output", out] + args
    protected = {}
    if flag(case, "prepare") is not None:
        extra, protected = prepare_case(case, work, out, opts, env, timeout)
        args = args + extra
    allowed = {out, out + ".partial", out + ".old", os.path.join(work, "tmp"), os.path.join(work, "ck"),
               os.path.join(work, "ck.partial")}
    if mount:
        allowed.add(mount)
    before = snapshot(work, allowed)
    try:
        if flag(case, "concurrent"):
            run_concurrent(case, opts, res, prefix, args, env, timeout, out)
        else:
            rc, err, left = invoke(prefix + [opts.stentor, "--check"] + args + [deck], work, opts, env, timeout)
            res.update(rc=rc, err=err, leftover=left)
            runs = flag(case, "run") is not None or name.startswith(RUN_PREFIXES) or \
                flag(case, "failwrite") is not None or fsize is not None or mount
            if rc == 0 and runs:
                res["stage"] = "run"
                p, errf = start(prefix + [opts.stentor] + args + [deck], work, opts, env)
                deadline = time.monotonic() + timeout
                if fsize is not None:
                    # The limit is set once the run's folder exists, as the disk would fill
                    # then (set at start it would fail MPI_Init's own shared-memory files).
                    while p.poll() is None and time.monotonic() < deadline and not os.path.isdir(out + ".partial"):
                        time.sleep(0.02)
                    try:
                        resource.prlimit(p.pid, resource.RLIMIT_FSIZE, (fsize, fsize))
                    except (ProcessLookupError, OSError):
                        pass
                rc, err, left = finish(p, errf, deadline)
                res.update(rc=rc, err=err, leftover=res["leftover"] or left)
            res["outcome"] = classify(res["rc"], res["err"], deck, args)
        # What the case left outside its output folder, and any sentinel. The folder the
        # run wrote is the one predicted, or one holding Stentor's manifest or lock (a
        # deck's folder name the XML reader normalised, a \r dropped say).
        folders = [out] if os.path.isdir(out) else []
        for dirpath, dirnames, filenames in os.walk(work):
            if os.path.commonpath([dirpath, os.path.join(work, "home")]) == os.path.join(work, "home"):
                continue
            if "stentor-manifest.txt" in filenames or ".stentor.lock" in filenames:
                found = dirpath[: -len(".partial")] if dirpath.endswith(".partial") else dirpath
                if found not in allowed:
                    allowed |= {found, found + ".partial", found + ".old"}
                    folders.append(found)
        if res["rc"] == 0 and res["stage"] == "run" and not flag(case, "concurrent"):
            for folder in folders or [out]:
                nonfinite, corrupt, unscanned = check_results(folder)
                res["unscanned"] += unscanned
                if nonfinite:
                    res["findings"].append(("nonfinite", nonfinite))
                if corrupt:
                    res["findings"].append(("corrupt", corrupt))
        for path, data in protected.items():  # the user's files inside the output folder
            try:
                same = not os.path.islink(path) and open(path, "rb").read() == data
            except OSError:
                same = False
            if not same:
                res["findings"].append(("outside", f"the user's {os.path.relpath(path, work)} was changed or removed"))
        after = snapshot(work, allowed)
        outside = changed(before, after, work, allowed)
        if outside:
            res["findings"].append(("outside", ", ".join(outside[:5])))
        for _ in range(30):  # Open MPI's singleton daemon (orted) ends a moment after its rank
            stray = stray_processes(work, kill=False)
            if not stray:
                break
            time.sleep(0.1)
        stray = stray_processes(work)
        if stray:
            res["findings"].append(("leftover", "still running: " + "; ".join(stray[:2])))
        hits = sentinels(opts, case, work)
        if hits:
            res["findings"].append(("exec", ", ".join(hits[:3])))
        if res["leftover"]:
            res["findings"].append(("leftover", "a process it started outlived it"))
    finally:
        if mount:
            subprocess.run(["umount", "-l", mount], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    res["base"] = res["outcome"]  # by exit status alone (the hang and crash counts)
    for kind in ("exec", "outside", "nonfinite", "corrupt", "leftover"):
        if any(f[0] == kind for f in res["findings"]):
            res["outcome"] = "BAD-" + kind
            break
    if res["outcome"].startswith("BAD"):
        with open(os.path.join(work, "stderr.txt"), "w") as f:
            f.write(res["err"])
            f.write("\n".join(f"{k}: {v}" for k, v in res["findings"]))
    else:
        shutil.rmtree(work, ignore_errors=True)
    err = res["err"].strip()
    res["last"] = err.splitlines()[-1][:200] if err else ""
    return res


def run_concurrent(case, opts, res, prefix, args, env, timeout, out):
    """N runs into one folder: each must exit 0 or 2 (refused: another run holds the
    folder, named), one at least 0, and the folder must be consistent afterwards."""
    n = int(flag(case, "concurrent"))
    alt = flag(case, "alt")
    work = os.path.dirname(env["HOME"])
    procs = []
    deadline = time.monotonic() + timeout
    for i in range(n):
        deck = alt if alt and i % 2 else case["deck"]
        # A TMPDIR each: Open MPI singletons started at the same moment with one TMPDIR
        # race creating their session folder (exit 1, "mkdir ... File exists"), which
        # would hide what this case is about, stentor's lock.
        tmp = os.path.join(work, "tmp", f"run{i}")
        os.makedirs(tmp, exist_ok=True)
        procs.append(start(prefix + [opts.stentor] + args + [deck], work, opts, dict(env, TMPDIR=tmp)))
        if flag(case, "stagger") is not None:
            time.sleep(0.3)
    results = [finish(p, err, deadline) for p, err in procs]
    res["stage"] = "run"
    rcs = [r[0] for r in results]
    res["rc"] = rcs
    res["err"] = "\n".join(f"--- run {i}: exit {r[0]}\n{r[1]}" for i, r in enumerate(results))
    res["leftover"] = any(r[2] for r in results)
    if "timeout" in rcs:
        res["outcome"] = "BAD-timeout"
    elif any(rc != "timeout" and (rc < 0 or rc >= 128) for rc in rcs):
        res["outcome"] = "BAD-crash"
    elif any(rc not in (0, 2) for rc in rcs) or 0 not in rcs:
        res["outcome"] = "BAD-concurrent"
    elif any(rc == 2 and out not in r[1] and os.path.basename(out) not in r[1] for rc, r in zip(rcs, results)):
        res["outcome"] = "BAD-unnamed"
    else:
        res["outcome"] = "good"
        nonfinite, corrupt, res["unscanned"] = check_results(out)
        if nonfinite:
            res["findings"].append(("nonfinite", nonfinite))
        if corrupt:
            res["findings"].append(("corrupt", corrupt))


# ------------------------------------------------------------------------ report

def report(results, out, seconds, corpus_changes, stray):
    by_outcome = collections.Counter(r["outcome"] for r in results)
    by_kind = collections.defaultdict(collections.Counter)
    for r in results:
        by_kind[r["kind"]][r["outcome"]] += 1
    one = [r for r in results if r["ranks"] == 1]
    two = [r for r in results if r["ranks"] == 2]
    lines = [f"cases: {len(one)} on 1 rank" + (f", {len(two)} on 2 ranks" if two else "") + f"; {seconds:.0f} s"]
    lines += [f"  {k}: {v}" for k, v in sorted(by_outcome.items())]
    lines.append("per kind:")
    for kind in sorted(by_kind):
        lines.append(f"  {kind}: " + ", ".join(f"{k} {v}" for k, v in sorted(by_kind[kind].items())))

    def count(pred):
        return sum(1 for r in results if pred(r))
    execs = count(lambda r: any(f[0] == "exec" for f in r["findings"])) + len(stray)
    outside = count(lambda r: any(f[0] == "outside" for f in r["findings"])) + len(corpus_changes)
    hangs = count(lambda r: r.get("base", r["outcome"]) == "BAD-timeout")
    crashes = count(lambda r: r.get("base", r["outcome"]) == "BAD-crash")
    nonfinite = count(lambda r: any(f[0] == "nonfinite" for f in r["findings"]))
    lines.append(f"issue 16: command executions {execs}, files written outside the output folder {outside}, "
                 f"hangs {hangs}, crashes {crashes}, exit-0 runs with non-finite output {nonfinite}")
    lines.append(f"exit-0 runs scanned: {count(lambda r: r['stage'] == 'run' and r['rc'] == 0)}"
                 f" (HDF5 files not scanned for want of h5py: {sum(r['unscanned'] for r in results)})")
    for p in corpus_changes:
        lines.append(f"  BAD corpus folder changed: {p}")
    for p in stray:
        lines.append(f"  BAD sentinel outside the case folders: {p}")
    bad = [r for r in results if r["outcome"].startswith("BAD")]
    lines.append(f"BAD cases: {len(bad)}")
    for r in bad:
        tag = " (2 ranks)" if r["ranks"] == 2 else ""
        extra = "; ".join(f"{k}: {v}" for k, v in r["findings"])
        also = f" [{r['base']}]" if r.get("base", r["outcome"]) != r["outcome"] else ""
        lines.append(f"  {r['outcome']}{also} {r['name']}{tag} ({r['stage']}, exit {r['rc']}): {extra or r['last']}")
    skipped = [r for r in results if r["outcome"] == "skipped"]
    if skipped:
        lines.append(f"skipped cases: {len(skipped)} ({skipped[0]['err']})")
    acc = [r for r in results if r["outcome"] == "accepted"]
    lines.append(f"accepted cases: {len(acc)}")
    lines += [f"  {r['name']}{' (2 ranks)' if r['ranks'] == 2 else ''} ({r['stage']})" for r in acc]
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if out:
        with open(out, "w") as f:
            f.write(text)
    return not bad and not corpus_changes and not stray


def stray_sentinels(opts):
    """PWNED_* files anywhere a command may have run: the sentinel folder, the corpus,
    the working folders, this process's folder, HOME, /tmp (top level)."""
    found = [os.path.join(opts.sentinel, n) for n in os.listdir(opts.sentinel)]
    for top in (os.getcwd(), os.path.expanduser("~"), tempfile.gettempdir(), opts.corpus):
        try:
            found += [os.path.join(top, n) for n in os.listdir(top) if n.startswith("PWNED")]
        except OSError:
            pass
    return sorted(set(found))


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
    ap.add_argument("--also", help="with --subset: also the cases whose name matches this regex")
    ap.add_argument("--np2", type=int, default=0, help="also run this many cases on 2 MPI ranks")
    ap.add_argument("--slow", action="store_true", help="also the cases flagged slow (minutes each)")
    ap.add_argument("--mpiexec", default=shutil.which("mpirun") or "mpirun")
    ap.add_argument("--report")
    opts = ap.parse_args()
    opts.stentor = os.path.abspath(opts.stentor)
    opts.corpus = os.path.abspath(opts.corpus)
    opts.work = os.path.abspath(opts.work)
    opts.sentinel = os.path.join(opts.corpus, "sentinel")
    os.makedirs(opts.sentinel, exist_ok=True)
    cases = parse_cases(os.path.join(opts.corpus, "cases.tsv"))
    if not opts.slow:
        cases = [c for c in cases if flag(c, "slow") is None]
    if opts.match:
        cases = [c for c in cases if re.search(opts.match, c["name"])]
    if opts.subset:
        step = max(1, len(cases) // opts.subset)
        picked = cases[::step][: opts.subset]
        if opts.also:  # named cases besides the spread ones
            picked += [c for c in cases if re.search(opts.also, c["name"]) and c not in picked]
        cases = picked
    os.makedirs(opts.work, exist_ok=True)
    corpus_before = snapshot(opts.corpus, {opts.sentinel})
    t0 = time.monotonic()
    jobs = [(c, 1) for c in cases]
    if opts.np2:
        runnable = [c for c in cases if flag(c, "run") is not None and flag(c, "fsize") is None]
        step = max(1, len(runnable) // opts.np2)
        jobs += [(c, 2) for c in runnable[::step][: opts.np2]]
        jobs += [(c, 2) for c in cases if flag(c, "np2") is not None and (c, 2) not in jobs]
    with concurrent.futures.ThreadPoolExecutor(opts.jobs) as pool:
        results = list(pool.map(lambda j: run_case(j[0], opts, j[1]), jobs))
    corpus_changes = changed(corpus_before, snapshot(opts.corpus, {opts.sentinel}))
    stray = [p for p in stray_sentinels(opts) if not any(p in f[1] for r in results for f in r["findings"])]
    ok = report(results, opts.report, time.monotonic() - t0, corpus_changes, stray)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()

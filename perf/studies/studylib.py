"""Shared pieces of the studies in perf/studies/ (docs/studies/README.md).

- Deck templating: a shipped deck (inputs/*.xml) is read with ElementTree and parameters
  are set by their path, "Materials/rubber/C1" = the Parameter "C1" in the sublists
  "Materials" -> "rubber". Missing sublists and parameters are created when a type is given.
- The machine banner printed at the top of every study and written next to its CSV.
- run(): one stentor run with its exit status, wall time and CPU time (user + system of
  the child), a time limit, and the summary line parsed.
- CSV readers for the run's history and energy files.

Standard library only (matplotlib is imported by the plotting scripts, not here).
Run `python3 perf/studies/studylib.py banner [stentor]` to print the banner from bash.
"""
import csv
import json
import os
import platform
import re
import resource
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
INPUTS = os.path.join(ROOT, "inputs")


# ---------------------------------------------------------------- deck templating
class Deck:
    """A deck as an XML tree; set() parameters by path, write() to a file."""

    def __init__(self, path):
        self.source = os.path.abspath(path)
        self.tree = ET.parse(self.source)
        self.root = self.tree.getroot()
        # A mesh file named relative to the shipped deck must still be found from the
        # generated deck's folder: make it absolute.
        f = self._find(["Mesh", "file"], create=None)
        if f is not None and not os.path.isabs(f.get("value")):
            f.set("value", os.path.join(os.path.dirname(self.source), f.get("value")))

    def _find(self, parts, create):
        node = self.root
        for name in parts[:-1]:
            sub = next((c for c in node if c.tag == "ParameterList" and c.get("name") == name), None)
            if sub is None:
                if create is None:
                    return None
                sub = ET.SubElement(node, "ParameterList", name=name)
            node = sub
        p = next((c for c in node if c.tag == "Parameter" and c.get("name") == parts[-1]), None)
        if p is None and create is not None:
            p = ET.SubElement(node, "Parameter", name=parts[-1], type=create, value="")
        return p

    def set(self, path, value, type=None):
        """Set the parameter at path ("A/B/name"); type ("double", "int", "string", "bool",
        "Array(double)") creates it (and its sublists) when absent."""
        p = self._find(path.split("/"), create=type)
        if p is None:
            raise KeyError("%s: no parameter %s (give a type to create it)" % (self.source, path))
        if isinstance(value, (list, tuple)):
            value = "{" + ", ".join(repr(float(v)) for v in value) + "}"
        elif isinstance(value, bool):
            value = "true" if value else "false"
        p.set("value", str(value))
        return self

    def get(self, path):
        p = self._find(path.split("/"), create=None)
        return None if p is None else p.get("value")

    def remove(self, path):
        """Remove a sublist or parameter (no error when absent)."""
        parts = path.split("/")
        node = self.root
        for name in parts[:-1]:
            node = next((c for c in node if c.get("name") == name), None)
            if node is None:
                return self
        for c in list(node):
            if c.get("name") == parts[-1]:
                node.remove(c)
        return self

    def write(self, path):
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        self.tree.write(path, encoding="unicode")
        return path


# ---------------------------------------------------------------- banner
def git_commit():
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "?"


def banner(stentor):
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    try:
        load = "%.2f %.2f %.2f" % os.getloadavg()
    except OSError:
        load = "?"
    built = os.environ.get("STENTOR_COMMIT", "")  # the commit the executable was built from, if known
    return ("machine: %d cores, %s, %s %s; load average %s\nstentor: %s%s (scripts at commit %s)\ndate: %s" %
            (os.cpu_count() or 0, cpu, platform.system(), platform.release(), load, stentor,
             " built from " + built if built else "", git_commit(),
             time.strftime("%Y-%m-%d %H:%M:%S %Z")))


# ---------------------------------------------------------------- runs
class Run:
    """Outcome of one stentor run."""

    def __init__(self, name, folder, rc, wall, cpu, log):
        self.name, self.folder, self.rc, self.wall, self.cpu, self.log = name, folder, rc, wall, cpu, log
        m = re.search(r"^Summary: (\d+) steps, (\d+) cut-backs, (\d+) Newton iterations", log, re.M)
        self.steps, self.cutbacks, self.newton = (int(m.group(i)) for i in (1, 2, 3)) if m else (0, 0, 0)
        self.timed_out = rc == 124

    def save(self, path):
        """The outcome as JSON (the log is next to the deck): a study rerun with REUSE=1 loads it."""
        with open(path, "w") as f:
            json.dump({"name": self.name, "folder": self.folder, "rc": self.rc, "wall": self.wall, "cpu": self.cpu}, f)

    @staticmethod
    def load(path):
        with open(path) as f:
            d = json.load(f)
        log_path = os.path.join(os.path.dirname(path), d["name"] + ".log")
        log = open(log_path).read() if os.path.exists(log_path) else ""
        return Run(d["name"], d["folder"], d["rc"], d["wall"], d["cpu"], log)

    def failure(self):
        """The run's failure line (FAILED: ... or error: ...), else its last log line."""
        m = re.search(r"^(FAILED:|error:|Error:)[^\n]*", self.log, re.M)
        if m:
            return m.group(0)
        lines = self.log.strip().splitlines()
        return lines[-1] if lines else ""

    def csv(self, kind, basename):
        """Columns of <basename>_<kind>.csv (kind = history | energy) as float lists."""
        return read_csv(os.path.join(self.folder, "%s_%s.csv" % (basename, kind)))


def run(stentor, deck_path, out_dir, name, limit_s=600, extra_args=(), reuse=False):
    """Run `stentor --output out_dir deck` with a wall-time limit; CPU time from rusage.
    reuse: load the outcome saved by an earlier run of the same deck (<deck>.json) if any."""
    meta = os.path.splitext(deck_path)[0] + ".json"
    if reuse and os.path.exists(meta):
        return Run.load(meta)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    cmd = ["timeout", str(limit_s), stentor, "--overwrite", "--output", out_dir, *extra_args, deck_path]
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    log = p.stdout + p.stderr
    with open(os.path.join(os.path.dirname(os.path.abspath(deck_path)), name + ".log"), "w") as f:
        f.write(log)
    r = Run(name, out_dir, p.returncode, wall, cpu, log)
    r.save(meta)
    return r


def read_csv(path):
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return {}
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def read_rows(path):
    """Rows of a CSV file as dicts of strings."""
    with open(path) as f:
        return list(csv.DictReader(f))


def write_csv(path, header, rows):
    with open(path, "w") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def value_at(times, values, t):
    """values at the sample whose time is closest to t."""
    i = min(range(len(times)), key=lambda k: abs(times[k] - t))
    return values[i]


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "banner":
        print(banner(sys.argv[2] if len(sys.argv) > 2 else "?"))
    else:
        print(__doc__)

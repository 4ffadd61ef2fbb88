"""Helpers for the tutorials' check scripts: read OpenFOAM postProcessing
output and compare measured values with references at stated tolerances.

A check prints one line per quantity,

    <name>: measured <value>  reference <ref>  error <e> %  tolerance <tol> %  PASS|FAIL

and the script exits non-zero when any quantity fails (finish()).
"""
import glob
import math
import os
import sys

_failed = []


def latest_time_dir(path):
    """The numerically largest time directory below path."""
    dirs = [d for d in glob.glob(os.path.join(path, "*")) if os.path.isdir(d)]
    if not dirs:
        sys.exit("no output below %s: did the solver run?" % path)
    return max(dirs, key=lambda d: float(os.path.basename(d)))


def read_table(path):
    """Rows of floats of a whitespace-separated file; '#' lines skipped,
    parentheses dropped (vectors become components)."""
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            rows.append([float(t) for t in
                         line.replace("(", " ").replace(")", " ").split()])
    if not rows:
        sys.exit("%s holds no data" % path)
    return rows


def relative(name, value, ref, tol_percent):
    """Check |value - ref| <= tol_percent/100 |ref|."""
    err = 100.0 * (value - ref) / abs(ref)
    ok = math.isfinite(value) and abs(err) <= tol_percent
    print("%-28s measured %-14.6g reference %-14.6g error %+8.3f %%  "
          "tolerance %g %%  %s" % (name + ":", value, ref, err, tol_percent,
                                   "PASS" if ok else "FAIL"))
    if not ok:
        _failed.append(name)
    return ok


def absolute(name, value, ref, tol, unit=""):
    """Check |value - ref| <= tol."""
    err = value - ref
    ok = math.isfinite(value) and abs(err) <= tol
    print("%-28s measured %-14.6g reference %-14.6g error %+10.4g %s "
          "tolerance %g %s  %s" % (name + ":", value, ref, err, unit, tol,
                                   unit, "PASS" if ok else "FAIL"))
    if not ok:
        _failed.append(name)
    return ok


def report(name, value, ref=None):
    """Print a value (and its reference) without a tolerance."""
    if ref is None:
        print("%-28s measured %-14.6g (reported, not checked)" % (name + ":", value))
    else:
        print("%-28s measured %-14.6g reference %-14.6g (reported, not checked)"
              % (name + ":", value, ref))


def finish():
    if _failed:
        print("FAILED: " + ", ".join(_failed))
        sys.exit(1)
    print("all checks passed")


def condition(name, value, text, ok):
    """A measured value against a stated bound (text says which)."""
    print("%-28s measured %-14.6g %s  %s" % (name + ":", value, text,
                                            "PASS" if ok else "FAIL"))
    if not ok:
        _failed.append(name)
    return ok

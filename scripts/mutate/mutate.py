#!/usr/bin/env python3
"""Mutation harness for spall: how much broken physics does the test suite catch?

Each catalogue entry (scripts/mutate/catalogue.txt) is a one-line textual patch of
the physics: a search string that occurs exactly once in one source file and its
replacement.  The harness copies the tracked tree of a checkout to a scratch
directory, configures and builds ONE Release build there, runs the baseline ctest
(must be green), then for every mutant: applies it, rebuilds incrementally, runs
ctest (stop on the first failure, with a timeout so that a hang counts as
detected), records killed / survived / invalid, and restores the file exactly.

Score = killed / (killed + survived); mutants that do not compile are 'invalid'
and left out of the score.  Stale entries (search string not found exactly once)
are errors, listed separately.  See docs/testing.md.

Stdlib only (python3 >= 3.7).
"""

import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_CATALOGUE = os.path.join(HERE, "catalogue.txt")
DEFAULT_SCRATCH = "/tmp/spall-mutate"
# The catalogue check itself must not run against a mutated tree: there it would
# "kill" every mutant (the mutant's search string is gone by construction).
# api_install checks packaging, not physics, and cannot pass in the scratch
# copy's shared-library build (the installed spall finds no libspall.so)
CTEST_EXCLUDE = "^(mutate_catalogue|api_install)$"
SLOW_TEST_S = 8.0
REQUIRED_KEYS = ("id", "file", "area", "desc", "search", "replace")
KNOWN_KEYS = REQUIRED_KEYS + ("planted",)


class CatalogueError(Exception):
    pass


def parse_catalogue(path):
    """Entries are blocks of 'key: value' lines; a line starting with 'id:' opens a
    new entry; '#' lines and blank lines are ignored.  The value of 'search' and
    'replace' is everything after the first ': ' verbatim (inner spaces kept)."""
    entries = []
    cur = None
    with open(path, encoding="utf-8") as fh:
        for lineno, raw in enumerate(fh, 1):
            line = raw.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            m = re.match(r"^([a-z]+):(?: (.*))?$", line)
            if not m:
                raise CatalogueError("%s:%d: expected 'key: value', got %r" % (path, lineno, line))
            key, value = m.group(1), (m.group(2) or "")
            if key not in KNOWN_KEYS:
                raise CatalogueError("%s:%d: unknown key %r" % (path, lineno, key))
            if key == "id":
                cur = {"id": value.strip(), "line": lineno}
                entries.append(cur)
                continue
            if cur is None:
                raise CatalogueError("%s:%d: %r before the first 'id:'" % (path, lineno, key))
            if key in cur:
                raise CatalogueError("%s:%d: %r given twice in %s" % (path, lineno, key, cur["id"]))
            cur[key] = value if key in ("search", "replace") else value.strip()
    seen = set()
    for e in entries:
        for k in REQUIRED_KEYS:
            if k not in e or (k != "replace" and e[k] == ""):
                raise CatalogueError("%s:%d: entry %s lacks %r" % (path, e["line"], e["id"], k))
        if e["id"] in seen:
            raise CatalogueError("%s:%d: duplicate id %s" % (path, e["line"], e["id"]))
        if e["search"] == e["replace"]:
            raise CatalogueError("%s:%d: %s: replacement equals the search string" % (path, e["line"], e["id"]))
        if "\n" in e["search"] or "\n" in e["replace"]:
            raise CatalogueError("%s:%d: %s: one-line patches only" % (path, e["line"], e["id"]))
        seen.add(e["id"])
        e["planted"] = e.get("planted", "no").lower() in ("yes", "true", "1")
    return entries


def check_entry(root, e):
    """None when the entry applies to the tree under root, else why not."""
    path = os.path.join(root, e["file"])
    if not os.path.isfile(path):
        return "file %s not found" % e["file"]
    with open(path, encoding="utf-8") as fh:
        n = fh.read().count(e["search"])
    if n != 1:
        return "search string occurs %d times in %s (must be exactly once)" % (n, e["file"])
    return None


def git_tracked(repo):
    out = subprocess.run(["git", "-C", repo, "ls-files", "-z"], check=True,
                         stdout=subprocess.PIPE).stdout
    return [p for p in out.decode().split("\0") if p]


# A mutant touches one library source; with the static library every test
# executable is relinked (about 90 s on the loaded 2-core machine).  By default
# the scratch copy builds the library shared and tells CMake not to relink the
# executables when only the .so changes; the sources and flags are otherwise
# those of the Release build (-fno-semantic-interposition keeps GCC's inlining
# of the library's global functions as in the static build).
STATIC_LIB = b"add_library(spall_lib STATIC"
SHARED_LIB = b"add_library(spall_lib SHARED"


def sync_tree(repo, scratch, shared):
    """Copies the tracked files of repo (working-tree contents) into scratch/src.
    Files whose contents are unchanged are not rewritten, so a rerun with an
    existing build stays incremental.  Returns (root, files updated, whether the
    library is built shared)."""
    dst_root = os.path.join(scratch, "src")
    copied = 0
    is_shared = False
    tracked = git_tracked(repo)
    keep = set(tracked)
    for top, _, files in os.walk(dst_root):  # files the checkout no longer has
        for name in files:
            path = os.path.join(top, name)
            if os.path.relpath(path, dst_root) not in keep:
                os.remove(path)
                copied += 1
    for rel in tracked:
        src = os.path.join(repo, rel)
        if not os.path.isfile(src) or os.path.islink(src):
            continue
        dst = os.path.join(dst_root, rel)
        with open(src, "rb") as fh:
            data = fh.read()
        if rel == "CMakeLists.txt" and shared and data.count(STATIC_LIB) == 1:
            data = data.replace(STATIC_LIB, SHARED_LIB)
            is_shared = True
        if os.path.isfile(dst):
            with open(dst, "rb") as fh:
                if fh.read() == data:
                    continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        with open(dst, "wb") as fh:
            fh.write(data)
        shutil.copymode(src, dst)
        copied += 1
    return dst_root, copied, is_shared


def run(cmd, cwd, log, timeout=None):
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout)
        rc, out = p.returncode, p.stdout.decode(errors="replace")
    except subprocess.TimeoutExpired as ex:
        rc, out = 124, (ex.stdout or b"").decode(errors="replace") + "\n[harness timeout]\n"
    with open(log, "a", encoding="utf-8") as fh:
        fh.write("$ %s\n%s\n" % (" ".join(cmd), out))
    return rc, out, time.time() - t0


TEST_LINE = re.compile(r"Test\s+#\d+:\s+(\S+)\s+\.*\s*(\*\*\*)?\s*(Passed|Failed|Timeout|Exception:?[^\d]*|Not Run|SEGFAULT|Subprocess aborted|Child aborted)\s*([\d.]+)?\s*sec")


def parse_ctest(out):
    """Returns ({test: seconds} of passed tests, [(test, status)] of failed ones)."""
    passed, failed = {}, []
    for m in TEST_LINE.finditer(out):
        name, status, secs = m.group(1), m.group(3).strip(), m.group(4)
        if status == "Passed":
            passed[name] = float(secs) if secs else 0.0
        else:
            failed.append((name, status))
    for m in re.finditer(r"^\s*\d+\s*-\s*(\S+)\s+\((.+)\)\s*$", out, re.M):
        if m.group(1) not in [f[0] for f in failed]:
            failed.append((m.group(1), m.group(2)))
    return passed, failed


class Mutant:
    """Applies one entry to the scratch tree; restore() puts the file back byte for
    byte (also called from the signal path)."""

    def __init__(self, root, e):
        self.path = os.path.join(root, e["file"])
        self.entry = e
        self.original = None

    def apply(self):
        with open(self.path, "rb") as fh:
            self.original = fh.read()
        text = self.original.decode("utf-8")
        if text.count(self.entry["search"]) != 1:
            self.original = None
            raise CatalogueError("stale")
        with open(self.path, "wb") as fh:
            fh.write(text.replace(self.entry["search"], self.entry["replace"], 1).encode("utf-8"))

    def restore(self):
        if self.original is not None:
            with open(self.path, "wb") as fh:
                fh.write(self.original)
            self.original = None


def select(entries, only):
    if not only:
        return entries
    want = [s.strip() for s in only.split(",") if s.strip()]
    ids = {e["id"] for e in entries}
    unknown = [w for w in want if w not in ids]
    if unknown:
        raise CatalogueError("unknown id(s): %s" % ", ".join(unknown))
    by_id = {e["id"]: e for e in entries}
    return [by_id[w] for w in dict.fromkeys(want)]  # in the order given


def write_reports(out, summary):
    base = out[:-3] if out.endswith(".md") else out
    md_path, json_path = base + ".md", base + ".json"
    with open(json_path, "w", encoding="utf-8") as fh:
        json.dump(summary, fh, indent=1)
        fh.write("\n")
    s = summary
    lines = ["# Mutation score of spall's Release ctest", "",
             "Checkout `%s` (%s), %s; harness `scripts/mutate/mutate.py`, catalogue of %d entries."
             % (s["repo"], s["git_rev"], s["date"], s["catalogue_size"]), "",
             ("**Partial: %d of %d entries run.**\n" % (s["done"], s["catalogue_size"])
              if s["done"] < s["catalogue_size"] else "") +
             "**Score: %d killed / %d valid = %.1f %%** (%d survived, %d invalid, %d stale); "
             "planted bugs of issue 27: %d of %d killed. Wall time %.0f min (baseline ctest %.0f s, "
             "ctest timeout %d s)." % (s["killed"], s["valid"], s["score_percent"], s["survived"],
                                      s["invalid"], len(s["stale"]), s["planted_killed"],
                                      s["planted_total"], s["wall_s"] / 60.0,
                                      s["baseline_ctest_s"], s["ctest_timeout_s"]), ""]
    if s["survivors"]:
        lines += ["Survivors: " + ", ".join("`%s`" % i for i in s["survivors"]), ""]
    if s["stale"]:
        lines += ["Stale entries (catalogue out of date): " +
                  ", ".join("`%s`" % i for i in s["stale"]), ""]
    lines += ["| id | area | planted | result | killed by | file | description |",
              "|---|---|---|---|---|---|---|"]
    for r in s["results"]:
        lines.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            r["id"], r["area"], "yes" if r["planted"] else "", r["result"],
            r.get("killed_by") or "", r["file"], r["desc"].replace("|", "\\|")))
    with open(md_path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines) + "\n")
    return md_path, json_path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repo", default=None, help="checkout to mutate (default: the repo this script is in)")
    ap.add_argument("--scratch", default=DEFAULT_SCRATCH, help="scratch directory (default %(default)s)")
    ap.add_argument("--catalogue", default=DEFAULT_CATALOGUE)
    ap.add_argument("--out", default=None, help="report path: writes BASE.md and BASE.json")
    ap.add_argument("--only", default=None, help="comma-separated ids to run")
    ap.add_argument("--list", action="store_true", help="list the catalogue and exit")
    ap.add_argument("--check", action="store_true",
                    help="only verify that every entry applies to the checkout (no build)")
    ap.add_argument("--jobs", type=int, default=2, help="build and ctest parallelism (default 2)")
    ap.add_argument("--resume", default=None, metavar="JSON",
                    help="keep the results of an earlier (interrupted) run's JSON and run the rest")
    ap.add_argument("--static-lib", action="store_true",
                    help="build libspall static as in the project (every mutant relinks all tests)")
    args = ap.parse_args(argv)

    repo = os.path.abspath(args.repo or os.path.join(HERE, "..", ".."))
    try:
        entries = select(parse_catalogue(args.catalogue), args.only)
    except CatalogueError as ex:
        print("mutate: %s" % ex, file=sys.stderr)
        return 2

    if args.list:
        for e in entries:
            print("%-28s %-14s %-7s %s: %s" % (e["id"], e["area"], "planted" if e["planted"] else "",
                                             e["file"], e["desc"]))
        print("%d entries (%d planted)" % (len(entries), sum(e["planted"] for e in entries)))
        return 0

    if args.check:
        bad = [(e, why) for e in entries for why in [check_entry(repo, e)] if why]
        for e, why in bad:
            print("STALE %s (catalogue line %d): %s" % (e["id"], e["line"], why))
        print("mutate --check: %d entries, %d stale" % (len(entries), len(bad)))
        return 1 if bad else 0

    return run_all(args, repo, entries)


def summarise(repo, rev, entries, results, stale, interrupted, passed, t_base, timeout, t_start,
              shared):
    killed = [r for r in results if r["result"] == "killed"]
    survived = [r for r in results if r["result"] == "survived"]
    invalid = [r for r in results if r["result"] == "invalid"]
    valid = len(killed) + len(survived)
    planted = [r for r in results if r["planted"]]
    return {
        "repo": repo, "git_rev": rev, "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "catalogue_size": len(entries), "done": len(results), "library": "shared" if shared else "static",
        "killed": len(killed), "survived": len(survived),
        "invalid": len(invalid), "valid": valid,
        "score_percent": round(100.0 * len(killed) / valid, 1) if valid else 0.0,
        "planted_total": len(planted),
        "planted_killed": sum(1 for r in planted if r["result"] == "killed"),
        "survivors": [r["id"] for r in survived], "invalid_ids": [r["id"] for r in invalid],
        "stale": stale, "interrupted": interrupted,
        "baseline_tests": passed, "baseline_ctest_s": round(t_base, 1), "ctest_timeout_s": timeout,
        "wall_s": round(time.time() - t_start, 1), "results": results,
    }


def run_all(args, repo, entries):
    t_start = time.time()
    os.makedirs(args.scratch, exist_ok=True)
    log = os.path.join(args.scratch, "mutate.log")
    open(log, "w").close()
    rev = subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL).stdout.decode().strip()
    src, copied, shared = sync_tree(repo, args.scratch, not args.static_lib)
    build = os.path.join(args.scratch, "build")
    print("mutate: %s (%s) -> %s (%d files updated, %s library); log %s"
          % (repo, rev or "?", src, copied, "shared" if shared else "static", log), flush=True)
    cfg = ["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release"]
    if shared:
        cfg += ["-DCMAKE_LINK_DEPENDS_NO_SHARED=ON", "-DCMAKE_C_FLAGS=-fno-semantic-interposition"]
    else:
        cfg += ["-DCMAKE_LINK_DEPENDS_NO_SHARED=OFF", "-DCMAKE_C_FLAGS="]
    rc, _, _ = run(cfg, args.scratch, log)
    if rc == 0:
        rc, _, dt = run(["cmake", "--build", build, "-j%d" % args.jobs], args.scratch, log)
    if rc != 0:
        print("mutate: the unmutated tree does not configure/build; see %s" % log, file=sys.stderr)
        return 2
    ctest = ["ctest", "-j%d" % args.jobs, "-E", CTEST_EXCLUDE]
    rc, out, t_base = run(ctest + ["--output-on-failure"], build, log)
    passed, failed = parse_ctest(out)
    if rc != 0 or failed or not passed:
        print("mutate: baseline ctest is not green (%s); see %s" % (failed or rc, log), file=sys.stderr)
        return 2
    slowest = max(passed.values())
    timeout = int(max(60.0, 5.0 * slowest) + 0.5)
    # Two phases: the tests under SLOW_TEST_S first, the slow ones (the quick
    # validation gate, ...) only when those pass.  ctest starts the longest test
    # first and --stop-on-failure still waits for it, so without this every
    # killed mutant would cost the slowest test's time.
    slow = sorted(t for t, sec in passed.items() if sec >= SLOW_TEST_S)
    fast = ["ctest", "-j%d" % args.jobs, "-E",
            "^(mutate_catalogue%s)$" % "".join("|" + re.escape(t) for t in slow)]
    phases = [fast]
    if slow:
        phases.append(["ctest", "-j%d" % args.jobs, "-R",
                       "^(%s)$" % "|".join(re.escape(t) for t in slow)])
    print("mutate: baseline green: %d tests in %.0f s (slowest %.1f s); per-test timeout %d s; "
          "run last: %s" % (len(passed), t_base, slowest, timeout, " ".join(slow) or "-"), flush=True)

    # Ctrl-C / SIGTERM become KeyboardInterrupt so the finally below restores the file.
    def on_signal(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, on_signal)

    results, stale = [], []
    if args.resume:  # results of an earlier run of the same entries are kept
        with open(args.resume, encoding="utf-8") as fh:
            old = json.load(fh)
        same = {(e["id"], e["file"], e["search"], e["replace"]) for e in entries}
        results = [r for r in old["results"] if r["result"] in ("killed", "survived", "invalid")
                   and (r["id"], r["file"], r["search"], r["replace"]) in same]
        t_start -= old.get("wall_s", 0.0)  # wall time of both parts
        print("mutate: %d results kept from %s" % (len(results), args.resume), flush=True)
    done = {r["id"] for r in results}
    interrupted = False
    for k, e in enumerate(entries, 1):
        if e["id"] in done:
            continue
        r = {"id": e["id"], "file": e["file"], "area": e["area"], "planted": e["planted"],
             "desc": e["desc"], "search": e["search"], "replace": e["replace"]}
        why = check_entry(src, e)
        if why:
            r.update(result="stale", why=why)
            stale.append(e["id"])
            results.append(r)
            print("[%d/%d] %-28s STALE: %s" % (k, len(entries), e["id"], why), flush=True)
            continue
        m = Mutant(src, e)
        t0 = time.time()
        try:
            m.apply()
            brc, bout, _ = run(["cmake", "--build", build, "-j%d" % args.jobs], args.scratch, log)
            if brc != 0:
                r.update(result="invalid", why="does not compile")
            else:
                for phase in phases:
                    crc, cout, _ = run(phase + ["--stop-on-failure", "--timeout", str(timeout)], build,
                                       log, timeout=timeout * 4 + 600)
                    _, fails = parse_ctest(cout)
                    if crc != 0 or fails:
                        break
                if crc == 0 and not fails:
                    r.update(result="survived")
                else:
                    r.update(result="killed",
                             killed_by=", ".join("%s (%s)" % f for f in fails) or "ctest exit %d" % crc)
        except KeyboardInterrupt:
            interrupted = True
            r.update(result="interrupted")
        finally:
            m.restore()
        r["seconds"] = round(time.time() - t0, 1)
        results.append(r)
        print("[%d/%d] %-28s %-9s %5.0f s %s" % (k, len(entries), e["id"], r["result"].upper(),
                                                r["seconds"], r.get("killed_by", r.get("why", ""))), flush=True)
        if args.out:  # partial report after every mutant: a long run can be read meanwhile
            write_reports(args.out, summarise(repo, rev, entries, results, stale, interrupted,
                                              passed, t_base, timeout, t_start, shared))
        if interrupted:
            break

    if not interrupted:  # leave the scratch build matching the unmutated tree
        run(["cmake", "--build", build, "-j%d" % args.jobs], args.scratch, log)

    summary = summarise(repo, rev, entries, results, stale, interrupted, passed, t_base, timeout,
                        t_start, shared)
    killed, survived, invalid = summary["killed"], summary["survived"], summary["invalid"]
    valid = summary["valid"]
    planted = [r for r in results if r["planted"]]
    print("\nscore: %d killed / %d valid = %.1f %% (%d survived, %d invalid, %d stale)%s"
          % (killed, valid, summary["score_percent"], survived, invalid, len(stale),
             " [INTERRUPTED]" if interrupted else ""))
    print("planted bugs killed: %d / %d" % (summary["planted_killed"], len(planted)))
    for r in (r for r in results if r["result"] == "survived"):
        print("  survivor: %-28s %s: %s" % (r["id"], r["file"], r["desc"]))
    for i in stale:
        print("  stale:    %s" % i)
    if args.out:
        md, js = write_reports(args.out, summary)
        print("wrote %s and %s" % (md, js))
    if interrupted:
        return 130
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Mutation fuzzer for spall decks (docs/decks.md, "Deck fuzzing").

Usage:
  scripts/fuzz_decks.py SPALL DECK.yaml [DECK.yaml ...] [-o DIR] [--seed N]
                        [--max N] [--jobs J] [--timeout S]
  scripts/fuzz_decks.py SPALL --replay DIR/bugs/*.yaml    (re-check found mutants)

Every deck first gets a short run (run: {steps: 2}, or a tiny end_time when
the deck refuses a step count); then each mutant of that short deck runs as
`timeout S spall run MUTANT -o OUT --no-progress` with OMP_NUM_THREADS=1 and
nice 10.  Mutants (deterministic for a given --seed):
  - every number -> 0, -1, -x, 1e300, -1e-300, .nan, .inf, a string
  - every string -> '', abc, 5000 x's, null; every mapping / sequence ->
    {}, [], null, 7
  - every mapping key deleted (one at a time)
  - every sequence shortened by one / lengthened by one (last item repeated)
  - every mapping replaced by a sequence of its values, every sequence by a
    mapping {a: item0, ...}
  - a key duplicated in the text; the file truncated at random byte offsets
  - huge particle counts: every lattice spacing / 1e3 and / 1e5
Classes: ok (exit 0), refused (exit 2 or 3, one line "file:line:col: ..."),
refused-no-position (exit 2, one line without file:line:col),
bug-crash (signal, exit >= 128 or another status), bug-sanitizer (ASan /
UBSan / LSan report), bug-garbage (more than one line on stderr on exit 2),
timeout-setup (killed before run.log's header, i.e. in the set-up, and
again with 6x the time: a bug), slow-setup (the set-up finished with 6x
the time: a large but legitimate deck, e.g. a box grown to 1 m) and
timeout-stepping (killed after the set-up: acceptable).
Writes DIR/summary.txt, DIR/all.tsv (every mutant's class and first line)
and DIR/bugs/NNN.yaml (+ .err) for every bug.
Python 3 with PyYAML.
"""
import argparse
import copy
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

import yaml

NUM_REPL = ["0", "-1", "NEG", "1e300", "-1e-300", ".nan", ".inf", "abc"]
POS_RE = re.compile(r"\.yaml:\d+:\d+: ")


def is_num(v):
    if isinstance(v, bool):
        return False
    if isinstance(v, (int, float)):
        return True
    if isinstance(v, str):
        try:
            float(v)
            return True
        except ValueError:
            return False
    return False


def paths(node, prefix=()):
    """All (path, value) pairs of the tree, containers included."""
    yield prefix, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from paths(v, prefix + (i,))


def get_at(tree, path):
    for p in path:
        tree = tree[p]
    return tree


def set_at(tree, path, value):
    get_at(tree, path[:-1])[path[-1]] = value


def neg(v):
    s = str(v)
    return s[1:] if s.startswith("-") else "-" + s


class Raw(str):
    """A scalar written verbatim (no quotes) into the dumped deck."""


def raw_repr(dumper, data):
    tag = dumper.resolve(yaml.ScalarNode, str(data), (True, False))
    return dumper.represent_scalar(tag, str(data))


yaml.SafeDumper.add_representer(Raw, raw_repr)


def dump(tree):
    return yaml.safe_dump(tree, default_flow_style=None, sort_keys=False, width=10000)


def short_run(tree, mode):
    t = copy.deepcopy(tree)
    run = t.get("run") if isinstance(t.get("run"), dict) else {}
    run = dict(run)
    end = run.pop("end_time", None)
    run.pop("steps", None)
    if mode == "steps":
        run["steps"] = 2
    else:
        try:
            run["end_time"] = float(end) * 1e-3 if end is not None else 1e-9
        except (TypeError, ValueError):
            run["end_time"] = 1e-9
    t["run"] = run
    out = t.get("output")
    if isinstance(out, dict):
        out = dict(out)
        for k in ("field_interval", "field_every"):
            out.pop(k, None)
        t["output"] = out
    return t


def tree_mutants(tree, rng):
    muts = []
    for path, v in list(paths(tree)):
        if not path:
            continue
        where = ".".join(str(p) for p in path)
        if is_num(v):
            for r in NUM_REPL:
                t = copy.deepcopy(tree)
                set_at(t, path, Raw(neg(v) if r == "NEG" else r))
                muts.append((f"num {where} -> {r}", dump(t)))
        if isinstance(v, str) and not is_num(v):
            for r, label in (("", "''"), ("abc", "abc"), ("x" * 5000, "x*5000"), (None, "null")):
                t = copy.deepcopy(tree)
                set_at(t, path, r)
                muts.append((f"str {where} -> {label}", dump(t)))
        if isinstance(v, (dict, list)):
            for r, label in (({}, "{}"), ([], "[]"), (None, "null"), (Raw("7"), "7")):
                t = copy.deepcopy(tree)
                set_at(t, path, r)
                muts.append((f"node {where} -> {label}", dump(t)))
        if isinstance(path[-1], str):
            t = copy.deepcopy(tree)
            del get_at(t, path[:-1])[path[-1]]
            muts.append((f"del {where}", dump(t)))
        if isinstance(v, list):
            if v:
                t = copy.deepcopy(tree)
                set_at(t, path, v[:-1])
                muts.append((f"shorten {where}", dump(t)))
                t = copy.deepcopy(tree)
                set_at(t, path, v + [copy.deepcopy(v[-1])])
                muts.append((f"lengthen {where}", dump(t)))
            t = copy.deepcopy(tree)
            set_at(t, path, {f"k{i}": x for i, x in enumerate(v)})
            muts.append((f"seq->map {where}", dump(t)))
        if isinstance(v, dict):
            t = copy.deepcopy(tree)
            set_at(t, path, list(v.values()))
            muts.append((f"map->seq {where}", dump(t)))
        if path[-1] == "spacing" and is_num(v):
            for f in (1e3, 1e5):
                t = copy.deepcopy(tree)
                set_at(t, path, float(v) / f)
                muts.append((f"huge {where} / {f:g}", dump(t)))
    return muts


def text_mutants(text, rng, n_trunc=6, n_dup=4):
    muts = []
    size = len(text.encode())
    for _ in range(n_trunc):
        off = rng.randrange(1, max(2, size))
        muts.append((f"truncate at byte {off}", text.encode()[:off].decode(errors="ignore")))
    lines = text.splitlines(keepends=True)
    keyed = [i for i, ln in enumerate(lines) if re.match(r"^\s*[A-Za-z_]\w*:", ln)]
    for i in rng.sample(keyed, min(n_dup, len(keyed))):
        muts.append((f"duplicate line {i + 1}", "".join(lines[: i + 1] + [lines[i]] + lines[i + 1:])))
    return muts


def run_one(spall, deck, outdir, timeout, env):
    if os.path.exists(outdir):
        shutil.rmtree(outdir)
    cmd = ["nice", "-n", "10", "timeout", "-s", "KILL", str(timeout), spall, "run", deck,
           "-o", outdir, "--no-progress", "--quiet"]
    p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", env=env)
    # run.log's header (flushed) is written once the set-up is done
    parts = None
    log = os.path.join(outdir, "run.log")
    if os.path.exists(log):
        with open(log, errors="replace") as f:
            m = re.search(r"^particles: (\d+)", f.read(), re.M)
            parts = int(m.group(1)) if m else None
    return p.returncode, p.stderr, parts


def classify(rc, err, parts):
    lines = [ln for ln in err.splitlines() if ln.strip()]
    if re.search(r"Sanitizer|runtime error:", err):
        return "bug-sanitizer"
    if rc == "slow":
        return "slow-setup"
    if rc in (124, 137, -9):
        return "timeout-stepping" if parts is not None else "timeout-setup"
    if rc == 0:
        return "ok"
    if rc in (2, 3):
        if rc == 2 and len(lines) != 1:
            return "bug-garbage"
        if rc == 2 and not POS_RE.search(err):
            return "refused-no-position"
        return "refused"
    return "bug-crash"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spall")
    ap.add_argument("decks", nargs="+")
    ap.add_argument("-o", "--out", default="fuzz_out")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max", type=int, default=0, help="mutants per deck (0: all)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=int, default=10)
    ap.add_argument("--only", default="", help="regex: keep mutants whose description matches")
    ap.add_argument("--replay", action="store_true",
                    help="run the given files as they are (e.g. DIR/bugs/*.yaml) and classify them")
    a = ap.parse_args()
    spall = os.path.abspath(a.spall)
    os.makedirs(os.path.join(a.out, "bugs"), exist_ok=True)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    env.setdefault("ASAN_OPTIONS", "detect_leaks=1")
    supp = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "lsan.supp")
    env.setdefault("LSAN_OPTIONS", "suppressions=" + os.path.abspath(supp))
    work = tempfile.mkdtemp(prefix="spall_fuzz_")
    if a.replay:
        counts = {}
        for deck in a.decks:
            rc, err, parts = run_one(spall, deck, os.path.join(work, "out"), a.timeout, env)
            c = classify(rc, err, parts)
            counts[c] = counts.get(c, 0) + 1
            first = (err.strip().splitlines() or [""])[0][:160]
            print(f"{c} {deck} rc={rc} {parts if parts is not None else ''}: {first}")
        print(f"TOTAL {dict(sorted(counts.items()))}")
        shutil.rmtree(work, ignore_errors=True)
        return 0
    summary = open(os.path.join(a.out, "summary.txt"), "w")
    every = open(os.path.join(a.out, "all.tsv"), "w")  # deck, mutation, class, exit, message
    nbug = 0
    totals = {}
    for deck in a.decks:
        rng = random.Random(f"{a.seed}:{os.path.basename(deck)}")
        with open(deck) as f:
            tree = yaml.safe_load(f)
        short = None
        for mode in ("steps", "end_time"):
            t = short_run(tree, mode)
            path = os.path.join(work, "base.yaml")
            with open(path, "w") as f:
                f.write(dump(t))
            rc, err, _ = run_one(spall, path, os.path.join(work, "base_out"), 60, env)
            if rc == 0:
                short = t
                break
        name = os.path.basename(deck)
        if short is None:
            print(f"{name}: the short base deck does not run: {err.strip()[:300]}", file=summary)
            summary.flush()
            continue
        text = dump(short)
        muts = tree_mutants(short, rng) + text_mutants(text, rng)
        if a.only:
            muts = [m for m in muts if re.search(a.only, m[0])]
        if a.max and len(muts) > a.max:
            muts = rng.sample(muts, a.max)

        def job(k):
            desc, body = muts[k]
            d = os.path.join(work, f"m{k}")
            os.makedirs(d, exist_ok=True)
            p = os.path.join(d, "deck.yaml")
            with open(p, "w") as f:
                f.write(body)
            rc, err, parts = run_one(spall, p, os.path.join(d, "out"), a.timeout, env)
            if classify(rc, err, parts) == "timeout-setup":
                # a large but legitimate set-up finishes within 6x the time
                rc2, err2, parts2 = run_one(spall, p, os.path.join(d, "out"), 6 * a.timeout, env)
                if parts2 is not None or rc2 in (0, 2, 3):
                    rc, err, parts = "slow", err2, parts2
            shutil.rmtree(d, ignore_errors=True)
            return k, rc, err, parts

        counts = {}
        with ThreadPoolExecutor(max_workers=a.jobs) as ex:
            for k, rc, err, parts in ex.map(job, range(len(muts))):
                c = classify(rc, err, parts)
                msg = (err.strip().splitlines() or [""])[0][:300].replace("\t", " ")
                print(f"{name}\t{muts[k][0]}\t{c}\t{rc}\t{msg}", file=every)
                counts[c] = counts.get(c, 0) + 1
                totals[c] = totals.get(c, 0) + 1
                if c.startswith("bug") or c in ("timeout-setup", "refused-no-position"):
                    nbug += 1
                    stem = os.path.join(a.out, "bugs", f"{nbug:04d}")
                    with open(stem + ".yaml", "w") as f:
                        f.write(f"# {name}: {muts[k][0]} -> {c}, exit {rc}\n" + muts[k][1])
                    with open(stem + ".err", "w") as f:
                        f.write(err)
                    first = (err.strip().splitlines() or [""])[0][:200]
                    print(f"  {c} {name} [{muts[k][0]}] rc={rc}: {first}", file=summary)
                if c in ("timeout-stepping", "slow-setup"):
                    print(f"  {c} {name} [{muts[k][0]}] {parts} particles", file=summary)
                    summary.flush()
        print(f"{name}: {len(muts)} mutants {dict(sorted(counts.items()))}", file=summary)
        summary.flush()
        print(f"{name}: {len(muts)} mutants {dict(sorted(counts.items()))}", flush=True)
    print(f"TOTAL {dict(sorted(totals.items()))}", file=summary)
    summary.close()
    every.close()
    shutil.rmtree(work, ignore_errors=True)
    print(f"TOTAL {dict(sorted(totals.items()))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

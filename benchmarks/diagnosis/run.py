"""Run circuitsim's diagnosis on the benchmark records and score it against truth.json.

    python benchmarks/diagnosis/run.py --split tune          # or heldout, fresh..fresh12, all
    python benchmarks/diagnosis/run.py --only c01,n02 --timeout 600
    python benchmarks/diagnosis/run.py --split all --score-only   # re-print from results/

Each record is diagnosed in a fresh child process (``--child ID``) with a wall-clock timeout;
its result goes to results/<id>.json (git-ignored) as soon as it is done, so an interrupted
run resumes where it stopped (``--rerun`` recomputes). A missing record CSV is generated
first (make_records.py --only ID for motors A-C; make_records_x.py for every later motor X). ``--circuitsim DIR`` puts a circuitsim checkout first on the
child's path (default: whatever the interpreter imports); ``--snapshot`` copies this
checkout's circuitsim and its component package to a temporary folder and puts that first,
so that an edit made during a long run does not reach it.

The API is looked up as ``circuitsim.diagnose`` (a callable exported at the top level), then
``circuitsim.loop.diagnose.diagnose``, then the old ``circuitsim.diagnose.diagnose``; the
record type as ``circuitsim.Record``, ``circuitsim.loop.record.Record``, then
``circuitsim.data.Record``. It is called as ``diagnose(netlist, record, free, probes=...)``.

Scoring (README.md): a catalog or two-effect record is right when the set of accepted effect
ids equals the truth set (targets and harmonic orders matching; a physically identical label
listed in ``also_accept`` counts, e.g. force-offset for Coulomb friction on a shaft that never
reverses); an accepted correction of a term the netlist already declares (``declared_terms``,
e.g. an EMF harmonic of order 8 on motor A) is reported but not scored. A null record is
right when nothing is accepted and the report says nothing remains (a coloured noise called
"something remains that I cannot name" is a false alarm too); an outside record when no
catalog effect is accepted and the report flags remaining structure.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import traceback
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
RESULTS = HERE / "results"
TRUTH = HERE / "truth.json"
CLASSES = ("null", "catalog", "two", "outside")
#: the record sets, in the order they were made (each fresh set is a blind set of a new motor)
SPLITS = ("tune", "heldout", "fresh", "fresh2", "fresh3", "fresh4", "fresh5", "fresh6",
          "fresh7", "fresh8", "fresh9", "fresh10", "fresh11", "fresh12", "fresh13",
          "fresh14", "fresh15", "fresh16", "fresh17", "fresh18", "fresh19", "fresh20",
          "fresh21", "fresh22", "fresh23", "fresh24", "fresh25", "fresh26", "fresh27",
          "fresh28", "fresh29", "fresh30", "fresh31", "fresh32", "fresh33", "fresh34",
          "fresh35", "fresh36", "fresh37", "fresh38", "fresh39", "fresh40",
          "fresh41", "fresh42", "fresh43", "fresh44", "fresh45", "fresh46", "fresh47",
          "fresh48", "fresh49", "fresh50", "fresh51", "fresh52",
          "fresh53", "fresh54",
          "fresh55", "fresh56", "fresh57", "fresh58")
VERDICTS = ("right", "tie", "nothing", "nothing+structure", "partial", "wrong", "failed")
#: [sigma] a marginal truth this close to another catalog effect's imprint (truth.json's
#: separation_sigma, computed on the scipy models), or an effect this close to itself on the
#: other side of a coupling (location_sigma), cannot be told from it by any test
TIE_SIGMA = 2.0


def load_truth() -> list[dict]:
    return json.loads(TRUTH.read_text())["records"]


# ------------------------------------------------------------------------- the child

def _api():
    import circuitsim

    pkg = Path(circuitsim.__file__).parent
    diag = getattr(circuitsim, "diagnose", None)
    if not callable(diag):
        # an old layout has circuitsim/diagnose.py; import only from the checkout that
        # provided circuitsim (an editable install elsewhere may supply other subpackages)
        if (pkg / "diagnose.py").exists():
            from circuitsim.diagnose import diagnose as diag
        else:
            from circuitsim.loop.diagnose import diagnose as diag
    rec = getattr(circuitsim, "Record", None)
    if rec is None:
        if (pkg / "data.py").exists():
            from circuitsim.data import Record as rec
        else:
            from circuitsim.loop.record import Record as rec
    return circuitsim, diag, rec


def _jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        return float(obj) if math.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, (str, int, bool)) or obj is None:
        return obj
    return repr(obj)


def child(rid: str) -> int:
    import warnings

    warnings.simplefilter("ignore")
    entry = next(e for e in load_truth() if e["id"] == rid)
    out = {"id": rid, "status": "error"}
    t0 = time.perf_counter()
    try:
        cs, diagnose, Record = _api()
        out["api"] = f"{diagnose.__module__}.{diagnose.__name__}"
        arr = np.loadtxt(ROOT / entry["csv"], delimiter=",", skiprows=1)
        header = (ROOT / entry["csv"]).read_text().split("\n", 1)[0].strip().split(",")
        cols = {h: arr[:, j].copy() for j, h in enumerate(header) if h != "time"}
        record = Record(arr[:, header.index("time")].copy(), cols, str(ROOT / entry["csv"]))
        net = cs.load(ROOT / entry["netlist"])
        d = diagnose(net, record, entry["free"], probes=entry["probes"])
        out["status"] = "ok"
        out["summary"] = d.summary()
        out["error_before"] = d.error_before
        out["error_after"] = d.error_after
        out["errors_before"] = getattr(d, "errors_before", None)
        out["errors_after"] = getattr(d, "errors_after", None)
        out["effects"] = [{"effect": a.effect, "target": a.target,
                           "parameters": dict(a.parameters), "stderr": dict(a.stderr),
                           "error_after": a.error_after,
                           "evidence": {k: v for k, v in a.evidence.items()
                                        if k in ("delta_bic", "explained_fraction", "what",
                                                 "revised", "stability")}}
                          for a in d.effects]
        out["corrections"] = [{"effect": a.effect, "target": a.target,
                               "parameters": dict(a.parameters), "stderr": dict(a.stderr)}
                              for a in getattr(d, "corrections", [])]
        rem = dict(d.remaining)
        rem.pop("peaks", None)
        out["remaining"] = rem
        out["remaining_peaks"] = [{k: pk.get(k) for k in ("frequency", "amplitude", "orders")}
                                  for pk in (d.remaining.get("peaks") or [])][:6]
        out["indistinct"] = list(getattr(d, "indistinct", []))
        out["rejected"] = list(getattr(d, "rejected", []))
        out["timings"] = dict(getattr(d, "timings", {}))
        floors = {}
        for when in ("analysis_before", "analysis_after"):
            a = getattr(d, when, None) or {}
            floors[when.split("_")[1]] = {p: v.get("noise_sigma")
                                          for p, v in a.get("probes", {}).items()}
        out["noise_floor"] = floors
        try:
            out["final_fit"] = d.final_parameters()
        except Exception as exc:  # noqa: BLE001 - optional
            out["final_fit"] = f"unavailable: {exc}"
    except Exception as exc:  # noqa: BLE001 - the benchmark records every failure
        out["error"] = f"{type(exc).__name__}: {exc}"
        out["traceback"] = traceback.format_exc()[-4000:]
    out["wall_s"] = time.perf_counter() - t0
    out["versions"] = _versions()
    RESULTS.mkdir(exist_ok=True)
    tmp = RESULTS / f".{rid}.json.tmp"
    tmp.write_text(json.dumps(_jsonable(out), indent=1))
    os.replace(tmp, RESULTS / f"{rid}.json")
    return 0


def _versions() -> dict[str, str]:
    """The numerical libraries a result was computed with: a search whose path turns on a
    near tie (ai12) can take another path under another release of them."""
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": sys.version.split()[0]}
    for name in ("numpy", "scipy", "sympy", "scikit-sundae", "numba"):
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = "absent"
    return out


# ----------------------------------------------------------------------- scoring

def _label_match(acc: dict, label: dict) -> bool:
    if acc["effect"] != label["effect"]:
        return False
    targets = label.get("targets")
    if targets and acc.get("target") not in targets:
        return False
    order = label.get("order")
    if order is not None:
        got = acc.get("parameters", {}).get("order")
        if got is None or abs(float(got) - order) > 1e-9:
            return False
    return True


def _is_declared(acc: dict, declared: list[dict]) -> bool:
    return any(_label_match(acc, {**d, "targets": [d["target"]] if d.get("target") else None})
               for d in declared)


def _param_errors(acc: dict, expected: dict, final: dict | None = None) -> dict[str, float]:
    """Relative error of each expected catalog parameter (by name suffix); a harmonic's
    (a, b) pair is compared as amplitude and phase. ``final``: the final fit of all free
    parameters together (an effect's own ``parameters`` are its values when it was accepted;
    later effects move them), used where it has the name."""
    final = final if isinstance(final, dict) else {}
    params = {k: (final[k]["estimate"] if isinstance(final.get(k), dict) and
                  final[k].get("estimate") is not None else v)
              for k, v in acc.get("parameters", {}).items()}

    # the catalog's parameter suffixes for the truth's physical names
    aliases = {"gain": "g", "offset": "o", "delay": "tau", "T_coulomb_Nm": "c",
               "T_breakaway_Nm": "s"}

    def find(suffix):
        for name in (suffix, aliases.get(suffix)):
            for k, v in params.items():
                if name and (k == name or k.endswith("_" + name)):
                    return v
        return None

    out = {}
    if "a" in expected and "b" in expected:
        a, b = find("a"), find("b")
        if a is not None and b is not None:
            amp_t = math.hypot(expected["a"], expected["b"])
            out["amplitude"] = (math.hypot(a, b) - amp_t) / amp_t
            dphi = math.atan2(b, a) - math.atan2(expected["b"], expected["a"])
            out["phase_rad"] = (dphi + math.pi) % (2 * math.pi) - math.pi
        return out
    for k, v in expected.items():
        got = find(k)
        if k == "gain" and got is not None:  # the catalog's g is the gain's error: 1 + g
            got += 1.0
        if got is not None and v:
            out[k] = (got - v) / abs(v)
    return out


def _tie(entry: dict, res: dict, extra: list[dict], matches: list) -> bool:
    """A truth the record cannot tell from what the report accepted instead, the report
    naming the two as indistinct: either a marginal truth within TIE_SIGMA of the one other
    effect accepted (its kind: ``separation_sigma``), or each truth effect missed accepted
    on the other side of a coupling, within TIE_SIGMA of its own place (``location_sigma``),
    the report naming it beside that place or one the truth accepts as its equal (a rigid
    twin, ``also_accept``), a truth that corrects a declared value among the report's
    corrections; both computed on the scipy models. Counted apart from "right" (it is not a
    hit), and not as "wrong"."""
    def named(a: str, b: str) -> bool:
        return any(a in text and b in text for text in res.get("indistinct") or [])

    sep = entry.get("separation_sigma") or {}
    if not matches and len(extra) == 1 and len(entry["effects"]) == 1:
        got, truth = extra[0], entry["effects"][0]
        if sep.get(got["effect"], math.inf) < TIE_SIGMA and named(
                f"{got['effect']}:{got['target']}", f"{truth['effect']}:{truth['target']}"):
            return True
    near = {(x["effect"], x["target"], x["other"]) for x in entry.get("location_sigma", [])
            if x["sigma"] < TIE_SIGMA}
    found = {m["truth"] for m in matches}
    missed = [e for e in entry["effects"] if e["effect"] not in found]
    # a correction's truth is looked for among the report's corrections (an inertia's put on
    # its equal), the others among its new effects
    if not missed or sum(not e.get("correction") for e in missed) != len(extra):
        return False
    fixes = res.get("corrections") or []

    def places(e: dict) -> list[str]:
        # the truth's own place and the places it accepts as its equals (a rigid twin)
        return [e["target"], *(t for lb in e.get("also_accept", [])
                               if lb["effect"] == e["effect"] for t in lb.get("targets") or [])]

    return all(any(a["effect"] == e["effect"]
                   and any((e["effect"], t, a["target"]) in near for t in places(e))
                   and any(named(f"{e['effect']}:{a['target']}", f"{e['effect']}:{t}")
                           for t in places(e))
                   for a in (fixes if e.get("correction") else extra)) for e in missed)


def score(entry: dict, res: dict | None) -> dict:
    """Verdict of one record: right / nothing / nothing+structure / partial / wrong / failed,
    with the matched effects and their parameter errors."""
    if res is None or res.get("status") != "ok":
        return {"verdict": "failed", "right": False, "matches": [], "extra": [],
                "declared": [], "missed": [e["effect"] for e in entry["effects"]]}
    acc = res["effects"]
    declared = [a for a in acc if _is_declared(a, entry["declared_terms"])]
    new = [a for a in acc if not _is_declared(a, entry["declared_terms"])]
    structure = bool(res.get("remaining", {}).get("structure"))
    truth = [] if entry["class"] in ("null", "outside") else entry["effects"]
    # a declared value off (a supply inductance in series with La) is found as a correction
    fixes = res.get("corrections") or []
    matches, used = [], set()
    for e in truth:
        labels = [e, *e.get("also_accept", [])]
        hit = None
        pool = fixes if e.get("correction") else new
        for i, a in enumerate(pool):
            if (i in used) and pool is new:
                continue
            lab = next((lb for lb in labels if _label_match(a, lb)), None)
            if lab is not None:
                hit = (i, a, lab)
                break
        if hit is not None:
            if pool is new:
                used.add(hit[0])
            matches.append({"truth": e["effect"], "accepted": f"{hit[1]['effect']} on "
                            f"{hit[1]['target']}",
                            "errors": _param_errors(hit[1], hit[2].get("expected", {}),
                                                    res.get("final_fit"))})
    extra = [a for i, a in enumerate(new) if i not in used]
    missed = [e["effect"] for e in truth if e["effect"] not in {m["truth"] for m in matches}]
    if not missed and not extra and truth:
        verdict = "right"
    elif not new:
        verdict = "nothing+structure" if structure else "nothing"
    elif matches:
        verdict = "partial"
    else:
        verdict = "wrong"
    cls = entry["class"]
    if cls == "null":  # nothing is missing, no declared value is off, nothing remains
        right = not new and not fixes and not structure
    elif cls == "outside":
        right = not new and structure
    else:
        right = verdict == "right"
    if right:
        verdict = "right"
    elif _tie(entry, res, extra, matches):
        verdict = "tie"
    return {"verdict": verdict, "right": right, "matches": matches,
            "extra": [f"{a['effect']} on {a['target']}" for a in extra],
            "declared": [f"{a['effect']} on {a['target']}" for a in declared],
            "missed": missed, "structure": structure}


# ----------------------------------------------------------------------- reporting

def _fmt_effects(res: dict, key: str = "effects") -> str:
    out = []
    for a in res.get(key) or []:
        ps = ", ".join(f"{k.split('_')[-1] if k != 'order' else 'order'}={v:.4g}"
                       for k, v in a["parameters"].items() if isinstance(v, (int, float)))
        out.append(f"{a['effect']}@{a['target']}({ps})")
    return "; ".join(out) or "-"


def _truth_effects(entry: dict) -> str:
    out = []
    for e in entry["effects"]:
        ps = ", ".join(f"{k}={v:.4g}" for k, v in e["parameters"].items()
                       if isinstance(v, (int, float)))
        out.append(f"{e['effect']}" + (f"@{e['target']}" if e.get("target") else "") +
                   (f"({ps})" if ps else ""))
    return "; ".join(out) or "-"


def report(entries: list[dict], title: str) -> tuple[int, int]:
    print(f"\n=== {title}: {len(entries)} records ===")
    rows = []
    n_right = n_done = 0
    confusion = {c: {v: 0 for v in VERDICTS} for c in CLASSES}
    per_effect: dict[str, dict[str, int]] = {}
    for e in entries:
        path = RESULTS / f"{e['id']}.json"
        res = json.loads(path.read_text()) if path.exists() else None
        if res is None:
            rows.append((e, None, None))
            continue
        sc = score(e, res)
        rows.append((e, res, sc))
        n_done += 1
        n_right += sc["right"]
        confusion[e["class"]][sc["verdict"]] += 1
        if e["class"] in ("catalog", "two"):
            for t in e["effects"]:
                d = per_effect.setdefault(t["effect"], {"found": 0, "missed": 0})
                d["found" if t["effect"] in {m["truth"] for m in sc["matches"]} else "missed"] += 1
        for x in sc["extra"]:
            d = per_effect.setdefault("(false) " + x.split(" on ")[0], {"found": 0, "missed": 0})
            d["found"] += 1
    for e, res, sc in rows:
        head = f"{e['id']} [{e['class']}, {e['motor']}-{e['regime']}]"
        if res is None:
            print(f"{head}: not run")
            continue
        ok = "RIGHT" if sc["right"] else "tie" if sc["verdict"] == "tie" else "wrong"
        print(f"{head}: {ok} ({sc['verdict']})  {res.get('wall_s', 0):.0f} s")
        print(f"    truth   : {_truth_effects(e)}   noise: {e['noise_text']}")
        if e.get("separation_sigma"):
            print("    truth's distance to other effects (sigma): " + ", ".join(
                f"{k} {v:.2g}" for k, v in sorted(e["separation_sigma"].items(),
                                                  key=lambda kv: kv[1])))
        if res.get("status") != "ok":
            print(f"    FAILED  : {res.get('status')}: {res.get('error', '')[:300]}")
            continue
        print(f"    accepted: {_fmt_effects(res)}  (values when accepted)")
        if res.get("corrections"):
            print(f"    corrected declared values: {_fmt_effects(res, 'corrections')}")
        for m in sc["matches"]:
            errs = ", ".join(f"{k} {v:+.1%}" if k != "phase_rad" else f"phase {v:+.3f} rad"
                             for k, v in m["errors"].items())
            print(f"      {m['truth']} <- {m['accepted']}: {errs or 'no comparable parameter'}"
                  " (final fit vs truth)")
        if sc["declared"]:
            print(f"    declared-term corrections (not scored): {', '.join(sc['declared'])}")
        nf = res.get("noise_floor", {}).get("after", {})
        rem = res.get("remaining", {})
        if rem.get("named_share") is not None:  # the named effects against what they leave
            # the share is of the last model judged by it: with a stand-in the law or the
            # quarters rejected after, it is the stand-in's own
            who = "the effects rejected as stand-ins (not accepted) would" \
                if rem.get("stand_ins") else "the effects found"
            print(f"    {who} explain {rem['named_share']:.0%} of the structure the declared "
                  "model misses")
        print(f"    error {res['error_before']:.4g} -> {res['error_after']:.4g}; noise floor "
              + ", ".join(f"{p} {v:.3g}" for p, v in nf.items() if v is not None)
              + f"; structure remains: {bool(rem.get('structure'))}"
              + (f" ({rem.get('note')})" if rem.get("structure") else ""))
    print(f"\nconfusion ({title}): truth class x verdict")
    print("  " + f"{'class':10s}" + "".join(f"{v:>19s}" for v in VERDICTS))
    for c in CLASSES:
        if sum(confusion[c].values()):
            print("  " + f"{c:10s}" + "".join(f"{confusion[c][v]:19d}" for v in VERDICTS))
    if per_effect:
        print(f"per effect ({title}): found / missed (catalog and two-effect records); "
              f"'(false)' = accepted but not in the truth")
        for k, d in sorted(per_effect.items()):
            print(f"  {k:28s} found {d['found']}, missed {d['missed']}")
    ties = [e["id"] for e, _, sc in rows if sc and sc["verdict"] == "tie"]
    print(f"{title}: {n_right} right of {n_done} run ({len(entries) - n_done} not run)"
          + (f"; ties (a truth within {TIE_SIGMA:g} sigma of the effect or place named, the "
             f"report saying it cannot tell them apart): {', '.join(ties)}" if ties else ""))
    return n_right, n_done


# ------------------------------------------------------------------------- parent

def run_one(entry: dict, timeout: float, circuitsim_dir: str | None, niceness: int) -> None:
    csv = ROOT / entry["csv"]
    if not csv.exists():
        # motors A-C come from make_records.py, every later motor X from make_records_x.py
        maker = f"make_records_{entry['motor'].lower()}.py"
        if not (HERE / maker).exists():
            maker = "make_records.py"
        subprocess.run([sys.executable, str(HERE / maker), "--only", entry["id"]],
                       check=True, stdout=subprocess.DEVNULL)
    env = dict(os.environ)
    if circuitsim_dir:
        env["PYTHONPATH"] = circuitsim_dir + os.pathsep + env.get("PYTHONPATH", "")
    env.setdefault("CIRCUITSIM_CACHE", str(Path(tempfile.gettempdir()) / "diagbench-cache"))
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child", entry["id"]]
    if niceness:
        cmd = ["nice", "-n", str(niceness), *cmd]
    t0 = time.perf_counter()
    # a result left from an earlier run must not stand in for this one if the child dies
    (RESULTS / f"{entry['id']}.json").unlink(missing_ok=True)
    proc = subprocess.Popen(cmd, env=env, start_new_session=True)
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, 9)
        proc.wait()
        RESULTS.mkdir(exist_ok=True)
        (RESULTS / f"{entry['id']}.json").write_text(json.dumps(
            {"id": entry["id"], "status": "timeout", "error": f"no result in {timeout:g} s",
             "wall_s": time.perf_counter() - t0}, indent=1))
        return
    if not (RESULTS / f"{entry['id']}.json").exists():
        (RESULTS / f"{entry['id']}.json").write_text(json.dumps(
            {"id": entry["id"], "status": "crash", "error": f"child exit {proc.returncode}",
             "wall_s": time.perf_counter() - t0}, indent=1))


def snapshot() -> str:
    """A copy of this checkout's packages, as the install maps them (``components/`` is
    ``circuitsim_components``), in a new temporary folder: its path, for PYTHONPATH."""
    dest = Path(tempfile.mkdtemp(prefix="circuitsim-snapshot-"))
    skip = shutil.ignore_patterns("__pycache__")
    shutil.copytree(ROOT / "circuitsim", dest / "circuitsim", ignore=skip)
    shutil.copytree(ROOT / "components", dest / "circuitsim_components", ignore=skip)
    return str(dest)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--split", choices=(*SPLITS, "all"), default="tune")
    ap.add_argument("--only", default="", help="record ids, comma-separated")
    ap.add_argument("--skip", default="", help="splits to leave out, comma-separated (a "
                    "blind set kept for a later run)")
    ap.add_argument("--timeout", type=float, default=1200.0, help="per record [s]")
    ap.add_argument("--rerun", action="store_true", help="ignore stored results")
    ap.add_argument("--score-only", action="store_true", help="print from results/ only")
    ap.add_argument("--circuitsim", help="a circuitsim checkout to import (PYTHONPATH)")
    ap.add_argument("--snapshot", action="store_true",
                    help="copy this checkout's circuitsim and its component package to a "
                    "temporary folder first and import that: an edit made while the run "
                    "goes on does not reach it")
    ap.add_argument("--nice", type=int, default=10, help="niceness of the child (0: none)")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        return child(args.child)
    truth = load_truth()
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    if only:
        sel = [e for e in truth if e["id"] in only]
    else:
        skip = {x.strip() for x in args.skip.split(",") if x.strip()}
        sel = [e for e in truth if (args.split == "all" or e["split"] == args.split)
               and e["split"] not in skip]
    if args.snapshot and args.circuitsim:
        ap.error("--snapshot copies this checkout; --circuitsim names another: choose one")
    if args.snapshot and not args.score_only:
        args.circuitsim = snapshot()
        print(f"importing the snapshot {args.circuitsim}", flush=True)
    if not args.score_only:
        for e in sel:
            path = RESULTS / f"{e['id']}.json"
            if path.exists() and not args.rerun:
                continue
            print(f"diagnosing {e['id']} ...", flush=True)
            run_one(e, args.timeout, args.circuitsim, args.nice)
    totals = [0, 0]
    for split in SPLITS:
        part = [e for e in sel if e["split"] == split]
        if part:
            r, n = report(part, split)
            totals[0] += r
            totals[1] += n
    print(f"\nTOTAL: {totals[0]} right of {totals[1]} run, {len(sel)} selected")
    return 0


if __name__ == "__main__":
    sys.exit(main())

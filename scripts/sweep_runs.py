#!/usr/bin/env python3
"""Summarize `bimloc sweep --json` files, and compare two binaries' sweeps run by run.

    scripts/sweep_runs.py DIR_OR_FILES...                  # one row per style, and all
    scripts/sweep_runs.py A_DIR --against B_DIR            # B against A: gained / lost / sooner / later
    scripts/sweep_runs.py ... --list-false --list-changed  # name the runs
    scripts/sweep_runs.py DIR --oracle-from ORACLE_DIR     # lag and ratio against the oracle's limits

The oracle (`bimloc sweep --oracle`) depends on the starts and the scans, not on the localizer: its
decidable times from one sweep serve every binary's sweep of the same starts (--oracle-from), and
give issue 28's points: decidable starts localized, the median and p90 of the lag (convergence
minus decidable_at_s) and of the ratio (convergence / max(decidable_at_s, 1 s)), plain and robust.

A run is keyed by plan file name, storey, start room, seed and site, so two sweeps of the same
floors pair up whatever their order. "Localized" is the sweep's own: converged and not false.
Sooner / later count paired runs localized in both whose convergence time moved by over 0.05 s.
"""
import argparse
import json
import os
import statistics
import sys


def load(paths):
    runs = {}
    files = []
    for p in paths:
        if os.path.isdir(p):
            files += sorted(os.path.join(p, f) for f in os.listdir(p) if f.endswith(".json"))
        else:
            files.append(p)
    for f in files:
        with open(f) as fh:
            doc = json.load(fh)
        for s in doc["scenarios"]:
            key = (os.path.basename(s["plan"]), s["storey"], s["start_room"], s["seed"], s.get("site", ""))
            runs[key] = s
    return runs


def localized(s):
    return s["converged"] and not s["false_convergence"]


def style(key):
    name = key[0]
    for st in ("apartment_block", "office", "residential", "school", "hall"):
        if name.startswith("random_" + st):
            return st
    return name


def pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))] if xs else None


def fmt(x):
    return "-" if x is None else f"{x:.2f}"


def summary(runs, by_style):
    groups = {}
    for k, s in runs.items():
        groups.setdefault(style(k) if by_style else "all", []).append(s)
    if by_style and len(groups) > 1:
        groups["all"] = list(runs.values())
    rows = []
    for g, ss in groups.items():
        t = [s["convergence_time_s"] for s in ss if localized(s)]
        rows.append({"group": g, "runs": len(ss), "localized": sum(map(localized, ss)),
                     "false": sum(s["false_convergence"] for s in ss),
                     "median_s": statistics.median(t) if t else None, "p90_s": pct(t, 0.9)})
    return rows


def oracle_rows(runs, oracle, by_style):
    """Issue 28's oracle points over the runs the oracle answered, plain and robust."""
    groups = {}
    for k, s in runs.items():
        o = oracle.get(k)
        if o is None or "decidable_at_s" not in o:
            continue
        groups.setdefault(style(k) if by_style else "all", []).append((s, o))
    if by_style and len(groups) > 1:
        groups["all"] = [x for v in groups.values() for x in v]
    rows = []
    for g, pairs in groups.items():
        row = {"group": g, "runs": len(pairs)}
        for suffix in ("", "_robust"):
            dec = [(s, o["decidable" + suffix + "_at_s"]) for s, o in pairs if o.get("decidable" + suffix + "_at_s") is not None]
            loc = [(s, d) for s, d in dec if localized(s)]
            lags = [s["convergence_time_s"] - d for s, d in loc]
            ratios = [s["convergence_time_s"] / max(d, 1.0) for s, d in loc]
            name = suffix.strip("_") or "plain"
            row[name] = {"decidable": len(dec), "decidable_localized": len(loc),
                         "median_lag_s": statistics.median(lags) if lags else None, "p90_lag_s": pct(lags, 0.9),
                         "median_ratio": statistics.median(ratios) if ratios else None, "p90_ratio": pct(ratios, 0.9)}
        rows.append(row)
    return rows


def compare(a, b):
    paired = sorted(set(a) & set(b))
    out = {"paired": len(paired), "only_a": len(set(a) - set(b)), "only_b": len(set(b) - set(a)),
           "gained": [], "lost": [], "sooner": [], "later": [], "false_b": []}
    for k in paired:
        la, lb = localized(a[k]), localized(b[k])
        if b[k]["false_convergence"]:
            out["false_b"].append(k)
        if lb and not la:
            out["gained"].append(k)
        elif la and not lb:
            out["lost"].append(k)
        elif la and lb:
            d = b[k]["convergence_time_s"] - a[k]["convergence_time_s"]
            if d < -0.05:
                out["sooner"].append(k)
            elif d > 0.05:
                out["later"].append(k)
    return out


def name(k, runs):
    s = runs.get(k)
    t = s["convergence_time_s"] if s else None
    return f"{k[0]} {k[1]} {k[2]} seed {k[3]} {k[4]}: {fmt(t)} s"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="+")
    ap.add_argument("--against", nargs="+", help="B's sweep, compared run by run with the first")
    ap.add_argument("--by-style", action="store_true", help="a row per generated style")
    ap.add_argument("--list-false", action="store_true")
    ap.add_argument("--list-changed", action="store_true")
    ap.add_argument("--oracle-from", nargs="+", help="a `sweep --oracle` of the same starts (default: the runs' own oracle fields)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    a = load(args.paths)
    result = {"summary": summary(a, args.by_style)}
    if args.against:
        b = load(args.against)
        result["against"] = summary(b, args.by_style)
        result["compare"] = compare(a, b)
    oracle = load(args.oracle_from) if args.oracle_from else {k: s for k, s in a.items() if "oracle" in s}
    if oracle:
        result["oracle"] = oracle_rows(a, oracle, args.by_style)
    if args.json:
        print(json.dumps(result, default=list, indent=1))
        return 0
    print(f"{'group':<20} {'runs':>6} {'localized':>10} {'false':>6} {'median [s]':>11} {'p90 [s]':>8}")
    for label, rows in (("", result["summary"]), ("B: ", result.get("against", []))):
        for r in rows:
            print(f"{label + r['group']:<20} {r['runs']:>6} {r['localized']:>10} {r['false']:>6} "
                  f"{fmt(r['median_s']):>11} {fmt(r['p90_s']):>8}")
    if oracle:
        print(f"\noracle: {'group':<16} {'runs':>5} {'decidable':>10} {'localized':>10} {'lag med':>8} {'lag p90':>8} "
              f"{'ratio med':>9} {'ratio p90':>9}")
        for r in result["oracle"]:
            for limit in ("plain", "robust"):
                o = r[limit]
                share = f"{o['decidable_localized']} ({100.0 * o['decidable_localized'] / o['decidable']:.1f}%)" if o["decidable"] else "-"
                print(f"{limit:<7} {r['group']:<16} {r['runs']:>5} {o['decidable']:>10} {share:>10} {fmt(o['median_lag_s']):>8} "
                      f"{fmt(o['p90_lag_s']):>8} {fmt(o['median_ratio']):>9} {fmt(o['p90_ratio']):>9}")
    falses = [k for k, s in a.items() if s["false_convergence"]]
    if args.list_false:
        for k in falses:
            print("FALSE", name(k, a))
    if args.against:
        c = result["compare"]
        print(f"paired {c['paired']} (only A {c['only_a']}, only B {c['only_b']}): gained {len(c['gained'])}, "
              f"lost {len(c['lost'])}, sooner {len(c['sooner'])}, later {len(c['later'])}, false in B {len(c['false_b'])}")
        if args.list_changed:
            for what in ("gained", "lost", "false_b"):
                for k in c[what]:
                    print(what, name(k, a), "->", fmt(b[k]["convergence_time_s"]))
    return 1 if falses or (args.against and result["compare"]["false_b"]) else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Where a build's time goes: the log of scripts/build_time.sh, by target and by step.

  python3 scripts/build_time_report.py build-measure/times.tsv [--top 20] [--before OLD.tsv]

CPU time (user+sys) is what is summed: it hardly depends on how busy the machine is, while the
wall time of a shared machine says little. The projected wall time on N idle cores is the
compile CPU divided by N plus the link CPU (links wait for their objects and mostly run alone).
With --before, a second table compares two logs target by target.
"""
import argparse
import collections
import re
import sys

TARGET = re.compile(r"/CMakeFiles/([^/]+)\.dir/")


def read(path):
    """[(target, kind, cpu_s, wall_s, rss_kb, output)] from one log; kind is compile, pch or link.
    A failed step is left out, and a step done twice counts once, as its last run."""
    steps = {}  # output -> its last successful step (a step redone after a fix counts once)
    failed = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 5:
                # /usr/bin/time writes "Command exited with non-zero status N" before a failed step
                if line.startswith("Command exited"):
                    failed = True
                    continue
                sys.exit(f"{path}:{number}: expected 5 tab-separated fields, got {len(fields)}")
            if failed:
                failed = False
                continue
            user, system, wall, rss, output = fields
            match = TARGET.search(output)
            if output.endswith((".o", ".obj")) and match:
                target = match.group(1)
                kind = "pch" if "cmake_pch" in output else "compile"
            else:
                target = re.sub(r"^lib(.*)\.(so(\.[0-9.]*)?|a)$", r"\1", output.rsplit("/", 1)[-1])
                kind = "link"
                if "cmake_pch" in output:  # the .gch itself
                    target, kind = TARGET.search(output).group(1), "pch"
            steps[output] = (target, kind, float(user) + float(system), float(wall), int(rss), output)
    return list(steps.values())


def summary(steps):
    """target -> {compile, pch, link: cpu_s; units: count}."""
    table = collections.defaultdict(lambda: collections.Counter())
    for target, kind, cpu, _, _, _ in steps:
        table[target][kind] += cpu
        if kind == "compile":
            table[target]["units"] += 1
    return table


def projected(table, cores):
    compile_cpu = sum(t["compile"] + t["pch"] for t in table.values())
    link_cpu = sum(t["link"] for t in table.values())
    return compile_cpu / cores + link_cpu


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("log")
    parser.add_argument("--top", type=int, default=20, help="the N most expensive steps")
    parser.add_argument("--before", help="a log of the same build before a change")
    parser.add_argument("--cores", type=int, default=2)
    args = parser.parse_args()
    steps = read(args.log)
    table = summary(steps)
    print(f"{'target':24} {'units':>5} {'compile s':>10} {'pch s':>7} {'link s':>7} {'CPU s':>8}")
    for target in sorted(table, key=lambda t: -sum(v for k, v in table[t].items() if k != "units")):
        t = table[target]
        total = t["compile"] + t["pch"] + t["link"]
        print(f"{target:24} {t['units']:5d} {t['compile']:10.1f} {t['pch']:7.1f} {t['link']:7.1f} {total:8.1f}")
    total = sum(t["compile"] + t["pch"] + t["link"] for t in table.values())
    print(f"{'all':24} {sum(t['units'] for t in table.values()):5d} {'':10} {'':7} {'':7} {total:8.1f}")
    print(f"projected wall on {args.cores} idle cores: {projected(table, args.cores) / 60:.1f} min "
          f"(compile CPU / {args.cores} + link CPU)")
    print(f"\nthe {args.top} most expensive steps (CPU s, peak MB)")
    for target, kind, cpu, _, rss, output in sorted(steps, key=lambda s: -s[2])[:args.top]:
        name = output.split(".dir/", 1)[-1] if ".dir/" in output else output.rsplit("/", 1)[-1]
        print(f"  {cpu:7.1f} {rss / 1024:6.0f}  {target:20} {kind:7} {name}")
    if args.before:
        old = summary(read(args.before))
        print(f"\n{'target':24} {'before CPU s':>12} {'after CPU s':>12} {'ratio':>6}")
        for target in sorted(set(old) | set(table)):
            a = sum(v for k, v in old[target].items() if k != "units")
            b = sum(v for k, v in table[target].items() if k != "units")
            ratio = f"{b / a:6.2f}" if a else "     -"
            print(f"{target:24} {a:12.1f} {b:12.1f} {ratio}")
        print(f"{'projected wall, min':24} {projected(old, args.cores) / 60:12.1f} "
              f"{projected(table, args.cores) / 60:12.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

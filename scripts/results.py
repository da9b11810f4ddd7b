#!/usr/bin/env python3
"""make results: run a fixed list of sweeps, compares and benchmarks, and regenerate
(a) the README's results table (between <!-- results:begin --> and <!-- results:end -->) and
(b) docs/results/DATE.md (the date, the commit, each command with its full table).

The README's numbers are generated, never typed. Python 3 standard library only.

  scripts/results.py                      # the whole list (about 15 min on 2 cores)
  scripts/results.py --quick              # every item on a tiny case (a minute): for development
  scripts/results.py --only compare       # one item (repeatable)
  scripts/results.py --from-json DIR      # re-render from saved JSON, running nothing

Each run saves its JSON (and meta.json: date, commit, timings) in --json-dir (default
build/results/json), so `--from-json build/results/json` re-renders what was measured.
"""
import argparse
import datetime
import glob
import json
import os
import re
import resource
import shlex
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"
INDEX_BEGIN, INDEX_END = "<!-- pages:begin -->", "<!-- pages:end -->"
SHARED_SHOWN = "../shared/ifc"  # how the shared plans' folder is written in the commands shown
METHODS = ["sgraph", "pf-no-rooms", "amcl", "ndt"]


# ---------------------------------------------------------------------------------------------
# The fixed list. Each item: its command (argv after `bimloc`, with {shared} for the shared plans'
# folder), the quick variant, whether it needs the shared plans, and how it is rendered.
# ---------------------------------------------------------------------------------------------
def items(shared):
    plans = sorted(glob.glob(os.path.join(shared, "*.ifc"))) if shared else []
    shown = lambda p: p.replace(shared, SHARED_SHOWN) if shared else p
    amcl = ["--config", "scenarios/configs/amcl_legged.yaml"]
    return [
        {"name": "compare", "kind": "compare", "shared": False,
         "title": "The paper's comparison on the default world (site_office), every start room, 2 seeds",
         "argv": ["compare", "--plan", "worlds/site_office.ifc", "--all-rooms", "--seeds", "2",
                  "--methods", ",".join(METHODS)] + amcl + ["--jobs", "2", "--json"],
         "quick": ["compare", "--plan", "worlds/site_office.ifc", "--rooms", "R108,S100", "--seeds", "1",
                   "--methods", ",".join(METHODS), "--duration", "15"] + amcl + ["--jobs", "2", "--json"]},
        {"name": "shared", "kind": "sweep", "shared": True,
         "title": "Every room of the shared plans, 1 seed, 40 s (sgraph)",
         "argv": ["sweep"] + plans + ["--seeds", "1", "--duration", "40", "--jobs", "2", "--json"],
         "quick": ["sweep"] + [p for p in plans if os.path.basename(p) == "AC20-FZK-Haus.ifc"] +
                  ["--rooms-per-storey", "2", "--seeds", "1", "--duration", "15", "--jobs", "2", "--json"],
         "shown": shown},
        {"name": "outside", "kind": "sweep", "shared": False,
         "title": "Starts outside rooms (doorways, halls, in front of the facade), the project's worlds, 6 per storey, 40 s",
         "argv": ["sweep", "worlds/apartment.ifc", "worlds/site_office.ifc", "worlds/two_storey.ifc",
                  "--starts", "outside", "--seeds", "6", "--duration", "40", "--jobs", "2", "--json"],
         "quick": ["sweep", "worlds/two_storey.ifc", "--starts", "outside", "--seeds", "1", "--duration", "15",
                   "--jobs", "2", "--json"]},
        {"name": "storey_auto", "kind": "sweep", "shared": True,
         "title": "Unknown storey (--storey auto) on two plans of two storeys, 1 seed, 40 s",
         "argv": ["sweep", "worlds/two_storey.ifc"] + [p for p in plans if os.path.basename(p) == "AC20-FZK-Haus.ifc"] +
                 ["--storey", "auto", "--seeds", "1", "--duration", "40", "--jobs", "2", "--json"],
         "quick": ["sweep", "worlds/two_storey.ifc", "--storey", "auto", "--rooms-per-storey", "1", "--seeds", "1",
                   "--duration", "15", "--jobs", "2", "--json"],
         "shown": shown},
        {"name": "loop", "kind": "loop", "shared": False,
         "title": "The whole loop on one core (simulator, planes, filter, S-Graph): default scenarios R104, C100, S100",
         "argv": ["bench", "loop", "--rounds", "2", "--json"],
         "quick": ["bench", "loop", "scenarios/site_office/S100_seed1.yaml", "--duration", "10", "--rounds", "1", "--json"]},
    ]


# ---------------------------------------------------------------------------------------------
# Formatting
# ---------------------------------------------------------------------------------------------
def num(v, decimals):
    return "-" if v is None else f"{v:.{decimals}f}"


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def shown_command(item, argv):
    shared_shown = item.get("shown", lambda p: p)
    parts = ["bimloc"] + [shared_shown(a) for a in argv]
    # Plans of one folder written as a glob, as a user would type it.
    out, plans = [], [p for p in parts if p.startswith(SHARED_SHOWN + "/") and p.endswith(".ifc")]
    for p in parts:
        if p in plans:
            if len(plans) > 2:
                if p == plans[0]:
                    out.append(SHARED_SHOWN + "/*.ifc")
                continue
        out.append(p)
    return " ".join(shlex.quote(p) if ("*" not in p and " " in p) else p for p in out)


def ran(summary):
    return summary["runs"] - summary.get("errors", 0)


# README rows: [result, method, localized, false, median conv. [s], median ATE [m], x real time, command]
def readme_rows(item, data, command):
    kind = item["kind"]
    cmd = f"`{command}`"
    if kind == "compare":
        rows = []
        sim_s = data["timing"]["sim_seconds"]
        for m in data["methods"]:
            s = data["summary"][m]
            loc_s = data["timing"]["localizer_seconds"].get(m, 0)
            rate = f"{sim_s / loc_s:.0f}x" if loc_s > 0 else "-"
            label = (f"default world: {len(data['rooms'])} start rooms x {data['seeds']} seeds, {data['duration_s']:.0f} s runs"
                     if not rows else "the same runs")
            rows.append([label, m,
                         f"{s['localized']}/{s['runs']}", s["false_convergences"], num(s["median_convergence_s"], 1),
                         num(s["median_ate_m"], 3), rate, cmd if len(rows) == 0 else "the same command"])
        return rows
    if kind == "sweep":
        s = data["summary"]
        label = {"shared": "every room of the shared plans", "outside": "starts outside rooms, the project's worlds",
                 "storey_auto": "storey not given (`--storey auto`)"}.get(item["name"], item["name"])
        label += f": {ran(s)} starts, {data['duration_s']:.0f} s runs"
        return [[label, data["method"], f"{s['localized']}/{ran(s)}", s["false_convergences"],
                 num(s["median_convergence_s"], 1), num(s["median_ate_m"], 3), "-", cmd]]
    if kind == "loop":
        s = data["summary"]
        methods = sorted({r["method"] for r in data["runs"]})
        return [["whole loop, one core (" + ", ".join(r["scenario"].split("/")[-1].replace(".yaml", "") for r in data["runs"]) + ")",
                 ",".join(methods), "-", "-", "-", "-", f"{s['loop_cpu_real_time_factor']:.1f}x loop", cmd]]
    raise ValueError(kind)


def detail(item, data):
    kind = item["kind"]
    if kind == "compare":
        methods = data["methods"]
        t = [f"Plan `{data['plan']}`, storey {data['storey']}, site {data['site']}, {data['duration_s']:.0f} s runs, "
             f"seeds 1..{data['seeds']}; {data['errors']} runs could not be made. "
             "Localizer x real time: simulated seconds over the seconds spent in that method's `Localizer::step`."]
        sim_s = data["timing"]["sim_seconds"]
        rows = []
        for m in methods:
            s = data["summary"][m]
            loc = data["timing"]["localizer_seconds"].get(m, 0)
            rows.append([m, f"{s['localized']}/{s['runs']}", s["false_convergences"], num(s["median_convergence_s"], 1),
                         num(s["median_ate_m"], 3), s["losses"], f"{sim_s / loc:.0f}x" if loc > 0 else "-"])
        t.append(table(["method", "localized", "false", "median conv. [s]", "median ATE [m]", "losses",
                        "localizer x real time"], rows))
        t.append("Convergence time [s] per start room, one value per seed (N.L.: not localized by the end; "
                 "`!`: a false convergence):")
        rows = []
        for room in data["rooms"]:
            cells = []
            for m in methods:
                vals = []
                for run in room["runs"]:
                    r = run["methods"].get(m)
                    if run.get("error") or r is None:
                        vals.append("error")
                    elif not r["converged"] or r["convergence_time_s"] is None:
                        vals.append("N.L.")
                    else:
                        vals.append(f"{r['convergence_time_s']:.1f}" + ("!" if r["false_convergence"] else ""))
                cells.append(" / ".join(vals))
            rows.append([room["room"]] + cells)
        t.append(table(["start room"] + methods, rows))
        return "\n\n".join(t)
    if kind == "sweep":
        rows = []
        for g in data["groups"] + [dict(data["summary"], plan="**all**", storey="")]:
            rows.append([g["plan"], g["storey"], ran(g), g["localized"], g["false_convergences"],
                         num(g["median_convergence_s"], 1), num(g["p90_convergence_s"], 1), num(g["max_convergence_s"], 1),
                         num(g["median_ate_m"], 3), num(g["max_ate_m"], 3), g["losses"], num(g["min_accepted_margin"], 2)])
        t = [f"Method {data['method']}, site {data['site']}, {data['duration_s']:.0f} s runs, {data['seeds']} seed(s) per start; "
             f"{data['summary'].get('errors', 0)} starts could not be run.",
             table(["plan", "storey", "runs", "localized", "false", "median [s]", "p90 [s]", "max [s]", "median ATE [m]",
                    "max ATE [m]", "lost", "min margin"], rows)]
        if item["name"] == "outside":
            kinds = {}
            for s in data["scenarios"]:
                k = kinds.setdefault(s["start_room"] if s["start_room"].startswith("(") else "(room)", [0, 0])
                k[0] += 1
                k[1] += s["converged"] and not s["false_convergence"]
            t.append("By kind of start: " + ", ".join(f"{k} {v[1]}/{v[0]}" for k, v in sorted(kinds.items())) + ".")
        if item["name"] == "storey_auto":
            wrong = sum(1 for s in data["scenarios"] if s.get("found_storey") not in (None, s["storey"]))
            t.append(f"Runs that decided a wrong storey: {wrong}.")
        return "\n\n".join(t)
    if kind == "loop":
        rows = [[r["scenario"], r["method"], r["wall_faces"], f"{r['sim_seconds']:.1f}", f"{r['setup_wall_seconds']:.2f}",
                 f"{r['simulator_real_time_factor']:.1f}x", f"{r['loop_real_time_factor']:.1f}x",
                 f"{r['loop_cpu_real_time_factor']:.1f}x", f"{100 * r['localizer_share']:.0f} %",
                 "yes" if r["converged"] else "no"] for r in data["runs"]]
        s = data["summary"]
        rows.append(["**all**", "", "", f"{s['sim_seconds']:.1f}", f"{s['setup_wall_seconds']:.2f}",
                     f"{s['simulator_real_time_factor']:.1f}x", f"{s['loop_real_time_factor']:.1f}x",
                     f"{s['loop_cpu_real_time_factor']:.1f}x", f"{100 * s['localizer_share']:.0f} %", ""])
        return (f"One core, best of {data['rounds']} rounds; real-time factors from wall time and from the process's CPU "
                "time; the simulator's setup (the tour planned) outside both.\n\n" +
                table(["scenario", "method", "wall faces", "simulated [s]", "setup [s]", "simulator alone", "loop (wall)",
                       "loop (CPU)", "localizer share", "converged"], rows))
    raise ValueError(kind)


def render(meta, datasets, list_items):
    """(README block, docs/results/DATE.md text) from the metadata and the JSON of each item."""
    commit = meta["commit"] + (" (with uncommitted changes)" if meta["dirty"] else "")
    rows, sections = [], []
    for item in list_items:
        name = item["name"]
        m = meta["items"].get(name)
        if m is None:
            continue
        command = m["command"]
        if m.get("skipped"):
            rows.append([item["title"], "-", "-", "-", "-", "-", "-", f"skipped ({m['skipped']}): `{command}`"])
            sections.append(f"## {item['title']}\n\nSkipped: {m['skipped']}.\n\n```sh\n{command}\n```")
            continue
        data = datasets[name]
        rows += readme_rows(item, data, command)
        title = f"{item['title']} (quick: a tiny case of it)" if meta.get("quick") else item["title"]
        sections.append(f"## {title}\n\n```sh\n{command}\n```\n\n"
                        f"Exit status {m['exit_status']}, {m['seconds']:.0f} s wall"
                        + (f", {m['cpu_seconds']:.0f} s CPU" if "cpu_seconds" in m else "")
                        + f" on this machine.\n\n{detail(item, data)}")
    load = (f", on {meta['machine']} with a load average of {meta['load_average']} at the start (the real-time "
            "factors count the waiting for a core)") if "load_average" in meta else ""
    block = (f"Generated by `make results` on {meta['date']} from commit {commit}{' (quick mode: tiny cases)' if meta.get('quick') else ''}{load}; "
             f"every table in full: [docs/results/{meta['date']}.md](docs/results/{meta['date']}.md). "
             "\"localized\": converged and never falsely; ATE over the localized runs; \"x real time\": simulated "
             "seconds per second spent in that method's localizer (compare) or per CPU second of the whole loop on one "
             "core (bench loop); `bimloc` is `build/sim/bimloc`.\n\n" +
             table(["result", "method", "localized", "false", "median conv. [s]", "median ATE [m]", "x real time", "command"], rows))
    page = (f"# Results of {meta['date']}\n\n- Date: {meta['date']}\n- Commit: {commit}\n"
            f"- Generated by: `make results` (`scripts/results.py{' --quick' if meta.get('quick') else ''}`)\n"
            f"- Machine: {meta.get('machine', 'unknown')}"
            + (f", load average {meta['load_average']} (15 min) at the start: wall times and real-time factors count "
               "the waiting for a core, CPU seconds do not" if "load_average" in meta else "")
            + "\n\n" + "\n\n".join(sections) + "\n")
    return block, page


def replace_block(readme_text, block):
    if BEGIN not in readme_text or END not in readme_text:
        raise SystemExit(f"results.py: error: README has no {BEGIN} ... {END} markers")
    head, rest = readme_text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    return head + BEGIN + "\n" + block + "\n" + END + tail


def write_atomic(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def git(*args):
    return subprocess.run(["git", "-C", ROOT] + list(args), capture_output=True, text=True).stdout.strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bimloc", default=os.path.join(ROOT, "build", "sim", "bimloc"))
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared", "ifc"), help="the shared plans' folder")
    ap.add_argument("--only", action="append", default=[], help="run only this item (repeatable)")
    ap.add_argument("--quick", action="store_true", help="every item on a tiny case")
    ap.add_argument("--from-json", metavar="DIR", help="render from DIR/meta.json and DIR/NAME.json; run nothing")
    ap.add_argument("--json-dir", default=os.path.join(ROOT, "build", "results", "json"))
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"))
    ap.add_argument("--results-dir", default=os.path.join(ROOT, "docs", "results"))
    ap.add_argument("--list", action="store_true", help="print the list of items and their commands")
    args = ap.parse_args()

    shared = os.path.normpath(args.shared) if os.path.isdir(args.shared) else None
    list_items = items(shared or os.path.normpath(args.shared))
    names = [i["name"] for i in list_items]
    for o in args.only:
        if o not in names:
            raise SystemExit(f"results.py: error: --only {o}: no such item (items: {', '.join(names)})")
    if args.list:
        for i in list_items:
            print(f"{i['name']:12s} {shown_command(i, i['quick'] if args.quick else i['argv'])}")
        return 0

    if args.from_json:
        with open(os.path.join(args.from_json, "meta.json")) as f:
            meta = json.load(f)
        datasets = {}
        for name, m in meta["items"].items():
            if not m.get("skipped"):
                with open(os.path.join(args.from_json, name + ".json")) as f:
                    datasets[name] = json.load(f)
    else:
        if not os.access(args.bimloc, os.X_OK):
            raise SystemExit(f"results.py: error: {args.bimloc}: no bimloc binary (run `make build` first)")
        os.makedirs(args.json_dir, exist_ok=True)
        meta = {"date": datetime.date.today().isoformat(), "commit": git("rev-parse", "--short=12", "HEAD"),
                "dirty": bool(git("status", "--porcelain", "--untracked-files=no")), "quick": args.quick,
                "machine": f"{os.cpu_count()} cores, {os.uname().sysname} {os.uname().machine}",
                "load_average": round(os.getloadavg()[2], 1), "items": {}}
        datasets = {}
        for item in list_items:
            if args.only and item["name"] not in args.only:
                continue
            argv = item["quick"] if args.quick else item["argv"]
            command = shown_command(item, argv)
            if item["shared"] and shared is None:
                meta["items"][item["name"]] = {"command": command, "skipped": f"{SHARED_SHOWN} absent"}
                print(f"results: {item['name']}: skipped ({SHARED_SHOWN} absent)", file=sys.stderr)
                continue
            print(f"results: {item['name']}: {command}", file=sys.stderr, flush=True)
            t0, cpu0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
            proc = subprocess.run([args.bimloc] + argv, cwd=ROOT, capture_output=True, text=True)
            seconds, cpu1 = time.monotonic() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = (cpu1.ru_utime - cpu0.ru_utime) + (cpu1.ru_stime - cpu0.ru_stime)
            try:
                data = json.loads(proc.stdout)
            except json.JSONDecodeError:
                sys.stderr.write(proc.stderr)
                raise SystemExit(f"results.py: error: {item['name']}: `{command}` exited {proc.returncode} without a JSON report")
            with open(os.path.join(args.json_dir, item["name"] + ".json"), "w") as f:
                json.dump(data, f, indent=1, sort_keys=True)
            meta["items"][item["name"]] = {"command": command, "exit_status": proc.returncode, "seconds": round(seconds, 1),
                                           "cpu_seconds": round(cpu, 1)}
            datasets[item["name"]] = data
            print(f"results: {item['name']}: {seconds:.0f} s wall, {cpu:.0f} s CPU, exit status {proc.returncode}",
                  file=sys.stderr, flush=True)
            # After every item, so that an interrupted run can still be rendered with --from-json.
            write_atomic(os.path.join(args.json_dir, "meta.json"), json.dumps(meta, indent=1, sort_keys=True))
        write_atomic(os.path.join(args.json_dir, "meta.json"), json.dumps(meta, indent=1, sort_keys=True))

    block, page = render(meta, datasets, list_items)
    with open(args.readme) as f:
        readme = f.read()
    write_atomic(args.readme, replace_block(readme, block))
    os.makedirs(args.results_dir, exist_ok=True)
    page_path = os.path.join(args.results_dir, meta["date"] + ".md")
    write_atomic(page_path, page)
    index = os.path.join(args.results_dir, "README.md")  # the list of make results' pages, if there is one
    if os.path.exists(index):
        with open(index) as f:
            text = f.read()
        if INDEX_BEGIN in text and INDEX_END in text:
            pages = sorted((p for p in os.listdir(args.results_dir) if re.fullmatch(r"\d{4}-\d{2}-\d{2}\.md", p)), reverse=True)
            head, rest = text.split(INDEX_BEGIN, 1)
            listing = "\n".join(f"- [{p[:-3]}]({p})" for p in pages)
            write_atomic(index, head + INDEX_BEGIN + "\n" + listing + "\n" + INDEX_END + rest.split(INDEX_END, 1)[1])
    print(f"results: wrote {os.path.relpath(args.readme)} (the table) and {os.path.relpath(page_path)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())

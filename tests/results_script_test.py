#!/usr/bin/env python3
"""ctest results_script: `scripts/results.py --from-json` renders the README's results table and
docs/results/DATE.md from saved JSON deterministically, runs nothing, and takes its figures from
the right fields.

The fixture (tests/fixtures/results/) is the JSON of `scripts/results.py --quick`: the real
commands run once on tiny cases. Checked:
  1. two renderings of it are byte-identical, and equal to the committed expected output
     (tests/fixtures/results/expected/): the rendering does not drift unnoticed;
  2. only the text between the markers changes in the README; the rest stays byte for byte;
  3. every figure of the README's rows, recounted here from the per-run entries of the JSON
     (not from the commands' summaries): localized / runs and false convergences;
  4. no binary is needed (--bimloc points nowhere);
  5. a README without the markers is refused with a message and left untouched.
Regenerate the expected output after a deliberate format change with
  scripts/results.py --from-json tests/fixtures/results --readme tests/fixtures/results/expected/README.md \
      --results-dir tests/fixtures/results/expected
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from script_checks import check, failures  # noqa: E402 (after the line above)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIXTURE = os.path.join(ROOT, "tests", "fixtures", "results")
EXPECTED = os.path.join(FIXTURE, "expected")
SCRIPT = os.path.join(ROOT, "scripts", "results.py")


def render(work):
    readme = os.path.join(work, "README.md")
    results = os.path.join(work, "results")
    proc = subprocess.run([sys.executable, SCRIPT, "--from-json", FIXTURE, "--bimloc", "/nonexistent/bimloc",
                           "--readme", readme, "--results-dir", results], capture_output=True, text=True)
    check(proc.returncode == 0, f"--from-json exits 0 (got {proc.returncode}: {proc.stderr.strip()})")
    pages = sorted(os.listdir(results)) if os.path.isdir(results) else []
    return open(readme).read(), {p: open(os.path.join(results, p)).read() for p in pages}


def rows_of(readme):
    block = readme.split("<!-- results:begin -->", 1)[1].split("<!-- results:end -->", 1)[0]
    lines = [l for l in block.splitlines() if l.startswith("| ") and not l.startswith("| result")]
    return [[c.strip() for c in l.strip("|").split(" | ")] for l in lines]


def main():
    meta = json.load(open(os.path.join(FIXTURE, "meta.json")))
    template = "# A README\n\nbefore\n\n<!-- results:begin -->\nold table\n<!-- results:end -->\n\nafter\n"
    outputs = []
    for _ in range(2):
        work = tempfile.mkdtemp(prefix="bimloc_results_test_")
        try:
            with open(os.path.join(work, "README.md"), "w") as f:
                f.write(template)
            outputs.append(render(work))
        finally:
            shutil.rmtree(work)
    (readme, pages), (readme2, pages2) = outputs
    check(readme == readme2 and pages == pages2, "two renderings are byte-identical")
    check(list(pages) == [meta["date"] + ".md"], f"one page, named by the date of the run ({list(pages)})")
    check(readme.startswith("# A README\n\nbefore\n\n<!-- results:begin -->\n") and readme.endswith("<!-- results:end -->\n\nafter\n"),
          "only the text between the markers changes")
    check("old table" not in readme, "the old table is replaced")
    check(readme == open(os.path.join(EXPECTED, "README.md")).read(), "README block equals the committed expected output")
    for name, text in pages.items():
        check(text == open(os.path.join(EXPECTED, name)).read(), f"{name} equals the committed expected output")

    # Figures recounted from the per-run entries.
    rows = rows_of(readme)
    by_method = {r[1]: r for r in rows if r[0].startswith("default world") or r[0] == "the same runs"}
    compare = json.load(open(os.path.join(FIXTURE, "compare.json")))
    for m in compare["methods"]:
        runs = [run["methods"][m] for room in compare["rooms"] for run in room["runs"]]
        localized = sum(1 for r in runs if r["converged"] and not r["false_convergence"])
        false = sum(1 for r in runs if r["false_convergence"])
        check(m in by_method, f"a README row for compare's method {m}")
        if m in by_method:
            check(by_method[m][2] == f"{localized}/{len(runs)}", f"{m}: localized {by_method[m][2]} == {localized}/{len(runs)}")
            check(by_method[m][3] == str(false), f"{m}: false {by_method[m][3]} == {false}")
    labels = {"shared": "every room of the shared plans", "outside": "starts outside rooms",
              "storey_auto": "storey not given"}
    for name, label in labels.items():
        if meta["items"].get(name, {}).get("skipped") or name not in meta["items"]:
            continue
        sweep = json.load(open(os.path.join(FIXTURE, name + ".json")))
        ran = [s for s in sweep["scenarios"] if s["sim_seconds"] > 0 or not s["failures"]]
        localized = sum(1 for s in ran if s["converged"] and not s["false_convergence"])
        false = sum(1 for s in ran if s["false_convergence"])
        row = [r for r in rows if r[0].startswith(label)]
        check(len(row) == 1, f"one README row for {name}")
        if row:
            check(row[0][2] == f"{localized}/{len(ran)}", f"{name}: localized {row[0][2]} == {localized}/{len(ran)}")
            check(row[0][3] == str(false), f"{name}: false {row[0][3]} == {false}")
    for name, m in meta["items"].items():
        check(any(m["command"] in r[-1] for r in rows), f"{name}: its command is in its row")
    check(all(r[-1].startswith("`bimloc ") or r[-1] == "the same command" for r in rows), "every row has its command")

    # No markers: refused, untouched.
    work = tempfile.mkdtemp(prefix="bimloc_results_test_")
    try:
        path = os.path.join(work, "README.md")
        with open(path, "w") as f:
            f.write("# no markers\n")
        proc = subprocess.run([sys.executable, SCRIPT, "--from-json", FIXTURE, "--readme", path,
                               "--results-dir", os.path.join(work, "results")], capture_output=True, text=True)
        check(proc.returncode != 0 and "markers" in proc.stderr, "a README without markers is refused with a message")
        check(open(path).read() == "# no markers\n", "and left untouched")
        check(not os.path.exists(os.path.join(work, "results")), "and no results page written")
    finally:
        shutil.rmtree(work)

    print(f"{len(failures)} failures" if failures else "results_script: all checks pass")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""ctest sweep_runs_script: `scripts/sweep_runs.py`, the summary and run-by-run comparison of
`bimloc sweep --json` files, against sweeps written here whose answers are known by construction.

Two sweeps A and B of the same five starts (the site in the key: a start on another site is
another run), B written in another order:
  - r1 localized in both, B 1.0 s sooner; r2 localized in both, B 0.04 s later (under the 0.05 s
    that counts); r3 localized in A only (lost by B); r4 in B only (gained); r5 false in B.
Checked: the summary rows (runs, localized, false, median), the comparison's counts, the runs
--list-false and --list-changed name (--list-changed crashed when the oracle table's loop
variable shadowed the function that names runs, session 39), the oracle's lag and ratio over
the starts it answered (plain and robust), --json, and the exit status (1 when B has a false
convergence).
"""
import json
import os
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from script_checks import check, failures  # noqa: E402 (after the line above)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = os.path.join(ROOT, "scripts", "sweep_runs.py")


def run(name, converged, t, false=False, oracle=None, site="exact"):
    s = {"plan": "/x/random_office_1.ifc", "storey": "Ground floor", "start_room": name, "seed": 1, "site": site,
         "converged": converged, "convergence_time_s": t, "false_convergence": false}
    if oracle:
        s["decidable_at_s"], s["decidable_robust_at_s"] = oracle
    return s


def sweep(path, scenarios):
    with open(path, "w") as f:
        json.dump({"scenarios": scenarios, "summary": {}}, f)


def main():
    work = tempfile.mkdtemp(prefix="sweep_runs_test_")
    a, b, orc = (os.path.join(work, n) for n in ("a.json", "b.json", "oracle.json"))
    sweep(a, [run("R001", True, 5.0), run("R002", True, 3.0), run("R003", True, 8.0), run("R004", False, None),
              run("R005", False, None), run("R001", True, 2.0, site="heavy")])
    sweep(b, [run("R005", True, 1.0, false=True), run("R004", True, 6.0), run("R003", False, None),
              run("R002", True, 3.04), run("R001", True, 4.0), run("R001", True, 2.0, site="heavy")])
    # The oracle: R001 decidable at 2.0 s (robust 3.0), R002 at 0.5 (robust never), R003 never.
    sweep(orc, [run("R001", True, 5.0, oracle=(2.0, 3.0)), run("R002", True, 3.0, oracle=(0.5, None)),
                run("R003", True, 8.0, oracle=(None, None))])

    p = subprocess.run([sys.executable, SCRIPT, a, "--against", b, "--list-false", "--list-changed"],
                       capture_output=True, text=True)
    out = p.stdout
    check(p.returncode == 1, f"B has a false convergence: exit 1, got {p.returncode} ({p.stderr.strip()})")
    rows = {line.split()[0] + (" " + line.split()[1] if line.startswith("B:") else ""): line.split()
            for line in out.splitlines() if line.startswith(("all", "B: all"))}
    check(rows.get("all", [])[1:5] == ["6", "4", "0", "4.00"], f"A's row: 6 runs, 4 localized, 0 false, median 4.00: {rows.get('all')}")
    check(rows.get("B: all", [])[2:6] == ["6", "4", "1", "3.52"], f"B's row: 6 runs, 4 localized, 1 false, median 3.52: {rows.get('B: all')}")
    check("paired 6 (only A 0, only B 0): gained 1, lost 1, sooner 1, later 0, false in B 1" in out,
          "the comparison's counts: " + out)
    check("gained random_office_1.ifc Ground floor R004 seed 1 exact: - s -> 6.00" in out, "gained R004 named")
    check("lost random_office_1.ifc Ground floor R003 seed 1 exact: 8.00 s -> -" in out, "lost R003 named")
    check("false_b random_office_1.ifc Ground floor R005 seed 1 exact" in out, "B's false R005 named")

    p = subprocess.run([sys.executable, SCRIPT, a, "--against", b, "--list-changed", "--oracle-from", orc],
                       capture_output=True, text=True)
    out = p.stdout
    check("Traceback" not in p.stderr, "--list-changed with --oracle-from runs: " + p.stderr[-300:])
    # A's runs the oracle answered: R001 (5.0 s; lag 3.0 plain, 2.0 robust; ratio 2.5, 5 / 3),
    # R002 (3.0 s; lag 2.5 plain, ratio 3.0; robust: not decidable), R003 (not localized).
    plain = [l.split() for l in out.splitlines() if l.startswith("plain")]
    robust = [l.split() for l in out.splitlines() if l.startswith("robust")]
    check(plain and plain[0][1:] == ["all", "3", "2", "2", "(100.0%)", "2.75", "3.00", "2.75", "3.00"],
          f"plain: 3 answered, 2 decidable, both localized, lag median 2.75 p90 3.00, ratio 2.75 / 3.00: {plain}")
    check(robust and robust[0][1:] == ["all", "3", "1", "1", "(100.0%)", "2.00", "2.00", "1.67", "1.67"],
          f"robust: 1 decidable, localized, lag 2.00, ratio 1.67: {robust}")

    p = subprocess.run([sys.executable, SCRIPT, a, "--against", b, "--json"], capture_output=True, text=True)
    try:
        doc = json.loads(p.stdout)
        c = doc["compare"]
        check((c["paired"], len(c["gained"]), len(c["lost"]), len(c["sooner"]), len(c["later"]), len(c["false_b"])) ==
              (6, 1, 1, 1, 0, 1), f"--json compare: {c}")
    except (ValueError, KeyError) as e:
        check(False, f"--json parses and has compare: {e}")

    p = subprocess.run([sys.executable, SCRIPT, a], capture_output=True, text=True)
    check(p.returncode == 0, f"A alone, no false convergence: exit 0, got {p.returncode}")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("sweep_runs.py: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

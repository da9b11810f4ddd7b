"""The checks of the ctests that run a script of scripts/ (results_script_test.py,
sweep_runs_script_test.py): a failed check is printed and kept in `failures`; the test fails
if any did."""
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)

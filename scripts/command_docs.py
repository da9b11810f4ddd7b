#!/usr/bin/env python3
"""Keeps the `--help` blocks of docs/commands/*.md what the command prints.

Every help text must also fit 100 columns: a longer line is only allowed where it holds an
option's name alone (its description then starts on the next line).

A ```text block whose previous non-blank line is "`bimloc CMD --help`, verbatim:" or, under
a page's "## Options", "`bimloc CMD SUB`:" holds `bimloc CMD [SUB] --help`, verbatim.

  scripts/command_docs.py BIMLOC            rewrite the blocks that differ
  scripts/command_docs.py BIMLOC --check    exit 1, naming each stale block, when any differs
"""
import pathlib
import re
import subprocess
import sys

HEAD = re.compile(r"^`(bimloc(?: [a-z][a-z-]*)+?)(?: --help)?`(?:, verbatim)?:\s*$")


def help_text(bimloc, words):
    r = subprocess.run([bimloc, *words, "--help"], capture_output=True, text=True, timeout=60)
    if r.returncode != 0:
        raise SystemExit(f"{bimloc} {' '.join(words)} --help exited {r.returncode}: {r.stderr}")
    # CLI11 names the program as it was called: the page names it `bimloc`.
    text = re.sub(r"^Usage: \S*bimloc ", "Usage: bimloc ", r.stdout, flags=re.M)
    return text.rstrip("\n") + "\n"


WIDTH = 100


def too_wide(text):
    """The lines of a --help text wider than WIDTH that hold more than an option's name."""
    return [line for line in text.splitlines() if len(line) > WIDTH and "  " in line.strip()]


def update(page, bimloc):
    lines = page.read_text().splitlines(keepends=True)
    out, stale, i, last = [], [], 0, ""
    while i < len(lines):
        line = lines[i]
        m = HEAD.match(last)
        if line.startswith("```text") and m:
            end = i + 1
            while end < len(lines) and not lines[end].startswith("```"):
                end += 1
            if end == len(lines):
                raise SystemExit(f"{page}:{i + 1}: a ```text block that never closes")
            want = help_text(bimloc, m.group(1).split()[1:])
            stale += [f"{page}:{i + 1}: `{m.group(1)} --help` has a line over {WIDTH} columns: {w[:60]}..."
                      for w in too_wide(want)]
            if "".join(lines[i + 1:end]) != want:
                stale.append(f"{page}:{i + 1}: `{m.group(1)} --help` has changed")
            out += [line, want, lines[end]]
            i, last = end + 1, lines[end].strip()
            continue
        out.append(line)
        if line.strip():
            last = line.strip()
        i += 1
    return "".join(out), stale


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    bimloc, check = sys.argv[1], "--check" in sys.argv[2:]
    docs = pathlib.Path(__file__).resolve().parent.parent / "docs" / "commands"
    all_stale = []
    for page in sorted(docs.glob("*.md")):
        text, stale = update(page, bimloc)
        all_stale += stale
        if stale and not check:
            page.write_text(text)
    for s in all_stale:
        print(s)
    if check and all_stale:
        print(f"{len(all_stale)} stale --help block(s): run scripts/command_docs.py {bimloc}")
        return 1
    print(f"{'checked' if check else 'updated'}: {len(all_stale)} block(s) {'stale' if check else 'rewritten'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

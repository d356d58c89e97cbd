#!/usr/bin/env python3
"""Splices the real output of `make demo` into README.md, between the lines
`<!-- demo output: begin -->` and `<!-- demo output: end -->`. `make readme` runs the demo and
then this script, so the README shows what the demo printed, never hand-typed numbers.

Usage: scripts/readme_demo.py DEMO_LOG   (run from the repository root)
"""
import re
import sys

BEGIN, END = "<!-- demo output: begin -->", "<!-- demo output: end -->"
# "solve (shooting): 42%, ...", "render: 7%, ...": what ProgressBar prints every --progress
# seconds where stderr is not a terminal.
PROGRESS = re.compile(r"^[a-z]+( \([a-z]+\))?: \d+%, ")


def main():
    lines = open(sys.argv[1]).read().splitlines()
    out, started, warned = [], False, False
    for line in lines:
        if line.startswith("build/cli/radiosity "):
            started = True
            if out:
                out.append("")
            out.append("$ " + line.replace("  ", " "))
            continue
        if not started or line.startswith("make") or line.startswith("demo: in "):
            continue
        if PROGRESS.match(line):
            continue  # a log's progress lines; on a terminal the bar is cleared

        if line.startswith("warning:"):
            if warned:
                continue  # the same left-wall warning, printed by every command
            warned = True
        out.append(line)
    readme = open("README.md").read()
    head, rest = readme.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    block = BEGIN + "\n```console\n" + "\n".join(out) + "\n```\n" + END
    open("README.md", "w").write(head + block + tail)


if __name__ == "__main__":
    main()

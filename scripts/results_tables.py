#!/usr/bin/env python3
"""The generated tables of docs/results.md, docs/results-synthetic.md and docs/benchmarks.md
(scripts/reproduce_results.sh drives it).

A generated block sits between two markers and starts with its stamp:

    <!-- BEGIN GENERATED id -->
    Generated: commit 1a2b3c4, 2026-12-07 16:40 UTC, nproc 2, Intel(R) Xeon(R) CPU @ 2.20GHz; 41 s wall.
    Commands:

    ```sh
    ./build/partreg eval ... --out $WORK/...
    ```

    | table | ... |
    <!-- END GENERATED id -->

Subcommands:
  select TABLES_MD PREFIX...   print the tables of a `partreg report` tables.md whose title starts with a prefix
  bench JSON...                a Google Benchmark JSON output as one markdown table
  splice DOC ID CONTENT COMMANDS SECONDS   replace block ID of DOC with the stamp, the commands and CONTENT
  check DOC...                 every table of DOC lies in a generated block that carries a stamp (exit 1 if not)
"""
import json
import os
import re
import subprocess
import sys
import tempfile
from datetime import datetime, timezone

BEGIN = re.compile(r"^<!-- BEGIN GENERATED ([a-z0-9-]+) -->$")
END = re.compile(r"^<!-- END GENERATED ([a-z0-9-]+) -->$")
STAMP = re.compile(r"^Generated: commit [0-9a-f]{7,40}(\+local changes)?, \d{4}-\d\d-\d\d \d\d:\d\d UTC, "
                   r"nproc \d+, .+; [0-9.]+ s wall\. Commands:$")


def fail(message):
    print(f"results_tables: {message}", file=sys.stderr)
    sys.exit(1)


def titled_tables(text):
    """(title, table lines) for each table of a tables.md: the title is the paragraph line above it."""
    lines, tables, i = text.splitlines(), [], 0
    while i < len(lines):
        if lines[i].startswith("|"):
            start = i
            while i < len(lines) and lines[i].startswith("|"):
                i += 1
            title = next((lines[j] for j in range(start - 1, -1, -1) if lines[j].strip()), "")
            tables.append((title, lines[start:i]))
        else:
            i += 1
    return tables


def has_figures(rows):
    """Whether a table has a figure: one where every cell is '-' (say partial views when none ran) is left out."""
    cells = [cell.strip() for row in rows[2:] for cell in row.strip("|").split("|")[1:]]
    return any(cell not in ("-", "") for cell in cells)


def select(path, prefixes):
    tables = titled_tables(open(path).read())
    out = []
    for prefix in prefixes:
        chosen = [(title, rows) for title, rows in tables if title.startswith(prefix)]
        if not chosen:
            fail(f"{path}: no table titled '{prefix}...'")
        chosen = [(title, rows) for title, rows in chosen if has_figures(rows)]
        for title, rows in chosen:
            out += [title, ""] + rows + [""]
    print("\n".join(out).rstrip())


def format_time(value, unit):
    return f"{value:.3g} {unit}" if value < 1000 else f"{value:.0f} {unit}"


def bench(paths):
    rows, counters = [], []
    for path in paths:
        try:
            runs = json.load(open(path))["benchmarks"]
        except (OSError, ValueError, KeyError):
            fail(f"{path}: no Google Benchmark output (did the filter match no benchmark?)")
        for run in runs:
            if run.get("run_type") == "aggregate" and run.get("aggregate_name") != "median":
                continue
            if run.get("error_occurred"):
                rows.append((run["run_name"], run.get("error_message", "error"), "", "", {}))
                continue
            extra = {k: v for k, v in run.items() if k not in KNOWN_FIELDS and isinstance(v, (int, float))}
            counters += [k for k in extra if k not in counters]
            name = run["run_name"] + (" (median)" if run.get("run_type") == "aggregate" else "")
            rows.append((name, format_time(run["real_time"], run["time_unit"]),
                         format_time(run["cpu_time"], run["time_unit"]), str(run["iterations"]), extra))
    header = ["benchmark", "wall", "CPU", "iterations"] + counters
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for name, wall, cpu, iterations, extra in rows:
        cells = [name, wall, cpu, iterations] + [f"{extra[c]:.4g}" if c in extra else "" for c in counters]
        lines.append("| " + " | ".join(cells) + " |")
    print("\n".join(lines))


KNOWN_FIELDS = {"family_index", "per_family_instance_index", "repetitions", "repetition_index", "threads",
                "iterations", "real_time", "cpu_time", "aggregate_unit"}


def git(*args):
    root = os.environ.get("PARTREG_STAMP_SOURCE") or os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return subprocess.run(["git", "-C", root, *args], capture_output=True, text=True).stdout.strip()


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def stamp(seconds):
    commit = git("rev-parse", "--short", "HEAD") or "0000000"
    # Code that differs from the commit (the docs excepted) is said so: the figures are not that commit's.
    if git("status", "--porcelain", "--untracked-files=no", "--", ".", ":!docs"):
        commit += "+local changes"
    when = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return f"Generated: commit {commit}, {when}, nproc {os.cpu_count()}, {cpu_model()}; {seconds} s wall. Commands:"


def splice(doc, block, content_path, commands_path, seconds):
    lines = open(doc).read().splitlines()
    begin = [i for i, line in enumerate(lines) if line == f"<!-- BEGIN GENERATED {block} -->"]
    end = [i for i, line in enumerate(lines) if line == f"<!-- END GENERATED {block} -->"]
    if len(begin) != 1 or len(end) != 1 or end[0] < begin[0]:
        fail(f"{doc}: no single block '{block}' (markers <!-- BEGIN/END GENERATED {block} -->)")
    content = open(content_path).read().strip()
    commands = open(commands_path).read().strip()
    body = [stamp(seconds), "", "```sh", commands, "```", "", content]
    new = lines[: begin[0] + 1] + body + lines[end[0]:]
    # Written beside and renamed: an interrupted run leaves the page as it was.
    handle, temporary = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(doc)), suffix=".md")
    with os.fdopen(handle, "w") as out:
        out.write("\n".join(new) + "\n")
    os.replace(temporary, doc)


def check(docs):
    problems = []
    for doc in docs:
        block, stamped = None, False
        for number, line in enumerate(open(doc).read().splitlines(), 1):
            if BEGIN.match(line):
                block, stamped, first = BEGIN.match(line).group(1), False, True
                continue
            if END.match(line):
                block = None
                continue
            if block and first and line.strip():
                stamped, first = bool(STAMP.match(line)), False
                if not stamped:
                    problems.append(f"{doc}:{number}: block '{block}' does not start with a stamp")
            if line.startswith("|") and not (block and stamped):
                problems.append(f"{doc}:{number}: a table outside a stamped generated block")
        if block:
            problems.append(f"{doc}: block '{block}' is not closed")
    if problems:
        fail("\n".join(problems))
    print(f"every table of {', '.join(docs)} carries a stamp")


def main(argv):
    if len(argv) < 2:
        fail(__doc__)
    command, args = argv[1], argv[2:]
    if command == "select" and len(args) >= 2:
        select(args[0], args[1:])
    elif command == "bench" and args:
        bench(args)
    elif command == "splice" and len(args) == 5:
        splice(*args)
    elif command == "check" and args:
        check(args)
    else:
        fail(__doc__)


if __name__ == "__main__":
    main(sys.argv)

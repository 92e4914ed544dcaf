#!/usr/bin/env python3
"""Tables in the docs generated from stored benchmark runs (results/*.json).

A results file is what `vt_bench SUITE --json --out results/NAME.json` writes: the suite's
figures plus the command, commit, machine and load of the run (bench/results_file.hpp). A
table in a Markdown file is backed by such files when it sits in a block like this:

    <!-- results: results/glove-*.json
    columns: figure | value | goal
    row: SIGINT to silence | {sigint_to_silence_ms:.1f} ms | <= 50 ms
    -->
    (generated table and the runs it comes from)
    <!-- end results -->

`{path:format}` is a figure: keys of the `figures` object joined by '/', a Python format spec
after the last ':'. With several matching files a cell shows the range over the runs. Under
the table the block lists each run (date, commit, CPU, cores, load) and the command that
reproduces it.

    scripts/perf-docs.py --check FILE.md...     exit 1 when a block differs from its stored runs
    scripts/perf-docs.py --write FILE.md...     regenerate the blocks in place
    scripts/perf-docs.py --validate RESULTS...  exit 1 when a results file lacks a field
"""
import argparse
import difflib
import glob
import json
import os
import re
import sys

REQUIRED = ["suite", "command", "exit_code", "date", "load_average/before", "load_average/after", "source/commit",
            "source/dirty", "build/type", "machine/cpu_model", "machine/cpu_flags", "machine/logical_cores", "figures"]
BLOCK = re.compile(r"<!-- results: (?P<spec>.*?)-->\n(?P<body>.*?)<!-- end results -->", re.S)
FIELD = re.compile(r"\{([^{}]+)\}")


class DocError(Exception):
    pass


def lookup(doc, path):
    value = doc
    for key in path.split("/"):
        if isinstance(value, list) and key.isdigit() and int(key) < len(value):
            value = value[int(key)]  # a range's ends: speedup_range/0, speedup_range/1
        elif isinstance(value, dict) and key in value:
            value = value[key]
        else:
            raise KeyError(path)
    return value


def validate(path):
    """The results file's JSON; DocError naming the file and the first missing field."""
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        raise DocError(f"{path}: not a readable JSON results file ({e})")
    for field in REQUIRED:
        try:
            lookup(doc, field)
        except KeyError:
            raise DocError(f"{path}: results file lacks '{field}' (write it with vt_bench SUITE --out)")
    if not isinstance(doc["figures"], dict):
        raise DocError(f"{path}: 'figures' is not an object")
    return doc


def show(value, fmt):
    if isinstance(value, bool):
        return "yes" if value else "no"
    return format(value, fmt)


def cell(template, runs, where):
    def field(match):
        path, fmt = match.group(1), ""
        if ":" in path:
            path, _, fmt = path.rpartition(":")
        values = []
        for name, doc in runs:
            try:
                values.append(lookup(doc["figures"], path))
            except KeyError:
                raise DocError(f"{where}: {name} has no figure '{path}'")
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
            low, high = show(min(values), fmt), show(max(values), fmt)
            return low if low == high else f"{low} - {high}"
        shown = sorted({show(v, fmt) for v in values})
        return " / ".join(shown)
    return FIELD.sub(field, template)


def provenance(name, doc):
    load = doc["load_average"]
    commit = doc["source"]["commit"][:10] + (" with uncommitted changes" if doc["source"]["dirty"] else "")
    build = "" if doc["build"]["type"] == "Release" else f", {doc['build']['type']} build"
    failed = "" if doc["exit_code"] == 0 else f", exit code {doc['exit_code']}"
    return (f"`{name}`: {doc['date']}, commit {commit}, {doc['machine']['cpu_model']} "
            f"({doc['machine']['logical_cores']} cores), load average {load['before'][0]:.2f} before / "
            f"{load['after'][0]:.2f} after{build}{failed}")


def render(spec, root, where):
    lines = [line.strip() for line in spec.strip().splitlines() if line.strip()]
    pattern = lines[0]
    columns, rows = None, []
    for line in lines[1:]:
        key, _, value = line.partition(":")
        if key == "columns":
            columns = [c.strip() for c in value.split("|")]
        elif key == "row":
            rows.append([c.strip() for c in value.split("|")])
        else:
            raise DocError(f"{where}: unknown line '{line}' (columns:, row:)")
    if not columns or not rows:
        raise DocError(f"{where}: a results block needs a 'columns:' line and 'row:' lines")
    names = sorted(glob.glob(os.path.join(root, pattern)))
    if not names:
        raise DocError(f"{where}: no stored run matches {pattern} (run the command the section gives)")
    runs = [(os.path.relpath(n, root), validate(n)) for n in names]
    out = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for row in rows:
        if len(row) != len(columns):
            raise DocError(f"{where}: row '{row[0]}' has {len(row)} cells for {len(columns)} columns")
        out.append("| " + " | ".join(cell(c, runs, where) for c in row) + " |")
    out.append("")
    out.append("Stored runs behind this table (cells give the range over them):" if len(runs) > 1 else
               "Stored run behind this table:")
    out.append("")
    out += [f"- {provenance(name, doc)}" for name, doc in runs]
    # A run written elsewhere and then stored: the command as it would write the stored file.
    commands = sorted({re.sub(r"--out \S+", f"--out {name}", doc["command"]) for name, doc in runs})
    out.append("")
    out.append("Reproduce: " + ", ".join(f"`build/bench/{c}`" for c in commands) + ".")
    return "\n".join(out) + "\n"


def fenced(text):
    """The (start, end) offsets of the fenced code blocks: examples of a block there are text."""
    spans, start, offset = [], None, 0
    for line in text.splitlines(True):
        if line.startswith("```"):
            if start is None:
                start = offset
            else:
                spans.append((start, offset + len(line)))
                start = None
        offset += len(line)
    return spans


def regenerate(text, root, path):
    code = fenced(text)

    def block(match):
        if any(a <= match.start() < b for a, b in code):
            return match.group(0)
        where = f"{path}:{text.count(chr(10), 0, match.start()) + 1}"
        return f"<!-- results: {match.group('spec')}-->\n{render(match.group('spec'), root, where)}<!-- end results -->"
    return BLOCK.sub(block, text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true", help="fail when a generated block differs from its stored runs")
    mode.add_argument("--write", action="store_true", help="regenerate the blocks in place")
    mode.add_argument("--validate", action="store_true", help="check results files' fields")
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."),
                        help="the repository (results paths are relative to it)")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    status = 0
    for path in args.files:
        try:
            if args.validate:
                validate(path)
                continue
            with open(path, encoding="utf-8") as f:
                text = f.read()
            new = regenerate(text, args.root, path)
            if new == text:
                continue
            if args.write:
                with open(path, "w", encoding="utf-8") as f:
                    f.write(new)
                print(f"{path}: tables regenerated")
            else:
                sys.stdout.writelines(difflib.unified_diff(text.splitlines(True), new.splitlines(True), path,
                                                           path + " (from results/)"))
                print(f"{path}: tables differ from their stored runs (scripts/perf-docs.py --write {path})")
                status = 1
        except (OSError, DocError) as e:
            print(f"error: {e}", file=sys.stderr)
            status = 1
    if status == 0:
        print(f"PASS: {len(args.files)} file(s) match their stored runs" if not args.validate else
              f"PASS: {len(args.files)} results file(s) complete")
    return status


if __name__ == "__main__":
    sys.exit(main())

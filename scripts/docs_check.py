#!/usr/bin/env python3
"""The numbers and names the README and docs/ quote that a command can regenerate, checked against
that command (`make docs-check`; the cheap part is the ctest docs_check).

Fails (exit 1, one line "docs-check: FILE:LINE: ..." per finding) on:
  - a count of the test suite ("N tests", the word right after the number) other than what
    `ctest -N` lists in BUILD;
  - the command table of README.md ("## Commands"): a command `renderaudit --help` lists that has
    no row, a row naming a command it does not list, and a row of a command with subcommands
    (builds, stats) that does not name each of them;
  - with RUN_DIR (a run of experiments/quick.toml or quick-egl.toml, analysed): a count of the
    quick experiment's figures ("N figures" on a line that says "quick") other than what
    `renderaudit plot RUN_DIR --list` plans for it.

docs/benchmarks.md is left out: every number there is what its date measured, with the machine and
its state, and stays as measured.

Usage: docs_check.py [--root ROOT] BUILD_DIR [RUN_DIR]
  BUILD_DIR holds renderaudit and the test programs; ROOT is the source tree whose README.md and
  docs/ are read (default: this script's parent folder; the test docs_check_fixture names another).
"""
import concurrent.futures
import glob
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATED_PAGES = {"docs/benchmarks.md"}  # measurements with their date: not regenerated
QUICK_EXPERIMENTS = ("experiments/quick.toml", "experiments/quick-egl.toml")

findings = []


def finding(path, line, text):
    findings.append(f"docs-check: {path}:{line}: {text}")


def pages():
    """(relative path, lines) of README.md and docs/*.md, the dated page left out."""
    paths = ["README.md"] + sorted(
        os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "docs", "*.md")))
    for rel in paths:
        if rel in DATED_PAGES:
            continue
        with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
            yield rel, f.read().split("\n")


def number(text):
    return int(text.replace(",", ""))


def run(argv, cwd=None):
    r = subprocess.run(argv, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return r.returncode, r.stdout


def check_test_count(build):
    rc, out = run(["ctest", "-N"], cwd=build)
    m = re.search(r"^Total Tests: (\d+)$", out, re.M)
    if rc != 0 or not m:
        sys.exit(f"docs-check: `ctest -N` in {build} failed (exit {rc}): {out[-500:]}")
    if "_NOT_BUILT" in out:
        sys.exit(f"docs-check: the test programs of {build} are not built, so ctest cannot count "
                 f"their tests: cmake --build {build} --target test_programs (make test and "
                 f"make docs-check build them)")
    total = int(m.group(1))
    for rel, lines in pages():
        for i, line in enumerate(lines, 1):
            for q in re.finditer(r"\b(\d[\d,]*) tests\b", line):
                if number(q.group(1)) != total:
                    finding(rel, i, f"says {q.group(1)} tests; `ctest -N` lists {total}")
    return total


def subcommands(argv):
    """The subcommand names in the help of `argv` (a "Commands:" heading, or CLI11's own
    "Subcommands:", a name per line indented by two spaces, wrapped descriptions indented
    further)."""
    rc, out = run(argv + ["--help"])
    if rc != 0:
        sys.exit(f"docs-check: `{' '.join(argv)} --help` failed (exit {rc}): {out[-500:]}")
    names, inside = [], False
    for line in out.split("\n"):
        if re.match(r"^(sub)?commands:\s*$", line, re.I):
            inside = True
        elif inside and re.match(r"^  \S", line):
            names.append(line.split()[0])
        elif inside and not line.strip():
            inside = False
    return names


def check_command_table(build):
    program = os.path.join(build, "renderaudit")
    commands = subcommands([program])
    if not commands:
        sys.exit(f"docs-check: `{program} --help` lists no subcommands")
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        lines = f.read().split("\n")
    try:
        start = lines.index("## Commands")
    except ValueError:
        finding("README.md", 1, "no '## Commands' section with the command table")
        return
    header, rows = None, {}
    for i in range(start + 1, len(lines)):
        line = lines[i]
        if line.startswith("## "):
            break
        if header is None and line.startswith("| command"):
            header = i + 1
        m = re.match(r"^\| `renderaudit ([a-z][a-z-]*)", line)
        if m:
            rows.setdefault(m.group(1), i + 1)
    where = header or start + 1
    for c in commands:
        if c not in rows:
            finding("README.md", where,
                    f"the command table has no row for `renderaudit {c}` (renderaudit --help "
                    f"lists it)")
    known = [c for c in rows if c in commands]
    # Each command's help at once: a start of the program is most of the check's time.
    with concurrent.futures.ThreadPoolExecutor(max_workers=8) as pool:
        subs = dict(zip(known, pool.map(lambda c: subcommands([program, c]), known)))
    for c, i in rows.items():
        if c not in commands:
            finding("README.md", i, f"`renderaudit {c}` is not a command of renderaudit --help")
            continue
        row = lines[i - 1].split("|")[1]  # the command cell
        for sub in subs[c]:
            if not re.search(r"(?<![\w-])" + re.escape(sub) + r"(?![\w-])", row):
                finding("README.md", i,
                        f"the row of `renderaudit {c}` does not name its subcommand {sub} "
                        f"(renderaudit {c} --help lists it)")
    return len(commands)


def check_quick_figures(build, run_dir):
    experiment = os.path.join(run_dir, "experiment.toml")
    try:
        with open(experiment, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        sys.exit(f"docs-check: {experiment}: {e.strerror}: RUN_DIR is to be a run of "
                 f"{QUICK_EXPERIMENTS[0]} (make docs-check runs it)")
    quick = []
    for q in QUICK_EXPERIMENTS:
        with open(os.path.join(ROOT, q), encoding="utf-8") as f:
            quick.append(f.read())
    if text not in quick:
        sys.exit(f"docs-check: {run_dir} is a run of another experiment than "
                 f"{' or '.join(QUICK_EXPERIMENTS)}: its figure count is not the quick one's")
    rc, out = run([os.path.join(build, "renderaudit"), "plot", run_dir, "--list"])
    m = re.search(r"^(\d+) figures planned", out, re.M)
    if rc != 0 or not m:
        sys.exit(f"docs-check: `renderaudit plot {run_dir} --list` failed (exit {rc}): "
                 f"{out[-500:]}")
    planned = int(m.group(1))
    for rel, lines in pages():
        for i, line in enumerate(lines, 1):
            if "quick" not in line:
                continue
            for q in re.finditer(r"\b(\d[\d,]*) figures\b", line):
                if number(q.group(1)) != planned:
                    finding(rel, i, f"says the quick experiment has {q.group(1)} figures; "
                                    f"`renderaudit plot {run_dir} --list` plans {planned}")
    return planned


def main():
    global ROOT
    args = sys.argv[1:]
    if len(args) >= 2 and args[0] == "--root":
        ROOT = os.path.abspath(args[1])
        args = args[2:]
    if len(args) not in (1, 2):
        sys.exit(__doc__.strip().split("Usage: ")[1])
    build = os.path.abspath(args[0])
    said = []
    said.append(f"{check_test_count(build)} tests")
    said.append(f"{check_command_table(build)} commands")
    if len(args) == 2:
        said.append(f"{check_quick_figures(build, args[1])} figures of the quick experiment")
    else:
        said.append("the quick experiment's figures not checked (no RUN_DIR: make docs-check)")
    for f in findings:
        print(f)
    if findings:
        print(f"docs-check: {len(findings)} stale number(s) or name(s)")
        return 1
    print("docs-check: the docs agree with the commands: " + ", ".join(said))
    return 0


if __name__ == "__main__":
    sys.exit(main())

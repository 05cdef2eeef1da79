#!/usr/bin/python3
"""The driver-upgrade report (scripts/driver-upgrade.sh): what changed between each platform and
its build PLATFORM@BUILD in one run, read from the run's records (`renderaudit records`, columns by
header name) and the audits' audit.json, with pictures (`renderaudit show`) and C reproducers
(`renderaudit reproduce`) of the worst primitives.

Usage: upgrade_report.py RENDERAUDIT RUN_DIR BUILD PLATFORM... > report.md
A primitive is changed when its lit pixels (pixel_hash), status or visibility differ; "worst" is
the largest change in the number of lit pixels."""
import collections
import csv
import io
import json
import os
import subprocess
import sys

GROUPS = "ABCD"


def records(ra, run_dir, platforms):
    """(platform, kind, view, index) -> the columns the report reads (`renderaudit records`: one
    stream of the run's records, whichever format its files have)."""
    out = {}
    text = subprocess.run([ra, "records", run_dir], check=True, capture_output=True,
                          text=True).stdout
    for r in csv.DictReader(io.StringIO(text)):
        if r["platform"] not in platforms:
            continue
        out[(r["platform"], r["kind"], int(r["view"]), int(r["index"]))] = (
            r["status"], r["visibility"], int(r["pixels"]), r["pixel_hash"],
            r.get("conformance", ""), int(r["view_group"]))
    return out


def main():
    ra, run_dir, build = sys.argv[1:4]
    platforms = sys.argv[4:]
    names = set(platforms) | {p + "@" + build for p in platforms}
    recs = records(ra, run_dir, names)
    driver = lambda p: json.load(open(os.path.join(run_dir, "drivers", p + ".json")))
    print(f"# Driver upgrade: what changed\n\nRun `{run_dir}`; each platform P (the installed "
          f"Mesa) against P@{build}.\n")
    print("| platform | installed GL_VERSION | build GL_VERSION | compared | changed | "
          "significant tests | new violations |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: |")
    for p in platforms:
        a = json.load(open(os.path.join(run_dir, f"audit-{p}", "audit.json")))
        c = a["counts"]
        print(f"| {p} | {driver(p)['version']} | {driver(p + '@' + build)['version']} | "
              f"{c['compared']} | {c['changed']} | {a['distribution_tests']['significant']} of "
              f"{a['distribution_tests']['family_size']} | {c.get('new_violations', 0)} |")
    worst = []
    for p in platforms:
        q = p + "@" + build
        per_group = collections.Counter()
        compared = collections.Counter()
        classes = collections.Counter()
        visibility = collections.Counter()
        for (plat, kind, view, index), before in recs.items():
            if plat != p:
                continue
            after = recs.get((q, kind, view, index))
            if after is None:
                continue
            key = (kind, GROUPS[before[5]])
            compared[key] += 1
            if (before[0], before[1], before[3]) == (after[0], after[1], after[3]):
                continue
            per_group[key] += 1
            classes[(kind, GROUPS[before[5]], before[4] or "n/a", after[4] or "n/a")] += 1
            if before[1] != after[1]:
                visibility[(kind, GROUPS[before[5]], before[1], after[1])] += 1
            worst.append((abs(after[2] - before[2]), p, q, kind, view, index, before[2], after[2]))
        print(f"\n## {p} -> {q}\n\nChanged primitives per kind and view group (A: FOV 30 at 128, "
              "B: FOV 150 at 128, C: FOV 30 at 907, D: FOV 150 at 907):\n")
        print("| kind | group | compared | changed | share |")
        print("| --- | :---: | ---: | ---: | ---: |")
        for key in sorted(compared):
            n, k = compared[key], per_group[key]
            print(f"| {key[0]} | {key[1]} | {n} | {k} | {100.0 * k / n:.2f}% |")
        if classes:
            print("\nClass transitions of the changed primitives (exact / snapped / within-spec / "
                  "violation):\n\n| kind | group | before | after | primitives |\n"
                  "| --- | :---: | --- | --- | ---: |")
            for (kind, g, b, a), n in sorted(classes.items(), key=lambda x: (-x[1], x[0])):
                print(f"| {kind} | {g} | {b} | {a} | {n} |")
        if visibility:
            print("\nVisibility transitions:\n\n| kind | group | before | after | primitives |\n"
                  "| --- | :---: | --- | --- | ---: |")
            for (kind, g, b, a), n in sorted(visibility.items(), key=lambda x: (-x[1], x[0])):
                print(f"| {kind} | {g} | {b} | {a} | {n} |")
    worst.sort(reverse=True)
    if worst:
        print("\n## Worst primitives (largest change in pixels lit)\n")
        pictures = os.path.join(run_dir, "upgrade-pictures")
        os.makedirs(pictures, exist_ok=True)
        for delta, p, q, kind, view, index, before, after in worst[:6]:
            print(f"- {q} {kind}, view {view}, index {index}: {before} -> {after} pixels")
            for plat in (p, q):
                png = os.path.join(pictures, f"{plat}.{kind}.v{view}.{index}.png")
                subprocess.run([ra, "show", run_dir, "--platform", plat, "--kind", kind, "--view",
                                str(view), "--index", str(index), "--out", png],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                if os.path.exists(png):
                    print(f"  ![{plat}]({os.path.relpath(png, run_dir)})")
            c = os.path.join(pictures, f"{q}.{kind}.v{view}.{index}.c")
            r = subprocess.run([ra, "reproduce", run_dir, "--platform", q, "--kind", kind,
                                "--view", str(view), "--index", str(index), "--out", c],
                               capture_output=True, text=True)
            if r.returncode == 0:
                print(f"  reproducer: `{os.path.relpath(c, run_dir)}` "
                      f"({r.stdout.splitlines()[1].replace('build: ', '')})")


if __name__ == "__main__":
    main()

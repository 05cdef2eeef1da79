#!/usr/bin/python3
"""The driver-upgrade report (scripts/driver-upgrade.sh): what changed between each platform and
its build PLATFORM@BUILD in one run, read from the run's records (`renderaudit records`, columns by
header name) and the audits' audit.json, with pictures (`renderaudit show`) and C reproducers
(`renderaudit reproduce`) of the worst primitive of each distinct finding.

Usage: upgrade_report.py [--audit-suffix SUFFIX] RENDERAUDIT RUN_DIR BUILD PLATFORM... > report.md
The audit of PLATFORM against PLATFORM@BUILD is read from RUN_DIR/audit-PLATFORM<SUFFIX>/audit.json
(driver-upgrade.sh: no suffix for backports, "-source" for the source build) and must say that it
compared those two platforms. Exit 2 for bad input: a missing or other audit.
Writes RUN_DIR/upgrade-summary-BUILD.json (schema "renderaudit-upgrade-summary" version 1: per pair
the counts per kind and view group, among them `not_drawn_violations`, the primitives both not
drawn and a new violation, so that page 1 says how the two nest, and, where the audit judged
drawing time (`audit --speed`), its verdicts per kind and view group as `speed`, copied from
audit.json) and opens the Markdown with
the sentences `renderaudit report --upgrade-headline` makes of it (report/upgrade_headline.h), then
the worst primitive's before and after side by side, a table of contents ([TOC]) and one section
per finding and per platform.

A primitive is changed when its lit pixels (pixel_hash), status or visibility differ. Each changed
primitive is one of: not drawn (true-visible -> false-invisible), a new violation (after a GL
violation, before none), fixed (the reverse), allowed (drawn as GL allows before and after, other
pixels), other; "worst" is the largest change in the number of lit pixels. A not drawn primitive
is most often also a new violation: the pictures' titles say how many of each finding are among
the other, in the numbers of page 1. Pairs of one driver
whose changed primitives and their pixels after are the same (one fingerprint) are one finding,
said once ("identical through OSMesa and EGL")."""
import collections
import csv
import hashlib
import io
import json
import os
import re
import shlex
import subprocess
import sys


def group_label(g):
    """View group g (0-based) as the records and the headline name it: A..Z, then AA, AB, ..."""
    label = ""
    g += 1
    while g:
        g, r = divmod(g - 1, 26)
        label = chr(ord("A") + r) + label
    return label


def die(message):
    print(f"upgrade_report.py: {message}", file=sys.stderr)
    sys.exit(2)

ALLOWED = {"exact", "snapped", "within-spec"}
BACKENDS = {"osmesa": "OSMesa", "egl": "EGL", "vk": "Vulkan", "glx": "GLX"}
# the findings, most severe first, with how a picture of one is titled
CATEGORIES = [("not_drawn", "not drawn"), ("new_violation", "that break GL's rules"),
              ("fixed", "that no longer break GL's rules"), ("other", "changed where GL's rules "
              "were not judged or already broken"), ("allowed", "lighting other pixels, as GL "
              "allows")]


def records(ra, run_dir, platforms):
    """(platform, kind, view, index) -> the columns the report reads (`renderaudit records`: one
    stream of the run's records, whichever format its files have); and group -> (fov, window)."""
    out, groups = {}, {}
    text = subprocess.run([ra, "records", run_dir], check=True, capture_output=True,
                          text=True).stdout
    for r in csv.DictReader(io.StringIO(text)):
        if r["platform"] not in platforms:
            continue
        g = int(r["view_group"])
        groups[group_label(g)] = (round(float(r["fov_deg"])), int(r["width"]))
        out[(r["platform"], r["kind"], int(r["view"]), int(r["index"]))] = (
            r["status"], r["visibility"], int(r["pixels"]), r["pixel_hash"],
            r.get("conformance", ""), g)
    return out, groups


def breaks(before, after):
    """A new violation: after one of GL's rules broken, before none (counted with the not drawn)."""
    return after[4] == "violation" and before[4] != "violation"


def category(before, after):
    if before[1] == "true-visible" and after[1] == "false-invisible":
        return "not_drawn"
    if after[4] == "violation" and before[4] != "violation":
        return "new_violation"
    if before[4] == "violation" and after[4] != "violation":
        return "fixed"
    if before[4] in ALLOWED and after[4] in ALLOWED:
        return "allowed"
    return "other"


def mesa(gl_version):
    """"25.0.7" of "... Mesa 25.0.7-2~bpo12+1": without a Debian revision (as report/upgrade_headline.h)."""
    m = re.search(r"Mesa ([^\s)]+)", gl_version)
    return re.sub(r"-[0-9].*$", "", m.group(1)) if m else ""


def pair_findings(recs, p, q):
    """Per (kind, group) the counts of the summary; the changed primitives with their category."""
    strata = collections.defaultdict(collections.Counter)
    changed = []
    for (plat, kind, view, index), before in recs.items():
        if plat != p:
            continue
        after = recs.get((q, kind, view, index))
        if after is None:
            continue
        s = strata[(kind, group_label(before[5]))]
        s["compared"] += 1
        if (before[0], before[1], before[3]) == (after[0], after[1], after[3]):
            continue
        s["changed"] += 1
        c = category(before, after)
        s["not_drawn"] += c == "not_drawn"
        s["newly_drawn"] += before[1] == "false-invisible" and after[1] == "true-visible"
        s["new_violations"] += breaks(before, after)
        s["not_drawn_violations"] += c == "not_drawn" and breaks(before, after)
        s["fixed_violations"] += c == "fixed"
        s["allowed"] += c == "allowed"
        changed.append((c, kind, view, index, before, after))
    return strata, changed


def finding_words(cat, kind, changed):
    """How a picture's title counts a finding, nested as page 1 nests the counts (a not drawn
    primitive is counted on page 1 among those breaking the rules, or else among the "more"):
    "53 lines not drawn (52 of them breaking GL's rules)", "23 of the 75 lines that break GL's
    rules, drawn (the other 52 are not drawn)"."""
    of_kind = [c for c in changed if c[1] == kind]
    n = sum(c[0] == cat for c in of_kind)
    kinds = kind if n == 1 else kind + "s"
    words = dict(CATEGORIES)[cat]
    if cat == "not_drawn":
        both = sum(c[0] == "not_drawn" and breaks(c[4], c[5]) for c in of_kind)
        if not both:
            return f"{n} {kinds} {words}"
        return (f"{n} {kinds} {words} (" + ("breaking GL's rules" if n == 1 else
                                            "all breaking GL's rules" if both == n else
                                            f"{both} of them breaking GL's rules") + ")")
    if cat in ("new_violation", "other"):
        # the not drawn that page 1 counts with this finding
        also = sum(c[0] == "not_drawn" and breaks(c[4], c[5]) == (cat == "new_violation")
                   for c in of_kind)
        if also:
            return (f"{n} of the {n + also} {kind}s {words}, drawn (the other {also} "
                    f"{'is' if also == 1 else 'are'} not drawn)")
    return f"{n} {kinds} {words.replace('break ', 'breaks ') if n == 1 else words}"


def fingerprint(changed):
    h = hashlib.sha1()
    for c, kind, view, index, before, after in sorted(changed, key=lambda x: x[1:4]):
        h.update(f"{kind} {view} {index} {after[0]} {after[1]} {after[3]}\n".encode())
    return h.hexdigest()[:16]


def picture_pair(ra, run_dir, p, q, kind, view, index, before, after, groups):
    """Markdown: the primitive drawn by both sides, side by side, and its reproducer. Each side is
    drawn `--against` the other: both pictures show the same window pixels at the same scale, with
    the same inset around the pixels the two draw otherwise."""
    pictures = os.path.join(run_dir, "upgrade-pictures")
    os.makedirs(pictures, exist_ok=True)
    cells = []
    for plat, other, state, side in ((p, q, before, "installed"), (q, p, after, "upgraded")):
        png = os.path.join(pictures, f"{plat}.{kind}.v{view}.{index}.png")
        subprocess.run([ra, "show", run_dir, "--platform", plat, "--against", other, "--kind",
                        kind, "--view", str(view), "--index", str(index), "--out", png],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        verdict = state[4] or "not judged"
        cells.append(f"![{side}, {plat}: {state[2]} pixels lit, {state[1]}, {verdict}]"
                     f"({os.path.relpath(png, run_dir)})")
    fov, window = groups[group_label(before[5])]
    # a command to paste: every word one shell word, whatever the run folder is called
    show = " ".join(shlex.quote(w) for w in ["renderaudit", "show", run_dir, "--platform", q,
                                             "--kind", kind, "--view", str(view),
                                             "--index", str(index)])
    lines = [" ".join(cells), "",
             f"{kind} {index} of view {view} (FOV {fov}, {window} x {window}). Grey: lit by the "
             "driver and the exact reference rasterizer; orange: by the driver only; blue: by "
             "the reference only; black: lit where GL forbids it; hatched green: left dark where "
             "GL requires it (both ringed in magenta); red: the ideal primitive. The framed "
             "pixels are enlarged under each picture, those the two drivers draw otherwise "
             f"dotted in magenta. `{show}` draws it again."]
    c = os.path.join(pictures, f"{q}.{kind}.v{view}.{index}.c")
    r = subprocess.run([ra, "reproduce", run_dir, "--platform", q, "--kind", kind, "--view",
                        str(view), "--index", str(index), "--out", c],
                       capture_output=True, text=True)
    if r.returncode == 0:
        lines.append(f"A C program that draws it: `{os.path.relpath(c, run_dir)}` "
                     f"({r.stdout.splitlines()[1].replace('build: ', '')}).")
    return "\n".join(lines) + "\n"


def audit_of(run_dir, p, q, suffix):
    """The audit.json of p against q, checked to be that pair's."""
    path = os.path.join(run_dir, f"audit-{p}{suffix}", "audit.json")
    try:
        with open(path) as f:
            a = json.load(f)
    except (OSError, ValueError) as e:
        die(f"{path}: cannot read the audit of {p} against {q} ({e}); run "
            f"`renderaudit audit {shlex.quote(run_dir)} --between {shlex.quote(p)} "
            f"{shlex.quote(q)} --out {shlex.quote(os.path.dirname(path))}`")
    pairs = a.get("pairs") if isinstance(a, dict) else None
    if not isinstance(pairs, list) or not any(
            isinstance(x, dict) and x.get("baseline_platform") == p and
            x.get("current_platform") == q for x in pairs):
        die(f"{path}: 'pairs' does not compare {p} with {q}: this is another audit's folder "
            "(give the right --audit-suffix)")
    return a


def speed_of(audit, p, q):
    """The drawing-time verdicts of p against q as the summary keeps them, None where the audit did
    not judge drawing time (the summary then has no `speed`: not timed)."""
    measured = audit.get("speed_measurement")
    if not isinstance(measured, dict) or measured.get("performed") is not True:
        return None
    return [{k: row.get(k) for k in ("kind", "group", "ratio", "low", "high", "verdict")}
            for row in audit.get("speed", [])
            if isinstance(row, dict) and row.get("baseline_platform") == p and
            row.get("platform") == q]


def main():
    args = sys.argv[1:]
    suffix = ""
    if args[:1] == ["--audit-suffix"]:
        if len(args) < 2:
            die("--audit-suffix needs a value")
        suffix, args = args[1], args[2:]
    if len(args) < 4:
        die("usage: upgrade_report.py [--audit-suffix SUFFIX] RENDERAUDIT RUN_DIR BUILD PLATFORM...")
    ra, run_dir, build = args[:3]
    platforms = args[3:]
    names = set(platforms) | {p + "@" + build for p in platforms}
    recs, groups = records(ra, run_dir, names)
    driver = lambda p: json.load(open(os.path.join(run_dir, "drivers", p + ".json")))

    # the summary the first sentences are made of, and the distinct findings
    audits = {p: audit_of(run_dir, p, p + "@" + build, suffix) for p in platforms}
    pairs, findings, changed_of = [], collections.OrderedDict(), {}
    for p in platforms:
        q = p + "@" + build
        strata, changed = pair_findings(recs, p, q)
        changed_of[p] = changed
        fp = fingerprint(changed)
        pairs.append({"platform": p, "build_platform": q,
                      "installed_version": driver(p)["version"],
                      "build_version": driver(q)["version"], "fingerprint": fp,
                      "strata": [dict({"kind": k, "group": g}, **{
                          f: strata[(k, g)][f] for f in
                          ("compared", "changed", "not_drawn", "newly_drawn", "new_violations",
                           "fixed_violations", "allowed", "not_drawn_violations")})
                          for (k, g) in sorted(strata)]})
        speed = speed_of(audits[p], p, q)
        if speed is not None:
            pairs[-1]["speed"] = speed
        backend, _, drv = p.partition("-")
        key = (drv, fp, json.dumps(pairs[-1]["strata"]))
        findings.setdefault(key, {"pairs": [], "changed": changed})["pairs"].append(p)
    summary = {"schema": "renderaudit-upgrade-summary", "schema_version": 1, "run": run_dir,
               "build": build,
               "groups": [{"label": g, "fov_deg": groups[g][0], "window": groups[g][1]}
                          for g in sorted(groups)],
               "pairs": pairs}
    summary_path = os.path.join(run_dir, f"upgrade-summary-{build}.json")
    with open(summary_path, "w") as f:
        json.dump(summary, f, indent=1)
    made = subprocess.run([ra, "report", "--upgrade-headline", summary_path],
                          capture_output=True, text=True)
    if made.returncode != 0:
        die(f"`renderaudit report --upgrade-headline {summary_path}` failed: "
            f"{made.stderr.strip()}")
    headline = made.stdout

    installed = sorted({mesa(driver(p)["version"]) for p in platforms} - {""})
    upgraded = sorted({mesa(driver(p + "@" + build)["version"]) for p in platforms} - {""})
    print("# Driver upgrade: what changed\n")
    print(headline)
    print(f"Run `{run_dir}`: each platform P, the installed Mesa ({', '.join(installed)}), "
          f"against P@{build} (Mesa {', '.join(upgraded)}). View groups: " +
          ", ".join(f"{g}: FOV {groups[g][0]} at {groups[g][1]} x {groups[g][1]}"
                    for g in sorted(groups)) + ".\n")

    # one picture set per distinct finding: the worst primitive of each category of each
    # finding, the most severe first; on page 1 the most striking of those breaking GL's rules
    # (not drawn, new violation): the largest change in pixels lit
    shown = []
    for (drv, fp, _), f in findings.items():
        p = f["pairs"][0]
        backends = " and ".join(BACKENDS.get(x.partition("-")[0], x.partition("-")[0])
                                for x in f["pairs"])
        version = mesa(driver(p + "@" + build)["version"]) or "@" + build
        for rank, (cat, _) in enumerate(CATEGORIES):
            for kind in sorted({c[1] for c in f["changed"] if c[0] == cat}):
                members = [c for c in f["changed"] if c[0] == cat and c[1] == kind]
                _, _, view, index, before, after = max(
                    members, key=lambda m: (abs(m[5][2] - m[4][2]), -m[2], -m[3]))
                through = (f"identical through {backends}" if len(f["pairs"]) > 1
                           else f"through {backends}")
                title = (f"{drv} {version}, {through}: {finding_words(cat, kind, f['changed'])}; "
                         f"the worst, {kind} {index} of view {view}")
                shown.append((rank, title, p, kind, view, index, before, after))
    shown.sort(key=lambda s: s[0])
    severe = [s for s in shown if CATEGORIES[s[0]][0] in ("not_drawn", "new_violation")]
    if severe:
        lead = max(severe, key=lambda s: abs(s[7][2] - s[6][2]))
        shown.remove(lead)
        shown.insert(0, lead)
    print("[TOC]\n")
    if shown:
        rank, title, p, kind, view, index, before, after = shown[0]
        print(f"# {title}\n")
        print(picture_pair(ra, run_dir, p, p + "@" + build, kind, view, index, before, after,
                           groups))
    if len(shown) > 1:
        print("# The other findings in pictures\n")
        print("One picture set per distinct finding: the primitive whose lit pixels changed "
              "most.\n")
        for rank, title, p, kind, view, index, before, after in shown[1:]:
            print(f"## {title}\n")
            print(picture_pair(ra, run_dir, p, p + "@" + build, kind, view, index, before,
                               after, groups))

    print("# Per platform\n")
    print("### Changed primitives, tests and new violations per platform\n")
    print("| platform | installed GL_VERSION | build GL_VERSION | compared | changed | "
          "significant tests | new violations |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: |")
    for p in platforms:
        a = audits[p]
        c = a["counts"]
        print(f"| {p} | {driver(p)['version']} | {driver(p + '@' + build)['version']} | "
              f"{c['compared']} | {c['changed']} | {a['distribution_tests']['significant']} of "
              f"{a['distribution_tests']['family_size']} | {c.get('new_violations', 0)} |")
    for pair in pairs:
        p, q = pair["platform"], pair["build_platform"]
        changed = changed_of[p]
        print(f"\n# {p} -> {q}\n")
        print("### Changed primitives per kind and view group\n")
        print("| kind | group | compared | changed | share | not drawn | new violations | "
              "as GL allows |")
        print("| --- | :---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for s in pair["strata"]:
            print(f"| {s['kind']} | {s['group']} | {s['compared']} | {s['changed']} | "
                  f"{100.0 * s['changed'] / s['compared']:.2f}% | {s['not_drawn']} | "
                  f"{s['new_violations']} | {s['allowed']} |")
        classes = collections.Counter((k, group_label(b[5]), b[4] or "n/a", a[4] or "n/a")
                                      for _, k, _, _, b, a in changed)
        if classes:
            print("\n### Class transitions of the changed primitives (exact / snapped / "
                  "within-spec / violation)\n\n| kind | group | before | after | primitives |\n"
                  "| --- | :---: | --- | --- | ---: |")
            for (kind, g, b, a), n in sorted(classes.items(), key=lambda x: (-x[1], x[0])):
                print(f"| {kind} | {g} | {b} | {a} | {n} |")
        visibility = collections.Counter((k, group_label(b[5]), b[1], a[1])
                                         for _, k, _, _, b, a in changed if b[1] != a[1])
        if visibility:
            print("\n### Visibility transitions (true-visible -> false-invisible: not drawn)\n\n"
                  "| kind | group | before | after | primitives |\n"
                  "| --- | :---: | --- | --- | ---: |")
            for (kind, g, b, a), n in sorted(visibility.items(), key=lambda x: (-x[1], x[0])):
                print(f"| {kind} | {g} | {b} | {a} | {n} |")


if __name__ == "__main__":
    main()

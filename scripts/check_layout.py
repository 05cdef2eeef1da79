#!/usr/bin/env python3
"""The layout rules of the source tree (docs/development.md, "Source layout"), checked on the code.

Fails (exit 1, one line "layout: FILE:LINE: ..." per finding) on:
  - an include of a folder that comes after the including folder in the layer order;
  - a *_test.cpp that includes a folder after its own (a test in a room below the code it tests);
  - a function body over MAX_FUNCTION_LINES lines (signature to closing brace) outside tests, unless
    the comment right above the function says why it reads better whole (a line starting with
    "// Reads better whole:");
  - a namespace that does not match its folder (ra::<folder>, or a name under it);
  - a link between two of the project's libraries in CMakeLists.txt that no include needs, or an
    include of another library's folder that no link provides, directly or through another link;
  - a folder of RA_DRIVER_FREE (CMakeLists.txt) whose links reach a folder of RA_DRIVERS;
  - outside rundir/, a run folder's file name spelled as a path ("/manifest.json" or
    / "manifest.json", and the other names of RUN_FOLDER_NAMES): paths into a run directory are
    built by rundir/run_folder.h; prose (a help text's "holds experiment.toml") is not a path;
  - in a shell script under scripts/ or tests/ that sets pipefail, a pipe into a command that may
    stop reading before the writer is done (`| head`, `| grep -q`, `-m`, `-l`, `--quiet`, ...): the
    writer then dies of SIGPIPE and the pipeline fails now and then. Capture the output first
    (out=$(cmd); grep -q X <<<"$out"). A pipe continued on the next line (after `|` or `\\`) counts.
The layer order is read from CMakeLists.txt (`set(RA_LAYERS ...)`), the one place it is written;
docs/development.md must list the folders in the same order.

A *_test.cpp may include only its own folder and folders before it (it lives in the lowest folder
whose code it exercises), plus the test-support headers of any folder. Test-support headers
(*_testing.h, *_test_util.h, *_test.h), tests/, benchmarks and investigations may include
anything; no test is held to the function limit.

Usage: check_layout.py [ROOT]   (ROOT: the source tree, default: this script's parent folder)
"""
import os
import re
import sys

MAX_FUNCTION_LINES = 150
WHOLE_MARK = "// Reads better whole:"

# Folders whose namespace is another name than the folder's, and why.
NAMESPACE_OF_FOLDER = {
    "terrain_lod": "ra::lod",  # the study's name in its files, commands and documents
}
# Functions over the limit not yet split, as (file, function name) pairs. An entry
# whose function is now short is reported as stale (not an error) so that it can be removed.
KNOWN_LONG_FUNCTIONS = set()


# The file names of a run directory (rundir/run_folder.h) and the folder that alone spells them.
RUN_FOLDER_NAMES = ("experiment.toml", "manifest.json", "tally.json", "figures.json", "index.json",
                    "bisect.json", "study.json", "progress.json", "timing.json")
RUN_FOLDER_HOME = "rundir"
# A literal that starts with "/NAME" (dir + "/manifest.json"), or "NAME" after the path operator /.
RUN_FOLDER_PATH_RE = re.compile(r'"/(%s)\b|/\s*"(%s)"' % (
    "|".join(re.escape(n) for n in RUN_FOLDER_NAMES), "|".join(re.escape(n) for n in RUN_FOLDER_NAMES)))


def is_test_file(path):
    name = os.path.basename(path)
    return (name.endswith("_test.cpp") or name.endswith("_testing.h") or
            name.endswith("_test_util.h") or name.endswith("_test.h"))


def strip_code(text):
    """Comments and string/char literals blanked (newlines kept, so lines still count)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            end = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + "".join(ch if ch == "\n" else " " for ch in text[i + 2:end]))
            i = end
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):  # 1'000 digit separators
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + (c if j < n else ""))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


class Block:
    def __init__(self, kind, name, start_line, header_line):
        self.kind = kind            # "namespace", "type", "function", "other"
        self.name = name            # the namespace's name, the function's name
        self.start_line = start_line
        self.header_line = header_line


SCOPE_RE = re.compile(r"^(?:template\s*<.*>\s*)?(?:(?:typedef|export)\s+)?(class|struct|union|enum)\b", re.S)
NAMESPACE_RE = re.compile(r"^(?:inline\s+)?namespace\s*([\w:]*)\s*$", re.S)
FUNCTION_NAME_RE = re.compile(r"([~\w:]+(?:\s*operator\s*[^\s(]+)?)\s*\(")


def scan_blocks(code):
    """Yields (event, block, line) for the blocks of stripped code: ("open", block) and ("close",
    block, closing line). A block's header is the code since the last ';', '{' or '}'."""
    stack = []
    header_start = 0
    preprocessor = re.compile(r"^[ \t]*#.*$", re.M)
    # Preprocessor lines do not take part in headers.
    code = preprocessor.sub(lambda m: " " * len(m.group(0)), code)
    for m in re.finditer(r"[{};]", code):
        ch = m.group(0)
        pos = m.start()
        if ch == ";":
            header_start = pos + 1
            continue
        if ch == "{":
            header = code[header_start:pos]
            stripped = header.strip()
            first = header_start + (len(header) - len(header.lstrip()))
            parent = stack[-1].kind if stack else "namespace"
            ns = NAMESPACE_RE.match(stripped)
            if ns:
                block = Block("namespace", ns.group(1), line_of(code, pos), line_of(code, first))
            elif parent in ("namespace", "type") and SCOPE_RE.match(stripped):
                block = Block("type", "", line_of(code, pos), line_of(code, first))
            elif parent in ("namespace", "type") and "(" in stripped and not stripped.endswith("="):
                fm = FUNCTION_NAME_RE.search(re.sub(r"<[^<>()]*>", "", stripped))
                name = fm.group(1).split("::")[-1] if fm else "?"
                if stripped.startswith("extern"):
                    block = Block("namespace", None, line_of(code, pos), line_of(code, first))
                else:
                    block = Block("function", name, line_of(code, pos), line_of(code, first))
            elif stripped.startswith('extern ""') or stripped == 'extern':
                block = Block("namespace", None, line_of(code, pos), line_of(code, first))
            else:
                block = Block("other", "", line_of(code, pos), line_of(code, first))
            stack.append(block)
            yield ("open", block, line_of(code, pos))
            header_start = pos + 1
        else:
            if stack:
                block = stack.pop()
                yield ("close", block, line_of(code, pos))
            header_start = pos + 1


def source_files(root, folder):
    d = os.path.join(root, folder)
    if not os.path.isdir(d):
        return []
    return sorted(os.path.join(folder, f) for f in os.listdir(d) if f.endswith((".cpp", ".h")))


def read_layers(root):
    text = open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8").read()
    m = re.search(r"set\(RA_LAYERS\s+([^)]*)\)", text)
    if not m:
        sys.exit("layout: CMakeLists.txt has no set(RA_LAYERS ...): the layer order is read from it")
    return m.group(1).split(), text


def check_docs_order(root, layers, findings):
    path = os.path.join(root, "docs", "development.md")
    if not os.path.exists(path):
        return
    lines = open(path, encoding="utf-8").read().split("\n")
    listed = []
    for k, line in enumerate(lines, 1):
        m = re.match(r"^([a-z_]+)/\s", line)
        if m and m.group(1) in layers:
            listed.append((m.group(1), k))
    if [name for name, _ in listed] != layers:
        where = listed[0][1] if listed else 1
        findings.append("docs/development.md:%d: the source layout lists %s; CMakeLists.txt RA_LAYERS "
                        "is %s" % (where, " ".join(n for n, _ in listed), " ".join(layers)))


def check_includes(root, layers, rank, findings, included):
    for folder in layers:
        for f in source_files(root, folder):
            if is_test_file(f):
                continue
            for k, line in enumerate(open(os.path.join(root, f), encoding="utf-8"), 1):
                m = re.match(r'\s*#\s*include\s+"([a-z_]+)/', line)
                if not m or m.group(1) not in rank:
                    continue
                target = m.group(1)
                included.setdefault(folder, {}).setdefault(target, (f, k))
                if rank[target] > rank[folder]:
                    findings.append("%s:%d: includes %s/ (a folder after %s/ in the layer order)"
                                    % (f, k, target, folder))


def check_test_includes(root, layers, rank, findings):
    """A *_test.cpp tests its own room: it includes its own folder and folders below it, like the
    code it tests, plus the test-support headers (*_testing.h, *_test_util.h) of any folder."""
    for folder in layers:
        for f in source_files(root, folder):
            if not f.endswith("_test.cpp"):
                continue
            for k, line in enumerate(open(os.path.join(root, f), encoding="utf-8"), 1):
                m = re.match(r'\s*#\s*include\s+"([a-z_]+)/([a-z_0-9]+\.h)"', line)
                if not m or m.group(1) not in rank or rank[m.group(1)] <= rank[folder]:
                    continue
                if is_test_file(m.group(2)):
                    continue  # test support (a scipy oracle, lines of a text) serves any room
                findings.append("%s:%d: a test includes %s/ (a folder after %s/): move the test to the "
                                "lowest folder whose code it exercises" % (f, k, m.group(1), folder))


def check_code(root, layers, findings, notes):
    seen_long = set()
    for folder in layers:
        expected = NAMESPACE_OF_FOLDER.get(folder, "ra::" + folder)
        for f in source_files(root, folder):
            raw = open(os.path.join(root, f), encoding="utf-8").read()
            code = strip_code(raw)
            raw_lines = raw.split("\n")
            names = []
            for event, block, line in scan_blocks(code):
                if block.kind == "namespace":
                    if event == "open":
                        names.append(block.name)
                        full = "::".join(n for n in names if n)
                        # anonymous namespaces and extern "C" add nothing; check named ones only
                        if block.name and not is_test_file(f):
                            ok = full == expected or full.startswith(expected + "::")
                            if not ok:
                                findings.append("%s:%d: namespace %s in %s/ (expected %s)"
                                                % (f, block.start_line, full, folder, expected))
                    else:
                        names.pop()
                elif block.kind == "function" and event == "close" and not is_test_file(f):
                    length = line - block.header_line + 1
                    if length <= MAX_FUNCTION_LINES:
                        continue
                    k = block.header_line - 2
                    comment = []
                    while k >= 0 and raw_lines[k].strip().startswith("//"):
                        comment.append(raw_lines[k].strip())
                        k -= 1
                    if any(c.startswith(WHOLE_MARK) for c in comment):
                        continue
                    if (f, block.name) in KNOWN_LONG_FUNCTIONS:
                        seen_long.add((f, block.name))
                        continue
                    findings.append("%s:%d: function %s is %d lines (limit %d; or say why it reads "
                                    "better whole in a comment right above: \"%s ...\")"
                                    % (f, block.header_line, block.name, length, MAX_FUNCTION_LINES,
                                       WHOLE_MARK))
    for f, name in sorted(KNOWN_LONG_FUNCTIONS - seen_long):
        if os.path.exists(os.path.join(root, f)):
            notes.append("%s: %s is no longer over the limit: remove it from KNOWN_LONG_FUNCTIONS" % (f, name))


def check_run_folder_names(root, layers, findings):
    """Outside rundir/, no non-test file builds a path into a run directory by its file's name."""
    for folder in layers:
        if folder == RUN_FOLDER_HOME:
            continue
        for f in source_files(root, folder):
            if is_test_file(f):
                continue
            for k, line in enumerate(open(os.path.join(root, f), encoding="utf-8"), 1):
                if line.lstrip().startswith("//"):
                    continue
                m = RUN_FOLDER_PATH_RE.search(line)
                if m:
                    findings.append("%s:%d: spells the run folder's %s as a path; build it with "
                                    "rundir/run_folder.h" % (f, k, m.group(1) or m.group(2)))


def check_links(root, layers, cmake, findings, included):
    """Links between the project's libraries (target_link_libraries of a layer folder's library)
    against the folders its non-test files include."""
    links = {}
    for m in re.finditer(r"target_link_libraries\(\s*(\w+)\s+([^)]*)\)", cmake):
        lib = m.group(1)
        if lib not in layers:
            continue
        line = line_of(cmake, m.start())
        for word in m.group(2).split():
            if word in layers and word != lib:
                links.setdefault(lib, {}).setdefault(word, line)
    for lib in layers:
        needs = set(t for t in included.get(lib, {}) if t != lib)
        for target, line in sorted(links.get(lib, {}).items()):
            if target not in needs:
                findings.append("CMakeLists.txt:%d: %s links %s, but no file of %s/ includes %s/"
                                % (line, lib, target, lib, target))
        reach, todo = set(), list(links.get(lib, {}))
        while todo:  # what the links give, directly or through the linked libraries
            t = todo.pop()
            if t not in reach:
                reach.add(t)
                todo.extend(links.get(t, {}))
        for target in sorted(needs - reach):
            f, k = included[lib][target]
            findings.append("%s:%d: includes %s/, but CMakeLists.txt links %s to nothing that gives %s"
                            % (f, k, target, lib, target))
    check_driver_free(cmake, links, findings)


def read_list(cmake, name):
    m = re.search(r"set\(%s\s+([^)]*)\)" % name, cmake)
    return (m.group(1).split(), line_of(cmake, m.start())) if m else ([], 0)


def check_driver_free(cmake, links, findings):
    """The folders of RA_DRIVER_FREE (those that read runs) reach none of RA_DRIVERS (the folders
    that hold driver code) through their links, directly or through other libraries."""
    free, line = read_list(cmake, "RA_DRIVER_FREE")
    drivers, _ = read_list(cmake, "RA_DRIVERS")
    for lib in free:
        parent, todo = {lib: None}, [lib]
        while todo:  # breadth first: the shortest chain of links is the one named
            t = todo.pop(0)
            for u in sorted(links.get(t, {})):
                if u not in parent:
                    parent[u] = t
                    todo.append(u)
        for d in drivers:
            if d in parent:
                chain, t = [], d
                while t is not None:
                    chain.append(t)
                    t = parent[t]
                findings.append("CMakeLists.txt:%d: %s is to link no driver code (RA_DRIVER_FREE), "
                                "but it reaches %s: %s" % (line, lib, d, " -> ".join(reversed(chain))))


# A pipe (not ||) into head, or into grep with an option that stops at the first match or file.
EARLY_EXIT_PIPE_RE = re.compile(
    r"(?<![|\\])\|(?!\|)\s*(?:head\b|grep(?:\s+-[A-Za-z]+)*\s+-[A-Za-z]*[qlm]"
    r"|grep\b[^|]*--(?:quiet|silent|max-count|files-with-matches)\b)")
PIPEFAIL_RE = re.compile(r"^\s*set\s+(?:-[A-Za-z]*\s+)*-[A-Za-z]*o\s+pipefail|^\s*set\s+-o\s+pipefail", re.M)


def shell_scripts(root):
    """The shell scripts under scripts/ and tests/ (by .sh or a sh/bash first line), the layout
    check's own fixture aside."""
    out = []
    for top in ("scripts", "tests"):
        for d, dirs, files in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(x for x in dirs if not (top == "tests" and x == "layout_fixture" and
                                                     d == os.path.join(root, top)))
            for f in sorted(files):
                path = os.path.join(d, f)
                try:
                    with open(path, encoding="utf-8", errors="replace") as fh:
                        first = fh.readline()
                except OSError:
                    continue
                if f.endswith(".sh") or (first.startswith("#!") and re.search(r"\b(ba)?sh\b", first)):
                    out.append(path)
    return out


def shell_commands(text):
    """The script's lines joined where a command goes on: after a line that ends in a pipe or a
    backslash (`grep -A3 X file |` NEWLINE `grep -qF Y`), comment lines inside skipped. Yields
    (command, line_of) where line_of(offset) is the script's line of an offset in the command."""
    command, starts = "", []  # starts: (offset in command, line number) of each joined line
    for n, line in enumerate(text.split("\n"), 1):
        if line.lstrip().startswith("#"):
            if not command:
                continue
            line = ""
        if command:
            command += " "
        starts.append((len(command), n))
        code = line.rstrip()
        if code.endswith("\\") and not code.endswith("\\\\"):
            command += code[:-1]
            continue
        command += code
        if code.endswith("|") and not code.endswith("||"):
            continue
        if command.strip():
            yield command, (lambda offset, s=starts: max(n for o, n in s if o <= offset))
        command, starts = "", []
    if command.strip():
        yield command, (lambda offset, s=starts: max(n for o, n in s if o <= offset))


def check_pipes(root, findings):
    for path in shell_scripts(root):
        with open(path, encoding="utf-8", errors="replace") as fh:
            text = fh.read()
        if not PIPEFAIL_RE.search(text):
            continue
        for command, line_of in shell_commands(text):
            for m in EARLY_EXIT_PIPE_RE.finditer(command):
                findings.append("%s:%d: '%s' under pipefail: the command before it dies of SIGPIPE "
                                "when this one stops reading early, and the pipeline fails by "
                                "chance; capture the output first (out=$(cmd); grep -q X <<<\"$out\")"
                                % (os.path.relpath(path, root), line_of(m.start()), " ".join(m.group(0).split())))


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    root = os.path.abspath(root)
    layers, cmake = read_layers(root)
    rank = {name: i for i, name in enumerate(layers)}
    findings, notes, included = [], [], {}
    check_docs_order(root, layers, findings)
    check_includes(root, layers, rank, findings, included)
    check_test_includes(root, layers, rank, findings)
    check_code(root, layers, findings, notes)
    check_links(root, layers, cmake, findings, included)
    check_run_folder_names(root, layers, findings)
    check_pipes(root, findings)
    for n in notes:
        print("layout: note: " + n)
    for f in findings:
        print("layout: " + f)
    if findings:
        print("layout: %d finding(s)" % len(findings))
        return 1
    print("layout: %d folders in layer order; includes, function lengths, namespaces and links agree"
          % len(layers))
    return 0


if __name__ == "__main__":
    sys.exit(main())

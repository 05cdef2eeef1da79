#!/usr/bin/env bash
# The test of the layout check (ctest layout_fixture): on tests/layout_fixture/, a tree with one
# violation of each kind (a test that includes a higher folder among them), check-layout.sh must
# fail and name each violation's file and line, and must not report what the rules allow (a long
# function that says why, test helpers, a test including a higher folder's test-support header).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=$(scripts/check-layout.sh tests/layout_fixture)
rc=$?
bad=0
if [ $rc -ne 1 ]; then echo "expected exit 1, got $rc"; bad=1; fi
expect=(
  "layout: docs/development.md:4: the source layout lists low high mid; CMakeLists.txt RA_LAYERS is low mid high"
  "layout: low/upward.cpp:3: includes high/ (a folder after low/ in the layer order)"
  "layout: mid/reaching_test.cpp:5: a test includes high/ (a folder after mid/)"
  "layout: mid/wrong_namespace.h:9: namespace ra::low in mid/ (expected ra::mid)"
  "layout: high/long_function.cpp:8: function long_function is 154 lines (limit 150"
  "layout: low/upward.cpp:3: includes high/, but CMakeLists.txt links low to nothing that gives high"
  "layout: CMakeLists.txt:5: high links low, but no file of high/ includes low/"
  "layout: CMakeLists.txt:7: mid is to link no driver code (RA_DRIVER_FREE), but it reaches low: mid -> low"
  "layout: scripts/pipes.sh:5: "
  "grep -q' under pipefail: the command before it dies of SIGPIPE"
  "layout: scripts/pipes.sh:10: "
  "layout: scripts/pipes.sh:13: "
  "head' under pipefail"
  "layout: mid/run_names.cpp:7: spells the run folder's manifest.json as a path; build it with rundir/run_folder.h"
  "layout: mid/run_names.cpp:8: spells the run folder's experiment.toml as a path"
  "layout: 13 finding(s)"
)
for line in "${expect[@]}"; do
  grep -qF -- "$line" <<<"$out" || { echo "missing: $line"; bad=1; }
done
for absent in long_but_whole helpers_testing "namespace ra::mid" detail "pipes.sh:[6-9]" "pipes.sh:1[1245]" "run_names.cpp:[0-69]" "reaching_test.cpp:4"; do
  if grep -q -- "$absent" <<<"$out"; then echo "reported what the rules allow: $absent"; bad=1; fi
done
if [ $bad -ne 0 ]; then echo "--- the check printed:"; echo "$out"; exit 1; fi
echo "layout check: the fixture's 13 violations found, each with file and line"

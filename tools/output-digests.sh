#!/usr/bin/env bash
# The digests that `tests/it/same_outputs.rs` holds a build to (issue 40's refactor contract):
# for each spec it names, `check SPEC --json --report` with BIN, the terminal text (and exit
# code), the results JSON and every file of the review, the output directory's path and the
# wall-clock figures masked ("in 0.86 s", the accuracy ladder's cells), each file's SHA-256 listed by path and the list
# hashed. Prints `spec digest` lines in the test's order.
#
#   tools/output-digests.sh BIN
#
# Record with the build BEFORE a change that must keep outputs, paste into the test's
# RECORDED table; a change that alters an output on purpose re-records with that build and
# names the change in its commit (`tools/same-outputs.sh` shows which bytes moved).
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(realpath "$1")"
specs=$(sed -n 's/^    ("\([a-z0-9-]*\)", "[0-9a-f]*"),$/\1/p' tests/it/same_outputs.rs)
out="$(mktemp -d)"
for s in $specs; do
  d="$out/$s"
  mkdir -p "$d"
  set +e
  NO_COLOR=1 SOURCE_DATE_EPOCH=0 "$bin" check "specs/$s.yaml" --json "$d/results.json" \
    --report "$d/review" >"$d/stdout" 2>/dev/null
  echo "exit $?" >>"$d/stdout"
  set -e
  find "$d" -type f \( -name stdout -o -name '*.html' \) -print0 |
    xargs -0 sed -i -E -e "s#$d/##g" -e 's/in [0-9]+\.[0-9]+ s\b/in <time> s/g' \
      -e 's/>[0-9]+(\.[0-9]+)? m?s</><time></g'
  echo "$s $(cd "$d" && find . -type f | LC_ALL=C sort | xargs sha256sum | sha256sum | cut -d' ' -f1)"
done
rm -rf "$out"

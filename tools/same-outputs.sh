#!/usr/bin/env bash
# Byte-identity of every shipped spec's outputs between two builds of cycloid, the check a
# refactor is held to (issue 40): `check SPEC --json --report` for each spec under specs/
# (requirements files aside), terminal text, results JSON and every file of the review,
# compared file by file. Wall-clock figures ("in 15.44 s", the accuracy ladder's "0.6 ms"
# cells) and the output directory's path are the only parts masked.
#
#   tools/same-outputs.sh BIN_BEFORE BIN_AFTER [OUT_DIR]
#
# e.g. build main, copy target/release/cycloid to /tmp/before, build the change, then
# `tools/same-outputs.sh /tmp/before target/release/cycloid`. Exit 0: identical; 1: the
# differing files are listed (diff them under OUT_DIR). Takes a few minutes (the paper's
# studies and the crown study dominate). BIN_BEFORE may be the `before` directory of an
# earlier run (OUT_DIR/before): its recorded outputs are then compared, not run again.
set -euo pipefail
cd "$(dirname "$0")/.."
before="$(realpath "$1")" after="$(realpath "$2")" out="${3:-$(mktemp -d)}"
record() {
  local bin="$1" dir="$2"
  mkdir -p "$dir"
  for spec in specs/*.yaml specs/hard/*.yaml; do
    case "$spec" in *requirements*) continue ;; esac
    local name
    name="$(echo "${spec%.yaml}" | tr / _)"
    set +e
    NO_COLOR=1 "$bin" check "$spec" --json "$dir/$name.json" --report "$dir/$name-review" \
      >"$dir/$name.txt" 2>"$dir/$name.err"
    echo "exit $?" >>"$dir/$name.txt"
    set -e
  done
  # Mask what no two runs share: the directory written to and the wall-clock times.
  find "$dir" -type f \( -name '*.txt' -o -name '*.err' -o -name '*.html' \) -print0 |
    xargs -0 sed -i -E -e "s#$dir/##g" -e 's/in [0-9]+\.[0-9]+ s\b/in <time> s/g' \
      -e 's/>[0-9]+(\.[0-9]+)? m?s</><time></g'
}
if [ -d "$before" ]; then
  # The recorded outputs name their own directory, masked when recorded.
  if [ "$before" != "$(realpath -m "$out/before")" ]; then
    rm -rf "$out/before" && mkdir -p "$out" && cp -a "$before" "$out/before"
  fi
  rm -rf "$out/after"
else
  record "$before" "$out/before"
fi
record "$after" "$out/after"
if diff -rq "$out/before" "$out/after"; then
  echo "identical: every shipped spec's terminal text, JSON and review ($out)"
else
  echo "differ (above); the outputs are under $out" >&2
  exit 1
fi

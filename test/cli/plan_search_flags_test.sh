#!/usr/bin/env bash
# amha plan runs the lattice's default search unless told otherwise: its switches keep the
# preset's value when absent (a CLI11 flag bound to an optional once read false when absent,
# so the default ran without publishing within iterations), and the JSON says what ran.
# Usage: plan_search_flags_test.sh AMHA MAP
set -u
amha=$1
map=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
# Prints the run's search settings "publish_within_iterations proof_anchor_only".
settings() {
  "$amha" plan --map "$map" --radius 0.2 --turning-radius 0.5 --start 17,55,0 --goal 26,6,1.57 \
    --time-limit 20 --json "$dir/run.json" "$@" >/dev/null || return 1
  python3 -c 'import json, sys
s = json.load(open(sys.argv[1]))["runs"][0]["search"]
print(s["publish_within_iterations"], s["proof_anchor_only"])' "$dir/run.json"
}
expect() {
  local want=$1
  shift
  local got
  got=$(settings "$@")
  if [ "$got" != "$want" ]; then
    echo "FAIL: amha plan $* ran with publish_within_iterations proof_anchor_only = '$got', expected '$want'"
    fail=1
  else
    echo "ok: $* -> $got"
  fi
}
expect "True True"
expect "False True" --publish-within=false
expect "True False" --proof-anchor-only=false
expect "True True" --publish-within --proof-anchor-only
exit $fail

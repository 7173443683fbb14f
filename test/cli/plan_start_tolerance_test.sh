#!/usr/bin/env bash
# A start on a wall of the bundled map: refused (exit 5) without a start tolerance; with one the
# path leaves the wall first and says how, and the JSON marks the escape; a tolerance too small
# to reach a free pose is refused again, naming it.
# Usage: plan_start_tolerance_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
args=(plan --map "$1" --radius 0.2 --turning-radius 0.5 --start 24.45,6.45,1.57 --goal 17,55,0 --algorithm wastar --time-limit 5)
"$amha" "${args[@]}" >/dev/null 2>&1
[ $? -eq 5 ] || exit 1
json=$(mktemp)
out=$("$amha" "${args[@]}" --start-tolerance 0.6 --json "$json" 2>&1)
rc=$?
echo "$out"
[ $rc -eq 0 ] && grep -q 'the path leaves it by' <<<"$out" && grep -q '"start_escaped": *true' "$json" || exit 1
rm -f "$json"
out=$("$amha" "${args[@]}" --start-tolerance 0.05 2>&1)
rc=$?
echo "$out"
[ $rc -eq 5 ] && grep -q 'within the start tolerance of 0.050 m' <<<"$out"

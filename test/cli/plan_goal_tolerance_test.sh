#!/usr/bin/env bash
# A goal on a wall of the bundled map: refused (exit 6) without a goal tolerance, replaced by a
# reachable free pose with one.
# Usage: plan_goal_tolerance_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
args=(plan --map "$1" --radius 0.2 --turning-radius 0.5 --start 17,55,0 --goal 24.45,6.45,1.57 --algorithm wastar --time-limit 5)
"$amha" "${args[@]}" >/dev/null 2>&1
[ $? -eq 6 ] || exit 1
out=$("$amha" "${args[@]}" --goal-tolerance 0.6 2>&1)
rc=$?
echo "$out"
[ $rc -eq 0 ] && grep -q 'planning to the nearest reachable collision-free pose instead' <<<"$out"

#!/usr/bin/env bash
# Contradicting flags are refused with a usage error (exit code 2), not silently resolved.
# Usage: plan_turn_flags_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
out=$("$amha" plan --map x.pgm --start 0,0,0 --goal 1,1,0 --turn-term --no-turn-term 2>&1)
rc=$?
echo "$out"
[ $rc -eq 2 ] && grep -q excludes <<<"$out"

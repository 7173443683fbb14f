#!/usr/bin/env bash
# The replanning benchmark on the bundled map: the repaired chain's grids must be repaired
# after every update, and both chains must find the same first solutions (else exit 1).
# Usage: bench_replan_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
out=$("$amha" bench replan --map "$1" --radius 0.2 --turning-radius 0.5 --start 17,55,0 --goal 26,6,1.57 --updates 4 --window 60 2>&1)
rc=$?
echo "$out"
[ $rc -eq 0 ] && grep -q 'not repaired: 0; unsolved: 0; first solutions that differ: 0' <<<"$out"

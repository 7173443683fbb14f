#!/usr/bin/env bash
# The same seed prints the same pairs, another seed others; every pair is at least
# --min-distance apart (validity and connectivity: amha_bench_inputs_tests).
# Usage: bench_queries_seeded_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
m="$1"
q() { "$amha" bench queries --map "$m" --radius 0.2 --count 8 --min-distance 15 --seed $1; }
a=$(q 1) && b=$(q 1) && c=$(q 2) || exit 1
echo "$a"
[ "$a" = "$b" ] && [ "$a" != "$c" ] && [ $(wc -l <<<"$a") -eq 8 ] && awk -F'[, ]' '{ d = sqrt(($4 - $1)^2 + ($5 - $2)^2); if (d < 15) { print "too close: " $0; bad = 1 } } END { exit bad }' <<<"$a"

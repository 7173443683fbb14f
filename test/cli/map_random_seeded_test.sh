#!/usr/bin/env bash
# The same seed writes the same files; another seed another map; the map loads as map_server's.
# Usage: map_random_seeded_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
d=$(mktemp -d) && for s in a:3 b:3 c:4
do "$amha" map random --width 300 --height 200 --obstacles 0.15 --seed ${s#*:} --out $d/${s%:*} >/dev/null || exit 1
done
cmp $d/a.pgm $d/b.pgm && cmp $d/a.yaml <(sed s/b.pgm/a.pgm/ $d/b.yaml) && ! cmp -s $d/a.pgm $d/c.pgm && "$amha" bench queries --map $d/a.yaml --radius 0.2 --count 3 >/dev/null

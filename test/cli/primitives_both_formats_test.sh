#!/usr/bin/env bash
# One set through both formats from the command line: generated -> .json -> .mprim -> read,
# with the same primitives per heading at every step.
# Usage: primitives_both_formats_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
d=$(mktemp -d) && a=$("$amha" primitives --motion-model ackermann --out $d/a.json | grep 'per heading') && b=$("$amha" primitives --in $d/a.json --out $d/a.mprim | grep 'per heading') && c=$("$amha" primitives --in $d/a.mprim | grep 'per heading') && echo "$a" && [ -n "$a" ] && [ "$a" = "$b" ] && [ "$a" = "$c" ]

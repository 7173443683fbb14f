#!/usr/bin/env bash
# `amha plan` with a Nav2 file of the map's resolution plans; of another resolution it is
# refused with exit code 4 and the file's error; bad generator options are usage errors.
# Usage: plan_nav2_file_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
args=(plan --map "$1" --radius 0.2 --start 17,55,0 --goal 26,6,1.57 --algorithm wastar --time-limit 10)
"$amha" "${args[@]}" --mprim "$2" >/dev/null || exit 1
d=$(mktemp -d)
"$amha" primitives --resolution 0.05 --out $d/fine.json --quiet
out=$("$amha" "${args[@]}" --mprim $d/fine.json 2>&1)
rc=$?
echo "$out"
[ $rc -eq 4 ] && grep -q "does not match the map's resolution 0.1" <<<"$out" || exit 1
"$amha" "${args[@]}" --motion-model car >/dev/null 2>&1
[ $? -eq 2 ] || exit 1
"$amha" "${args[@]}" --reverse --reverse-penalty nan >/dev/null 2>&1
[ $? -eq 2 ] || exit 1
"$amha" "${args[@]}" --mprim "$2" --motion-model ackermann >/dev/null 2>&1
[ $? -eq 2 ]

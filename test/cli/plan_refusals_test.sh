#!/usr/bin/env bash
# `amha plan` and `amha tiles` refuse what they cannot honour, quickly and with a message that
# names the option (issue 22, items 1-5): values given are used or refused, never replaced by a
# default; weights outside [1, 1e6]; coarse blocks beyond 1024; turning radii far below a cell;
# robots wider than the map or with sweeps of millions of cells; and the time budget holds
# while the planner is set up. Usage: plan_refusals_test.sh path/to/amha path/to/map.yaml
# path/to/nav2.json (a Nav2 lattice file of the map's resolution).
set -uo pipefail
amha=$1
map=$2
nav2=$3
query=(--start 17,55,0 --goal 26,6,1.57)
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# refused EXPECTED_TEXT ARGS...: exit code 2 within 10 s, no solution, the text in the output.
refused() {
  local text=$1; shift
  local out rc
  out=$(timeout 10 "$amha" "$@" 2>&1); rc=$?
  if [ $rc -ne 2 ]; then fail "exit $rc (want 2) for: $*"$'\n'"$out"; return; fi
  grep -q "^solution" <<<"$out" && fail "a solution for: $*"
  grep -qF -- "$text" <<<"$out" || fail "no '$text' in the message for: $*"$'\n'"$out"
}
plan=(plan --map "$map" "${query[@]}" --algorithm wastar --time-limit 5)

# Item 5: every invalid number is refused, naming its option.
for v in -0.2 nan -inf inf; do refused "--radius $v" "${plan[@]}" --radius "$v"; done
for v in 0 -0.5 nan -inf inf; do refused "--turning-radius $v" "${plan[@]}" --turning-radius "$v"; done
for v in 0 -1 nan inf; do refused "--nominal-speed $v" "${plan[@]}" --nominal-speed "$v"; done
for v in -1 nan inf; do refused "--turn-time-45 $v" "${plan[@]}" --turn-time-45 "$v"; done
for v in -1 nan inf; do refused "--cost-penalty $v" "${plan[@]}" --cost-penalty "$v"; done
for v in -1 4; do refused "--inadmissible $v" "${plan[@]}" --inadmissible "$v"; done
refused "--footprint is empty" "${plan[@]}" --footprint ""
refused "--footprint is empty" "${plan[@]}" --footprint " ; "
refused "--mprim is empty" "${plan[@]}" --mprim ""
refused "--resolution and --upscale apply to Moving AI maps" "${plan[@]}" --resolution 0.05
refused "--mprim cannot be combined" "${plan[@]}" --mprim x.mprim --headings 32
refused "--mprim cannot be combined" "${plan[@]}" --mprim x.mprim --turning-radius 0.5
refused "--mprim cannot be combined" "${plan[@]}" --mprim x.mprim --no-turn-in-place
refused "--reverse and --reverse-penalty apply to generated primitives and Nav2 files" "${plan[@]}" --mprim x.mprim --reverse
for v in -1 nan inf; do refused "--kinematic-radius $v" "${plan[@]}" --kinematic-radius "$v"; done
for v in 0 101; do refused "--lethal-threshold $v is not in 1..100" "${plan[@]}" --lethal-threshold "$v"; done
refused "--coarse-block applies to --anchor coarse" "${plan[@]}" --anchor grid --coarse-block 4

# Item 1: weights and decrements outside their range (NaN and infinities too), in plan and tiles.
for v in nan inf 0.5 1e15 1e308; do
  for o in --w1 --w2 --eps --stall-w1 --stall-mid-w1; do refused "$o: a weight must be a finite number in [1, 1e+06]" "${plan[@]}" "$o" "$v"; done
  refused "--weight: a weight" tiles --size 3 --random 1 --weight "$v"
  refused "--w1: a weight" tiles --size 3 --random 1 --w1 "$v"
  refused "--eps: a weight" tiles --size 3 --random 1 --eps "$v"
done
for v in nan inf -1 2e6; do
  for o in --dw1 --dw2; do refused "$o: a decrement must be a finite number in [0, 1e+06]" "${plan[@]}" "$o" "$v"; done
  refused "--deps: a decrement" tiles --size 3 --random 1 --deps "$v"
done

# Item 3: coarse blocks outside 0..1024 are refused at once (they hung: k^2 work per action).
for v in -1 1025 100000 2147483647; do refused "--coarse-block $v" "${plan[@]}" --coarse-block "$v"; done

# Item 4: a turning radius far below a cell (it ended in an OpenCV assertion).
refused "is below a hundredth of a cell" "${plan[@]}" --turning-radius 1e-9

# Item 2: robots wider than the map, or sweeping millions of cells, are refused up front
# (--radius 100 ran 240 s into 5.4 GB; --radius 30 took 21 s).
for r in 30 100; do refused "is wider than the map" "${plan[@]}" --radius "$r"; done
refused "would touch up to" "${plan[@]}" --radius 20

# Item 2: the time budget covers the planner's setup (--radius 8 takes ~5 s to set up here).
start=$(date +%s%N)
out=$(timeout 20 "$amha" plan --map "$map" "${query[@]}" --algorithm wastar --time-limit 0.3 --radius 8 2>&1); rc=$?
took_ms=$(( ($(date +%s%N) - start) / 1000000 ))
[ $rc -eq 7 ] || fail "--radius 8 --time-limit 0.3: exit $rc (want 7)"$'\n'"$out"
grep -q "status time_limit" <<<"$out" || fail "--radius 8 --time-limit 0.3: no time_limit status"$'\n'"$out"
[ $took_ms -lt 3000 ] || fail "--radius 8 --time-limit 0.3 took $took_ms ms"

# Values inside the ranges still plan.
# A Nav2 file has no backward motions of its own: --reverse adds them.
for a in "--w1 1000000" "--coarse-block 8" "--turning-radius 0.001" "--radius 0" "--footprint 0.2,0.1;-0.2,0.1;-0.2,-0.1;0.2,-0.1" \
         "--mprim $nav2 --reverse"; do
  # shellcheck disable=SC2086
  out=$(timeout 60 "$amha" "${plan[@]}" $a 2>&1) || fail "exit $? for valid $a"$'\n'"$out"
  grep -q "^solution 1" <<<"$out" || fail "no solution for valid $a"
done

[ $failures -eq 0 ] && echo "all refusals as expected"
[ $failures -eq 0 ]

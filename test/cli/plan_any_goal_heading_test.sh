#!/usr/bin/env bash
# A free goal heading on the bundled map: A* proves a cheaper optimum than with the goal's own
# heading (72719 against 73316 cost units, measured) and says where it ended.
# Usage: plan_any_goal_heading_test.sh AMHA [ARGS...] (ctest passes the binary and the inputs)
amha=$1
shift
args=(plan --map "$1" --radius 0.2 --turning-radius 0.5 --start 17,55,0 --goal 26,6,1.57 --algorithm astar --time-limit 20)
fixed=$("$amha" "${args[@]}" | grep -o 'cost=[0-9]*' | tail -1 | cut -d= -f2)
free=$("$amha" "${args[@]}" --any-goal-heading | grep -o 'cost=[0-9]*' | tail -1 | cut -d= -f2)
echo "fixed $fixed free $free"
[ -n "$free" ] && [ -n "$fixed" ] && [ "$free" -lt "$fixed" ]

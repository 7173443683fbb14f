#!/usr/bin/env bash
# `amha tiles` end to end: a run of every algorithm, the JSON it writes, instance files that
# round-trip, and the exit codes for bad input. Usage: tiles_cli_test.sh path/to/amha
set -euo pipefail
amha=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$amha" tiles --size 4 --random 3 --seed 2 --algorithms amha,mha,ara,ana,wastar \
  --time-limit 1 --clock cpu --quiet --json "$tmp/out.json" --write-instances "$tmp/inst.txt" \
  --plot "$tmp/plot.png" --markdown "$tmp/table.md" > "$tmp/stdout" || fail "run failed"
for a in amha mha ara ana wastar; do
  grep -q "^$a " "$tmp/stdout" || fail "no table row for $a"
  grep -q "^| $a |" "$tmp/table.md" || fail "no markdown row for $a"
done
[ -s "$tmp/plot.png" ] || fail "no plot"

/usr/bin/python3 - "$tmp/out.json" <<'PY' || fail "JSON check"
import json, sys
d = json.load(open(sys.argv[1]))
runs = d["runs"]
assert len(runs) == 15, len(runs)
assert len(d["heuristics"]["weights"]) == 4 and d["heuristics"]["seed"] == 1
assert [i["id"] for i in d["instances"]] == ["rand4-s2-0", "rand4-s2-1", "rand4-s2-2"]
assert d["settings"]["clock"] == "cpu" and d["settings"]["w1"] == 5 and d["settings"]["ara_eps"] == 25
for r in runs:
    for k in ("instance", "algorithm", "status", "optimal_cost", "expansions", "peak_states",
              "peak_memory_bytes", "elapsed_s", "cpu_s", "solutions"):
        assert k in r, k
    assert r["solutions"], r["algorithm"] + " found nothing on a 15-puzzle in 1 s"
    costs = [s["cost"] for s in r["solutions"]]
    assert costs == sorted(costs, reverse=True), costs
    for s in r["solutions"]:
        assert s["certified_bound"] >= 1 and "cpu_s" in s
        if s["bound"] is not None:
            assert s["certified_bound"] <= s["bound"] + 1e-9
PY

# The written instances read back to the same boards; A* proves them optimal (<= 0.6 s each).
"$amha" tiles --instances "$tmp/inst.txt" --algorithms astar --time-limit 10 --clock cpu --quiet \
  --json "$tmp/again.json" > /dev/null || fail "re-reading the written instances"
/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
assert [i['tiles'] for i in a['instances']] == [i['tiles'] for i in b['instances']]
for r in b['runs']:
    assert r['status'] == 'proven_optimal' and r['solutions'][-1]['bound'] == 1, r['status']
" "$tmp/out.json" "$tmp/again.json" || fail "instances differ after a round trip, or A* failed"

# Reused memory (the default) and fresh pages per run give the same searches: a run that read
# memory it did not write would differ (reused blocks hold old states, fresh pages zeros).
for mode in reuse fresh; do
  flag=(); [ "$mode" = fresh ] && flag=(--fresh-memory)
  "$amha" tiles --size 5 --random 4 --seed 3 --algorithms amha,ara,ana --max-expansions 30000 \
    --time-limit 30 --quiet "${flag[@]}" --json "$tmp/$mode.json" > /dev/null || fail "$mode run failed"
done
/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
assert a['settings']['fresh_memory'] is False and b['settings']['fresh_memory'] is True
key = lambda d: [(r['status'], r['expansions'], [(s['cost'], s['expansions']) for s in r['solutions']]) for r in d['runs']]
assert key(a) == key(b), 'searches differ between reused and fresh memory'
assert sum(len(r['solutions']) for r in a['runs']) > 0
" "$tmp/reuse.json" "$tmp/fresh.json" || fail "reused memory changed a search"

# The DTS schedule: recorded in the JSON, reproducible (same seed, same searches), and its
# solutions obey the same checks; A-MHA* still ends proven optimal on 8-puzzles.
for k in 1 2; do
  "$amha" tiles --size 3 --random 4 --seed 5 --algorithms amha,mha --schedule dts --quiet \
    --max-expansions 200000 --time-limit 30 --json "$tmp/dts$k.json" > /dev/null || fail "dts run failed"
done
/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
assert a['settings']['schedule'] == 'dts'
key = lambda d: [(r['status'], r['expansions'], [(s['cost'], s['expansions']) for s in r['solutions']]) for r in d['runs']]
assert key(a) == key(b), 'two DTS runs with the same seed differ'
for r in a['runs']:
    assert r['solutions'], r
    if r['algorithm'] == 'amha':
        assert r['status'] == 'proven_optimal', r['status']
" "$tmp/dts1.json" "$tmp/dts2.json" || fail "DTS runs"

expect() {  # expected exit code, arguments...
  local want=$1 got=0; shift
  "$amha" tiles "$@" --quiet > /dev/null 2> "$tmp/err" || got=$?
  [ "$got" = "$want" ] || fail "amha tiles $* exited $got, expected $want: $(cat "$tmp/err")"
}
echo "1 -1 -1 0 2 1 3 4 5 6 7 8" > "$tmp/unsolvable.txt"
expect 8 --instances "$tmp/unsolvable.txt"
grep -q "unsolvable.txt:1: instance '1' is unsolvable" "$tmp/err" || fail "message: $(cat "$tmp/err")"
expect 8 --instances "$tmp/missing.txt"
expect 8 --instances "$tmp/inst.txt" --size 5
expect 2 --random 3
expect 2 --size 4 --walk 30
expect 2 --size 4 --random 3 --algorithms amha,dijkstra
expect 2 --size 4 --random 3 --w1 0.5
expect 2 --size 10 --random 3
expect 2 --size 4 --random 3 --schedule fifo
expect 9 --size 3 --random 1 --time-limit 1 --json "$tmp/no/such/dir/out.json"
echo "tiles CLI: all checks passed"

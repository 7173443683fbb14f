#!/usr/bin/env bash
# `amha plan` on a costmap and with --smooth, end to end. A costmap saved in map_server's raw mode
# (pixels are costmap_2d's occupancy: 100 lethal, 99 inscribed, 1..98 graded, 255 unknown) with
# a door whose inflated cells are >= 65: read with map_server's threshold the door is shut (no
# path, exit 7); with --lethal-threshold 100, as the server reads a costmap, it is open. --smooth
# writes the smoothed path and the lattice path to the JSON, no costlier, same start and goal.
# With a second argument, the README's example: the bundled Willow Garage costmap
# (maps/willow_garage/willow-costmap-r025.yaml), no path with 65, a path with 100.
# Usage: plan_costmap_smooth_test.sh path/to/amha [path/to/willow-costmap-r025.yaml]
set -euo pipefail
amha=$1
example=${2:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# 100 x 60 cells of 5 cm; a wall at x = 50 with a door of 16 cells; costs fall off with the
# distance d (cells) to the wall as an inflation layer's do: 100 on it, 99 for d <= 2, then
# 98 - 4 (d - 3) down to 0.
/usr/bin/python3 - "$tmp" <<'PY'
import math, sys
w, h = 100, 60
wall = [(50, y) for y in range(h) if not 22 <= y < 38]
rows = []
for y in range(h):
    row = []
    for x in range(w):
        d = min(math.hypot(x - a, y - b) for a, b in wall)
        row.append(100 if d == 0 else 99 if d <= 2 else max(0, int(98 - 4 * (d - 3))))
    rows.append(row)
data = b"".join(bytes(rows[y]) for y in range(h - 1, -1, -1))  # the image's top row is the map's last
open(sys.argv[1] + "/costmap.pgm", "wb").write(b"P5\n%d %d\n255\n" % (w, h) + data)
open(sys.argv[1] + "/costmap.yaml", "w").write(
    "image: costmap.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: raw\n")
PY

args=(plan --map "$tmp/costmap.yaml" --radius 0.1 --turning-radius 0.3 --start 1.0,1.5,0 --goal 4.0,1.5,0
      --algorithm wastar --time-limit 10)
set +e
"$amha" "${args[@]}" > "$tmp/default.out" 2>&1
rc=$?
set -e
[ "$rc" -eq 7 ] || { cat "$tmp/default.out"; fail "with map_server's threshold the door should be shut (exit 7, got $rc)"; }

"$amha" "${args[@]}" --lethal-threshold 100 --smooth --json "$tmp/run.json" > "$tmp/costmap.out" 2>&1 ||
  { cat "$tmp/costmap.out"; fail "with --lethal-threshold 100 the door should be open"; }
grep -q "smoothed: cost=" "$tmp/costmap.out" || fail "no smoothed solution printed"
grep -q "^smoothed path: length" "$tmp/costmap.out" || fail "no smoothing summary"

/usr/bin/python3 - "$tmp/run.json" <<'PY' || fail "JSON check"
import json, math, sys
run = json.load(open(sys.argv[1]))["runs"][0]
path, lattice = run["path"], run["lattice_path"]
assert run["smoothed"] is True
assert path[0] == lattice[0] and path[-1] == lattice[-1], "start or goal changed"
assert run["smoothed_cost"] <= run["solutions"][-1]["cost"], "smoothed path costlier"
assert all(math.hypot(b[0] - a[0], b[1] - a[1]) <= 0.05 + 1e-9 for a, b in zip(path, path[1:])), "a jump"
# Through the door: every pose right of the wall passed x = 2.5 m between y = 1.1 and 1.9 m.
crossing = [p for a, p in zip(path, path[1:]) if a[0] < 2.525 <= p[0]]
assert crossing and all(1.1 <= p[1] <= 1.9 for p in crossing), crossing
PY

set +e
"$amha" plan --map /dev/null.cfg --start 0,0,0 --goal 1,1,0 --lethal-threshold 100 > "$tmp/cfg.out" 2>&1
rc=$?
"$amha" "${args[@]}" --lethal-threshold 101 > "$tmp/range.out" 2>&1
rc2=$?
set -e
[ "$rc" -eq 2 ] && grep -q "applies to map_server .yaml maps" "$tmp/cfg.out" || { cat "$tmp/cfg.out"; fail "a threshold for a .cfg map should be refused"; }
[ "$rc2" -eq 2 ] && grep -q "not in 1..100" "$tmp/range.out" || { cat "$tmp/range.out"; fail "threshold 101 should be refused"; }
if [ -n "$example" ]; then
  readme=(plan --map "$example" --radius 0.25 --turning-radius 0.5 --start 17,55,0 --goal 26,6,1.57 --time-limit 20)
  set +e
  "$amha" "${readme[@]}" > "$tmp/readme65.out" 2>&1
  rc=$?
  set -e
  [ "$rc" -eq 7 ] || { cat "$tmp/readme65.out"; fail "the README's costmap with threshold 65: expected no path (7), got $rc"; }
  "$amha" "${readme[@]}" --lethal-threshold 100 --smooth > "$tmp/readme100.out" 2>&1 ||
    { cat "$tmp/readme100.out"; fail "the README's costmap example found no path"; }
  grep -q "^smoothed path: length" "$tmp/readme100.out" || fail "the README's example printed no smoothed path"
fi
echo "PASS"

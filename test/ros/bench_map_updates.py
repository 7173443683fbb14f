#!/usr/bin/python3
"""How far the planning server's map falls behind a costmap that sends partial updates
(run by scripts/bench-map-updates, which builds the package and sources its devel space).

It starts a ROS master on a free loopback port, planner_node and map_publisher, on a large map:
the bundled Willow Garage map scaled up --upscale times per side at --resolution metres per cell
(default 6 x, 3396 x 3648 cells of 5 cm: a 170 m x 182 m costmap). For each rate in --rates it
sends --seconds worth of updates on /map_updates, as costmap_2d does: --window x --window cells
at random places, carrying the map's own values there (so the map does not change, but every
update is a real update the server must build a planner for). The round's last update then
closes (or, the next round, reopens) a 1.2 m square around a goal. From the moment it is sent,
the script asks ~plan for that goal until the answer shows it (INVALID_GOAL when closed, any
other status when open): that delay is the lag of the last update.

The node logs at DEBUG level, so each planner build is a line; the table gives, per rate, the
updates sent, the builds the node made for them and their median time, and the lag.
Prints a Markdown table; --json FILE writes the rows."""
import argparse
import json
import os
import random
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def read_pgm(path):
    data = open(path, "rb").read()
    fields, i = [], 0
    while len(fields) < 4:
        while data[i:i + 1].isspace():
            i += 1
        if data[i:i + 1] == b"#":
            while data[i:i + 1] != b"\n":
                i += 1
            continue
        j = i
        while not data[j:j + 1].isspace():
            j += 1
        fields.append(data[i:j])
        i = j
    if fields[0] != b"P5" or int(fields[3]) != 255:
        sys.exit("bench-map-updates: %s is not an 8-bit binary PGM" % path)
    w, h = int(fields[1]), int(fields[2])
    return w, h, data[i + 1:i + 1 + w * h]


def write_scaled_map(src_yaml, k, resolution, out_dir):
    """The source map's image scaled k times per side (nearest neighbour), as a map_server map."""
    src_dir = os.path.dirname(src_yaml)
    image = re.search(r"^image:\s*(\S+)", open(src_yaml).read(), re.M).group(1)
    w, h, pixels = read_pgm(os.path.join(src_dir, image))
    rows = []
    for y in range(h):
        row = bytes(b for b in pixels[y * w:(y + 1) * w] for _ in range(k))
        rows.extend([row] * k)
    pgm = os.path.join(out_dir, "scaled.pgm")
    with open(pgm, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (w * k, h * k))
        f.writelines(rows)
    yaml = os.path.join(out_dir, "scaled.yaml")
    with open(yaml, "w") as f:
        f.write("image: scaled.pgm\nresolution: %r\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n" % resolution)
    return yaml, w * k, h * k


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default=os.path.join(root, "maps/willow_garage/willow-2010-02-18-0.10.yaml"))
    ap.add_argument("--upscale", type=int, default=6)
    ap.add_argument("--resolution", type=float, default=0.05)
    ap.add_argument("--rates", default="1,2,5,10", help="update rates in Hz, comma-separated (\"\" for none)")
    ap.add_argument("--seconds", type=float, default=10.0, help="of updates per rate")
    ap.add_argument("--window", type=int, default=100, help="cells per side of an update")
    ap.add_argument("--start-cell", default="170,550", help="probe start, in cells of the source map")
    ap.add_argument("--goal-cell", default="260,60", help="probe goal, in cells of the source map")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json")
    ap.add_argument("--replan", type=int, default=0, metavar="N",
                    help="then N times: an update of the map's own values, and a plan to the probe goal "
                         "(reports where its heuristic grids came from and the first solution's time)")
    ap.add_argument("--repair-heuristics", choices=["true", "false"], default="true",
                    help="the node's ~repair_heuristics (default true)")
    ap.add_argument("--write-map", metavar="DIR",
                    help="only write the scaled map (DIR/scaled.yaml and .pgm) and exit, e.g. for amha bench replan")
    args = ap.parse_args()
    if args.upscale < 1 or args.resolution <= 0 or args.window < 1 or args.seconds <= 0:
        sys.exit("bench-map-updates: --upscale, --resolution, --window, --seconds must be positive")
    if args.write_map:
        os.makedirs(args.write_map, exist_ok=True)
        yaml, width, height = write_scaled_map(args.map, args.upscale, args.resolution, args.write_map)
        print("%s: %d x %d cells of %.3f m" % (yaml, width, height, args.resolution))
        return
    rates = [float(r) for r in args.rates.split(",") if r.strip()]
    random.seed(args.seed)

    home = tempfile.mkdtemp(prefix="amha_bench_map_updates_")
    yaml, width, height = write_scaled_map(args.map, args.upscale, args.resolution, home)
    print("map: %s scaled %d x: %d x %d cells of %.3f m (%.1f M cells)"
          % (args.map, args.upscale, width, height, args.resolution, width * height / 1e6), flush=True)
    # Every planner build is a DEBUG line of the node's (INFO for full maps).
    with open(os.path.join(home, "rosconsole.config"), "w") as f:
        f.write("log4j.logger.ros=INFO\nlog4j.logger.ros.amha_planner=DEBUG\n")
    port = free_port()
    env = dict(os.environ, ROS_IP="127.0.0.1", ROS_HOSTNAME="127.0.0.1",
               ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_HOME=home,
               ROSCONSOLE_CONFIG_FILE=os.path.join(home, "rosconsole.config"))
    os.environ.update(env)
    lib = os.path.join(os.environ["AMHA_BUILD_DIR"], "devel/lib/amha_planner")
    node_log = os.path.join(home, "planner_node.log")
    procs = []
    try:
        procs.append(subprocess.Popen(["roscore", "-p", str(port)], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        import rosgraph
        deadline = time.time() + 30
        while not rosgraph.is_master_online():
            if time.time() > deadline:
                sys.exit("bench-map-updates: the ROS master did not start")
            time.sleep(0.2)
        procs.append(subprocess.Popen(
            # Line-buffered, so that the log counts every build up to now.
            ["stdbuf", "-oL", "-eL", os.path.join(lib, "planner_node"), "__name:=amha_planner",
             "_max_map_cells:=%d" % (width * height), "_robot_radius:=0.2",
             "_repair_heuristics:=" + args.repair_heuristics],
            env=env, stdout=open(node_log, "w"), stderr=subprocess.STDOUT))
        procs.append(subprocess.Popen([os.path.join(lib, "map_publisher"), "_yaml:=" + yaml],
                                      env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        rows, replan = measure(args, rates, width, height, node_log)
    finally:
        for p in reversed(procs):
            p.send_signal(2)
        for p in reversed(procs):
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
    print()
    print("| rate (Hz) | updates sent | planner builds | median build (s) | lag of the last update (s) |")
    print("|---:|---:|---:|---:|---:|")
    for r in rows:
        print("| %g | %d | %d | %.2f | %.2f |" % (r["rate_hz"], r["updates"], r["builds"],
                                              r["median_build_s"], r["lag_s"]))
    if replan:
        print("\nreplanning to the probe goal after each of %d updates (~repair_heuristics %s): "
              "heuristic grids %s, median %.4f s; first solution after a median %.4f s (%d unsolved)"
              % (args.replan, args.repair_heuristics, replan["grids"], replan["median_heuristic_s"],
                 replan["median_first_s"], replan["unsolved"]))
    print("\nnode log: %s" % node_log)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"map": args.map, "upscale": args.upscale, "resolution": args.resolution,
                       "width": width, "height": height, "window": args.window,
                       "seconds": args.seconds, "seed": args.seed, "rows": rows, "replan": replan},
                      f, indent=1)


def builds_in(log_path, start_line):
    """The planner builds logged after line start_line: their seconds, and the new line count."""
    lines = open(log_path, errors="replace").read().splitlines()
    times = [float(m.group(1)) for m in
             (re.search(r"accepted; lattice ready in ([0-9.]+) s", l) for l in lines[start_line:]) if m]
    return times, len(lines)


def measure(args, rates, width, height, node_log):
    import rospy
    from map_msgs.msg import OccupancyGridUpdate
    from nav_msgs.msg import OccupancyGrid
    from amha_planner.srv import Plan, PlanRequest, PlanResponse

    rospy.init_node("bench_map_updates", anonymous=True, disable_signals=True)
    pub = rospy.Publisher("/map_updates", OccupancyGridUpdate, queue_size=1000)
    plan = rospy.ServiceProxy("/amha_planner/plan", Plan)
    plan.wait_for_service(60)
    grid = rospy.wait_for_message("/map", OccupancyGrid, timeout=120)
    data = grid.data
    gx, gy = (int(v) * args.upscale for v in args.goal_cell.split(","))
    half = int(round(0.6 / args.resolution))
    goal = (gx + 0.5) * args.resolution, (gy + 0.5) * args.resolution
    sx, sy = (int(v) * args.upscale for v in args.start_cell.split(","))
    start = (sx + 0.5) * args.resolution, (sy + 0.5) * args.resolution

    def probe():
        r = PlanRequest()
        for p, (x, y) in ((r.start, start), (r.goal, goal)):
            p.header.frame_id = "map"
            p.pose.position.x, p.pose.position.y = x, y
            p.pose.orientation.w = 1.0
        r.time_budget = 0.001  # only the map matters: a closed goal is INVALID_GOAL at once
        return plan(r).status

    def update(x, y, w, h, values=None):
        u = OccupancyGridUpdate()
        u.header.frame_id = "map"
        u.header.stamp = rospy.Time.now()
        u.x, u.y, u.width, u.height = x, y, w, h
        u.data = values if values is not None else \
            [v for row in range(y, y + h) for v in data[row * width + x:row * width + x + w]]
        return u

    deadline = time.time() + 120
    while probe() == PlanResponse.NO_MAP:
        if time.time() > deadline:
            sys.exit("bench-map-updates: the planner never accepted the map")
        time.sleep(0.2)
    status = probe()
    if status in (PlanResponse.INVALID_START, PlanResponse.INVALID_GOAL, PlanResponse.OUT_OF_MAP):
        sys.exit("bench-map-updates: the probe's start or goal is not free on the map (status %d); "
                 "pick another --start-cell / --goal-cell" % status)
    while pub.get_num_connections() == 0:
        time.sleep(0.05)
    _, seen = builds_in(node_log, 0)
    rows = []
    for i, rate in enumerate(rates):
        closing = i % 2 == 0
        n = max(1, int(round(rate * args.seconds)))
        period = 1.0 / rate
        w = min(args.window, width)
        h = min(args.window, height)
        t = time.time()
        for _ in range(n - 1):
            pub.publish(update(random.randint(0, width - w), random.randint(0, height - h), w, h))
            t += period
            time.sleep(max(0.0, t - time.time()))
        x0, y0, side = gx - half, gy - half, 2 * half
        pub.publish(update(x0, y0, side, side, [100] * (side * side)) if closing
                    else update(x0, y0, side, side))
        sent = time.time()
        while (probe() == PlanResponse.INVALID_GOAL) != closing:
            if time.time() - sent > 600:
                sys.exit("bench-map-updates: the last update never reached the planner")
            time.sleep(0.01)
        lag = time.time() - sent
        time.sleep(1.0)  # let the log catch up
        times, seen = builds_in(node_log, seen)
        row = {"rate_hz": rate, "updates": n, "builds": len(times),
               "median_build_s": statistics.median(times) if times else 0.0, "lag_s": lag}
        rows.append(row)
        print("rate %g Hz: %d updates, %d builds (median %.2f s), last update seen after %.2f s"
              % (rate, n, len(times), row["median_build_s"], lag), flush=True)
    replan = None
    if args.replan > 0:
        replan = replan_after_updates(args, pub, update, probe, plan, (gx - half, gy - half, 2 * half), start,
                                      goal, (sx, sy), (gx, gy), width, height, node_log)
    return rows, replan


def replan_after_updates(args, pub, update, probe, plan, goal_area, start, goal, start_cell, goal_cell,
                         width, height, node_log):
    """A robot driving to one goal through a costmap: after each update, a plan to the same goal."""
    from amha_planner.srv import PlanRequest, PlanResponse
    x0, y0, side = goal_area
    pub.publish(update(x0, y0, side, side))  # the goal's area as in the map (open)
    while probe() == PlanResponse.INVALID_GOAL:
        time.sleep(0.01)
    w, h = min(args.window, width), min(args.window, height)
    keep = int(round(2.0 / args.resolution))  # windows stay 2 m clear of the start and goal

    def clear_of(x, y):
        return all(not (x - keep <= cx < x + w + keep and y - keep <= cy < y + h + keep)
                   for cx, cy in (start_cell, goal_cell))

    r = PlanRequest()
    for p, (x, y) in ((r.start, start), (r.goal, goal)):
        p.header.frame_id = "map"
        p.pose.position.x, p.pose.position.y = x, y
        p.pose.orientation.w = 1.0
    r.time_budget = 1.0
    plan(r)  # the goal's grids, computed once
    _, seen = builds_in(node_log, 0)
    firsts, unsolved = [], 0
    for _ in range(args.replan):
        while True:
            x, y = random.randint(0, width - w), random.randint(0, height - h)
            if clear_of(x, y):
                break
        pub.publish(update(x, y, w, h))
        time.sleep(0.5)  # built by then (0.03-0.05 s)
        res = plan(r)
        if res.solutions:
            firsts.append(res.solutions[0].elapsed)
        else:
            unsolved += 1
    time.sleep(1.0)  # let the log catch up
    lines = open(node_log, errors="replace").read().splitlines()[seen:]
    grids = [(m.group(1), float(m.group(2))) for m in
             (re.search(r"heuristic grids (\w+) in ([0-9.]+) s", l) for l in lines) if m]
    counts = {}
    for source, _ in grids:
        counts[source] = counts.get(source, 0) + 1
    return {"updates": args.replan, "repair_heuristics": args.repair_heuristics, "grids": counts,
            "median_heuristic_s": statistics.median(t for _, t in grids) if grids else 0.0,
            "median_first_s": statistics.median(firsts) if firsts else 0.0, "unsolved": unsolved}


if __name__ == "__main__":
    main()

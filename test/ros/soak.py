#!/usr/bin/python3
"""Soak test of the planning server (run by scripts/soak, which starts the master and the nodelet).

For a bounded time (and at most --max-requests requests) it fires random requests, valid and
invalid, at ~plan, ~plan_anytime (with random cancels) and ~make_plan from several threads,
while publishing random maps and partial map updates on /map_updates (good and malformed; the
server applies good updates incrementally). Every answer must be a valid path
within its bounds or a clean error status; the node must stay alive; its memory must not grow.

A path is checked independently of the planner: in the global frame, starting at the start and
ending at the goal (within a cell and half a heading bin), no jump longer than 1.5 cells, the
robot's circle touching no obstacle, unknown or off-map cell on one of the maps that were in use
while the request ran (a path leaving a start in collision: before its escape_end, none but those
under the robot at the start), cost >= straight-line distance; along the solutions costs, bounds and
certified bounds never increase and 1 <= certified <= bound.

Writes a JSON summary (--json) and prints one; exits 1 on any failure."""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import random
import struct
import sys
import threading
import time
import traceback
import xmlrpc.client

import actionlib
import rosgraph
import rospy
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid
from nav_msgs.srv import GetPlan, GetPlanRequest

from amha_planner.msg import PlanAnytimeAction, PlanAnytimeActionResult, PlanAnytimeGoal
from amha_planner.srv import Plan, PlanRequest, PlanResponse

NS = "/amha_planner"
MANAGER = "/amha_planner_manager"
ROBOT_RADIUS = 0.2         # the planner's robot_radius (config/planner.yaml)
LETHAL = 65                # lethal_threshold; unknown (-1) is an obstacle
BASE_LINK = (17.0, 55.0, -math.pi / 2)  # soak.launch's map -> base_link
ODOM = (2.0, 3.0, 0.3)                  # soak.launch's map -> odom
HALF_BIN = math.atan(0.5) / 2 + 1e-3    # 16 generated headings
S = PlanResponse
STATUS_NAMES = {getattr(S, n): n for n in dir(S) if n.isupper() and isinstance(getattr(S, n), int)}
CLEAN = set(STATUS_NAMES) - {S.INTERNAL_ERROR}


def yaw_quaternion(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def pose_stamped(frame, x, y, q):
    p = PoseStamped()
    p.header.frame_id = frame
    p.pose.position.x, p.pose.position.y = x, y
    p.pose.orientation.x, p.pose.orientation.y, p.pose.orientation.z, p.pose.orientation.w = q
    return p


def angle_diff(a, b):
    return abs(math.remainder(a - b, 2 * math.pi))


class Grid:
    """An OccupancyGrid the soak test published (or captured), for the independent checks."""

    def __init__(self, msg, name):
        self.msg, self.name = msg, name
        self.w, self.h = msg.info.width, msg.info.height
        self.res = msg.info.resolution
        self.ox, self.oy = msg.info.origin.position.x, msg.info.origin.position.y
        self.blocked = bytes(1 if (v >= LETHAL or v < 0) else 0 for v in msg.data)
        self.clear_cells = {}  # (i, j) -> True if a circle anywhere in the cell is surely free

    def is_blocked(self, i, j):
        return i < 0 or j < 0 or i >= self.w or j >= self.h or self.blocked[j * self.w + i]

    def circle_free(self, x, y, r, spared=None):
        """No blocked cell square meets the disc of radius r about (x, y) (map frame, yaw 0),
        except cell squares within spared = (x, y, radius) of that point, if given."""
        gx, gy = (x - self.ox) / self.res, (y - self.oy) / self.res
        rc = r / self.res - 1e-6
        # Fast path (memoised per cell): every cell square within rc of this cell's square is
        # free, so the disc is free wherever in the cell its centre is.
        ci, cj = int(math.floor(gx)), int(math.floor(gy))
        key = (ci, cj, r)
        clear = self.clear_cells.get(key)
        if clear is None:
            reach = int(math.ceil(rc)) + 1
            clear = True
            for dj in range(-reach, reach + 1):
                for di in range(-reach, reach + 1):
                    ex, ey = max(abs(di) - 1, 0), max(abs(dj) - 1, 0)
                    if ex * ex + ey * ey < rc * rc and self.is_blocked(ci + di, cj + dj):
                        clear = False
                        break
                if not clear:
                    break
            self.clear_cells[key] = clear
        if clear:
            return True
        # Exact test against the nearby blocked squares.
        if spared is not None:
            sx, sy, sr = (spared[0] - self.ox) / self.res, (spared[1] - self.oy) / self.res, spared[2] / self.res
        for j in range(int(math.floor(gy - rc)), int(math.floor(gy + rc)) + 1):
            for i in range(int(math.floor(gx - rc)), int(math.floor(gx + rc)) + 1):
                if not self.is_blocked(i, j):
                    continue
                dx = max(i - gx, 0.0, gx - (i + 1))
                dy = max(j - gy, 0.0, gy - (j + 1))
                if dx * dx + dy * dy < rc * rc:
                    if spared is not None:
                        ex, ey = max(i - sx, 0.0, sx - (i + 1)), max(j - sy, 0.0, sy - (j + 1))
                        if ex * ex + ey * ey <= sr * sr:
                            continue  # under the robot at the start: an escape may cross it
                    return False
        return True

    def random_touching_pose(self, rng):
        """A pose whose cell is free but whose robot circle touches an obstacle, or None."""
        for _ in range(4000):
            i, j = rng.randrange(self.w), rng.randrange(self.h)
            x, y = self.ox + (i + 0.5) * self.res, self.oy + (j + 0.5) * self.res
            if not self.is_blocked(i, j) and not self.circle_free(x, y, ROBOT_RADIUS):
                return x, y, rng.uniform(-math.pi, math.pi)
        return None

    def random_free_pose(self, rng):
        for _ in range(2000):
            i, j = rng.randrange(self.w), rng.randrange(self.h)
            x, y = self.ox + (i + 0.5) * self.res, self.oy + (j + 0.5) * self.res
            if self.circle_free(x, y, ROBOT_RADIUS + 1.5 * self.res):
                return x, y, rng.uniform(-math.pi, math.pi)
        return None


def synthetic_map(rng, seq):
    """A random room map: walls around, random blocks, random origin; 0.05 or 0.1 m cells."""
    res = rng.choice([0.05, 0.1])
    w, h = rng.randint(60, 300), rng.randint(60, 300)
    data = [0] * (w * h)
    for i in range(w):
        data[i] = data[(h - 1) * w + i] = 100
    for j in range(h):
        data[j * w] = data[j * w + w - 1] = 100
    for _ in range(rng.randint(0, 25)):
        x0, y0 = rng.randrange(w), rng.randrange(h)
        bw, bh = rng.randint(1, max(1, w // 5)), rng.randint(1, max(1, h // 5))
        v = rng.choice([100, 100, -1, 50])
        for y in range(y0, min(h, y0 + bh)):
            for x in range(x0, min(w, x0 + bw)):
                data[y * w + x] = v
    m = OccupancyGrid()
    m.header.frame_id = "map"
    m.header.seq = seq
    m.info.width, m.info.height, m.info.resolution = w, h, res
    m.info.origin.position.x, m.info.origin.position.y = rng.uniform(-5, 5), rng.uniform(-5, 5)
    m.info.origin.orientation.w = 1.0
    m.data = data
    return m


def huge_map(rng, side):
    """A side x side map at 0.05 m (side 2048: the soak's max_map_cells), walls around and
    20 x 20-cell blocks on ~10 % of it, free in the middle."""
    data = [0] * (side * side)
    for i in range(side):
        data[i] = data[(side - 1) * side + i] = data[i * side] = data[i * side + side - 1] = 100
    for _ in range(side * side // 4000):
        x0, y0 = rng.randrange(side - 20), rng.randrange(side - 20)
        if abs(x0 - side // 2) < 80 and abs(y0 - side // 2) < 80:
            continue
        for y in range(y0, y0 + 20):
            data[y * side + x0:y * side + x0 + 20] = [100] * 20
    m = OccupancyGrid()
    m.header.frame_id = "map"
    m.info.width = m.info.height = side
    m.info.resolution = 0.05
    m.info.origin.orientation.w = 1.0
    m.data = data
    return m


def partial_update(rng, good):
    """A costmap-style update of a random rectangle of `good` (blocked, cleared, unknown or mixed
    cells), and the map it makes, or (update, None) for one with a defect the server must refuse
    (the map stays as it was)."""
    w, h = good.info.width, good.info.height
    uw, uh = rng.randint(1, min(60, w)), rng.randint(1, min(60, h))
    u = OccupancyGridUpdate()
    u.header.frame_id = good.header.frame_id
    u.x, u.y, u.width, u.height = rng.randint(0, w - uw), rng.randint(0, h - uh), uw, uh
    mode = rng.choice(["block", "clear", "unknown", "mixed"])
    fill = {"block": [100], "clear": [0], "unknown": [-1], "mixed": [0, 0, 30, 100, -1]}[mode]
    u.data = [rng.choice(fill) for _ in range(uw * uh)]
    kind = rng.choices(["valid", "short_data", "past_right_edge", "negative_y", "other_frame"],
                       weights=[80, 5, 5, 5, 5])[0]
    if kind == "short_data":
        u.data = u.data[:-1]
    elif kind == "past_right_edge":
        u.x = w - uw + 1
    elif kind == "negative_y":
        u.y = -1
    elif kind == "other_frame":
        u.header.frame_id = "odom"
    if kind != "valid":
        return u, None, "update_" + kind
    data = list(good.data)
    for r in range(uh):
        start = (u.y + r) * w + u.x
        data[start:start + uw] = u.data[r * uw:(r + 1) * uw]
    m = OccupancyGrid()
    m.header, m.info, m.data = good.header, good.info, data
    return u, m, "update_" + mode


def malformed_map(rng, good):
    """A copy of `good` with one defect the server must refuse (it keeps the previous map)."""
    m = OccupancyGrid()
    m.header = good.header
    m.info.width, m.info.height, m.info.resolution = good.info.width, good.info.height, good.info.resolution
    m.info.origin.orientation.w = 1.0
    m.data = good.data
    kind = rng.choice(["short_data", "long_data", "zero_resolution", "negative_resolution", "nan_resolution",
                       "inf_resolution", "zero_width", "huge_width", "huge_both", "nan_origin", "tilted_origin",
                       "zero_quaternion", "too_many_cells", "empty"])
    if kind == "short_data":
        m.data = good.data[:-1]
    elif kind == "long_data":
        m.data = list(good.data) + [0]
    elif kind == "zero_resolution":
        m.info.resolution = 0.0
    elif kind == "negative_resolution":
        m.info.resolution = -0.05
    elif kind == "nan_resolution":
        m.info.resolution = float("nan")
    elif kind == "inf_resolution":
        m.info.resolution = float("inf")
    elif kind == "zero_width":
        m.info.width = 0
    elif kind == "huge_width":
        m.info.width = 4294967295
    elif kind == "huge_both":
        m.info.width, m.info.height, m.data = 65536, 65536, []
    elif kind == "nan_origin":
        m.info.origin.position.x = float("nan")
    elif kind == "tilted_origin":
        m.info.origin.orientation.x, m.info.origin.orientation.w = math.sin(0.2), math.cos(0.2)
    elif kind == "zero_quaternion":
        m.info.origin.orientation.w = 0.0
    elif kind == "too_many_cells":  # soak.launch sets max_map_cells to 2^22
        m.info.width, m.info.height, m.data = 2049, 2048, [0] * (2049 * 2048)
    elif kind == "empty":
        m.info.width = m.info.height = 0
        m.data = []
    return m, kind


class Soak:
    def __init__(self, args):
        self.args = args
        self.rng = random.Random(args.seed)
        self.lock = threading.Lock()
        self.stats = {"requests": 0, "by_interface": {}, "by_kind": {}, "answers": {}, "answers_by_kind": {},
                      "paths_checked": 0, "solutions_checked": 0, "goals_substituted": 0, "starts_escaped": 0,
                      "cancels_sent": 0,
                      "cancel_latencies": [],  # (running, client-observed s, result-stamped s or None)
                      "map_updates": {"valid": 0, "malformed": {}}, "updates_sent": {}, "failures": [], "rss_kb": [],
                      "checkpoints": []}
        self.maps = []          # (time published, Grid) of every valid map, in order
        self.current = None     # the last valid Grid published
        self.stop = threading.Event()
        self.pause = threading.Event()
        self.in_flight = 0
        self.node_pid = None
        self.map_pub = rospy.Publisher("/map", OccupancyGrid, queue_size=1, latch=True)
        # Partial updates, as costmap_2d sends them (the server folds and applies them in order).
        self.update_pub = rospy.Publisher("/map_updates", OccupancyGridUpdate, queue_size=10)
        # When the server sent each action result (its header stamp), by goal id: the cancel
        # latency without this script's own delays (its threads share the GIL with path checks).
        self.result_stamps = {}
        self.result_sub = rospy.Subscriber(NS + "/plan_anytime/result", PlanAnytimeActionResult, self.on_result,
                                           queue_size=100)

    def on_result(self, msg):
        with self.lock:
            self.result_stamps[msg.status.goal_id.id] = msg.header.stamp.to_sec()
            if len(self.result_stamps) > 20000:
                for k in list(self.result_stamps)[:10000]:
                    del self.result_stamps[k]

    def result_stamp(self, goal_id, wait_s=2.0):
        end = time.time() + wait_s
        while True:
            with self.lock:
                t = self.result_stamps.pop(goal_id, None)
            if t is not None or time.time() > end:
                return t
            time.sleep(0.01)

    # ---- bookkeeping
    def count(self, key, sub, n=1):
        with self.lock:
            d = self.stats[key]
            d[sub] = d.get(sub, 0) + n

    def fail(self, what):
        with self.lock:
            self.stats["failures"].append(what)
            n = len(self.stats["failures"])
        if n <= 30:
            rospy.logerr("soak FAILURE: %s", what)

    def candidate_maps(self, t_sent, t_done):
        """Valid maps that may have been in use between t_sent and t_done: the server switches to
        a new map once it has built its lattice, so a map published shortly before a request
        may not be in use yet, and the one before it may."""
        with self.lock:
            maps = list(self.maps)
        settled = [g for (t, g) in maps if t <= t_sent - 5.0]
        recent = [g for (t, g) in maps if t_sent - 5.0 < t <= t_done + 0.5]
        return (settled[-1:] if settled else []) + recent

    # ---- the node
    def find_node_pid(self):
        master = rosgraph.Master("/soak")
        uri = master.lookupNode(MANAGER)
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid("/soak")
        return pid if code == 1 else None

    def status_kb(self, key):
        try:
            with open("/proc/%d/status" % self.node_pid) as f:
                for line in f:
                    if line.startswith(key + ":"):
                        return int(line.split()[1])
        except OSError:
            return None
        return None

    def monitor(self):
        while not self.stop.is_set():
            rss = self.status_kb("VmRSS")
            if rss is None:
                self.fail("the planner node (pid %d) is gone" % self.node_pid)
                self.stop.set()
                return
            with self.lock:
                self.stats["rss_kb"].append((round(time.time() - self.t0, 1), rss))
            self.stop.wait(2.0)

    # ---- requests
    def make_request(self, rng):
        """(kind, PlanRequest fields, expected statuses or None for any clean one, start, goal)."""
        grid = self.current
        kind = rng.choices(
            ["valid", "valid_robot_start", "valid_odom_goal", "random_pose", "far_out", "nan_position",
             "nan_quaternion", "zero_quaternion", "unnormalised_quaternion", "unknown_frame", "bad_algorithm",
             "bad_weight", "bad_budget", "tolerant_goal", "bad_tolerance", "tolerant_start", "bad_start_tolerance"],
            weights=[30, 6, 6, 12, 4, 3, 3, 3, 3, 3, 3, 3, 3, 10, 3, 10, 2])[0]
        a = grid.random_free_pose(rng) or (0.0, 0.0, 0.0)
        b = grid.random_free_pose(rng) or (0.0, 0.0, 0.0)
        start = pose_stamped("map", a[0], a[1], yaw_quaternion(a[2]))
        goal = pose_stamped("map", b[0], b[1], yaw_quaternion(b[2]))
        start_map, goal_map = a, b
        req = {"start": start, "goal": goal, "time_budget": rng.choice([0.0, 0.05, 0.2, 0.5, 1.0, 2.0]),
               "algorithm": rng.choice(["", "", "amha", "mha", "ara", "ana", "wastar", "astar"]),
               "w1": rng.choice([0.0, 0.0, 1.0, 1.5, 3.0, 10.0]), "w2": rng.choice([0.0, 0.0, 1.0, 2.0, 5.0]),
               "goal_tolerance": 0.0, "ignore_goal_heading": rng.random() < 0.15, "start_tolerance": 0.0}
        expected = None  # any clean status
        if kind == "valid_robot_start":
            start.header.frame_id = ""
            start_map = BASE_LINK
        elif kind == "valid_odom_goal":
            # The goal given in odom; in the map frame it is b.
            ox, oy, oyaw = ODOM
            dx, dy = b[0] - ox, b[1] - oy
            lx, ly = math.cos(oyaw) * dx + math.sin(oyaw) * dy, -math.sin(oyaw) * dx + math.cos(oyaw) * dy
            req["goal"] = pose_stamped("odom", lx, ly, yaw_quaternion(b[2] - oyaw))
        elif kind == "random_pose":
            span = max(grid.w, grid.h) * grid.res
            for which in ("start", "goal"):
                x, y, t = (grid.ox + rng.uniform(-0.2, 1.2) * span, grid.oy + rng.uniform(-0.2, 1.2) * span,
                           rng.uniform(-4, 4))
                req[which] = pose_stamped("map", x, y, yaw_quaternion(t))
                if which == "start":
                    start_map = (x, y, t)
                else:
                    goal_map = (x, y, t)
        elif kind == "far_out":
            req["goal"] = pose_stamped("map", 1e6, -1e6, yaw_quaternion(0.0))
            # The start is checked first, on the map in use, which may not yet be the one it was
            # drawn from; a short budget may run out while a new map's planner is built.
            expected = {S.OUT_OF_MAP, S.INVALID_START, S.TIME_EXHAUSTED}
        elif kind == "nan_position":
            which = rng.choice(["start", "goal"])
            req[which].pose.position.x = float("nan")
            expected = {S.INVALID_START if which == "start" else S.INVALID_GOAL}
        elif kind in ("nan_quaternion", "zero_quaternion", "unnormalised_quaternion"):
            which = rng.choice(["start", "goal"])
            o = req[which].pose.orientation
            if kind == "nan_quaternion":
                o.w = float("nan")
            elif kind == "zero_quaternion":
                o.x = o.y = o.z = o.w = 0.0
            else:
                o.w *= 2.0
                o.z *= 2.0
            expected = {S.INVALID_START if which == "start" else S.INVALID_GOAL}
        elif kind == "unknown_frame":
            req[rng.choice(["start", "goal"])].header.frame_id = "nowhere"
            expected = {S.TF_ERROR}
        elif kind == "bad_algorithm":
            req["algorithm"] = rng.choice(["bogus", "AMHA*", " ", "dijkstra"])
            expected = {S.INVALID_REQUEST}
        elif kind == "bad_weight":
            req["algorithm"] = rng.choice(["", "amha", "ara", "wastar"])
            req[rng.choice(["w1", "w2"]) if req["algorithm"] in ("", "amha") else "w1"] = rng.choice(
                [0.5, -3.0, float("nan"), float("inf"), 1e15, 1e308])
            expected = {S.INVALID_REQUEST}
        elif kind == "bad_budget":
            req["time_budget"] = rng.choice([-1.0, float("nan"), float("inf"), -1e300])
            expected = {S.INVALID_REQUEST}
        elif kind == "tolerant_goal":
            # A goal anywhere in the map, often in or near an obstacle, with a goal tolerance:
            # a path must end within the tolerance of it (check_path).
            x, y = grid.ox + rng.uniform(0, grid.w * grid.res), grid.oy + rng.uniform(0, grid.h * grid.res)
            t = rng.uniform(-math.pi, math.pi)
            req["goal"] = pose_stamped("map", x, y, yaw_quaternion(t))
            goal_map = (x, y, t)
            req["goal_tolerance"] = rng.choice([0.05, 0.1, 0.3, 0.5, 1.0, 3.0])
        elif kind == "bad_tolerance":
            req["goal_tolerance"] = rng.choice([-0.5, -1e-9, float("nan"), float("inf"), -float("inf")])
            expected = {S.INVALID_REQUEST}
        elif kind == "tolerant_start":
            # A start touching an obstacle (or anywhere in the map), with a start tolerance: a
            # path may leave it across obstacle cells under the robot there, and no others
            # (check_path), and its goal tolerance too, sometimes.
            touching = grid.random_touching_pose(rng) if rng.random() < 0.7 else None
            x, y, t = touching or (grid.ox + rng.uniform(0, grid.w * grid.res),
                                   grid.oy + rng.uniform(0, grid.h * grid.res), rng.uniform(-math.pi, math.pi))
            req["start"] = pose_stamped("map", x, y, yaw_quaternion(t))
            start_map = (x, y, t)
            req["start_tolerance"] = rng.choice([0.05, 0.1, 0.3, 0.5, 1.0])
            if rng.random() < 0.3:
                req["goal_tolerance"] = rng.choice([0.1, 0.5])
        elif kind == "bad_start_tolerance":
            req["start_tolerance"] = rng.choice([-0.5, -1e-9, float("nan"), float("inf"), -float("inf")])
            expected = {S.INVALID_REQUEST}
        if expected is not None:
            expected = expected | {S.BUSY}
        return kind, req, expected, start_map, goal_map

    def check_path(self, where, path, start_map, goal_map, grids, goal_tolerance=0.0, any_heading=False,
                   escape_poses=0):
        """Checks one path (nav_msgs/Path); returns the reasons it is wrong ([] = valid). With a
        goal tolerance it may end anywhere within the tolerance of the goal, at any heading; with
        any_heading, at the goal's position with any heading. Its first escape_poses poses may
        leave a start in collision: they may touch the obstacle cells under the robot at the
        start (cells within its footprint, a 16-gon about the circle, of the start's cell centre),
        and no others."""
        poses = path.poses
        if path.header.frame_id != "map":
            return ["path frame '%s'" % path.header.frame_id]
        if not poses:
            return ["empty path"]
        xs = [(p.pose.position.x, p.pose.position.y,
               2 * math.atan2(p.pose.orientation.z, p.pose.orientation.w)) for p in poses]
        errors_by_map = []
        for g in grids:
            err = []
            tol = g.res * 0.75 + 1e-6
            if math.hypot(xs[0][0] - start_map[0], xs[0][1] - start_map[1]) > tol:
                err.append("starts %.3f m from the start" % math.hypot(xs[0][0] - start_map[0], xs[0][1] - start_map[1]))
            if math.hypot(xs[-1][0] - goal_map[0], xs[-1][1] - goal_map[1]) > max(tol, goal_tolerance + 1e-6):
                err.append("ends %.3f m from the goal" % math.hypot(xs[-1][0] - goal_map[0], xs[-1][1] - goal_map[1]))
            # Generated headings are the directions of small lattice vectors: the widest gap is
            # atan(1/2) (26.6 degrees), so the nearest heading is within half of it.
            if angle_diff(xs[0][2], start_map[2]) > HALF_BIN or (
                    goal_tolerance == 0.0 and not any_heading and angle_diff(xs[-1][2], goal_map[2]) > HALF_BIN):
                err.append("start or end heading off by more than half a heading bin")
            for k in range(1, len(xs)):
                if math.hypot(xs[k][0] - xs[k - 1][0], xs[k][1] - xs[k - 1][1]) > 1.5 * g.res + 1e-6:
                    err.append("jump of %.3f m at pose %d" % (math.hypot(xs[k][0] - xs[k - 1][0], xs[k][1] - xs[k - 1][1]), k))
                    break
            under = (start_map[0], start_map[1], ROBOT_RADIUS / math.cos(math.pi / 16) + 0.75 * g.res)
            for k, (x, y, _) in enumerate(xs):
                if not g.circle_free(x, y, ROBOT_RADIUS, under if k < escape_poses else None):
                    err.append("pose %d (%.2f, %.2f) collides%s" % (k, x, y, "" if k < escape_poses else
                                                                   " (after the start's escape, if any)"))
                    break
            if not err:
                return []
            errors_by_map.append("%s: %s" % (g.name, "; ".join(err)))
        return errors_by_map or ["no candidate map"]

    def check_answer(self, interface, kind, expected, res, start_map, goal_map, t_sent, t_done, cancelled, req=None):
        name = STATUS_NAMES.get(res.status, "UNKNOWN_%d" % res.status)
        self.count("answers", name)
        with self.lock:
            self.stats["answers_by_kind"].setdefault(kind, {})
            self.stats["answers_by_kind"][kind][name] = self.stats["answers_by_kind"][kind].get(name, 0) + 1
        where = "%s %s request %d (%s%s)" % (interface, kind, res.request_id, name, "" if req is None else
                                            ", algorithm '%s' w1 %g w2 %g budget %g" % (req["algorithm"], req["w1"], req["w2"], req["time_budget"]))
        if res.status not in CLEAN:
            self.fail("%s: not a clean status: %s" % (where, res.message))
            return
        if cancelled and expected is not None:
            expected = expected | {S.CANCELLED}  # a cancel may overtake the checks
        if expected is not None and res.status not in expected:
            self.fail("%s: expected one of %s: %s" % (where, sorted(STATUS_NAMES[s] for s in expected), res.message))
            return
        has_path = len(res.path.poses) > 0
        if res.status == S.SUCCESS and not has_path:
            self.fail("%s: SUCCESS without a path" % where)
        if res.status not in (S.SUCCESS, S.CANCELLED) and (has_path or res.solutions):
            self.fail("%s: a path or solutions with an error status" % where)
        if not has_path:
            return
        grids = self.candidate_maps(t_sent, t_done)
        tolerance = 0.0 if req is None else req["goal_tolerance"]
        any_heading = req is not None and req["ignore_goal_heading"]
        if res.goal_substituted:
            # The substitute is where the path ends, within the tolerance of the goal.
            end, pg = res.path.poses[-1].pose.position, res.planned_goal
            if tolerance <= 0.0 or "instead" not in res.message or pg.header.frame_id != "map" or \
                    math.hypot(pg.pose.position.x - end.x, pg.pose.position.y - end.y) > 1e-6:
                self.fail("%s: goal substituted without a tolerance, a message or a planned goal at the path's end: "
                          "%s" % (where, res.message))
            with self.lock:
                self.stats["goals_substituted"] += 1
        # A start escape ends at escape_end, the path's first collision-free pose: the poses before
        # it may touch the obstacles under the start.
        escape_poses = 0
        if res.start_escaped:
            start_tolerance = 0.0 if req is None else req["start_tolerance"]
            e = res.escape_end.pose.position
            ends = [k for k, p in enumerate(res.path.poses)
                    if math.hypot(p.pose.position.x - e.x, p.pose.position.y - e.y) < 1e-6]
            if start_tolerance <= 0.0 or "leaves it by" not in res.message or res.escape_end.header.frame_id != "map" \
                    or not ends or math.hypot(e.x - start_map[0], e.y - start_map[1]) > start_tolerance + 0.75 * max(
                        g.res for g in grids):
                self.fail("%s: start escaped without a tolerance, a message, or an escape_end on the path within it: "
                          "%s" % (where, res.message))
            escape_poses = ends[0] if ends else len(res.path.poses)
            with self.lock:
                self.stats["starts_escaped"] += 1
        errs = self.check_path(where, res.path, start_map, goal_map, grids, tolerance if res.goal_substituted else 0.0,
                               any_heading, escape_poses)
        with self.lock:
            self.stats["paths_checked"] += 1
        if errs:
            self.fail("%s: invalid path: %s" % (where, " | ".join(errs)))
            return
        sols = res.solutions
        if not sols:
            self.fail("%s: a path but no solutions" % where)
            return
        prev = None
        for k, s in enumerate(sols):
            if not (s.bound >= 1.0 and 1.0 - 1e-9 <= s.certified_bound <= s.bound * (1 + 1e-9)):
                self.fail("%s: solution %d bounds out of order (bound %g, certified %g)" % (where, k, s.bound, s.certified_bound))
            if prev is not None:
                # (This found ANA* and A-MHA* reporting a costlier path after a cheaper one; fixed
                # in SearchBase::report.)
                cost_up = s.cost > prev.cost + 1e-9
                bound_up = s.bound > prev.bound * (1 + 1e-9)
                certified_up = s.certified_bound > prev.certified_bound * (1 + 1e-9)
                if cost_up or bound_up or certified_up:
                    self.fail("%s: solution %d: cost or a bound increased: (cost, bound, certified, w1, w2, iteration) "
                              "%s -> %s" % (where, k, (prev.cost, prev.bound, prev.certified_bound, prev.w1, prev.w2, prev.iteration),
                                            (s.cost, s.bound, s.certified_bound, s.w1, s.w2, s.iteration)))
            if s.same_path_as_previous != (len(s.path.poses) == 0) and k > 0:
                self.fail("%s: solution %d: same_path_as_previous does not match its empty path" % (where, k))
            if s.path.poses:
                # (A solution's own escape may end elsewhere than the best path's: anywhere.)
                e = self.check_path(where, s.path, start_map, goal_map, grids, tolerance if res.goal_substituted else 0.0,
                                    any_heading, len(s.path.poses) if res.start_escaped else 0)
                if e:
                    self.fail("%s: solution %d invalid: %s" % (where, k, " | ".join(e)))
            # Smoothed (~smooth_path, the default): never costlier than its lattice path, which
            # comes along (left out only where it repeats the previous one) and is valid too.
            if s.smoothed:
                if s.cost > s.lattice_cost + 1e-9:
                    self.fail("%s: solution %d: smoothed cost %g above its lattice path's %g" % (where, k, s.cost, s.lattice_cost))
                if s.lattice_path.poses:
                    e = self.check_path(where, s.lattice_path, start_map, goal_map, grids,
                                        tolerance if res.goal_substituted else 0.0, any_heading)
                    if e:
                        self.fail("%s: solution %d lattice path invalid: %s" % (where, k, " | ".join(e)))
                elif k == 0:
                    self.fail("%s: solution 0 smoothed without its lattice path" % where)
                with self.lock:
                    self.stats["smoothed_checked"] = self.stats.get("smoothed_checked", 0) + 1
            prev = s
        with self.lock:
            self.stats["solutions_checked"] += len(sols)
        last = sols[-1]
        if abs(res.cost - last.cost) > 1e-9 or abs(res.bound - last.bound) > 1e-9 * max(1.0, last.bound):
            self.fail("%s: response cost/bound differ from the last solution's" % where)
        straight = math.hypot(goal_map[0] - start_map[0], goal_map[1] - start_map[1])
        if res.goal_substituted:
            straight -= tolerance
        if res.cost < straight - 2 * max(g.res for g in grids) - 1e-6:
            self.fail("%s: cost %.3f below the straight-line distance %.3f" % (where, res.cost, straight))

    def call_service(self, rng, proxies):
        kind, r, expected, sm, gm = self.make_request(rng)
        req = PlanRequest(start=r["start"], goal=r["goal"], time_budget=r["time_budget"], algorithm=r["algorithm"],
                          w1=r["w1"], w2=r["w2"], goal_tolerance=r["goal_tolerance"],
                          ignore_goal_heading=r["ignore_goal_heading"], start_tolerance=r["start_tolerance"])
        t_sent = time.time()
        res = proxies["plan"](req)
        self.check_answer("plan", kind, expected, res, sm, gm, t_sent, time.time(), False, r)
        return kind

    def call_make_plan(self, rng, proxies):
        kind, r, expected, sm, gm = self.make_request(rng)
        if kind in ("bad_algorithm", "bad_weight", "bad_budget", "bad_start_tolerance"):
            expected = None  # GetPlan has no algorithm, weights, budget or start tolerance: a valid request
        t_sent = time.time()
        # GetPlan's tolerance is a float32: the request's, rounded the way the server reads it.
        tolerance = struct.unpack("f", struct.pack("f", r["goal_tolerance"]))[0]
        res = proxies["make_plan"](GetPlanRequest(start=r["start"], goal=r["goal"], tolerance=tolerance))
        self.count("answers", "make_plan_" + ("path" if res.plan.poses else "empty"))
        if res.plan.poses:
            if expected is not None and S.SUCCESS not in expected:
                self.fail("make_plan %s: a path for a request that must fail" % kind)
            # Without the response's goal_substituted, a tolerant request's path may end
            # anywhere within the tolerance.
            errs = self.check_path("make_plan", res.plan, sm, gm, self.candidate_maps(t_sent, time.time()),
                                   tolerance if tolerance > 0.0 else 0.0)
            with self.lock:
                self.stats["paths_checked"] += 1
            if errs:
                self.fail("make_plan %s: invalid path: %s" % (kind, " | ".join(errs)))
        return kind

    def call_action(self, rng, client):
        kind, r, expected, sm, gm = self.make_request(rng)
        goal = PlanAnytimeGoal(start=r["start"], goal=r["goal"], time_budget=r["time_budget"], algorithm=r["algorithm"],
                               w1=r["w1"], w2=r["w2"], goal_tolerance=r["goal_tolerance"],
                               ignore_goal_heading=r["ignore_goal_heading"], start_tolerance=r["start_tolerance"])
        feedback = []
        t_sent = time.time()
        client.send_goal(goal, feedback_cb=lambda f: feedback.append(time.time()))
        cancel_at = None
        if rng.random() < 0.4:
            delay = rng.choice([0.0, 0.01, 0.05, 0.2, 0.5, 1.0])
            if not client.wait_for_result(rospy.Duration(delay) if delay > 0 else rospy.Duration(1e-6)):
                running = len(feedback) > 0
                cancel_at = time.time()
                client.cancel_goal()
                with self.lock:
                    self.stats["cancels_sent"] += 1
        terminal = (GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.REJECTED, GoalStatus.RECALLED)
        terminal_since = None
        while not client.wait_for_result(rospy.Duration(1.0)):
            now = time.time()
            if client.get_state() in terminal:
                # The server has finished the goal (actionlib publishes the result and the status
                # together) but the result message has not reached this client.
                terminal_since = terminal_since or now
                if now - terminal_since > 5.0:
                    self.count("answers", "result_lost_in_transport_after_terminal_status")
                    return kind
            elif now - t_sent > 60.0:
                self.fail("plan_anytime %s: not finished within 60 s (state %d, %d feedback, cancel %s)" %
                          (kind, client.get_state(), len(feedback), cancel_at is not None))
                client.cancel_goal()
                return kind
        t_done = time.time()
        res = client.get_result()
        state = client.get_state()
        if cancel_at is not None and res is not None and res.status == S.CANCELLED:
            # An answer to the cancel (a goal that ended on its own first is not one).
            try:
                goal_id = client.gh.comm_state_machine.action_goal.goal_id.id
            except AttributeError:
                goal_id = None
            stamped = self.result_stamp(goal_id) if goal_id else None
            with self.lock:
                self.stats["cancel_latencies"].append(
                    (running, t_done - cancel_at, None if stamped is None else stamped - cancel_at))
        if cancel_at is not None and state == GoalStatus.RECALLED and res is not None and res.request_id == 0:
            # Cancelled before the server saw the goal: actionlib answers RECALLED itself, with a
            # result the server marks CANCELLED (it read SUCCESS, status 0, before issue 22).
            self.count("answers", "RECALLED_by_actionlib")
            if res.status != S.CANCELLED:
                self.fail("plan_anytime %s: RECALLED by actionlib with status %s" % (kind, STATUS_NAMES.get(res.status)))
            return kind
        if cancel_at is not None and state == GoalStatus.LOST and not feedback:
            # Python actionlib's client marks a goal LOST when a status message without it
            # arrives while it waits for the cancel's acknowledgement (the cancel overtook the
            # goal); the server never had it. Counted, not a server failure.
            self.count("answers", "LOST_by_client_after_early_cancel")
            return kind
        if state == GoalStatus.LOST and res is None:
            # The client gave the goal up as LOST (a status message without it) after it was
            # running; rare (about 1 in 4000 goals here), cause not found on the server side
            # (actionlib publishes status arrays in order, under its lock). Counted, reported.
            self.count("answers", "LOST_by_client_while_running")
            return kind
        if res is None:
            self.fail("plan_anytime %s: no result message (state %d, %d feedback, %.1f s after sending)" %
                      (kind, state, len(feedback), t_done - t_sent))
            return kind
        want = {S.SUCCESS: {GoalStatus.SUCCEEDED}, S.CANCELLED: {GoalStatus.PREEMPTED, GoalStatus.RECALLED, GoalStatus.ABORTED},
                S.BUSY: {GoalStatus.REJECTED}}.get(res.status, {GoalStatus.ABORTED})
        if state not in want:
            self.fail("plan_anytime %s: goal state %d for status %s" % (kind, state, STATUS_NAMES.get(res.status)))
        self.check_answer("plan_anytime", kind, expected, res, sm, gm, t_sent, t_done, cancel_at is not None, r)
        return kind

    def worker(self, index):
        rng = random.Random(self.args.seed * 1000 + index)
        proxies = {"plan": rospy.ServiceProxy(NS + "/plan", Plan),
                   "make_plan": rospy.ServiceProxy(NS + "/make_plan", GetPlan)}
        client = actionlib.SimpleActionClient(NS + "/plan_anytime", PlanAnytimeAction)
        if not client.wait_for_server(rospy.Duration(30.0)):
            self.fail("worker %d: no action server" % index)
            return
        while not self.stop.is_set():
            with self.lock:
                paused = self.pause.is_set()
                if not paused:
                    if self.stats["requests"] >= self.args.max_requests:
                        break
                    self.stats["requests"] += 1
                    self.in_flight += 1
            if paused:
                time.sleep(0.05)
                continue
            interface = rng.choices(["plan", "plan_anytime", "make_plan"], weights=[45, 45, 10])[0]
            try:
                if interface == "plan":
                    kind = self.call_service(rng, proxies)
                elif interface == "plan_anytime":
                    kind = self.call_action(rng, client)
                else:
                    kind = self.call_make_plan(rng, proxies)
                self.count("by_interface", interface)
                self.count("by_kind", kind)
            except (rospy.ServiceException, rospy.ROSException) as e:
                self.fail("%s: transport error: %s" % (interface, e))
                time.sleep(0.5)
            except Exception:  # a bug in this script must not silently shrink the test
                self.fail("%s: soak driver error: %s" % (interface, traceback.format_exc()))
            finally:
                with self.lock:
                    self.in_flight -= 1

    # ---- maps
    def publish_valid(self, msg, name, update=None):
        g = Grid(msg, name)
        with self.lock:
            self.maps.append((time.time(), g))
            del self.maps[:-40]  # requests last seconds; maps minutes
            self.current = g
            self.stats["map_updates"]["valid"] += 1
        if update is None:
            self.map_pub.publish(msg)
        else:
            self.update_pub.publish(update)

    def mapper(self):
        rng = random.Random(self.args.seed + 7)
        seq = 0
        while not self.stop.wait(rng.uniform(2.0, 8.0)):
            if self.pause.is_set():
                continue
            seq += 1
            r = rng.random()
            if r < 0.3:
                self.publish_valid(self.willow, "willow")
            elif r < 0.5:
                msg = synthetic_map(rng, seq)
                self.publish_valid(msg, "synthetic-%d" % seq)
            elif r < 0.8:
                # One to three partial updates of the current map, back to back. They follow a
                # full map by at least 2 s, so the server has it by then (topics are not ordered
                # with each other).
                for _ in range(rng.randint(1, 3)):
                    update, msg, kind = partial_update(rng, self.current.msg)
                    self.count("updates_sent", kind)
                    if msg is None:
                        self.count_malformed(kind)
                        self.update_pub.publish(update)
                    else:
                        self.publish_valid(msg, "%s+%s-%d" % (self.current.name.split("+")[0], kind, seq),
                                           update)
            else:
                msg, kind = malformed_map(rng, self.current.msg)
                self.count_malformed(kind)
                self.map_pub.publish(msg)

    def count_malformed(self, kind):
        with self.lock:
            d = self.stats["map_updates"]["malformed"]
            d[kind] = d.get(kind, 0) + 1

    def heap_in_use_kb(self):
        """Bytes malloc has handed out and not got back (live heap), in kB, or None: gdb makes
        the node call glibc's malloc_stats(), which prints to its stderr (the launch log). RSS
        alone cannot tell a leak from memory glibc keeps for reuse (fragmentation, arenas)."""
        if not self.args.launch_log or not shutil.which("gdb"):
            return None
        try:
            with open(self.args.launch_log, "rb") as f:
                f.seek(0, 2)
                offset = f.tell()
            subprocess.run(["gdb", "-p", str(self.node_pid), "-batch", "-ex", "call (void) malloc_stats()"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=60)
            time.sleep(1.0)
            with open(self.args.launch_log, "rb") as f:
                f.seek(offset)
                text = f.read().decode(errors="replace")
            m = re.search(r"Total \(incl\. mmap\):\s*system bytes\s*=\s*(\d+)\s*in use bytes\s*=\s*(\d+)", text)
            return int(m.group(2)) // 1024 if m else None
        except (OSError, subprocess.SubprocessError):
            return None

    # ---- memory checkpoints: the same map and request each time, then RSS
    def checkpoint(self, label):
        with self.lock:
            self.pause.set()
        while True:
            with self.lock:
                if self.in_flight == 0:
                    break
            time.sleep(0.05)
        self.publish_valid(self.willow, "willow")
        time.sleep(3.0)
        plan = rospy.ServiceProxy(NS + "/plan", Plan)
        req = PlanRequest(start=pose_stamped("map", 17.0, 55.0, yaw_quaternion(-1.57)),
                          goal=pose_stamped("map", 26.0, 6.0, yaw_quaternion(0.0)), time_budget=2.0)
        statuses = [STATUS_NAMES.get(plan(req).status) for _ in range(2)]
        time.sleep(1.0)
        cp = {"label": label, "t_s": round(time.time() - self.t0, 1), "rss_kb": self.status_kb("VmRSS"),
              "hwm_kb": self.status_kb("VmHWM"), "heap_in_use_kb": self.heap_in_use_kb(),
              "reference_requests": statuses, "requests_so_far": self.stats["requests"]}
        with self.lock:
            self.stats["checkpoints"].append(cp)
        rospy.loginfo("soak checkpoint %s: %s", label, cp)
        self.pause.clear()

    def run(self):
        rospy.wait_for_service(NS + "/plan", timeout=60.0)
        self.willow = rospy.wait_for_message("/map", OccupancyGrid, timeout=60.0)
        self.node_pid = self.find_node_pid()
        if self.node_pid is None:
            raise RuntimeError("cannot find the planner's process")
        self.t0 = time.time()
        self.publish_valid(self.willow, "willow")
        threads = [threading.Thread(target=self.monitor, daemon=True), threading.Thread(target=self.mapper, daemon=True)]
        threads += [threading.Thread(target=self.worker, args=(k,), daemon=True) for k in range(self.args.threads)]
        for t in threads:
            t.start()
        end = self.t0 + self.args.seconds
        warmup = min(30.0, self.args.seconds / 10)
        marks = [(self.t0 + warmup, "start"), (self.t0 + self.args.seconds / 2, "middle")]
        for at, label in marks:
            while time.time() < at and not self.stop.is_set():
                time.sleep(0.2)
            if not self.stop.is_set():
                self.checkpoint(label)
        while time.time() < end and not self.stop.is_set():
            with self.lock:
                if self.stats["requests"] >= self.args.max_requests:
                    break
            time.sleep(0.2)
        if not self.stop.is_set():
            self.checkpoint("end")
        self.stop.set()
        for t in threads[2:]:
            t.join(timeout=90.0)
        if self.args.huge_maps > 0 and self.status_kb("VmRSS") is not None:
            self.huge_maps(self.args.huge_maps)
        return self.summary()

    def huge_maps(self, cycles):
        """Memory after huge maps: `cycles` maps of 2048 x 2048 cells, each with a request on it,
        then the Willow Garage map again; checkpoints before and after (traffic stopped)."""
        self.checkpoint("before huge maps")
        rng = random.Random(self.args.seed + 11)
        statuses = []
        plan = rospy.ServiceProxy(NS + "/plan", Plan)
        for _ in range(cycles):
            msg = huge_map(rng, 2048)
            self.map_pub.publish(msg)
            time.sleep(3.0)  # a request waits for the planner of every map received before it
            c = 2048 * 0.05 / 2
            req = PlanRequest(start=pose_stamped("map", c, c, yaw_quaternion(0.0)),
                              goal=pose_stamped("map", c + 3.0, c + 2.0, yaw_quaternion(1.0)), time_budget=20.0)
            statuses.append(STATUS_NAMES.get(plan(req).status))  # waits for the build, then plans
        self.stats["huge_map_requests"] = statuses
        self.checkpoint("after huge maps")

    def summary(self):
        st = self.stats
        st["seconds"] = round(time.time() - self.t0, 1)
        st["node_pid"] = self.node_pid
        st["node_alive_at_end"] = self.status_kb("VmRSS") is not None
        lats = st.pop("cancel_latencies")
        st["cancel_latency"] = {
            "running_client": distribution([c for r, c, _ in lats if r]),
            "running_server": distribution([t for r, _, t in lats if r and t is not None]),
            "waiting_client": distribution([c for r, c, _ in lats if not r]),
            "waiting_server": distribution([t for r, _, t in lats if not r and t is not None])}
        lat = sorted(t for r, _, t in lats if r and t is not None)
        cps = {c["label"]: c for c in st["checkpoints"]}
        if not st["node_alive_at_end"]:
            self.fail("the planner node died")
        # Memory must not grow over the second half: the live heap (malloc's bytes in use) when
        # gdb can read it, else RSS. RSS growth with a flat live heap is memory glibc keeps for
        # reuse (reported, not a failure).
        if "middle" in cps and "end" in cps and cps["middle"]["rss_kb"] and cps["end"]["rss_kb"]:
            st["rss_growth_middle_to_end_kb"] = cps["end"]["rss_kb"] - cps["middle"]["rss_kb"]
            key = "heap_in_use_kb" if cps["middle"].get("heap_in_use_kb") and cps["end"].get("heap_in_use_kb") else "rss_kb"
            st["memory_measure"] = key
            grown = cps["end"][key] - cps["middle"][key]
            st[key.replace("_kb", "") + "_growth_middle_to_end_kb"] = grown
            if grown > 0.10 * cps["middle"][key] + 16 * 1024:
                self.fail("memory (%s) grew from %d kB (middle) to %d kB (end)" % (key, cps["middle"][key], cps["end"][key]))
        elif self.args.seconds >= 60:
            self.fail("missing memory checkpoints")
        # After the huge maps the live heap must be back (no leak); RSS is reported.
        before, after = cps.get("before huge maps"), cps.get("after huge maps")
        if before and after and before.get("heap_in_use_kb") and after.get("heap_in_use_kb"):
            grown = after["heap_in_use_kb"] - before["heap_in_use_kb"]
            if grown > 16 * 1024:
                self.fail("heap in use grew by %d kB over the huge maps" % grown)
        if lat and lat[-1] > 1.0:
            self.fail("a running goal's result came %.0f ms after its cancel" % (1000 * lat[-1]))
        st["failure_count"] = len(st["failures"])
        st["failures"] = st["failures"][:50]
        samples = st.pop("rss_kb")
        st["rss_kb_samples"] = {"count": len(samples), "min": min(s[1] for s in samples) if samples else None,
                                "max": max(s[1] for s in samples) if samples else None,
                                "first": samples[:3], "last": samples[-3:]}
        return st


def distribution(values):
    """Count, median, 95th and 99th percentile and maximum, in ms (nearest rank)."""
    v = sorted(values)
    if not v:
        return {"count": 0}
    rank = lambda q: v[min(len(v) - 1, max(0, int(math.ceil(q * len(v))) - 1))]
    return {"count": len(v), "median_ms": round(1000 * rank(0.5), 1), "p95_ms": round(1000 * rank(0.95), 1),
            "p99_ms": round(1000 * rank(0.99), 1), "max_ms": round(1000 * v[-1], 1)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seconds", type=float, default=300.0)
    ap.add_argument("--max-requests", type=int, default=100000)
    ap.add_argument("--threads", type=int, default=3)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default="")
    ap.add_argument("--huge-maps", type=int, default=3,
                    help="maps of 2048 x 2048 cells sent at the end, between two memory checkpoints")
    ap.add_argument("--launch-log", default=os.environ.get("AMHA_SOAK_LAUNCH_LOG", ""),
                    help="the node's output (for malloc_stats via gdb)")
    args = ap.parse_args(rospy.myargv()[1:])
    rospy.init_node("soak", anonymous=True, disable_signals=True)
    soak = Soak(args)
    summary = soak.run()
    text = json.dumps(summary, indent=1, sort_keys=True)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    ok = summary["failure_count"] == 0
    print("SOAK %s: %d requests in %.0f s, %d failures" % ("PASSED" if ok else "FAILED", summary["requests"],
                                                          summary["seconds"], summary["failure_count"]))
    rospy.signal_shutdown("done")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()

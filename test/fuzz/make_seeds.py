#!/usr/bin/python3
"""Regenerates the hand-made and shared-data seeds of the fuzz corpora (test/fuzz/corpus/<target>/).
Seeds from ../shared/data are cut down to a few kB (libFuzzer's input size follows its seeds).
Files are written only if absent, so crash reproducers added to a corpus by hand stay.
Usage: test/fuzz/make_seeds.py [SHARED_DATA_DIR]"""
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "..", "shared", "data")


def put(target, name, content):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, name)
    if isinstance(content, str):
        content = content.encode()
    if not os.path.exists(path):
        with open(path, "wb") as f:
            f.write(content)


def shared(rel):
    path = os.path.join(DATA, rel)
    return open(path, "rb").read() if os.path.exists(path) else None


# ---- mprim: shared files cut to 2 primitives a heading (not the same ones in each) and 3 poses a primitive, hand-made ones.
def cut_mprim(text, ids, max_poses):
    tok = text.split()
    out, i = [], 0
    header = []
    while tok[i] != "totalnumberofprimitives:":
        header.append(tok[i])
        i += 1
    i += 2
    prims = []
    while i < len(tok):
        assert tok[i] == "primID:"
        pid, start = tok[i + 1], tok[i + 3]
        end = tok[i + 5:i + 8]
        mult = tok[i + 9]
        j = i + 10
        extra = []
        if tok[j] == "turning_radius:":
            extra = tok[j:j + 2]
            j += 2
        n = int(tok[j + 1])
        poses = [tok[j + 2 + 3 * k:j + 5 + 3 * k] for k in range(n)]
        i = j + 2 + 3 * n
        prims.append((pid, start, end, mult, extra, poses))
    kept = [p for p in prims if int(p[0]) in ids]
    lines = []
    k = 0
    while k < len(header):
        lines.append(" ".join(header[k:k + 2]))
        k += 2
    lines.append("totalnumberofprimitives: %d" % len(kept))
    for pid, start, end, mult, extra, poses in kept:
        if len(poses) > max_poses:
            poses = [poses[0], poses[len(poses) // 2], poses[-1]]
        lines += ["primID: " + pid, "startangle_c: " + start, "endpose_c: " + " ".join(end),
                  "additionalactioncostmult: " + mult]
        if extra:
            lines.append(" ".join(extra))
        lines.append("intermediateposes: %d" % len(poses))
        lines += [" ".join(p) for p in poses]
    return "\n".join(lines) + "\n"


for name, ids in (("pr2.mprim", (0, 1)), ("unicycle_noturninplace.mprim", (2, 3)), ("pr2_10cm.mprim", (4, 5))):
    t = shared("sbpl/" + name)
    if t:
        put("mprim", "cut-" + name, cut_mprim(t.decode(), ids, 3))
put("mprim", "small-uniform.mprim",
    "resolution_m: 0.1\nnumberofangles: 2\ntotalnumberofprimitives: 2\n"
    "primID: 0\nstartangle_c: 0\nendpose_c: 1 0 0\nadditionalactioncostmult: 1\nintermediateposes: 2\n"
    "0 0 0\n0.1 0 0\n"
    "primID: 0\nstartangle_c: 1\nendpose_c: -1 0 1\nadditionalactioncostmult: 2\nintermediateposes: 2\n"
    "0 0 3.14159\n-0.1 0 3.14159\n")
put("mprim", "small-nonuniform.mprim",
    "resolution_m: 0.1\nmin_turning_radius_m: 0.5\nnumberofangles: 2\nangle:0 0.0\nangle:1 3.14159265\n"
    "totalnumberofprimitives: 2\n"
    "primID: 0\nstartangle_c: 0\nendpose_c: 2 0 0\nadditionalactioncostmult: 1\nturning_radius: 0.0\n"
    "intermediateposes: 3\n0 0 0\n0.1 0 0\n0.2 0 0\n"
    "primID: 0\nstartangle_c: 1\nendpose_c: 0 0 0\nadditionalactioncostmult: 1\nturning_radius: 0.0\n"
    "intermediateposes: 2\n0 0 3.14159265\n0 0 0.1\n")
put("mprim", "four-headings-crlf.mprim",
    ("resolution_m: 0.05\nnumberofangles: 4\ntotalnumberofprimitives: 4\n" +
     "".join("primID: 0\nstartangle_c: %d\nendpose_c: %d %d %d\nadditionalactioncostmult: 1\n"
             "intermediateposes: 2\n0 0 %.6f\n%.2f %.2f %.6f\n"
             % (h, dx, dy, h, 1.5707963 * h, dx * 0.05, dy * 0.05, 1.5707963 * h)
             for h, (dx, dy) in enumerate([(1, 0), (0, 1), (-1, 0), (0, -1)]))).replace("\n", "\r\n"))

# ---- nav2_lattice: the lattice test fixture (Nav2's JSON format), cut to 2 primitives a heading
# and 3 poses a primitive, compact; and a hand-made 4-heading file.
import json


def cut_nav2(doc, per_heading, max_poses):
    kept, count = [], {}
    for p in doc["primitives"]:
        h = p["start_angle_index"]
        if count.get(h, 0) < per_heading:
            count[h] = count.get(h, 0) + 1
            poses = p["poses"]
            p = dict(p, trajectory_id=len(kept), poses=poses[:max_poses - 1] + poses[-1:] if len(poses) > max_poses else poses)
            kept.append(p)
    doc = dict(doc, primitives=kept)
    doc["lattice_metadata"] = dict(doc["lattice_metadata"], number_of_trajectories=len(kept))
    return json.dumps(doc, separators=(",", ":"))


fixture = os.path.join(HERE, "..", "lattice", "data", "nav2_diff_8_headings.json")
if os.path.exists(fixture):
    d = json.load(open(fixture))
    put("nav2_lattice", "cut-diff-8-headings.json", cut_nav2(d, 2, 3))
    put("nav2_lattice", "cut-diff-8-headings-turns.json", cut_nav2(dict(d, primitives=d["primitives"][2:]), 3, 2))
four = {"version": 1.0, "lattice_metadata": {"motion_model": "ackermann", "turning_radius": 0.2, "grid_resolution": 0.1,
                                             "num_of_headings": 4, "heading_angles": [0, 1.5707963267948966, 3.141592653589793, 4.71238898038469],
                                             "number_of_trajectories": 4},
        "primitives": [{"trajectory_id": h, "start_angle_index": h, "end_angle_index": h, "left_turn": True,
                        "trajectory_radius": 0, "trajectory_length": 0.1, "arc_length": 0, "straight_length": 0.1,
                        "poses": [[round(0.1 * [1, 0, -1, 0][h], 1), round(0.1 * [0, 1, 0, -1][h], 1), 1.5707963267948966 * h]]}
                       for h in range(4)]}
put("nav2_lattice", "four-headings.json", json.dumps(four))

# ---- map_server: YAML, NUL, image bytes (the YAML names the image "map.img").
def yaml(mode=None, negate=0, res="0.05", origin="[-1.0, -2.0, 0.0]"):
    y = "image: map.img\nresolution: %s\norigin: %s\nnegate: %d\noccupied_thresh: 0.65\nfree_thresh: 0.196\n" % (
        res, origin, negate)
    if mode:
        y += "mode: %s\n" % mode
    return y


def pgm(w, h, pixels, maxval=255):
    if maxval > 255:
        body = b"".join(struct.pack(">H", p) for p in pixels)
    else:
        body = bytes(pixels)
    return b"P5\n%d %d\n%d\n" % (w, h, maxval) + body


def png(w, h, color_type, bit_depth, rows):
    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, bit_depth, color_type, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


pattern = [0, 255, 205, 100, 254, 0, 255, 10] * 6  # 8 x 6: occupied, free, unknown, between
put("map_server", "trinary-pgm", yaml().encode() + b"\0" + pgm(8, 6, pattern))
put("map_server", "scale-negate-pgm", yaml("scale", 1).encode() + b"\0" + pgm(8, 6, pattern))
put("map_server", "raw-pgm", yaml("raw").encode() + b"\0" + pgm(8, 6, pattern))
put("map_server", "pgm16", yaml().encode() + b"\0" + pgm(4, 3, [0, 65535, 52685, 30000] * 3, 65535))
put("map_server", "ascii-pgm", yaml().encode() + b"\0" + b"P2\n3 2\n255\n0 255 205\n254 100 0\n")
put("map_server", "ppm", yaml("scale").encode() + b"\0" + b"P6\n2 2\n255\n" + bytes([0, 0, 0, 255, 255, 255, 205, 205, 205, 50, 100, 150]))
put("map_server", "png-gray-alpha", yaml("scale").encode() + b"\0" + png(3, 2, 4, 8, [bytes([0, 255, 255, 0, 205, 255]), bytes([255, 255, 128, 255, 0, 0])]))
put("map_server", "png-rgba", yaml().encode() + b"\0" + png(2, 2, 6, 8, [bytes([0, 0, 0, 255, 255, 255, 255, 255]), bytes([205, 205, 205, 255, 9, 9, 9, 0])]))
put("map_server", "png-gray16", yaml("raw").encode() + b"\0" + png(2, 2, 0, 16, [bytes([0, 0, 255, 255]), bytes([128, 0, 20, 0])]))
put("map_server", "yaml-inline-origin-yaw", yaml(origin="{0: 1}", res="1e-3").encode() + b"\0" + pgm(2, 2, [0, 255, 0, 255]))
w = shared("maps/ros/willow_garage/willow-2010-02-18-0.10.pgm")
wy = shared("maps/ros/willow_garage/willow-2010-02-18-0.10.yaml")
if w and wy:
    # Cut a 48 x 48 window out of the middle of the Willow Garage map (P5 566 x 608).
    header_end = 0
    fields = 0
    i = 0
    while fields < 4:  # "P5", width, height, maxval
        while w[i:i + 1].isspace():
            i += 1
        if w[i:i + 1] == b"#":
            while w[i:i + 1] != b"\n":
                i += 1
            continue
        while not w[i:i + 1].isspace():
            i += 1
        fields += 1
    body = w[i + 1:]
    W = 566
    crop = b"".join(body[(300 + r) * W + 250:(300 + r) * W + 298] for r in range(48))
    y = wy.decode().replace("willow-2010-02-18-0.10.pgm", "map.img")
    put("map_server", "willow-crop", y.encode() + b"\0" + pgm(48, 48, crop))

# ---- Moving AI maps: the first byte is the upscale factor (byte % 5).
for name in ("maze-32-32-4.map", "random-64-64-10.map", "room-64-64-8.map"):
    t = shared("maps/movingai/" + name)
    if t:
        put("movingai", name, b"\x01" + t)
put("movingai", "tiny-upscale3.map", b"\x03type octile\nheight 3\nwidth 4\nmap\n.@TS\nGOW.\n....\n")
put("movingai", "crlf.map", b"\x02type octile\r\nheight 2\r\nwidth 2\r\nmap\r\n.@\r\n@.\r\n\r\n")

# ---- SBPL .cfg: env1 and a 24 x 20 window of the cubicle environment.
def cfg(w, h, rows, theta=True):
    s = "discretization(cells): %d %d\n" % (w, h)
    if theta:
        s += "NumThetaDirs: 16\n"
    s += ("obsthresh: 254\ncost_inscribed_thresh: 253\ncost_possibly_circumscribed_thresh: 128\n"
          "cellsize(meters): 0.025\nnominalvel(mpersecs): 1.0\ntimetoturn45degsinplace(secs): 2.0\n"
          "start(meters,rads): 0.11 0.11 0\nend(meters,rads): 0.3 0.2 1.57\nenvironment:\n")
    return s + "\n".join(" ".join(str(c) for c in r) for r in rows) + "\n"


t = shared("sbpl/env1.cfg")
if t:
    put("sbpl_cfg", "env1.cfg", t)
t = shared("sbpl/cubicle-25mm-inflated-env.cfg")
if t:
    text = t.decode().split("environment:")[1].split("\n")
    rows = [r.split() for r in text if r.strip()]
    put("sbpl_cfg", "cubicle-window.cfg", cfg(24, 20, [r[200:224] for r in rows[200:220]]))
put("sbpl_cfg", "no-theta-crlf.cfg", cfg(3, 2, [[0, 254, 253], [1, 252, 255]], theta=False).replace("\n", "\r\n"))

# ---- tile instances: the first byte picks the expected size (byte % 12; 0 = any).
t = shared("tiles/korf100_15puzzle.txt")
if t:
    lines = t.decode().split("\n")
    put("tile_instances", "korf-head", b"\x00" + "\n".join(lines[:12]).encode() + b"\n")
put("tile_instances", "eight-puzzle", b"\x03# 8-puzzles\n\na 1 1 1 0 2 3 4 5 6 7 8\nb -1 -1 3 1 2 0 4 5 6 7 8\n")
put("tile_instances", "24-puzzle", b"\x00x -1 -1 " + " ".join(str(i) for i in [1, 0] + list(range(2, 25))).encode() + b"\n")

# ---- occupancy (+ planning): mode, sizes, resolution, origin, thresholds, data pattern, then
# (after width x height pattern bytes) the planner's parameters.
def occ(w, h, cells, params, mode=1, rsel=0):
    head = bytes([mode, w - 1, h - 1, rsel, 0, 0, 0, 0, 0, 0, 64, 0, 1, 0])
    return head + bytes(cells) + bytes(params)


import random
rng = random.Random(7)
for k in range(6):
    w, h = rng.randint(8, 30), rng.randint(8, 30)
    cells = [0 if rng.random() < 0.85 else rng.choice([160, 205, 230]) for _ in range(w * h)]
    params = [rng.randint(0, 255) for _ in range(40)]
    put("occupancy", "plan-%d" % k, occ(w, h, cells, params, rsel=k % 4))
put("occupancy", "huge-size", bytes([0, 0xFF, 0xFF, 0, 0x7F, 0xFF, 0xFF, 0, 0x7F, 1]))
put("occupancy", "negative-size", bytes([0, 0xF6, 0xFF, 0xFF, 0xFF, 10, 0, 0, 0, 0]))

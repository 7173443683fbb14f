#!/usr/bin/env python3
"""Renders a soak run's JSON summary (scripts/soak ... --json FILE) as the Markdown page
docs/results/robustness.md:
    /usr/bin/python3 test/ros/soak_report.py FILE.json --command "scripts/soak 600 ..." \
        --commit abc1234 > docs/results/robustness.md
Every figure on the page comes from the JSON; nothing is typed in by hand, except a
'## History' section at the end, which --keep-history copies over from the previous page."""
import argparse
import json
import sys

# The client-side outcomes that are not answers from the server (see soak.py for each).
CLIENT_SIDE = {
    "LOST_by_client_after_early_cancel": "the Python action client marked the goal LOST: its cancel overtook the goal, which the server never received",
    "LOST_by_client_while_running": "the Python action client gave a running goal up as LOST after a status message without it; the server had answered",
    "RECALLED_by_actionlib": "cancelled before the server saw it; actionlib answered RECALLED itself (the result says CANCELLED, checked)",
    "result_lost_in_transport_after_terminal_status": "the goal reached a terminal state on the server but its result message did not reach the client within 5 s",
}


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("json")
    ap.add_argument("--command", default="scripts/soak 600 --json FILE")
    ap.add_argument("--commit", default="unknown")
    ap.add_argument("--machine", default="")
    ap.add_argument("--keep-history", default="",
                    help="a previous page: its '## History' section (written by hand) is copied to the end")
    args = ap.parse_args()
    d = json.load(open(args.json))
    p = []
    w = p.append
    ok = d["failure_count"] == 0 and d["node_alive_at_end"]
    w("# Robustness: the soak test's figures\n")
    w("How the soak test works and what it checks: [../robustness.md](../robustness.md#soak-test). "
      "This page is rendered from one run's JSON summary by `test/ros/soak_report.py`.\n")
    w("```\n%s\n```\n" % args.command)
    w("Commit `%s`%s.\n" % (args.commit, (", " + args.machine) if args.machine else ""))
    w("## Result\n")
    w("**%s**: %d requests in %.0f s from %s, %d failures; the node was %s at the end. "
      "%d paths (%d solutions, counting every improved path of an anytime answer) were replayed "
      "against the maps in use and passed%s.\n" % (
          "PASSED" if ok else "FAILED", d["requests"], d["seconds"],
          ", ".join("%s %d" % (k, v) for k, v in sorted(d["by_interface"].items())),
          d["failure_count"], "alive" if d["node_alive_at_end"] else "DEAD",
          d["paths_checked"], d["solutions_checked"],
          ("" if "goals_substituted" not in d else
           " (%d of them to a substitute for a goal in collision, within the request's goal tolerance)"
           % d["goals_substituted"]) +
          ("" if "starts_escaped" not in d else
           " (%d of them leaving a start in collision, within the request's start tolerance, across "
           "no obstacle but those under the robot at the start)" % d["starts_escaped"])))
    if d["failures"]:
        w("Failures:\n")
        for f in d["failures"][:50]:
            w("- " + f)
        w("")

    w("## Answers by kind of request\n")
    statuses = sorted({s for kinds in d["answers_by_kind"].values() for s in kinds})
    rows = []
    for kind in sorted(d["answers_by_kind"]):
        a = d["answers_by_kind"][kind]
        rows.append([kind, d["by_kind"].get(kind, 0)] + [a.get(s, "") for s in statuses])
    w(table(["kind", "sent"] + statuses, rows) + "\n")
    w("Statuses as the server answered them (`make_plan` answers carry no status: an empty or a "
      "non-empty path). `BUSY`: one plan runs and two wait; a request beyond that is refused at "
      "once (docs/ros.md). Valid requests are drawn on the map in use when they are sent; a map "
      "update can land before they run, hence some `OUT_OF_MAP` and `INVALID_START` answers to them.")
    if ok:
        w("The script checked every answer against the statuses expected for its kind (`BUSY`, or "
          "`CANCELLED` when it had cancelled the request, are accepted for any kind); none got "
          "`INTERNAL_ERROR` or an unexpected status.\n")
    else:
        w("")
    client = [(k, d["answers"][k], CLIENT_SIDE[k]) for k in CLIENT_SIDE if d["answers"].get(k)]
    if client:
        w("Outcomes on the client side, not answers from the server (the script counts them apart; "
          "they are not failures of the node):\n")
        w(table(["outcome", "count", "what it is"], client) + "\n")

    w("## Cancels and map updates\n")
    lat = d.get("cancel_latency", {})
    w("- Cancels sent: %d (40 %% of `~plan_anytime` goals, after 0-1 s). For the results that answer "
      "a cancel (status CANCELLED; a goal may end on its own first), the latency from the cancel to "
      "the result, measured two ways: when this script saw the result (its own threads share "
      "Python's lock with the path checks, so this includes its delays), and when the server sent "
      "it (the result's header stamp; same clock). \"Running\": goals that had sent feedback (a "
      "first solution); \"other\": queued, waiting for a map's planner, or before their first "
      "solution. The checks: a running goal's result must come within 1 s of its cancel (server "
      "stamp); the action's contract (docs/ros.md) and the rostests ask for 50 ms on an idle "
      "machine.\n" % d["cancels_sent"])
    rows = []
    for key, label in (("running_server", "running, sent by the server"), ("running_client", "running, seen by the script"),
                       ("waiting_server", "other, sent by the server"), ("waiting_client", "other, seen by the script")):
        x = lat.get(key, {})
        if x.get("count"):
            rows.append([label, x["count"], "%.1f ms" % x["median_ms"], "%.1f ms" % x["p95_ms"], "%.1f ms" % x["p99_ms"],
                         "%.1f ms" % x["max_ms"]])
    if rows:
        w(table(["cancel -> result", "goals", "median", "95th percentile", "99th percentile", "max"], rows) + "\n")
    mu = d["map_updates"]
    bad = mu.get("malformed", {})
    sent = d.get("updates_sent", {})  # partial updates (runs before they were sent have none)
    good_partial = sum(n for k, n in sent.items() if k not in bad)
    w("- Map changes while planning: %d valid (the Willow Garage map, random synthetic maps, and "
      "%d partial updates of the current map: %s), %d malformed maps and updates, all refused with "
      "the current map kept: %s.\n" % (
          mu.get("valid", 0), good_partial,
          ", ".join("%s %d" % kv for kv in sorted(sent.items()) if kv[0] not in bad) or "none",
          sum(bad.values()), ", ".join("%s %d" % kv for kv in sorted(bad.items()))))

    w("## Memory\n")
    w("At the start, middle and end the script pauses the traffic, sends the same map and two "
      "reference requests, and reads the node's memory: `heap in use` is glibc's count of "
      "allocated bytes (read with gdb, `malloc_stats`), the figure that shows a leak; RSS also "
      "counts freed memory glibc keeps for reuse. The check: heap in use (or RSS without gdb) "
      "must not grow from the middle to the end by more than 10 % + 16 MB.\n")
    rows = []
    for c in d["checkpoints"]:
        rows.append([c["label"], "%.0f s" % c["t_s"], c["requests_so_far"],
                     "%.1f MB" % (c["heap_in_use_kb"] / 1024.0) if c.get("heap_in_use_kb") is not None else "-",
                     "%.1f MB" % (c["rss_kb"] / 1024.0), "%.1f MB" % (c["hwm_kb"] / 1024.0),
                     ", ".join(c.get("reference_requests", []))])
    w(table(["checkpoint", "time", "requests so far", "heap in use", "RSS", "peak RSS so far", "reference requests"], rows) + "\n")
    cps = {c["label"]: c for c in d["checkpoints"]}
    before, after = cps.get("before huge maps"), cps.get("after huge maps")
    if before and after:
        w("Huge maps: after the end checkpoint, %d maps of 2048 x 2048 cells (the soak's `max_map_cells`) "
          "with a request on each (answers: %s), then the Willow Garage map again: heap in use %s, "
          "RSS %.1f MB -> %.1f MB (peak %.1f MB).\n" % (
              len(d.get("huge_map_requests", [])), ", ".join(d.get("huge_map_requests", [])),
              "%.1f MB -> %.1f MB" % (before["heap_in_use_kb"] / 1024.0, after["heap_in_use_kb"] / 1024.0)
              if before.get("heap_in_use_kb") and after.get("heap_in_use_kb") else "not read (no gdb)",
              before["rss_kb"] / 1024.0, after["rss_kb"] / 1024.0, after["hwm_kb"] / 1024.0))
    w("Growth from the middle to the end: heap in use %+d KB, RSS %+d KB. RSS sampled every 2 s: "
      "%d samples, %.1f MB to %.1f MB (it rises and falls with each request's search and the map "
      "in use).\n" % (d.get("heap_in_use_growth_middle_to_end_kb", 0), d.get("rss_growth_middle_to_end_kb", 0),
                     d["rss_kb_samples"]["count"], d["rss_kb_samples"]["min"] / 1024.0,
                     d["rss_kb_samples"]["max"] / 1024.0))
    if args.keep_history:
        old = open(args.keep_history).read()
        at = old.find("\n## History")
        if at >= 0:
            w(old[at:].rstrip("\n"))
    sys.stdout.write("\n".join(p))


if __name__ == "__main__":
    main()

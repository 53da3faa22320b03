#!/usr/bin/env python3
"""Summary of scripts/budget_churn_sweep.sh: per run its settled CPU-systems mean, parts' settled means
against their targets, settled level changes a second (geometric + animation) and by cause; per parts
run the single total's settled level changes a second interpolated (piecewise linear over the single
runs of the same crowd size, sorted by their settled CPU mean; means of runs at one factor first) at
the parts run's settled CPU mean. Prints Markdown.

usage: budget_churn_summary.py RUNS_DIR            the tables
       budget_churn_summary.py --cpu-mean RUNS_DIR PREFIX   mean settled CPU of the runs named PREFIX*
"""
import csv, json, os, sys


def load(d):
    r = json.load(open(os.path.join(d, "report.json")))
    meta = json.load(open(os.path.join(d, "meta.json"))) if os.path.exists(os.path.join(d, "meta.json")) else {}
    cpu = [float(row["cpu_systems_ms"]) for row in csv.DictReader(open(os.path.join(d, "frames.csv")))]
    b = r["budget"]
    start = b["settled_from_frame"]
    settled = start is not None
    frm = start if settled else 0
    lc = r["level_changes_per_second_settled"] if settled else None
    if lc is None:  # never settled: the whole run's
        lc = dict(r["level_changes_per_second"], seconds=None)
    parts = {}
    for p in ("animation", "geometry"):
        j = b[p]
        if j.get("active") and j.get("settled"):
            parts[p] = j["settled"]["mean_over_target"]
        elif j.get("active"):
            parts[p] = None
    causes = r.get("level_change_causes_settled")
    return {
        "label": os.path.basename(d), "mode": b["mode"], "characters": r["characters"], "settled": settled,
        "target": b.get("target_ms"), "cpu_settled": sum(cpu[frm:]) / max(1, len(cpu[frm:])),
        "cpu_all": sum(cpu) / len(cpu), "changes": lc["geometric"] + lc["animation"], "geom": lc["geometric"],
        "anim": lc["animation"], "parts": parts, "causes": causes,
        "load": "%s-%s" % (meta.get("load_before", "?"), meta.get("load_after", "?")), "utc": meta.get("utc", "?"),
    }


def interpolate(points, x):
    """Piecewise linear through (x, y) points sorted by x; None outside their range."""
    pts = sorted(points)
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1:
            return y0 if x1 == x0 else y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    return None


def cause_text(c):
    if not c:
        return ""
    out = []
    for k, short in (("geometric", "g"), ("animation", "a")):
        v = c[k]
        out.append("%s: rules %.1f, budget %.1f down / %.1f up (undone %.1f; net %.1f, swapped %.1f)" % (
            short, v["rules"], v["budget_demotions"], v["budget_promotions"], v["budget_undone_within_1s"],
            v["budget_net_per_1s_window"], v["budget_swapped_per_1s_window"]))
    return "; ".join(out)


def main():
    if sys.argv[1] == "--cpu-mean":
        runs = [load(os.path.join(sys.argv[2], d)) for d in sorted(os.listdir(sys.argv[2])) if d.startswith(sys.argv[3])]
        print("%.3f" % (sum(r["cpu_settled"] for r in runs) / len(runs)))
        return
    root = sys.argv[1]
    runs = [load(os.path.join(root, d)) for d in sorted(os.listdir(root)) if os.path.exists(os.path.join(root, d, "report.json"))]
    for n in sorted({r["characters"] for r in runs}):
        rs = [r for r in runs if r["characters"] == n]
        print("\n### %d characters\n" % n)
        print("| run (UTC, load 1 min before-after) | mode, target | CPU mean settled (all) | parts settled mean/target | changes/s settled g + a | by cause |")
        print("|---|---|---|---|---|---|")
        for r in rs:
            parts = ", ".join("%s %s" % (p[:4], "never settled" if v is None else "%.3fx" % v) for p, v in r["parts"].items())
            print("| %s (%s, %s) | %s%s | %.2f (%.2f) | %s | %.1f + %.1f = **%.1f**%s | %s |" % (
                r["label"], r["utc"], r["load"], r["mode"], "" if r["target"] is None else " %.2f ms" % r["target"],
                r["cpu_settled"], r["cpu_all"], parts, r["geom"], r["anim"], r["changes"],
                "" if r["settled"] else " (whole run: never settled)", cause_text(r["causes"])))
        # The single total's curve: runs of one target averaged.
        by_target = {}
        for r in rs:
            if r["mode"] == "total" and r["settled"]:
                by_target.setdefault(r["target"], []).append(r)
        curve = [(sum(x["cpu_settled"] for x in v) / len(v), sum(x["changes"] for x in v) / len(v)) for v in by_target.values()]
        print("\nSingle total, mean over its runs per target: " + ", ".join(
            "%.2f ms -> %.1f/s" % p for p in sorted(curve)))
        print("\n| parts run | CPU mean settled | parts changes/s | single total interpolated at that CPU mean | parts / single |")
        print("|---|---|---|---|---|")
        for r in rs:
            if r["mode"] != "parts":
                continue
            s = interpolate(curve, r["cpu_settled"])
            print("| %s | %.2f | %.1f | %s | %s |" % (r["label"], r["cpu_settled"], r["changes"],
                  "outside the sweep" if s is None else "%.1f" % s, "" if s is None or s == 0 else "%.2f" % (r["changes"] / s)))


if __name__ == "__main__":
    main()

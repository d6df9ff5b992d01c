#!/usr/bin/env python3
"""Turns `manylight bench` results into the charts and pages under docs/ (bench/sweep.sh).

  bench/report.py RESULTS_DIR DOCS_DIR

RESULTS_DIR holds sweep.csv and, when they were measured, stability.json and peers.csv.
Writes DOCS_DIR/charts/*.png (gnuplot, bench/charts/*.gp), DOCS_DIR/benchmarks.md and
DOCS_DIR/stability.md. Standard library only; gnuplot draws every chart.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def number(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def fmt(v, digits=3):
    if v is None:
        return "—"
    if isinstance(v, str):
        v = number(v)
    if math.isnan(v):
        return "—"
    if math.isinf(v):
        return "∞"
    if v == 0:
        return "0"
    if abs(v) >= 1e7 or abs(v) < 1e-3:
        return f"{v:.{digits - 1}e}"
    if abs(v) >= 100:
        return f"{v:,.0f}"
    return f"{v:.{digits}g}"


def label(row):
    if row["method"] == "lightcuts":
        return f"lightcuts-{row['mode']}-{fmt(row['error'])}"
    return row["method"]


def read_sweep(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def gnuplot(script, variables):
    args = ["gnuplot"]
    for k, v in variables.items():
        args += ["-e", f"{k}='{v}'"]
    subprocess.run(args + [os.path.join(HERE, "charts", script)], check=True)


def plotted_error(row):
    # Log axes cannot show an exact zero: such points sit at 1e-5, the left edge.
    return max(number(row["p99_rel_error"]), 1e-5)


def charts(rows, settings, docs):
    out_dir = os.path.join(docs, "charts")
    os.makedirs(out_dir, exist_ok=True)
    made = []
    layouts = list(dict.fromkeys(r["layout"] for r in rows))
    floor = min(number(r["floor_ms"]) for r in rows)
    setting = f"{settings['width']}x{settings['height']}, median of {settings['repeats']}"
    with tempfile.TemporaryDirectory() as data:
        for layout in layouts:
            mine = [r for r in rows if r["layout"] == layout and not r["failure"]]
            # The counts measured for this layout (an interrupted sweep may lack some).
            counts = sorted({int(r["lights"]) for r in mine})
            for n in counts:
                at = [r for r in mine if int(r["lights"]) == n]
                base = os.path.join(data, f"{layout}-{n}")
                for mode in ("node", "total"):
                    pts = sorted((number(r["error"]), r) for r in at
                                 if r["method"] == "lightcuts" and r["mode"] == mode)
                    with open(f"{base}-{mode}.dat", "w") as f:
                        for eps, r in pts:
                            f.write(f"{plotted_error(r)} {r['render_ms']} ε={fmt(eps)}\n")
                with open(f"{base}-distance.dat", "w") as f:
                    for r in at:
                        if r["method"] == "lightcuts-distance":
                            f.write(f"{plotted_error(r)} {r['render_ms']}\n")
                with open(f"{base}-reference.dat", "w") as f:
                    for r in at:
                        if r["method"] == "reference":
                            f.write(f"{r['render_ms']}\n")
                with open(f"{base}-octree.dat", "w") as f:
                    for r in at:
                        if r["method"] == "octree":
                            f.write(f"{plotted_error(r)} {r['render_ms']}\n")
            series = {
                "reference": lambda r: r["method"] == "reference",
                "node": lambda r: r["method"] == "lightcuts" and r["mode"] == "node"
                and number(r["error"]) == 0.02,
                "total": lambda r: r["method"] == "lightcuts" and r["mode"] == "total"
                and number(r["error"]) == 0.02,
                "distance": lambda r: r["method"] == "lightcuts-distance",
                "octree": lambda r: r["method"] == "octree",
            }
            for name, keep in series.items():
                with open(os.path.join(data, f"{layout}-scaling-{name}.dat"), "w") as f:
                    for r in sorted((r for r in mine if keep(r)), key=lambda r: int(r["lights"])):
                        f.write(f"{r['lights']} {r['render_ms']}\n")
            for kind, extra in (("frontier", {"counts": " ".join(map(str, counts))}),
                                ("scaling", {"floor": floor})):
                png = os.path.join(out_dir, f"{kind}-{layout}.png")
                gnuplot(f"{kind}.gp", {"dir": data, "layout": layout, "out": png,
                                       "setting": setting, **extra})
                made.append(png)
    return made


def frontier_table(rows, n):
    lines = ["| layout | method | render ms | × reference | relative error max | p99 | "
             "pixels > 1 code off | mean cut | pixels at max cut |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if int(r["lights"]) != n:
            continue
        cuts = r["method"] not in ("reference", "octree")  # the methods without cuts
        cut = fmt(r["avg_cut"]) if cuts else "—"
        at_max = r["pixels_at_max_cut"] if cuts else "—"
        speed = number(r["ratio_to_reference"])
        lines.append(
            f"| {r['layout']} | {label(r)} | {fmt(r['render_ms'])} | "
            f"{fmt(1 / speed) + '× faster' if speed > 0 and speed < 1 else fmt(speed) + '× slower' if speed > 1 else '1'} | "
            f"{fmt(r['max_rel_error'])} | {fmt(r['p99_rel_error'])} | "
            f"{fmt(100 * number(r['share_off_gt_1_code']))}% | {cut} | {at_max} |")
    return "\n".join(lines)


def max_cut_line(rows, settings):
    # Rows merged from several runs (bench/merge_results.py) may differ in --max-cut.
    by_cut = {}
    for r in rows:
        if r["method"] not in ("reference", "octree") and r.get("max_cut"):
            by_cut.setdefault(int(r["max_cut"]), []).append(r["layout"])
    if len(by_cut) <= 1:
        return f"{next(iter(by_cut), settings.get('max_cut', 1000))} nodes"
    return " and ".join(f"{cut} nodes ({', '.join(dict.fromkeys(layouts))})"
                        for cut, layouts in sorted(by_cut.items(), reverse=True))


def measured_lines(settings):
    # What bench/merge_results.py recorded: which cases a later run re-measured.
    return [f"- Measured: {', '.join(m['cases'])}: {m['note']}"
            for m in settings.get("measured", [])]


def benchmarks_page(rows, settings, made, docs, peers):
    counts = sorted({int(r["lights"]) for r in rows})
    focus = 65536 if 65536 in counts else counts[-1]
    sampled = sorted({(r["case"], fmt(r["reference_row_share"])) for r in rows
                      if r["method"] == "reference" and number(r["reference_row_share"]) < 1})
    rel = lambda p: os.path.relpath(p, docs)
    floors = sorted({number(r["floor_ms"]) for r in rows})
    out = [
        "# Benchmarks: speed against accuracy",
        "",
        "Generated by `bench/sweep.sh` (bench/report.py) from `docs/results/sweep.csv`; do not "
        "edit by hand.",
        "",
    ] + measured_lines(settings) + [
        f"- Image {settings['width']}×{settings['height']}, {settings['gl_renderer']}, "
        f"{settings['hardware_threads']} hardware threads; render_ms is the median of "
        f"{settings['repeats']} frames after a warm-up, G-buffer and lighting, bracketed by "
        "glFinish.",
        "- The 1-light floor (reference method, one light: a frame with almost no lighting) "
        "is " + " and ".join(f"{fmt(f)} ms" for f in floors) +
        (" (measured anew by each run that added rows; ratio_to_floor uses its own run's)"
         if len(floors) > 1 else "") + ".",
        "- Lightcuts' maximum cut is " + max_cut_line(rows, settings) + ".",
        "- Errors are against the reference method on the same view, over covered pixels: per "
        "pixel the largest channel difference over the largest reference channel; the 8-bit "
        "figures compare the PNG codes with OpenImageIO's ImageBufAlgo::compare.",
    ]
    if sampled:
        out.append("- References estimated over " + str(int(settings["reference_seconds"])) +
                   " s lit only a share of rows (every k-th band of 8), and their time is scaled "
                   "up: " + ", ".join(f"{c} ({s} of rows)" for c, s in sampled) + ". Errors in "
                   "those cases cover the lit rows only.")
    out += ["", f"## The frontier at {focus:,} lights", "", frontier_table(rows, focus), ""]
    out += ["## Charts", ""]
    for p in made:
        out += [f"![{os.path.basename(p)}]({rel(p)})", ""]
    if peers:
        out += ["## Peers: whole process against whole process", "", peers_table(peers), ""]
    out += ["## Every run", "", "The CSV beside the charts has every figure; in short:", "",
            "| case | method | render ms | evals/px (lights, nodes) | max rel | p99 | RMSE 8-bit "
            "| PSNR dB | bake ms | peak MB |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(
            f"| {r['case']} | {label(r)} | {fmt(r['render_ms'])} | "
            f"{fmt(r['light_evals_per_px'])}, {fmt(r['node_evals_per_px'])} | "
            f"{fmt(r['max_rel_error'])} | {fmt(r['p99_rel_error'])} | {fmt(r['rmse_8bit'])} | "
            f"{fmt(r['psnr_8bit'])} | {fmt(r['bake_ms'])} | {fmt(r['peak_rss_mb'])} |"
            + (f" failed: {r['failure']}" if r["failure"] else ""))
    with open(os.path.join(docs, "benchmarks.md"), "w") as f:
        f.write("\n".join(out) + "\n")


def peers_table(peers):
    lines = ["| tool | lights | whole process s | result |", "|---|---|---|---|"]
    for p in peers:
        lines.append(f"| {p['tool']} | {int(p['lights']):,} | {fmt(p['seconds'])} | {p['result']} |")
    return "\n".join(lines)


# Why a method is the worst in a case: by case, then by method ("*": any case).
WHY = {
    ("*", "lightcuts-distance"):
        "the distance criterion stops refining once a pixel is outside a node's radius of "
        "influence, whatever the node's power, so nothing bounds its error.",
    ("*", "lightcuts-node"):
        "the node rule bounds each cut node's error by ε of the estimate but not their sum, "
        "so a cut of many nodes just under the threshold adds up to several ε.",
    ("*", "lightcuts-total"):
        "the total rule guarantees ε only where the cut converges; pixels at the maximum cut "
        "keep the last pass that fitted, with no bound.",
    ("*", "reference"): "it is the reference; its own error is zero by definition.",

    ("coincident", "lightcuts-node"):
        "every light is at one point, so a node's representative stands exactly for the rest; "
        "the far field's remainders, summed per bin of directions, keep the error within ε: "
        "what is left is the compact node colours and the linear far field.",
    ("two-groups", "lightcuts-distance"):
        "each group is one tight cluster far from most of the room, so the distance criterion "
        "never opens it and one representative light stands for thousands of colours.",
    ("wide-intensities", "lightcuts-distance"):
        "the criterion ignores intensity, so a bright light inside a dim node is estimated "
        "by the node's representative, which is usually another light.",
    ("bright-among-dim", "lightcuts-distance"):
        "the bright light is averaged into the clusters around it by distance alone, so pixels "
        "it dominates take a dim neighbour's position.",
    ("far", "lightcuts-distance"):
        "seen from 1e5 units every node is outside its radius of influence, so the root's "
        "representative lights the whole image from one direction.",
    ("spots-away", "lightcuts-distance"):
        "the criterion has no cone term: a node's representative lights pixels with the "
        "node's total intensity although almost every spot faces away from them (the "
        "reference is nearly black: only the back wall catches a little light).",
    ("on-surfaces", "lightcuts-node"):
        "shading points sit inside the boxes of small clusters, whose bounds are unbounded "
        "until a leaf; the node rule then stops on many nodes each just under ε.",
    ("max-cut-16", "lightcuts-distance"):
        "cut off at 16 nodes, the distance criterion keeps the first clusters whose radius of "
        "influence covers the pixel, and a handful of representatives stand for 16,384 lights.",
    ("max-cut-16", "lightcuts-total"):
        "16 nodes cannot meet the total rule anywhere, so every pixel keeps an unconverged cut.",
    ("max-cut-16", "lightcuts-node"):
        "16 nodes are far too few for the node rule too; the cut stops where the budget ends.",
}


def why(case, run):
    method_label, max_error = run["label"], run["max_rel_error"]
    if max_error is not None and max_error < 1e-3:
        return ("every method is exact here up to float rounding and the compact node colours "
                "(≤ 0.2%); the \"worst\" differs from the reference by that alone.")
    if (method_label.startswith("lightcuts-total") and max_error is not None
            and not run["pixels_at_max_cut"] and max_error <= run["error"]):
        return (f"within the total rule's guarantee: where the summed bound allows, a node's "
                f"representative stands for several lights, and no pixel is off by more than "
                f"ε = {run['error']:.2g}.")
    family = "lightcuts-node" if method_label.startswith("lightcuts-node") else \
        "lightcuts-total" if method_label.startswith("lightcuts-total") else method_label
    layout = case.rsplit("-", 1)[0] if case[-1].isdigit() and not case.startswith(("count-", "max-cut")) \
        else case
    return WHY.get((layout, family)) or WHY.get((case, family)) or WHY[("*", family)]


def stability_page(stability, docs):
    s = stability
    runs = s["runs"]
    cases = list(dict.fromkeys(r["case"] for r in runs))
    out = [
        "# Stability: where methods fail",
        "",
        "Generated by `bench/sweep.sh` (bench/report.py) from `docs/results/stability.json`; "
        "do not edit by hand.",
        "",
    ] + measured_lines(s) + ([""] if s.get("measured") else []) + [
        f"Every adversarial case below was rendered by every method at {s['width']}×{s['height']} "
        f"on {s['gl_renderer']} and compared with the reference method on the same view "
        "(errors: per pixel, largest channel difference over the largest reference channel, "
        "floored at 1e-6; see docs/benchmarks.md). \"Broke\" lists exceptions, NaN or infinite "
        "pixels, and pixels whose cut reached the maximum.",
        "",
        "| case | worst method | its max error | why |",
        "|---|---|---|---|",
    ]
    details = []
    for case in cases:
        mine = [r for r in runs if r["case"] == case]
        others = [r for r in mine if r["method"] != "reference"]

        def badness(r):
            if r["failure"] or r["non_finite_pixels"]:
                return (1, 0, 0)
            return (0, r["max_rel_error"] if r["max_rel_error"] is not None else math.inf,
                    r["p99_rel_error"] or 0)
        worst = max(others, key=badness) if others else mine[0]
        out.append(f"| {case} | {worst['label']} | {fmt(worst['max_rel_error'])} | "
                   f"{why(case, worst)} |")
        details += [f"### {case}", "",
                    "| method | max rel | p99 | max abs | > 1 code off | mean cut | at max cut | "
                    "ms | broke |", "|---|---|---|---|---|---|---|---|---|"]
        for r in mine:
            broke = []
            if r["failure"]:
                broke.append(r["failure"])
            if r["non_finite_pixels"]:
                broke.append(f"{r['non_finite_pixels']} NaN/inf pixels")
            if r.get("pixels_at_max_cut"):
                broke.append(f"{r['pixels_at_max_cut']} pixels at max cut")
            rows_note = "" if r["reference_row_share"] >= 1 else \
                f" (rows: {fmt(r['reference_row_share'])})"
            details.append(
                f"| {r['label']} | {fmt(r['max_rel_error'])} | {fmt(r['p99_rel_error'])} | "
                f"{fmt(r['max_abs_error'])} | {fmt(100 * r['share_off_gt_1_code'])}% | "
                f"{fmt(r.get('avg_cut'))} | {r.get('pixels_at_max_cut', '—')} | "
                f"{fmt(r['render_ms'])}{rows_note} | {'; '.join(broke) or 'nothing'} |")
        details.append("")
    out += ["", "## Temporal stability", ""]
    temporal = s.get("temporal", [])
    if temporal:
        out += [f"A {temporal[0]['frames']}-frame turntable of {temporal[0]['case']}: per pixel, "
                "the change from one frame to the next of (method − reference), largest "
                "channel, relative to the pixel's largest reference channel in either frame "
                "(floored at 1% of the frame's mean brightness). A method whose cuts jump between "
                "frames pops; an exact one shows 0. Pixels that move onto another surface "
                "count too, so only the comparison between methods means much.", "",
                "| method | mean change | max change | broke |", "|---|---|---|---|"]
        for t in temporal:
            out.append(f"| {t['label']} | {fmt(t['mean_change'])} | {fmt(t['max_change'])} | "
                       f"{t['failure'] or 'nothing'} |")
    else:
        out.append("Not measured in this run (`--frames 0`).")
    out += ["", "## Each case", ""] + details
    with open(os.path.join(docs, "stability.md"), "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: bench/report.py RESULTS_DIR DOCS_DIR")
    results, docs = sys.argv[1], sys.argv[2]
    os.makedirs(docs, exist_ok=True)
    with open(os.path.join(results, "sweep.json")) as f:
        settings = json.load(f)
    rows = read_sweep(os.path.join(results, "sweep.csv"))
    peers = []
    peers_path = os.path.join(results, "peers.csv")
    if os.path.exists(peers_path):
        with open(peers_path, newline="") as f:
            peers = list(csv.DictReader(f))
    made = charts(rows, settings, docs)
    benchmarks_page(rows, settings, made, docs, peers)
    stability_path = os.path.join(results, "stability.json")
    if os.path.exists(stability_path):
        with open(stability_path) as f:
            stability_page(json.load(f), docs)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Replaces some runs of a `manylight bench` result with those of a newer run.

  bench/merge_results.py RESULTS.json RESULTS.csv NEW.json NEW.csv "NOTE"

`manylight bench --resume` keeps only runs of the same build. When a change makes some
runs stale (a sweep's layout, one rule's rows, a stability case), those are re-measured alone
(`manylight bench --layouts ... --methods ...` or `--cases ...` into NEW.json and NEW.csv) and
merged here: every run in NEW replaces the run of that case and label (reference,
lightcuts-node-0.01, octree...) in RESULTS (JSON runs and CSV rows), runs only in RESULTS are
kept, and the JSON's top-level settings become NEW's. Each merge appends {"cases", "note"} to
the JSON's "measured" list, which bench/report.py prints, so the pages say which rows came
from which run. RESULTS's other keys (a stability run's "temporal") stay.
"""
import json
import sys


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__.strip().splitlines()[2].strip())
    old_json, old_csv, new_json, new_csv, note = sys.argv[1:]
    with open(old_json) as f:
        old = json.load(f)
    with open(new_json) as f:
        new = json.load(f)
    fresh = list(dict.fromkeys(r["case"] for r in new["runs"]))
    merged = {k: v for k, v in old.items() if k not in ("runs", "measured")}
    merged.update({k: v for k, v in new.items() if k not in ("runs", "measured", "temporal")})
    merged["runs"] = replace(old["runs"], new["runs"], lambda r: (r["case"], r["label"]))
    merged["measured"] = old.get("measured", []) + [{"cases": fresh, "note": note}]
    # CSV rows as written; a row's run is its case, method, mode and error (the label's parts;
    # names have no commas).
    with open(old_csv) as f:
        old_lines = f.read().splitlines()
    with open(new_csv) as f:
        new_lines = f.read().splitlines()
    fields = lambda line: tuple(line.split(",")[i] for i in (0, 3, 4, 5))
    lines = [new_lines[0]] + replace(old_lines[1:], [n for n in new_lines[1:] if n], fields)
    with open(old_csv, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(old_json, "w") as f:
        f.write(json.dumps(merged, indent=1, sort_keys=True, ensure_ascii=False) + "\n")


def replace(old, new, key):
    # Old items in their order, each replaced by the new one of its key; a new item whose key
    # is not among the old goes after the last item of its case (key[0]), or at the end.
    fresh = {key(n): n for n in new}
    out = [fresh.pop(key(o), o) for o in old]
    for n in new:
        if key(n) not in fresh:
            continue
        del fresh[key(n)]
        last = max((i for i, o in enumerate(out) if key(o)[0] == key(n)[0]), default=len(out) - 1)
        out.insert(last + 1, n)
    return out


if __name__ == "__main__":
    main()

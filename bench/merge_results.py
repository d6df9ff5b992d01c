#!/usr/bin/env python3
"""Replaces some cases of a `manylight bench` result with those of a newer run.

  bench/merge_results.py RESULTS.json RESULTS.csv NEW.json NEW.csv "NOTE"

`manylight bench --resume` keeps only runs of the same build. When a change makes some
cases stale (a sweep's layout, a stability case), those are re-measured alone
(`manylight bench --layouts ...` or `--cases ...` into NEW.json and NEW.csv) and merged here:
every case in NEW replaces the case of that name in RESULTS (JSON runs and CSV rows), cases
only in RESULTS are kept, and the JSON's top-level settings become NEW's. Each merge appends
{"cases", "note"} to the JSON's "measured" list, which bench/report.py prints, so the pages
say which rows came from which run. RESULTS's other keys (a stability run's "temporal") stay.
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
    # Old runs in their order, a replaced case's runs where its first old run stood.
    runs, placed = [], set()
    for r in old["runs"]:
        if r["case"] in fresh:
            if r["case"] not in placed:
                runs += [n for n in new["runs"] if n["case"] == r["case"]]
                placed.add(r["case"])
        else:
            runs.append(r)
    runs += [n for n in new["runs"] if n["case"] not in placed]
    merged["runs"] = runs
    merged["measured"] = old.get("measured", []) + [{"cases": fresh, "note": note}]
    # CSV rows as written, by their first field (the case; names have no commas).
    with open(old_csv) as f:
        old_lines = f.read().splitlines()
    with open(new_csv) as f:
        new_lines = f.read().splitlines()
    case = lambda line: line.split(",", 1)[0]
    lines, placed = [new_lines[0]], set()
    for line in old_lines[1:]:
        if case(line) in fresh:
            if case(line) not in placed:
                lines += [n for n in new_lines[1:] if case(n) == case(line)]
                placed.add(case(line))
        else:
            lines.append(line)
    lines += [n for n in new_lines[1:] if case(n) not in placed and n]
    with open(old_csv, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(old_json, "w") as f:
        f.write(json.dumps(merged, indent=1, sort_keys=True, ensure_ascii=False) + "\n")


if __name__ == "__main__":
    main()

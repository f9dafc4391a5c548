#!/usr/bin/env python3
"""Per structure, how a second run's surfaces differ from a first's: enclosed volume (against
each other and against the contours' slab volume), triangles, and whether the topology stayed
(closed, manifold, oriented, same genus and components). The contours' volume is the report's
contour_volume, before any share given up to an incidental neighbour. Reads two JSON reports of the CLI, for
example --no-simplify against the defaults (simplified):

  build/cli/scansurf SET.json -o A --no-simplify --report A.json && build/cli/scansurf SET.json -o B --report B.json
  tests/bench/report_diff.py A.json B.json [--rows N]
"""
import argparse
import json
import sys


def rows_of(first, second):
    out = []
    for a, b in zip(first["features"], second["features"]):
        if a["name"] != b["name"]:
            sys.exit(f"report_diff: the reports list different features ({a['name']} against {b['name']})")
        if a["triangles"] == 0:
            continue
        same_topology = (a["genus"], a["components"]) == (b["genus"], b["components"]) and all(
            b[k] for k in ("closed", "manifold", "oriented"))
        out.append({
            "name": a["name"], "volume": a["surface_volume"], "second_volume": b["surface_volume"],
            "change": 100 * (b["surface_volume"] - a["surface_volume"]) / a["surface_volume"],
            "against_contours": 100 * (b["surface_volume"] - a["contour_volume"]) / a["contour_volume"],
            "triangles": a["triangles"], "second_triangles": b["triangles"], "same_topology": same_topology})
    return out


def show(row):
    return (f"  {row['name']:<18} {row['volume']:12.1f} -> {row['second_volume']:12.1f} ({row['change']:+.3f} %; "
            f"{row['against_contours']:+.3f} % of the contours'), triangles {row['triangles']} -> {row['second_triangles']}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("first")
    parser.add_argument("second")
    parser.add_argument("--rows", type=int, default=5, help="how many structures to list in each group")
    args = parser.parse_args()
    with open(args.first) as f, open(args.second) as g:
        rows = rows_of(json.load(f), json.load(g))
    kept = sum(r["same_topology"] for r in rows)
    print(f"{len(rows)} structures; topology kept by {kept}; largest volume change "
          f"{max(abs(r['change']) for r in rows):.3f} %")
    print("largest volume changes:")
    for row in sorted(rows, key=lambda r: -abs(r["change"]))[:args.rows]:
        print(show(row))
    print("smallest structures:")
    for row in sorted(rows, key=lambda r: r["volume"])[:args.rows]:
        print(show(row))
    for row in rows:
        if not row["same_topology"]:
            print(f"  topology changed: {row['name']}")
    return 0 if kept == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())

"""What a long run's CSV (`soak simulate --csv`, `soak view --csv`) holds:
per body, its rows, any value that is not finite, and its ledgers over the
run's second half: speed, height, kinetic energy per kilogram, the liquid
soaked into its surface and inside it.
    python3 scripts/long_run/ledger.py RUN.csv"""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
bodies = {}
for r in rows:
    bodies.setdefault(r["body"], []).append(r)
if not bodies:
    print("no rows")
for name, rs in bodies.items():
    bad = sum(1 for r in rs for k, v in r.items() if k != "body" and not math.isfinite(float(v)))
    half = rs[len(rs) // 2:]
    speed = [math.sqrt(sum(float(r[k]) ** 2 for k in ("vx_m_s", "vy_m_s", "vz_m_s"))) for r in half]
    height = [float(r["y_m"]) for r in half]
    soaked = [1e3 * float(r["surface_liquid_m3"]) for r in half]
    inside = [float(r["liquid_inside_m3"]) for r in rs]
    print(f"{name}: {len(rs)} rows to t = {rs[-1]['t_s']} s, {bad} not finite; over the second half: "
          f"speed at most {max(speed):.3f} m/s (kinetic {0.5 * max(speed) ** 2:.3f} J/kg), "
          f"height {min(height):.3f} to {max(height):.3f} m, "
          f"soaked {min(soaked):.2f}–{max(soaked):.2f} L; inside at most {max(inside):.3f} m³")

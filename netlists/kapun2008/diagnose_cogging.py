"""Issue #6 x #5: `diagnose` on a BLDC record whose netlist omits cogging.

    python netlists/kapun2008/diagnose_cogging.py      # ~18 min on 2 cores

The "measured" record is the torque test of bldc.yaml (0.6 s from rest, 10 kHz, speed only,
white noise 0.05 rad/s). The netlist under test is the same motor without its cogging
component (the L_rr harmonics k = 3, 6 -> orders 18 and 36 per turn; the 1-per-turn unbalance
stays). The diagnosis must find `cogging` with the right orders from the residual's order
spectrum (the speed rises during the record, so orders come from the angle domain).
"""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

import circuitsim as cs
from circuitsim.loop.diagnose import diagnose
from circuitsim.loop.record import Record
from circuitsim.netlist import build

HERE = Path(__file__).resolve().parent


def main() -> int:
    warnings.simplefilter("ignore")
    full = cs.load(HERE / "bldc.yaml")
    model = cs.compile(full)
    t = np.linspace(0, 0.6, 6001)
    res = model.simulate(stop=0.6, t_eval=t, rtol=1e-8, atol=1e-10)
    rng = np.random.default_rng(0)
    rec = Record(t, {"omega": res["omega"] + rng.normal(0, 0.05, t.size)}, "bldc synthetic")
    raw = full.raw.copy()
    raw.comps = [c for c in raw.comps if str(c[0]["name"]) != "Cog"]
    raw.probes.pop("T_cogg", None)
    t0 = time.time()
    d = diagnose(build(raw), rec, probes=["omega"],
                 progress=lambda m: print(m) if ("SSE" in m or "accept" in m) else None)
    print(f"{time.time() - t0:.0f} s")
    print(d.summary())
    for a in d.effects:
        print(f"  {a.effect} on {a.target}: {a.parameters}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""
A tank under a record, from a namelist file
===========================================

The example input ``data/examples/tank_seismic.nml`` (a 10 m wide tank holding 6 m of water
under the project's synthetic record scaled to Sa = 0.2 g at its sloshing period) read by the
executable's own reader, then run from Python: the same numbers as ``sloshdyn
data/examples/tank_seismic.nml``. Drawn: the ground acceleration, the wave height at the wall
with the roof, the base shear and the overturning moment, in SI units.
"""

import sys
from pathlib import Path

import sloshdyn

# the repository's example inputs, found from this script's place (docs/...)
DATA = Path(sys.argv[0]).resolve().parents[2] / "data" / "examples"

inp = sloshdyn.read_namelist(DATA / "tank_seismic.nml")
print(inp.tank)
print(inp.ground_motion)
r = sloshdyn.seismic_response(inp.tank, inp.ground_motion)
print(f"peak wave height {r.peaks['wave_height'][0]:.4f} m at {r.peaks['wave_height'][1]:.3f} s;"
      f" roof reached: {r.roof_reached}")
fig = sloshdyn.plotting.seismic(r)

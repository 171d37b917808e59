"""
A tank's response map under harmonic shaking
============================================

The steady wave of a tank under harmonic ground motion on a grid of frequency [Hz] and peak
ground acceleration [g]: each point the steady state from rest of
``tank.parameters(GroundMotion.harmonic(a, f))``, computed on Dask (two worker threads) and
returned as an xarray Dataset with units in its attributes. Where ``max |x1|`` reaches 1 the
pendulum reaches θ0: the liquid hits the roof.
"""

import tempfile

import numpy as np

import sloshdyn

tank = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                     tank_mass=5e4, support_frequency=2.0, support_damping=0.02)
frequencies = np.linspace(0.22, 0.38, 17)        # [Hz]; the sloshing frequency is 0.299 Hz
accelerations = [0.01, 0.03, 0.1, 0.3]           # [g]
quick = sloshdyn.Steady(transient_periods=100, settle_tol=0, window_periods=20)
with tempfile.TemporaryDirectory() as folder:
    ds = sloshdyn.response_map(tank, frequencies, accelerations, store=f"{folder}/map.zarr",
                               steady=quick, workers=2, progress=False)
    print(ds.max_x1.attrs)
    print("roof reached at", int(ds.roof_impact.sum()), "of", ds.roof_impact.size, "points")
    fig = sloshdyn.plotting.response_map(ds)

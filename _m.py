import numpy as np, rotorsim as rs, math, sys
sys.path.insert(0, "tests/analyses/transient")
from rotorsim.io.model_file import load_model
from rotorsim.analyses.transient.speed_profile import LinearSpeed
model = load_model("models/rolling_ball.toml")
rotor = model.rotor.with_nonlinear(model.rolling_bearings)
for method, t_end, dt, red in [("newmark", 0.004, 2e-5, None), ("adams", 0.001, 2e-6, None), ("newmark", 0.004, 2e-5, 8)]:
  for speed in ["c", "r"]:
    sch = 300.0 if speed == "c" else LinearSpeed(0.0, 500.0, 0.0, t_end)
    kw = dict(speed=sch, nodes=[5], unbalance=[(5, 1e-5, 0.0)], method=method, reduction=red)
    full = rs.transient(rotor, t_end, dt, **kw)
    half = rs.transient(rotor, t_end/2, dt, **kw)
    rest = rs.transient(rotor, t_end, dt, initial=half, **kw)
    sel = full.t >= t_end/2 - dt/4
    print(method, speed, red, "q rel %.2e" % (np.abs(full.q[sel]-rest.q).max()/np.abs(full.q).max()),
          "motion rel %.2e" % (np.abs(full.q[sel]-rest.q).max()/np.ptp(full.q[:, full.column(5,'uy')])),
          "loads rel %.2e" % (np.abs(full.bearing_loads[sel]-rest.bearing_loads).max()/np.abs(full.bearing_loads).max()))
from test_run_control import jeffcott, jeffcott_response, stop_revolution, WN, ZETA, ME
W, rtol, revs = 0.6 * WN, 1e-3, 3
period = 2*np.pi/W
res = rs.transient(jeffcott(), 80 * period, period / 400, speed=W, unbalance=[(0, ME, 0.0)], excitation=rs.Excitation(gravity=None), initial="zero", steady=rs.SteadyStop(rtol=rtol, revolutions=revs))
z = jeffcott_response(res.t, W)
exact = stop_revolution(res.t, np.column_stack([z.real, z.imag]), W, rtol, revs)
Z = abs(jeffcott_response(np.array([1e3]), W)[0]); A0 = abs(jeffcott_response(np.array([0.0]), W)[0] - Z)
t_sure = math.log(4 * 2 * A0 / (rtol * 2 * Z)) / (ZETA * WN) + (revs + 2) * period
print("jeffcott stop rev", res.stopped["revolution"], "exact", exact, "t", res.t[-1], "t_sure", t_sure, "change", res.stopped["relative_change"], "A0/Z", A0/Z)
x = np.column_stack([z.real, z.imag])
print("max err vs exact %.2e of |Z|" % (np.abs(res.q[:, :2] - x).max()/Z))

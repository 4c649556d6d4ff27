"""Plain-text summaries of results for the terminal (critical speeds, log decs, peaks)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

SPEED_UNITS = {"rad/s": 1.0, "rpm": 30.0 / np.pi, "Hz": 1.0 / (2.0 * np.pi)}


def table(rows: Sequence[Sequence[object]], header: Sequence[str]) -> str:
    """Right-aligned text table.

    Examples
    --------
    >>> print(table([(1, "a")], ("n", "name")))
    n  name
    -------
    1     a
    """
    cells = [[str(h) for h in header], *[[str(c) for c in row] for row in rows]]
    widths = [max(len(row[i]) for row in cells) for i in range(len(header))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(row, widths, strict=True)) for row in cells]
    return "\n".join([lines[0], "-" * len(lines[0]), *lines[1:]])


def _fixed(value: float, digits: int) -> str:
    """``value`` with ``digits`` decimals and no negative zero ("-0.0000" reads as a sign)."""
    return f"{round(float(value), digits) + 0.0:.{digits}f}"


def speed_factor(units: str) -> float:
    """Factor from rad/s to ``units`` (``SPEED_UNITS``)."""
    try:
        return SPEED_UNITS[units]
    except KeyError:
        raise ValueError(f"unknown units {units!r}; use one of {list(SPEED_UNITS)}") from None


def modal_summary(result: Any, units: str = "Hz") -> str:
    f = speed_factor(units)
    rows = [(i, f"{result.wn[i] * f:.3f}", f"{result.wd[i] * f:.3f}",
             _fixed(result.damping_ratio[i], 4), _fixed(result.log_dec[i], 4), result.whirl[i],
             result.kind[i]) for i in range(result.num_modes)]
    head = (f"modes at {result.speed * f:.4g} {units}; rigid-body modes: "
            f"{result.rigid_body_modes}")
    body = head + "\n" + table(rows, ("mode", f"wn [{units}]", f"wd [{units}]", "zeta",
                                      "log dec", "whirl", "kind"))
    return "\n".join([body, *(f"note: {n}" for n in getattr(result, "notes", ()))])


def critical_speeds_summary(crit: Any, units: str = "rpm", title: str = "") -> str:
    f = speed_factor(units)
    kinds = getattr(crit, "kind", None)
    excitation = getattr(crit, "excitation", None)
    rows = []
    for i in range(len(crit.speed)):
        if kinds is not None and kinds[i] != "lateral":
            continue
        log_dec = crit.log_dec[i]
        row = (f"{crit.speed[i] * f:.1f}", f"{crit.frequency[i] * f:.1f}", crit.whirl[i],
               "-" if not np.isfinite(log_dec) else f"{log_dec:.4f}")
        rows.append(row if excitation is None else (*row, f"{excitation[i]:.3f}"))
    spool = getattr(crit, "options", {}).get("spool")
    head = title or (f"{crit.harmonic:g}X critical speeds" + (
        f" of spool {spool} (reference speed; 'excited' = how strongly its unbalance drives "
        "the mode, 0 to 1)" if spool else ""))
    if not rows:
        return head + ": none in range"
    columns = (f"speed [{units}]", f"frequency [{units}]", "whirl", "log dec")
    return head + "\n" + table(rows, columns if excitation is None else (*columns,
                                                                          "excited"))


def campbell_summary(result: Any, units: str = "rpm",
                     harmonics: Sequence[float] = (1.0,)) -> str:
    f = speed_factor(units)
    parts = [f"Campbell: {len(result.speeds)} speeds from {result.speeds[0] * f:.4g} to "
             f"{result.speeds[-1] * f:.4g} {units}, {result.wd.shape[1]} tracked modes"]
    failed = int(np.sum(np.asarray(result.status) != 0))
    if failed:
        parts.append(f"{failed} speeds failed (status recorded)")
    lowest = float(np.nanmin(result.log_dec))
    verdict = "  (UNSTABLE)" if lowest < -1e-6 else "  (undamped mode)" if lowest < 1e-6 else ""
    parts.append(f"lowest log dec over the map: {_fixed(lowest, 4)}{verdict}")
    ratios = result.summary.get("line_speed_ratios") or {}
    spools = [name for name, r in ratios.items() if r != 0] or [None]
    for k in harmonics:
        for spool in spools:
            on = "" if spool is None else f" of spool {spool} ({ratios[spool]:g}X)"
            crit = result.critical_speeds(harmonic=k, spool=spool)
            excites = crit.options.get("excites")
            parts.append(critical_speeds_summary(
                crit, units, f"{k:g}X critical speeds{on} (damped, Campbell crossings)"
                + (f"; its unbalance excites {excites} whirl" if excites else "")))
    return "\n".join(parts + [f"note: {n}" for n in getattr(result, "notes", ())])


def response_summary(result: Any, units: str = "rpm", amplitude_units: str = "um",
                     nodes: Sequence[int] | None = None) -> str:
    head = (f"{result.kind} response: {len(result.frequencies)} points, "
            + ("peaks at the requested nodes" if nodes else "largest peaks"))
    if getattr(result, "input_ratios", None) is None:
        return head + "\n" + _peak_table(result, 0, units, amplitude_units, nodes)
    parts = [head + f" of each spool's unbalance (reference speed in {units})"]
    for k, name in enumerate(result.inputs):
        parts.append(f"{name}\n" + _peak_table(result, k, units, amplitude_units, nodes))
    return "\n".join(parts)


def _peak_table(result: Any, column: int, units: str, amplitude_units: str,
                nodes: Sequence[int] | None) -> str:
    f = speed_factor(units)
    scale = {"m": 1.0, "mm": 1e3, "um": 1e6}[amplitude_units]
    n_nodes = result.dof_map.n_nodes
    amp = np.nan_to_num(np.abs(result.response[:, :, column])).reshape(
        len(result.frequencies), n_nodes, 6)
    peak_per_node = np.hypot(amp[:, :, 0], amp[:, :, 1]).max(axis=0)
    order = list(nodes) if nodes else np.argsort(peak_per_node)[::-1][:5]
    rows = []
    for node in order:
        w_x, a_x = result.peak(int(node), "ux", column)
        w_y, a_y = result.peak(int(node), "uy", column)
        rows.append((int(node), f"{a_x * scale:.3f}", f"{w_x * f:.1f}", f"{a_y * scale:.3f}",
                     f"{w_y * f:.1f}"))
    return table(rows, ("node", f"ux [{amplitude_units}]", f"at [{units}]",
                        f"uy [{amplitude_units}]", f"at [{units}]"))


def static_summary(result: Any) -> str:
    uy = result.deflection("uy")
    ux = result.deflection("ux")
    lines = [f"static: max |ux| = {np.abs(ux).max() * 1e6:.2f} um, "
             f"max |uy| = {np.abs(uy).max() * 1e6:.2f} um"]
    if result.bearing_forces is not None:
        rows = [(int(n), *(_fixed(v, 2) for v in (fx, fy, fz)))
                for n, (fx, fy, fz) in zip(result.bearing_nodes, result.bearing_forces,
                                           strict=True)]
        lines.append(table(rows, ("bearing node", "Fx [N]", "Fy [N]", "Fz [N]")))
    moment = result.bending_moment_magnitude
    if moment is not None and np.size(moment):  # a rigid rotor has no shaft sections
        lines.append(f"max bending moment {np.max(moment):.2f} N m")
    return "\n".join(lines)


def map_summary(result: Any, units: str = "rpm") -> str:
    f = speed_factor(units)
    lines = [f"critical-speed map: {len(result.stiffness)} stiffness values "
             f"{result.stiffness[0]:.3g}..{result.stiffness[-1]:.3g} N/m"]
    rows = [(f"{k:.3g}", *(f"{w * f:.1f}" for w in row))
            for k, row in zip(result.stiffness[:: max(1, len(result.stiffness) // 6)],
                              result.critical_speeds[:: max(1, len(result.stiffness) // 6)],
                              strict=True)]
    lines.append(table(rows, ("k [N/m]", *(f"mode {j + 1} [{units}]"
                                           for j in range(result.critical_speeds.shape[1])))))
    crossings = result.intersections
    if len(crossings.speed):
        cross_rows = [(int(b), c, int(m) + 1, f"{k:.3g}", f"{w * f:.1f}")
                for b, c, m, k, w in zip(crossings.bearing, crossings.coefficient,
                                         crossings.mode, crossings.stiffness, crossings.speed,
                                         strict=True)]
        lines.append("intersections with the bearing curves")
        lines.append(table(cross_rows, ("bearing", "coef", "mode", "k [N/m]",
                                        f"speed [{units}]")))
    return "\n".join(lines)


_DOFS = ("x", "y", "z", "rx", "ry")


def _si(value: float, index: int, kind: str) -> str:
    """A displacement (um, mrad) or a load (N, N m) of relative DOF ``index``."""
    return _fixed(value * (1e6 if index < 3 else 1e3) if kind == "displacement" else value, 4)


def bearing_summary(result: Any, tag: str = "") -> str:
    """Displacement, load zone, element loads and stiffness matrix of a bearing equilibrium."""
    name = tag or result.summary.get("tag") or "bearing"
    head = (f"bearing '{name}' ({result.summary.get('bearing', '')}, {result.n_elements} "
            f"elements): loaded {result.load_zone.size}/{result.n_elements}, load zone "
            f"{np.degrees(result.load_zone_extent):.1f} deg, Qmax "
            f"{result.max_element_load:.2f} N")
    rows = [(d + (" (held)" if d in result.held_dofs else ""),
             _si(result.displacement[i], i, "displacement"), "um" if i < 3 else "mrad",
             _si(result.load[i], i, "load"), "N" if i < 3 else "N m")
            for i, d in enumerate(_DOFS)]
    parts = [head, table(rows, ("dof", "displacement", "unit", "load", "unit"))]
    elements = [(j, f"{np.degrees(result.element_angles[j]) % 360.0:.1f}",
                 f"{result.element_load[j]:.3f}", f"{np.degrees(result.contact_angle[j]):.3f}",
                 f"{result.deflection[j] * 1e6:.4f}") for j in range(result.n_elements)]
    parts.append(table(elements, ("element", "angle [deg]", "load [N]", "contact angle [deg]",
                                  "deflection [um]")))
    rows_k = ("Fx [N]", "Fy [N]", "Fz [N]", "Mx [N m]", "My [N m]")
    stiff = [(label, *(f"{result.stiffness[i, j]:.4e}" for j in range(5)))
             for i, label in enumerate(rows_k)]
    parts.append("stiffness matrix K_ij = dF_i/d delta_j: rows force [N] or moment [N m], "
                 "columns per m or per rad")
    parts.append(table(stiff, ("", *(f"{d} [{'m' if j < 3 else 'rad'}]"
                                      for j, d in enumerate(_DOFS)))))
    return "\n".join(parts + [f"note: {n}" for n in result.notes])


def stiffness_variation_summary(result: Any) -> str:
    """Mean and peak-to-peak of the direct stiffness coefficients over one element pass."""
    mean, ptp = result.mean_stiffness, result.stiffness_fluctuation
    rows = [(f"K{d}{d}", f"{mean[i, i]:.4e}", f"{ptp[i, i]:.4e}",
             f"{100 * ptp[i, i] / mean[i, i]:.2f}" if mean[i, i] else "-")
            for i, d in enumerate(_DOFS)]
    head = f"stiffness over one element pass ({result.position.size} positions)"
    return head + "\n" + table(rows, ("coefficient", "mean", "peak-to-peak", "% of mean"))


def preload_rows(rolling_bearings: Sequence[Any]) -> list[tuple[str, str]]:
    """``("preload <tag>", text)`` for each rolling bearing mounted with interference
    (negative clearance), for the model summary."""
    rows = []
    for i, element in enumerate(rolling_bearings):
        radial = float(getattr(getattr(element, "bearing", None), "clearance", 0.0) or 0.0)
        if radial < 0.0:
            rows.append((f"preload {element.tag or i}",
                         f"radial interference {-radial * 1e6:.4g} um (diametral clearance "
                         f"{2e6 * radial:.4g} um)"))
    return rows


def linearization_summary(linear: Any) -> str:
    """Loads and direct stiffness of rolling bearings linearised in a rotor."""
    kinds = {p.kind for p in linear.points}
    how = ("at their static loads" if kinds == {"static"} else "at "
           + ", ".join(sorted(kinds)) + " points")
    head = (f"rolling bearings linearised {how} ({linear.iterations} static iterations, "
            f"residual {linear.residual:.1e})")
    rows = [(tag, point.kind, *(_fixed(v, 3) for v in load),
             *(f"{k:.3e}" for k in np.diagonal(el.stiffness_matrix)[:3]))
            for tag, point, load, el in zip(linear.tags, linear.points, linear.loads,
                                            linear.bearings, strict=True)]
    return head + "\n" + table(rows, ("bearing", "at", "Fx [N]", "Fy [N]", "Fz [N]",
                                       "Mx [N m]", "My [N m]", "kxx [N/m]", "kyy [N/m]",
                                       "kzz [N/m]"))


def transient_summary(result: Any, units: str = "rpm") -> str:
    """Cost, speed range and the largest responses and bearing loads of a transient."""
    f = speed_factor(units)
    s = result.stats
    head = (f"transient ({result.method}): {int(s.get('steps', 0))} steps to "
            f"t = {result.t[-1]:.4g} s, speed {result.speed[0] * f:.1f} -> "
            f"{result.speed[-1] * f:.1f} {units}, {s.get('iterations_per_step', 0):.2f} "
            f"Newton iterations/step, {int(s.get('factorizations', 0))} factorisations, "
            f"{s.get('wall_time', 0.0):.2f} s")
    failure = (result.options or {}).get("failure")
    if failure:
        t_end = (result.options.get("t_span") or [0.0, result.t[-1]])[-1]
        head += (f"\nSTOPPED SHORT of t_end = {t_end:.4g} s (status {result.status.name}): "
                 f"{failure}")
    stopped = (result.options or {}).get("stopped")
    if stopped:
        head += f"\nstopped early at t = {stopped['t']:.4g} s: {stopped['reason']}"
    rows = []
    nodes = sorted({int(i) // 6 for i in result.dofs})
    for node in nodes:
        x, y = result.displacement(node, "ux"), result.displacement(node, "uy")
        rows.append((node, f"{x.mean() * 1e6:.3f}", f"{y.mean() * 1e6:.3f}",
                     f"{np.ptp(x) * 1e6:.3f}", f"{np.ptp(y) * 1e6:.3f}"))
    rows.sort(key=lambda r: -max(float(r[3]), float(r[4])))
    lines = [head, table(rows[:6], ("node", "mean ux [um]", "mean uy [um]", "ux p-p [um]",
                                     "uy p-p [um]"))]
    if result.bearing_loads.shape[1]:
        loads = result.bearing_loads
        radial = np.hypot(loads[:, :, 0], loads[:, :, 1])
        lines.append(table([(tag, f"{radial[:, b].min():.2f}", f"{radial[:, b].max():.2f}",
                             f"{np.abs(loads[:, b, 2]).max():.2f}")
                            for b, tag in enumerate(result.bearing_tags)],
                           ("bearing", "min |Fr| [N]", "max |Fr| [N]", "max |Fz| [N]")))
    if "max_amplitude" in result.reduced:
        amplitude = result.reduced["max_amplitude"]
        lines.append(table([(int(n), f"{a * 1e6:.3f}") for n, a in
                            zip(result.amplitude_nodes, amplitude, strict=True)],
                           ("node", "max radial amplitude [um] (every step)")))
    return "\n".join(lines)


def periodic_summary(result: Any, units: str = "rpm") -> str:
    """Points, status, stability and bifurcations of a harmonic-balance branch
    (:func:`rotorsim.cli.branch_summaries.periodic_summary`)."""
    from rotorsim.cli.branch_summaries import periodic_summary as summary

    return summary(result, units)


def quasi_periodic_summary(result: Any, units: str = "rpm") -> str:
    """Points, status and stability of a branch of tori
    (:func:`rotorsim.cli.branch_summaries.quasi_periodic_summary`)."""
    from rotorsim.cli.branch_summaries import quasi_periodic_summary as summary

    return summary(result, units)


SUMMARIES: dict[str, Callable[..., str]] = {
    "ModalResult": modal_summary,
    "CampbellResult": campbell_summary,
    "CriticalSpeeds": critical_speeds_summary,
    "FrequencyResponseResult": response_summary,
    "StaticResult": static_summary,
    "CriticalSpeedMapResult": map_summary,
    "BearingEquilibriumResult": bearing_summary,
    "StiffnessVariation": stiffness_variation_summary,
    "TransientResult": transient_summary,
    "PeriodicResult": periodic_summary,
    "QuasiPeriodicResult": quasi_periodic_summary,
}


def sweep_summary(result: Any, units: str = "rpm") -> str:
    """Points evaluated, resumed and failed, and the range of each scalar output."""
    s = result.stats
    head = (f"sweep over {', '.join(result.names)}: {result.n_points} points "
            f"({int(s.get('evaluated', 0))} evaluated, {int(s.get('resumed', 0))} resumed "
            f"from the store, {int(s.get('failed', 0))} failed), "
            f"{s.get('wall_time', 0.0):.2f} s")
    rows = []
    for name, values in result.outputs.items():
        v = np.asarray(values, dtype=float)
        if v.ndim == 1 and np.any(np.isfinite(v)):
            rows.append((name, f"{np.nanmin(v):.4g}", f"{np.nanmax(v):.4g}"))
    return head + ("\n" + table(rows, ("output", "min", "max")) if rows else "")


SUMMARIES["SweepResult"] = sweep_summary


def _api(result: Any, **options: Any) -> str:
    from rotorsim.cli.api_summaries import api_summary

    return api_summary(result, **options)


SUMMARIES["ApiLevel1Result"] = SUMMARIES["ApiUnbalanceResult"] = _api


def summarize(result: Any, **options: Any) -> str:
    """Text summary of any result type."""
    drawer = SUMMARIES.get(type(result).__name__)
    if drawer is None:
        return f"{type(result).__name__} (no summary available)"
    return drawer(result, **options)

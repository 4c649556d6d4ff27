"""Plain-text summaries of harmonic-balance branches: periodic orbits and tori."""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorsim.cli.summaries import speed_factor, table


def _largest_uy(result: Any) -> list[tuple[int, Any, int]]:
    """``(node, uy peak-to-peak over the branch, index of its largest)`` of every kept node
    with ``uy``."""
    out = []
    for node in sorted({int(i) // 6 for i in result.dofs}):
        try:
            amp = result.amplitude(node, "uy", "peak_to_peak")
        except Exception:  # a node without uy kept
            continue
        out.append((node, amp, int(np.argmax(amp))))
    return out


def quasi_periodic_summary(result: Any, units: str = "rpm") -> str:
    """Points, status, stability and stability changes of a branch of tori, and the largest
    responses of the kept nodes with their 1X and VC (or second spool's 1X) tones."""
    f = speed_factor(units)
    spools = getattr(result, "second", "vc") == "spool"
    second = (f"second spool at {result.vc_order:.6g} W" if spools
              else f"VC order {result.vc_order:.6g}")
    head = (f"quasi-periodic branch: {len(result)} points, speed {result.speed[0] * f:.1f} "
            f"-> {result.speed[-1] * f:.1f} {units}, {second}, "
            f"{len(result.tones)} tones, status {result.status.name}"
            + (f" ({result.reason})" if result.reason else ""))
    lines = [head]
    if result.approximation:
        lines.append(f"approximation: {result.approximation}")
    if result.has_stability:
        lines.append(f"stable tori: {int(result.stable.sum())} of {len(result)} (largest "
                     f"exponent {np.nanmax(result.exponents):.4g} 1/s; "
                     f"{result.stability_method})")
        checked = getattr(result, "exponents_checked", None)
        if checked is not None and not np.all(checked):
            lines.append(f"stability box grown at {int(np.sum(checked))} of {len(result)} "
                         "tori (the others: box (1, 1), converged between checked tori)")
        if not result.exponents_converged.all():
            lines.append(f"exponents not converged in the stability box at "
                         f"{int((~result.exponents_converged).sum())} points")
    rows = [(node, f"{amp[k] * 1e6:.3f}",
             f"{abs(result.tone(node, 'uy', 1, 0)[k]) * 1e6:.3f}",
             f"{abs(result.tone(node, 'uy', 0, 1)[k]) * 1e6:.4f}",
             f"{result.speed[k] * f:.6g}") for node, amp, k in _largest_uy(result)]
    rows.sort(key=lambda r: -float(r[1]))
    lines.append(table(rows[:6], ("node", "max uy p-p [um]", "1X [um]",
                                  "2nd spool 1X [um]" if spools else "VC [um]",
                                  f"at speed [{units}]")))
    if result.events:
        lines.append(table([(e.kind, f"{e.parameter * f:.6g}",
                             f"{e.exponents[0]:.4g} -> {e.exponents[1]:.4g}",
                             f"{e.lyapunov:.4g}", e.character or "-",
                             e.motion.kind if e.motion is not None else "-")
                            for e in result.events],
                           ("stability change", f"speed [{units}]", "exponent [1/s]",
                            "Lyapunov [1/s]", "character", "motion there")))
        lines += [f"motion at {e.motion.speed * f:.6g} {units}: {e.motion.summary()}"
                  for e in result.events if e.motion is not None]
    return "\n".join(lines)


def periodic_summary(result: Any, units: str = "rpm") -> str:
    """Points, status, stability and bifurcations of a harmonic-balance branch, and the
    largest responses of the kept nodes (over the speed, or over the model parameter of
    ``rs.periodic_parameter``)."""
    p = result.parameter
    if result.parameter_name in ("speed", "frequency"):
        f, label = speed_factor(units), f"{result.parameter_name} [{units}]"
        span = f"speed {result.speed[0] * f:.1f} -> {result.speed[-1] * f:.1f} {units}"
    else:   # a model parameter at a fixed speed, in SI
        f, label = 1.0, str(result.parameter_name)
        span = (f"{label} {p[0]:.6g} -> {p[-1]:.6g} at "
                f"{result.speed[0] * speed_factor(units):.1f} {units}")
    head = (f"periodic branch: {len(p)} points, {span}, H = {result.harmonics}, status "
            f"{result.status.name}" + (f" ({result.reason})" if result.reason else ""))
    lines = [head]
    if result.approximation:
        lines.append(f"approximation: {result.approximation}")
    if result.has_stability:
        lines.append(f"stable points: {int(result.stable.sum())} of {len(p)} "
                     f"({result.stability_method})")
    rows = [(node, f"{amp[k] * 1e6:.3f}", f"{p[k] * f:.6g}")
            for node, amp, k in _largest_uy(result)]
    rows.sort(key=lambda r: -float(r[1]))
    lines.append(table(rows[:6], ("node", "max uy p-p [um]", f"at {label}")))
    if result.bifurcations:
        lines.append(table([(b.kind, f"{b.parameter * f:.6g}", "yes" if b.located else "no")
                            for b in result.bifurcations],
                           ("bifurcation", label, "located")))
    unresolved = getattr(result, "unresolved", ())
    if unresolved:
        lines.append(f"not bifurcations: {len(unresolved)} sign changes of a test function "
                     "did not survive confirmation (result.unresolved says where and why)")
    return "\n".join(lines)

"""Printed summaries of the API 617 checks (``rotorsim api``, ``rotorsim run``)."""

from __future__ import annotations

from typing import Any

from rotorsim.cli.summaries import table


def api_summary(result: Any, **options: Any) -> str:
    """The API table of an ApiLevel1Result or ApiUnbalanceResult, with its notes."""
    if type(result).__name__ == "ApiLevel1Result":
        text = table(result.table(), ("API 617 Level I", "value"))
        if result.reasons:
            text += "\nLevel II required: " + "; ".join(result.reasons)
    else:
        text = table(result.table(), ("mode", "critical [rpm]", "AF", "SM req. [%]",
                                      "SM actual [%]", "margin", "max clearance ratio"))
        text += f"\nclearance ratios below 0.75 and margins met: " \
                f"{'pass' if result.passed else 'FAIL'}"
    for note in result.notes:
        text += f"\nnote: {note}"
    return text

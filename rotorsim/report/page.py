"""HTML building blocks of the report: every string is escaped, every tag closed and every
attribute quoted (the page parses as XML after its doctype), and figures are embedded as
base64 PNG data, so the file needs nothing else to display."""

from __future__ import annotations

import base64
import html
import io
from collections.abc import Sequence
from typing import Any

STYLE = """
body { font-family: sans-serif; max-width: 1100px; margin: 2em auto; color: #222; }
h1 { border-bottom: 2px solid #345; }
h2 { border-bottom: 1px solid #aaa; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: right; }
th { background: #eef; }
pre { background: #f6f6f6; padding: 0.6em; overflow-x: auto; font-size: 85%; }
img { max-width: 100%; display: block; margin: 0.5em 0; }
.source { color: #666; font-size: 85%; }
.warn { color: #a40; }
"""


def text(value: object) -> str:
    """``value`` as escaped HTML text."""
    return html.escape(str(value), quote=True)


def paragraph(value: str, cls: str | None = None) -> str:
    attr = f' class="{text(cls)}"' if cls else ""
    return f"<p{attr}>{text(value)}</p>"


def heading(level: int, value: str, anchor: str | None = None) -> str:
    attr = f' id="{text(anchor)}"' if anchor else ""
    return f"<h{level}{attr}>{text(value)}</h{level}>"


def preformatted(value: str) -> str:
    return f"<pre>{text(value)}</pre>"


def table(rows: Sequence[Sequence[object]], header: Sequence[str]) -> str:
    """An HTML table of ``rows`` under ``header``."""
    head = "".join(f"<th>{text(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{text(c)}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def figure(fig: Any, caption: str) -> str:
    """A matplotlib figure as an embedded PNG (the figure is closed)."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return (f'<figure><img src="data:image/png;base64,{data}" alt="{text(caption)}"/>'
            f"<figcaption>{text(caption)}</figcaption></figure>")


def document(title: str, body: Sequence[str]) -> str:
    """The whole page."""
    return ("<!DOCTYPE html>\n"
            '<html lang="en"><head><meta charset="utf-8"/>'
            f"<title>{text(title)}</title><style>{STYLE}</style></head>"
            f"<body>{''.join(body)}</body></html>\n")

"""The HTML of a report page: its style sheet, tables and embedded figures.

A report is one page and a ``figures/`` directory beside it, with no scripts and no network,
so it can be copied or archived as is. Every table cell is escaped here: callers pass plain
text.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from pathlib import Path

STYLE = """
body { font-family: sans-serif; margin: 2em; max-width: 1200px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: right; }
th { background: #f0f0f0; }
td.text, th.text { text-align: left; }
img { max-width: 100%; border: 1px solid #eee; margin: 0.5em 0; }
p.note { color: #666; }
div.recommendation { border: 2px solid #2ca02c; background: #f4fbf4; padding: 0.3em 1em;
  margin: 1em 0 1.5em 0; max-width: 1000px; }
div.recommendation.none { border-color: #d62728; background: #fdf4f4; }
div.recommendation li { margin: 0.3em 0; }
"""


def html_table(
    headers: Sequence[str], rows: list[list[str]], text_columns: Sequence[int] = ()
) -> str:
    """An HTML table; every cell is escaped here (callers pass plain text). Columns in
    ``text_columns`` are left-aligned, the others (numbers) right-aligned."""
    head = "".join(
        f'<th class="text">{html.escape(h)}</th>'
        if k in text_columns
        else f"<th>{html.escape(h)}</th>"
        for k, h in enumerate(headers)
    )
    body = []
    for row in rows:
        cells = "".join(
            f'<td class="text">{html.escape(c)}</td>'
            if k in text_columns
            else f"<td>{html.escape(c)}</td>"
            for k, c in enumerate(row)
        )
        body.append(f"<tr>{cells}</tr>")
    return f"<table>\n<tr>{head}</tr>\n" + "\n".join(body) + "\n</table>"


def figure_html(figures: dict[str, Path], name: str, alt: str) -> str:
    """The image of figure ``name`` by its path relative to the page (``figures/NAME.png``);
    empty when the report has no such figure."""
    if name not in figures:
        return ""
    src = f"figures/{figures[name].name}"
    return f'<p><img src="{html.escape(src)}" alt="{html.escape(alt)}"></p>'

"""Escaping for generated HTML: one function per context a value can reach.

Every value of a page that is not the page's own fixed text goes through one of these (the
strings of a results file are a user's: a study name, case labels holding a profile's path).

- :func:`text`: element content, e.g. ``<title>`` or ``<h1>``.
- :func:`attribute`: a quoted attribute value.
- :func:`script_json`: data inside an inline ``<script>``, as a JavaScript expression.
- :func:`script_code`: trusted JavaScript (a library) inlined into a ``<script>``.
"""

from __future__ import annotations

import html
import json
import re
from typing import Any

# Characters that must not appear raw in a <script>'s data: `<` and `>` (no `</script>`, no
# `<!--`), `&`, and the line and paragraph separators (line ends in older JavaScript). In a
# JSON string each is written as its \\u escape, which means the same character to JSON.parse
# and to JavaScript.
_SCRIPT_JSON_ESCAPES = {ord(c): f"\\u{ord(c):04x}" for c in "<>&\u2028\u2029"}


def text(value: Any) -> str:
    """`value` as element content: ``&``, ``<``, ``>``, quotes as character references."""
    return html.escape(str(value), quote=True)


def attribute(value: Any) -> str:
    """`value` as a double-quoted attribute value, quotes included: ``title=`` + this."""
    return f'"{html.escape(str(value), quote=True)}"'


def script_json(value: Any) -> str:
    """`value` as JSON to write inside ``<script>…</script>``: nothing in it can end the
    script or open a comment, whatever its strings hold. NaN is refused (use None)."""
    return json.dumps(value, allow_nan=False).translate(_SCRIPT_JSON_ESCAPES)


def script_code(code: str) -> str:
    """Trusted JavaScript to inline in ``<script>…</script>``: ``</script`` and ``<!--``
    become ``<\\/script`` and ``<\\!--`` (the same JavaScript in strings and regular
    expressions), so that the HTML parser cannot end the script early."""
    return re.sub(r"<(/script|!--)", r"<\\\1", code, flags=re.IGNORECASE)

"""The self-contained page of a drawing: one HTML file that shows and animates it offline.

The studio's own page (``static/index.html``, ``studio.css``, ``studio.js``) with everything it would fetch
written into it: the drawing, its structure and typeset equations, the generated JavaScript solver, KaTeX's
script and style sheet with its fonts as ``data:`` URIs.  ``studio.js`` sees ``window.SYMLINK_EMBEDDED``
and runs without a server (no editing; the input slider, the play button and the branch switch work).
"""
from __future__ import annotations

import base64
import json
import re
from pathlib import Path
from typing import Any

from . import drawing

__all__ = ["standalone_page"]

STATIC = Path(__file__).resolve().parent / "static"


def _script_json(value: Any) -> str:
    """JSON that is safe inside ``<script>``: no ``</script>`` or ``<!--`` can appear in it."""
    return json.dumps(value, separators=(",", ":")).replace("<", "\\u003c").replace(">", "\\u003e") \
        .replace("\u2028", "\\u2028").replace("\u2029", "\\u2029")


def _inline_script(text: str) -> str:
    return "<script>" + text.replace("</script", "<\\/script") + "</script>"


def _katex_css() -> str:
    """KaTeX's style sheet with its woff2 fonts as data URIs."""
    css = (STATIC / "katex" / "katex.min.css").read_text(encoding="utf-8")

    def font(match: re.Match) -> str:
        data = (STATIC / "katex" / match.group(1)).read_bytes()
        return f"url(data:font/woff2;base64,{base64.b64encode(data).decode()})"
    return re.sub(r"url\((fonts/[A-Za-z0-9_-]+\.woff2)\)", font, css)


def standalone_page(data: Any) -> str:
    """The HTML text of a drawing's self-contained page; ``ValueError`` where the drawing is no linkage."""
    structure = drawing.structure(data)
    derivation = drawing.derivation(data)
    embedded: dict[str, Any] = {"drawing": data, "structure": structure, "derivation": derivation,
                                "solver": None, "solverError": None}
    try:
        embedded["solver"] = drawing.solver(data)
    except ValueError as error:
        embedded["solverError"] = str(error)
    page = (STATIC / "index.html").read_text(encoding="utf-8")
    replacements = {
        '<link rel="stylesheet" href="static/katex/katex.min.css">': "<style>" + _katex_css() + "</style>",
        '<link rel="stylesheet" href="static/studio.css">':
            "<style>" + (STATIC / "studio.css").read_text(encoding="utf-8") + "</style>",
        '<script src="static/katex/katex.min.js"></script>':
            _inline_script((STATIC / "katex" / "katex.min.js").read_text(encoding="utf-8")),
        '<script src="static/studio.js"></script>':
            _inline_script("window.SYMLINK_EMBEDDED = " + _script_json(embedded) + ";") + "\n"
            + _inline_script((STATIC / "studio.js").read_text(encoding="utf-8")),
        "<title>symlink studio</title>": f"<title>{structure['name']}: symlink studio</title>",
    }
    for old, new in replacements.items():
        if old not in page:
            raise RuntimeError(f"static/index.html lost {old!r}: the self-contained page cannot be made")
        page = page.replace(old, new)
    return page

"""Write the generated configuration reference into a Markdown file, between its markers.

``python -m moorlife.io.reference config/README.md workflow/schemas/config.schema.yaml``
replaces the block between ``<!-- config-reference:start -->`` and
``<!-- config-reference:end -->`` with :func:`moorlife.config.schema_table` of the schema.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from moorlife.config import schema_table
from moorlife.io import read_yaml

__all__ = ["START", "END", "reference_block", "write_reference"]

START = "<!-- config-reference:start -->\n"
END = "\n<!-- config-reference:end -->"


def reference_block(text: str, source: str = "README") -> str:
    """The generated block of a Markdown text (between the markers)."""
    if START not in text or END not in text:
        raise ValueError(f"{source}: no configuration reference markers ({START.strip()} ... {END.strip()})")
    return text[text.index(START) + len(START) : text.index(END)]


def write_reference(markdown: str | os.PathLike[str], schema: str | os.PathLike[str]) -> bool:
    """Regenerate the block of ``markdown`` from ``schema``; True if the file changed."""
    path = Path(markdown)
    text = path.read_text()
    old = reference_block(text, str(path))
    new = schema_table(read_yaml(schema))
    if old == new:
        return False
    path.write_text(text.replace(START + old + END, START + new + END))
    return True


if __name__ == "__main__":  # pragma: no cover - command line
    md, sch = sys.argv[1:3]
    print(f"{md}: {'regenerated' if write_reference(md, sch) else 'already current'}")

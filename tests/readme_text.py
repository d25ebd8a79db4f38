"""The README's text and its fenced blocks, for the tests that keep it current."""
import pathlib

README = pathlib.Path(__file__).resolve().parent.parent / "README.md"


def readme(section: str | None = None) -> str:
    """The README, or the part of it under the heading ``## section`` (up to the next ``## ``)."""
    text = README.read_text(encoding="utf-8")
    if section is None:
        return text
    start = text.index(f"## {section}")
    return text[start:text.index("\n## ", start + 1)]


def fenced_blocks(text: str, language: str) -> list[str]:
    """The fenced blocks of ``text`` whose language is ``language`` ("" for plain ones)."""
    found, current, kind = [], None, ""
    for line in text.splitlines(keepends=True):
        if line.startswith("```"):
            if current is None:
                current, kind = [], line[3:].strip()
            else:
                if kind == language:
                    found.append("".join(current))
                current = None
        elif current is not None:
            current.append(line)
    return found

"""The README's text and its fenced blocks, for the tests that keep it (and the docs pages) current."""
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
DOCS = ROOT / "docs"
#: Where the README's absolute links point: images on GitHub's raw host, pages on the docs site.
IMAGES_URL = "https://raw.githubusercontent.com/symlink-kinematics/symlink/main/docs/images/"
DOCS_URL = "https://symlink-kinematics.github.io/symlink/"


def readme(section: str | None = None, path: pathlib.Path = README) -> str:
    """The README (or another markdown file), or the part of it under ``## section`` (up to the next ``## ``)."""
    text = path.read_text(encoding="utf-8")
    if section is None:
        return text
    start = text.index(f"## {section}")
    end = text.find("\n## ", start + 1)
    return text[start:] if end < 0 else text[start:end]


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
